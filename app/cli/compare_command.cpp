// `weft compare`: see compare_command.h.

#include "app/cli/compare_command.h"

#include <CLI/CLI.hpp>
#include <memory>

#include <cmath>
#include <cstdio>
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <vector>

#include <nlohmann/json.hpp>

#include "app/io/finite_outputs.h"
#include "base/html_escape.h"
#include "app/scene/json_reader.h"
#include "app/cli/options.h"
#include "app/io/input_guard.h"
#include "app/io/output_files.h"
#include "base/constants.h"
#include "render/photo_compare/photo_compare.h"

namespace weft::app {
namespace {

namespace fs = std::filesystem;

struct BadInput : std::runtime_error {
  using std::runtime_error::runtime_error;
};

render::Image read_input(const fs::path& path, const char* what) {
  if (!fs::exists(path)) throw BadInput(std::string(what) + " " + path.string() + ": no such file");
  try {
    return render::read_image(path);
  } catch (const std::exception& e) {
    throw BadInput(std::string(what) + ": " + e.what());
  }
}

// mask_NNNN.png beside a weft frame frame_NNNN.png (weft run --mask), when there is one.
std::optional<fs::path> weft_mask_beside(const fs::path& image) {
  const std::string name = image.filename().string();
  if (name.size() != 14 || name.rfind("frame_", 0) != 0 || image.extension() != ".png")
    return std::nullopt;
  const fs::path mask = image.parent_path() / ("mask_" + name.substr(6));
  return fs::exists(mask) ? std::optional<fs::path>(mask) : std::nullopt;
}

// The mask images used: given (--mask-photo, --mask-render) or found beside a weft frame.
struct Masks {
  std::optional<fs::path> photo, render;
};

Masks masks_of(const CompareOptions& o) {
  Masks m{o.mask_photo, o.mask_render};
  if (o.segment) return m;
  if (!m.photo) m.photo = weft_mask_beside(o.photo);
  if (!m.render) m.render = weft_mask_beside(o.render);
  return m;
}

render::Silhouette silhouette(const render::Image& image, const fs::path& image_path,
                              const std::optional<fs::path>& mask_path, const char* what,
                              const char* flag) {
  std::optional<render::Image> mask;
  if (mask_path) mask = read_input(*mask_path, flag);
  try {
    return render::silhouette_of(image, mask);
  } catch (const std::invalid_argument& e) {
    throw BadInput(std::string(what) + " " + (mask_path ? *mask_path : image_path).string() + ": " +
                   e.what());
  }
}

nlohmann::json silhouette_json(const render::Silhouette& s, const std::optional<fs::path>& mask) {
  nlohmann::json j;
  j["source"] = s.from_mask_image ? "mask" : "segmentation";
  if (mask) j["mask"] = mask->string();
  j["area_px"] = render::moments(s.mask).area_px;
  if (!s.from_mask_image) {
    j["background"] = {s.background.r, s.background.g, s.background.b};
    j["threshold"] = s.threshold;
  }
  return j;
}

// The doubts about segmented silhouettes (render/photo_compare/photo_compare.h); with a given
// transform, each silhouette's expected area is the other's scaled by it.
std::vector<std::string> doubts(const render::Silhouette& ps, const render::Silhouette& rs,
                                const render::PhotoComparison& c) {
  const double photo_area = render::moments(ps.mask).area_px;
  const double render_area = render::moments(rs.mask).area_px;
  const double scale2 = c.transform.scale * c.transform.scale;
  std::vector<std::string> all = render::segmentation_doubts(
      ps, "photo", c.transform_given ? std::optional<double>(render_area * scale2) : std::nullopt);
  const std::vector<std::string> more = render::segmentation_doubts(
      rs, "render", c.transform_given ? std::optional<double>(photo_area / scale2) : std::nullopt);
  all.insert(all.end(), more.begin(), more.end());
  return all;
}

nlohmann::json result_json(const CompareOptions& o, const Masks& masks, const render::Silhouette& ps,
                           const render::Silhouette& rs, const render::PhotoComparison& c) {
  nlohmann::json j;
  j["photo"] = o.photo.string();
  j["render"] = o.render.string();
  j["width"] = c.photo_mask.width;
  j["height"] = c.photo_mask.height;
  j["transform"] = {{"scale", c.transform.scale},
                    {"tx_px", c.transform.tx_px},
                    {"ty_px", c.transform.ty_px},
                    {"angle_deg", c.transform.angle_rad * 180.0 / base::kPi},
                    {"given", c.transform_given}};
  j["silhouettes"] = {{"photo", silhouette_json(ps, masks.photo)},
                      {"render", silhouette_json(rs, masks.render)}};
  j["warnings"] = doubts(ps, rs, c);
  j["iou"] = c.iou;
  j["chamfer"] = {{"photo_to_render_px", c.chamfer.a_to_b_px},
                  {"render_to_photo_px", c.chamfer.b_to_a_px},
                  {"px", c.chamfer.symmetric_px},
                  {"percent_of_diagonal", c.chamfer.percent_of_diagonal}};
  j["folds"] = {{"sigma_px", c.folds.sigma_px},
                {"precision", c.folds.precision},
                {"recall", c.folds.recall},
                {"f_score", c.folds.f_score},
                {"compared_px", c.folds.compared_px}};
  j["ssim"] = c.ssim;
  j["ssim_mask"] = c.mask_ssim ? nlohmann::json(c.mask_ssim->mean) : nlohmann::json(nullptr);
  j["ssim_mask_windows"] = c.mask_ssim ? c.mask_ssim->windows : 0L;
  j["delta_e2000"] = {{"mean", c.delta_e.mean}, {"p95", c.delta_e.p95}, {"pixels", c.delta_e.pixels}};
  j["out"] = o.out.string();
  return j;
}

void print_text(const nlohmann::json& j) {
  const auto& t = j["transform"];
  std::printf("weft compare: %s vs %s (%dx%d)\n", j["photo"].get<std::string>().c_str(),
              j["render"].get<std::string>().c_str(), j["width"].get<int>(), j["height"].get<int>());
  std::printf("  silhouettes    photo: %s, %.0f px; render: %s, %.0f px\n",
              j["silhouettes"]["photo"]["source"].get<std::string>().c_str(),
              j["silhouettes"]["photo"]["area_px"].get<double>(),
              j["silhouettes"]["render"]["source"].get<std::string>().c_str(),
              j["silhouettes"]["render"]["area_px"].get<double>());
  std::printf("  alignment      %s: scale %.4f, shift (%.2f, %.2f) px, rotation %.2f deg\n",
              t["given"].get<bool>() ? "given" : "from the silhouettes", t["scale"].get<double>(),
              t["tx_px"].get<double>(), t["ty_px"].get<double>(), t["angle_deg"].get<double>());
  std::printf("  silhouette IoU %.4f\n", j["iou"].get<double>());
  std::printf("  Chamfer        %.3f px (%.3f %% of the diagonal)\n", j["chamfer"]["px"].get<double>(),
              j["chamfer"]["percent_of_diagonal"].get<double>());
  std::printf("  fold agreement F %.4f (precision %.4f, recall %.4f; sigma %.2f px, %ld px compared)\n",
              j["folds"]["f_score"].get<double>(), j["folds"]["precision"].get<double>(),
              j["folds"]["recall"].get<double>(), j["folds"]["sigma_px"].get<double>(),
              j["folds"]["compared_px"].get<long>());
  std::printf("  SSIM (overlap) %.4f\n", j["ssim"].get<double>());
  if (j["ssim_mask"].is_null())
    std::printf("  SSIM (mask)    none: no 11x11 window fits inside the photo's mask\n");
  else
    std::printf("  SSIM (mask)    %.4f (%ld windows inside the photo's mask)\n",
                j["ssim_mask"].get<double>(), j["ssim_mask_windows"].get<long>());
  std::printf("  dE2000 (mask)  mean %.3f, 95th percentile %.3f (%ld px)\n",
              j["delta_e2000"]["mean"].get<double>(), j["delta_e2000"]["p95"].get<double>(),
              j["delta_e2000"]["pixels"].get<long>());
}

std::string warnings_html(const nlohmann::json& warnings) {
  if (warnings.empty()) return "";
  std::string html = "<div style=\"border:2px solid #d55e00;padding:4px 10px\"><b>Warning: the "
                     "segmentation is doubtful</b><ul>\n";
  for (const auto& w : warnings) html += "<li>" + base::html_escape(w.get<std::string>()) + "</li>\n";
  return html + "</ul></div>\n";
}

void write_report(const fs::path& path, const nlohmann::json& j) {
  std::ostringstream html;
  const auto row = [&](const std::string& name, const std::string& value, const std::string& note) {
    html << "<tr><td>" << name << "</td><td>" << value << "</td><td>" << note << "</td></tr>\n";
  };
  const auto num = [](double v, int digits) {
    std::ostringstream s;
    s.setf(std::ios::fixed);
    s.precision(digits);
    s << v;
    return s.str();
  };
  const auto& t = j["transform"];
  html << "<!DOCTYPE html>\n<html><head><meta charset=\"utf-8\"><title>weft compare</title>\n"
          "<style>body{font-family:sans-serif;margin:1.5em}td,th{padding:2px 10px;text-align:left}"
          "img{max-width:48%;margin:4px;border:1px solid #ccc}</style></head><body>\n"
       << "<h1>weft compare</h1>\n<p>photo <code>" << base::html_escape(j["photo"].get<std::string>())
       << "</code>, render <code>" << base::html_escape(j["render"].get<std::string>()) << "</code>, "
       << j["width"].get<int>() << "x" << j["height"].get<int>() << " px</p>\n"
       << warnings_html(j["warnings"]) << "<table>\n"
       << "<tr><th>metric</th><th>value</th><th></th></tr>\n";
  row("silhouette IoU", num(j["iou"].get<double>(), 4), "1 = same silhouette after alignment");
  row("Chamfer distance", num(j["chamfer"]["px"].get<double>(), 3) + " px (" +
                              num(j["chamfer"]["percent_of_diagonal"].get<double>(), 3) +
                              " % of the diagonal)",
      "mean outline-to-outline distance, both directions");
  row("fold agreement F", num(j["folds"]["f_score"].get<double>(), 4),
      "ridge/valley labels (Hessian of the luminance, sigma " +
          num(j["folds"]["sigma_px"].get<double>(), 2) + " px); precision " +
          num(j["folds"]["precision"].get<double>(), 3) + ", recall " +
          num(j["folds"]["recall"].get<double>(), 3));
  row("SSIM in the overlap", num(j["ssim"].get<double>(), 4), "luminance, 11x11 Gaussian window");
  row("SSIM in the photo's mask",
      j["ssim_mask"].is_null() ? std::string("none") : num(j["ssim_mask"].get<double>(), 4),
      "mean over the " + std::to_string(j["ssim_mask_windows"].get<long>()) +
          " windows wholly inside the photo's cloth mask");
  row("colour difference", "&Delta;E2000 mean " + num(j["delta_e2000"]["mean"].get<double>(), 2) +
                               ", 95th percentile " + num(j["delta_e2000"]["p95"].get<double>(), 2),
      "CIEDE2000 (sRGB, D65) over the photo's mask pixels");
  row("alignment", "scale " + num(t["scale"].get<double>(), 4) + ", shift (" +
                       num(t["tx_px"].get<double>(), 2) + ", " + num(t["ty_px"].get<double>(), 2) +
                       ") px, " + num(t["angle_deg"].get<double>(), 2) + " deg",
      t["given"].get<bool>() ? "given (--transform)" : "centroid and sqrt of the area ratio");
  for (const char* which : {"photo", "render"}) {
    const auto& s = j["silhouettes"][which];
    row(std::string(which) + " silhouette", num(s["area_px"].get<double>(), 0) + " px",
        s["source"].get<std::string>() == "mask"
            ? "from the mask image " + base::html_escape(s["mask"].get<std::string>())
            : "segmented (border median, Otsu)");
  }
  html << "</table>\n<h2>Outlines</h2>\n<p>cyan: the photo's silhouette; magenta: the aligned "
          "render's.</p>\n<a href=\"overlay.png\"><img src=\"overlay.png\" alt=\"overlay\"></a>\n"
          "<h2>Photo and aligned render</h2>\n<a href=\"photo.png\"><img src=\"photo.png\" "
          "alt=\"photo\"></a><a href=\"render_aligned.png\"><img src=\"render_aligned.png\" "
          "alt=\"aligned render\"></a>\n<h2>Fold lines</h2>\n<p>ridges orange, valleys blue; "
          "left the photo, right the render; grey: compared, unlabelled.</p>\n<a "
          "href=\"folds.png\"><img src=\"folds.png\" alt=\"fold labels\" style=\"max-width:97%\">"
          "</a>\n</body></html>\n";
  write_text(path, html.str());
}

}  // namespace

render::Similarity parse_transform(const std::string& text) {
  const auto fail = [&](const std::string& why) {
    throw std::invalid_argument("--transform '" + text + "': " + why +
                                " (expected s,tx,ty[,deg]: scale > 0, shift in photo pixels, "
                                "rotation in degrees)");
  };
  std::vector<double> v;
  std::stringstream items(text);
  std::string item;
  while (std::getline(items, item, ',')) {
    std::size_t used = 0;
    double x = 0.0;
    try {
      x = std::stod(item, &used);
    } catch (const std::logic_error&) {
      fail("'" + item + "' is not a number");
    }
    if (used != item.size() || !std::isfinite(x)) fail("'" + item + "' is not a finite number");
    v.push_back(x);
  }
  if (v.size() != 3 && v.size() != 4) fail("expected 3 or 4 numbers, got " + std::to_string(v.size()));
  if (!(v[0] > 0.0)) fail("the scale must be positive");
  render::Similarity t;
  t.scale = v[0];
  t.tx_px = v[1];
  t.ty_px = v[2];
  if (v.size() == 4) t.angle_rad = v[3] * base::kPi / 180.0;
  return t;
}

namespace {

// What weft compare writes into --out; none may be one of its inputs.
void refuse_overwriting_compare_inputs(const CompareOptions& o, const Masks& masks) {
  std::vector<fs::path> inputs{o.photo, o.render};
  for (const auto& mask : {masks.photo, masks.render})
    if (mask) inputs.push_back(*mask);
  refuse_overwriting_inputs(
      o.out, {{"photo.png", "render_aligned.png", "overlay.png", "folds.png", "report.html"}, {}},
      inputs);
}

}  // namespace

int run_compare(const CompareOptions& o) {
  std::optional<render::Similarity> transform;
  render::Image photo, render;
  render::Silhouette ps, rs;
  render::PhotoComparison c;
  const Masks masks = masks_of(o);
  try {
    if (o.transform) transform = parse_transform(*o.transform);
    refuse_overwriting_compare_inputs(o, masks);
    photo = read_input(o.photo, "photo");
    render = read_input(o.render, "render");
    ps = silhouette(photo, o.photo, masks.photo, "photo", "--mask-photo");
    rs = silhouette(render, o.render, masks.render, "render", "--mask-render");
    try {
      c = render::compare_with_photo(photo, ps, render, rs, transform, o.fold_sigma_px);
    } catch (const std::invalid_argument& e) {
      throw BadInput(o.photo.string() + " vs " + o.render.string() + ": " + e.what());
    }
  } catch (const std::exception& e) {  // BadInput and parse_transform's invalid_argument
    std::fprintf(stderr, "weft compare: error: %s\n", e.what());
    return exit_bad_input;
  }
  const nlohmann::json j = result_json(o, masks, ps, rs, c);
  const std::string json_text = finite_json_text(j, "weft compare's result");
  for (const auto& w : j["warnings"])
    std::fprintf(stderr, "weft compare: warning: %s\n", w.get<std::string>().c_str());
  fs::create_directories(o.out);
  render::write_png(photo, o.out / "photo.png");
  render::write_png(c.render_aligned, o.out / "render_aligned.png");
  render::write_png(render::outline_overlay(photo, c), o.out / "overlay.png");
  render::write_png(render::fold_label_image(c), o.out / "folds.png");
  write_report(o.out / "report.html", j);
  if (o.json) std::printf("%s\n", json_text.c_str());
  else print_text(j);
  std::fprintf(stderr, "weft compare: wrote %s\n", (o.out / "report.html").c_str());
  return exit_ok;
}

Command register_compare(CLI::App& app, const std::string& /*command_line*/) {
  const auto o = std::make_shared<CompareOptions>();
  CLI::App* cmd = app.add_subcommand(
      "compare", "Compare a render with a photo: segment both, align, print silhouette IoU, Chamfer "
                 "distance, fold agreement, SSIM and CIEDE2000 inside the mask; write "
                 "DIR/overlay.png and DIR/report.html");
  cmd->add_option("photo", o->photo, "Photo (PNG or JPG, any size)")->required();
  cmd->add_option("render", o->render, "Render (PNG or JPG; resampled onto the photo)")->required();
  cmd->add_option("--mask-photo", o->mask_photo,
                  "Mask image of the photo (white = cloth), instead of segmentation");
  cmd->add_option("--mask-render", o->mask_render,
                  "Mask image of the render (white = cloth), instead of segmentation (default: "
                  "mask_NNNN.png beside a weft frame_NNNN.png, when there is one)");
  cmd->add_flag("--segment", o->segment,
                "Segment by colour even where a weft frame_NNNN.png has its mask_NNNN.png beside "
                "it (by default that mask is the silhouette)");
  cmd->add_option("--transform", o->transform,
                  "s,tx,ty[,deg]: render pixels to photo pixels, p = s R(deg) r + t, "
                  "instead of aligning the silhouettes");
  cmd->add_option("--out", o->out, "Output folder (default: out/compare)");
  cmd->add_flag("--json", o->json, "Print the numbers as one JSON object");
  check_range(cmd->add_option("--fold-sigma", o->fold_sigma_px,
                              "Gaussian sigma in photo pixels for the fold maps (default: 1 % of "
                              "the diagonal, at least 1.5)"),
              Range::gt(0.0).le(1000.0));
  return {cmd, [o] { return run_compare(*o); }};
}

}  // namespace weft::app
