// weft photo-scene (see photo_scene_command.h).

#include "app/cli/photo_scene_command.h"

#include <CLI/CLI.hpp>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>
#include <vector>

#include "app/cli/options.h"
#include "app/fit/photo_scene_fit.h"
#include "app/io/finite_outputs.h"
#include "app/io/input_error.h"
#include "app/io/input_guard.h"
#include "app/io/output_files.h"
#include "app/io/output_lock.h"
#include "app/io/progress.h"
#include "app/scene/json_reader.h"
#include "render/photo_compare/held_corners.h"
#include "render/photo_compare/photo_compare.h"

namespace weft::app {
namespace {

namespace fs = std::filesystem;
constexpr double kDegree = 3.14159265358979323846 / 180.0;

const OutputNames photo_scene_outputs = {
    {"scene.json", "texture.png", "render.png", "mask.png", "overlay.png", "corners.png",
     "placement.csv", "summary.json"},
    {}};

// "0.55x0.55": the cloth's width (between the held corners) and height, metres.
std::pair<double, double> parse_cloth_size(const std::string& text) {
  const std::size_t x = text.find('x');
  double w = 0.0, h = 0.0;
  std::size_t used_w = 0, used_h = 0;
  try {
    if (x != std::string::npos) {
      w = std::stod(text.substr(0, x), &used_w);
      h = std::stod(text.substr(x + 1), &used_h);
    }
  } catch (const std::logic_error&) {
    used_w = 0;
  }
  if (x == std::string::npos || used_w != x || used_h != text.size() - x - 1 || !(w > 0.0) ||
      !(h > 0.0) || !std::isfinite(w) || !std::isfinite(h) || w > 100.0 || h > 100.0)
    throw InputError("--cloth-size '" + text +
                     "': expected WIDTHxHEIGHT in metres, each in (0, 100], "
                     "e.g. 0.55x0.55 (the width is the edge between the held corners)");
  return {w, h};
}

PlacementFitSettings parse_fit(const std::string& text, int max_evaluations) {
  PlacementFitSettings s;
  s.max_evaluations = max_evaluations;
  s.corners = s.depth = s.depth_difference = s.tilt = s.density = false;
  if (text == "none") return s;
  std::stringstream items(text);
  std::string item;
  while (std::getline(items, item, ',')) {
    if (item == "corners")
      s.corners = true;
    else if (item == "depth")
      s.depth = true;
    else if (item == "depth-difference")
      s.depth_difference = true;
    else if (item == "tilt")
      s.tilt = true;
    else if (item == "density")
      s.density = true;
    else
      throw InputError("--fit '" + text + "': unknown '" + item +
                       "' (expected \"none\" or a comma "
                       "list of corners, depth, depth-difference, tilt, density)");
  }
  return s;
}

render::Image read_checked(const fs::path& path, const char* what) {
  if (!fs::exists(path))
    throw InputError(std::string(what) + " " + path.string() + ": no such file");
  try {
    return render::read_image(path);
  } catch (const std::exception& e) {
    throw InputError(std::string(what) + " " + path.string() + ": " + e.what());
  }
}

// The photo with the cleaned silhouette's outline (cyan) and the held corners (magenta crosses).
render::Image corners_picture(const render::Image& photo, const render::HeldCorners& c) {
  render::Image out = photo;
  const render::Mask o = render::outline(c.cleaned);
  for (int y = 0; y < out.height(); ++y)
    for (int x = 0; x < out.width(); ++x)
      if (o.at(x, y)) out.set(x, y, {0, 220, 255});
  const int arm = std::max(3, out.width() / 100);
  for (const Eigen::Vector2d& p : c.px) {
    const int cx = static_cast<int>(std::lround(p.x())), cy = static_cast<int>(std::lround(p.y()));
    for (int d = -arm; d <= arm; ++d)
      for (const auto& [x, y] : {std::pair{cx + d, cy}, std::pair{cx, cy + d}})
        if (x >= 0 && y >= 0 && x < out.width() && y < out.height()) out.set(x, y, {255, 0, 200});
  }
  return out;
}

// The mask at another image size with the same aspect ratio, nearest pixel (pixel centres
// mapped as the camera's intrinsics are: u' = s (u + ½) − ½).
render::Mask mask_at_size(const render::Mask& mask, int width, int height) {
  render::Mask out(width, height);
  const double sx = static_cast<double>(mask.width) / width, sy = static_cast<double>(mask.height) / height;
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x)
      out.set(x, y, mask.at(std::min(mask.width - 1, static_cast<int>(sx * (x + 0.5))),
                            std::min(mask.height - 1, static_cast<int>(sy * (y + 0.5)))));
  return out;
}

// The texture of the settled cloth from the photo, or from --texture-photo.
render::PhotoTexture texture_of(const PhotoSceneOptions& o, const Scene& scene,
                                const sim::Simulator& simulator, const render::Image& photo,
                                const render::Mask& photo_mask, int tw, int th) {
  if (!o.texture_photo) return settled_photo_texture(scene, simulator, photo, photo_mask, tw, th);
  const render::Image big = read_checked(*o.texture_photo, "--texture-photo");
  try {
    return settled_photo_texture(scene, simulator, big, mask_at_size(photo_mask, big.width(), big.height()),
                                 tw, th);
  } catch (const std::invalid_argument& e) {
    throw InputError("--texture-photo " + o.texture_photo->string() + ": " + e.what());
  }
}

std::string placement_text(const Placement& p) {
  char text[256];
  std::snprintf(
      text, sizeof text,
      "corners moved (%+.2f, %+.2f) and (%+.2f, %+.2f) px, depth x%.4f, depth difference "
      "%+.1f mm, tilt %+.2f deg%s",
      p.corner_shift_px[0].x(), p.corner_shift_px[0].y(), p.corner_shift_px[1].x(),
      p.corner_shift_px[1].y(), p.depth_scale, 1e3 * p.depth_difference_m, p.tilt_rad / kDegree,
      p.density_kg_m2 ? (", density " + std::to_string(*p.density_kg_m2) + " kg/m^2").c_str() : "");
  return text;
}

nlohmann::json placement_json(const PhotoSceneSetup& setup, const PlacementEvaluation& e) {
  const auto corners = held_corner_positions(setup, e.placement);
  const auto& shift = e.placement.corner_shift_px;
  nlohmann::json j = {
      {"corner_shift_px", {{shift[0].x(), shift[0].y()}, {shift[1].x(), shift[1].y()}}},
      {"depth_scale", e.placement.depth_scale},
      {"depth_difference_m", e.placement.depth_difference_m},
      {"tilt_deg", e.placement.tilt_rad / kDegree},
      {"held_corners_m",
       {{corners[0].x(), corners[0].y(), corners[0].z()},
        {corners[1].x(), corners[1].y(), corners[1].z()}}},
      {"iou", e.iou},
      {"chamfer_px", e.chamfer_px},
      {"settled", e.settled}};
  if (e.placement.density_kg_m2) j["density_kg_m2"] = *e.placement.density_kg_m2;
  return j;
}

// What the photo, its mask and the camera give: the setup of the placement problem, the held
// corners found and the silhouette measured against.
struct PhotoInputs {
  render::Image photo;
  PhotoSceneSetup setup;
  render::HeldCorners corners;
  render::Mask photo_mask;  // the mask's largest component, holes filled
};

PhotoInputs read_photo_inputs(const PhotoSceneOptions& o, double cloth_w, double cloth_h) {
  PhotoInputs in;
  in.photo = read_checked(o.photo, "photo");
  const render::Image mask_image = read_checked(o.mask, "--mask");
  if (mask_image.width() != in.photo.width() || mask_image.height() != in.photo.height())
    throw InputError("--mask " + o.mask.string() + ": " + std::to_string(mask_image.width()) + "x" +
                     std::to_string(mask_image.height()) + ", but the photo is " +
                     std::to_string(in.photo.width()) + "x" + std::to_string(in.photo.height()));
  PhotoSceneSetup& setup = in.setup;
  setup.camera = read_photo_camera(o.camera);
  setup.width_px = in.photo.width();
  setup.height_px = in.photo.height();
  try {
    (void)setup.camera.scaled_to(setup.width_px, setup.height_px);
  } catch (const std::invalid_argument& e) {
    throw InputError("--camera " + o.camera.string() + ": " + e.what());
  }
  setup.cloth_width_m = cloth_w;
  setup.cloth_height_m = cloth_h;
  const double longer = std::max(cloth_w, cloth_h);
  setup.resolution = {std::max(2, static_cast<int>(std::lround(o.resolution * cloth_w / longer))),
                      std::max(2, static_cast<int>(std::lround(o.resolution * cloth_h / longer)))};
  setup.material_preset = o.material_preset;
  try {
    in.corners = render::find_held_corners(render::mask_from_image(mask_image));
  } catch (const std::invalid_argument& e) {
    throw InputError("--mask " + o.mask.string() + ": " + e.what());
  }
  setup.corners_px = in.corners.px;
  in.photo_mask = render::fill_holes(render::largest_component(render::mask_from_image(mask_image)));
  return in;
}

// The start placement evaluated, then fitted as --fit asks; every evaluation logged to
// OUT/placement.csv and stderr. Returns the start's evaluation and the best one.
std::pair<PlacementEvaluation, PlacementEvaluation> fit_from_start(
    const PhotoSceneOptions& o, PhotoSceneProblem& problem, const Placement& start,
    const PlacementFitSettings& fit_settings) {
  std::ofstream csv(o.out / "placement.csv");
  csv << "evaluation,left_du_px,left_dv_px,right_du_px,right_dv_px,depth_scale,depth_difference_m,"
         "tilt_deg,density_kg_m2,iou,chamfer_px,settled,seconds\n";
  const auto log = [&](const PlacementEvaluation& e, int number) {
    const auto& shift = e.placement.corner_shift_px;
    csv << number << ',' << shift[0].x() << ',' << shift[0].y() << ',' << shift[1].x() << ','
        << shift[1].y() << ',' << e.placement.depth_scale << ',' << e.placement.depth_difference_m
        << ',' << e.placement.tilt_rad / kDegree << ',' << e.placement.density_kg_m2.value_or(0.0)
        << ',' << e.iou << ',' << e.chamfer_px << ',' << e.settled << ',' << e.seconds << '\n';
    std::fprintf(stderr, "photo-scene %3d  %s  IoU %.4f  Chamfer %.3f px  (%s%s)\n", number,
                 placement_text(e.placement).c_str(), e.iou, e.chamfer_px,
                 format_duration(e.seconds).c_str(), e.settled ? "" : ", NOT settled");
  };
  const PlacementEvaluation first = problem.evaluate(start);
  log(first, 0);
  PlacementEvaluation best = first;
  if (fit_settings.corners || fit_settings.depth || fit_settings.depth_difference ||
      fit_settings.tilt || fit_settings.density) {
    const PlacementFit fit = fit_placement(problem, start, fit_settings, log);
    if (fit.best.chamfer_px < best.chamfer_px) best = fit.best;
    std::fprintf(stderr, "weft photo-scene: fit %s after %zu evaluations\n",
                 fit.stop_reason.c_str(), fit.evaluations.size());
  }
  return {first, best};
}

// The written scene's description: where it came from and how well it fits.
std::string scene_description(const PhotoSceneOptions& o, const PlacementEvaluation& chosen) {
  return "A cloth held by two corners, placed from the photo " + o.photo.string() +
         " and its mask " + o.mask.string() + " by weft photo-scene (" + o.command_line +
         "): " + placement_text(chosen.placement) + "; outline Chamfer " +
         std::to_string(chosen.chamfer_px) + " px, IoU " + std::to_string(chosen.iou) +
         " at rest. The world is the camera's frame (x right, y down, z forward).";
}

// The summary's lines on stdout (--json prints the summary itself).
void print_summary(const nlohmann::json& j, const PhotoSceneSetup& setup,
                   const PlacementEvaluation& first, const PlacementEvaluation& chosen,
                   const render::PhotoComparison& c, const std::string& scene_path) {
  std::printf("weft photo-scene: %s\n", scene_path.c_str());
  std::printf("  held corners    (%.1f, %.1f) and (%.1f, %.1f) px\n", setup.corners_px[0].x(),
              setup.corners_px[0].y(), setup.corners_px[1].x(), setup.corners_px[1].y());
  for (const char* which : {"start", "chosen"}) {
    const auto& p = j[which];
    std::printf(
        "  %-15s %s: corners (%.4f, %.4f, %.4f) and (%.4f, %.4f, %.4f) m; IoU %.4f, "
        "Chamfer %.3f px\n",
        which,
        placement_text(std::string(which) == "start" ? first.placement : chosen.placement).c_str(),
        p["held_corners_m"][0][0].get<double>(), p["held_corners_m"][0][1].get<double>(),
        p["held_corners_m"][0][2].get<double>(), p["held_corners_m"][1][0].get<double>(),
        p["held_corners_m"][1][1].get<double>(), p["held_corners_m"][1][2].get<double>(),
        p["iou"].get<double>(), p["chamfer_px"].get<double>());
  }
  if (c.mask_ssim) std::printf("  SSIM (mask)     %.4f\n", c.mask_ssim->mean);
  std::printf("  dE2000 (mask)   mean %.3f, 95th percentile %.3f\n", c.delta_e.mean, c.delta_e.p95);
  if (j.contains("texture_seen_fraction"))
    std::printf("  texture         %.1f %% of its texels seen in the photo\n",
                100.0 * j["texture_seen_fraction"].get<double>());
}

}  // namespace

int run_photo_scene(const PhotoSceneOptions& o) {
  const auto [cloth_w, cloth_h] = parse_cloth_size(o.cloth_size);
  const PlacementFitSettings fit_settings = parse_fit(o.fit, o.max_evaluations);
  std::vector<fs::path> inputs{o.photo, o.mask, o.camera};
  if (o.texture_photo) inputs.push_back(*o.texture_photo);
  refuse_overwriting_inputs(o.out, photo_scene_outputs, inputs);
  const PhotoInputs in = read_photo_inputs(o, cloth_w, cloth_h);
  const PhotoSceneSetup& setup = in.setup;

  const OutputFolderLock lock(o.out);  // creates the folder
  const std::string scene_path = (o.out / "scene.json").string();
  PhotoSceneProblem problem(setup, in.photo_mask, scene_path, o.threads);
  Placement start;
  start.depth_scale = o.depth_scale;
  start.depth_difference_m = o.depth_difference_m;
  start.tilt_rad = o.tilt_deg * kDegree;
  start.density_kg_m2 = o.density_kg_m2;
  if (fit_settings.density && !start.density_kg_m2)
    start.density_kg_m2 = problem.scene_at(start).material.density_kg_m2;
  std::fprintf(stderr,
               "weft photo-scene: held corners at (%.1f, %.1f) and (%.1f, %.1f) px; depth "
               "from the %.3f m width %.4f m\n",
               setup.corners_px[0].x(), setup.corners_px[0].y(), setup.corners_px[1].x(),
               setup.corners_px[1].y(), cloth_w, depth_from_width(setup));
  const auto [first, best] = fit_from_start(o, problem, start, fit_settings);

  // The chosen placement, settled once more for its pictures (and texture).
  Settled settled;
  const PlacementEvaluation final_eval = problem.evaluate(best.placement, &settled);
  if (!settled.simulator)
    throw std::runtime_error("the chosen placement's simulation diverged: " + final_eval.failure);
  Scene scene = problem.scene_at(best.placement);
  std::string texture_file;
  double seen_fraction = 0.0;
  if (o.texture) {
    const double longer = std::max(cloth_w, cloth_h);
    const int tw = std::max(2, static_cast<int>(std::lround(o.texture_size * cloth_w / longer)));
    const int th = std::max(2, static_cast<int>(std::lround(o.texture_size * cloth_h / longer)));
    const render::PhotoTexture t =
        texture_of(o, scene, *settled.simulator, in.photo, in.photo_mask, tw, th);
    render::write_png(t.texture, o.out / "texture.png");
    texture_file = "texture.png";
    seen_fraction = t.seen_fraction;
    scene = problem.scene_at(best.placement, texture_file);
  }
  write_text(o.out / "scene.json",
             finite_json_text(photo_scene_json(setup, best.placement,
                                               scene_description(o, final_eval), texture_file),
                              (o.out / "scene.json").string()) +
                 "\n");

  const render::Mask mask = problem.silhouette(scene, *settled.simulator);
  const render::Image look = problem.render_look(scene, *settled.simulator);
  render::write_png(mask, o.out / "mask.png");
  render::write_png(look, o.out / "render.png");
  render::write_png(corners_picture(in.photo, in.corners), o.out / "corners.png");
  render::Silhouette ps{in.photo_mask, true, {}, 0.0}, rs{mask, true, {}, 0.0};
  const render::PhotoComparison c =
      render::compare_with_photo(in.photo, ps, look, rs, render::Similarity{});
  render::write_png(render::outline_overlay(in.photo, c), o.out / "overlay.png");

  nlohmann::json j;
  j["corners_px"] = {{setup.corners_px[0].x(), setup.corners_px[0].y()},
                     {setup.corners_px[1].x(), setup.corners_px[1].y()}};
  j["depth_from_width_m"] = depth_from_width(setup);
  j["start"] = placement_json(setup, first);
  j["chosen"] = placement_json(setup, final_eval);
  j["iou"] = c.iou;
  j["chamfer_px"] = c.chamfer.symmetric_px;
  j["ssim_mask"] = c.mask_ssim ? nlohmann::json(c.mask_ssim->mean) : nlohmann::json(nullptr);
  j["delta_e2000"] = {{"mean", c.delta_e.mean}, {"p95", c.delta_e.p95}};
  if (o.texture) j["texture_seen_fraction"] = seen_fraction;
  j["scene"] = scene_path;
  const std::string summary = finite_json_text(j, (o.out / "summary.json").string());
  write_text(o.out / "summary.json", summary + "\n");
  if (o.json) std::printf("%s\n", summary.c_str());
  else print_summary(j, setup, first, final_eval, c, scene_path);
  return exit_ok;
}

Command register_photo_scene(CLI::App& app, const std::string& command_line) {
  const auto o = std::make_shared<PhotoSceneOptions>();
  o->command_line = command_line;
  CLI::App* cmd = app.add_subcommand(
      "photo-scene",
      "Write a scene of a cloth held by two corners from one photo: its mask, the "
      "camera's intrinsics and the cloth's size; optionally fit depth, tilt and "
      "density to the outline and project the photo into a texture (docs/photos.md)");
  cmd->add_option("photo", o->photo, "Photo (PNG or JPG; the scene renders at its size)")
      ->required();
  cmd->add_option("--mask", o->mask, "The photo's cloth mask (white = cloth)")->required();
  cmd->add_option("--camera", o->camera,
                  "Camera JSON: {\"intrinsics\": {fx, fy, cx, cy, size}}, a weft scene with "
                  "render.camera.intrinsics, or a phi-SfT scene file (R1_scene.json)")
      ->required();
  cmd->add_option("--cloth-size", o->cloth_size,
                  "WIDTHxHEIGHT in metres (the width between the held corners), e.g. 0.55x0.55")
      ->required();
  cmd->add_option("--material", o->material_preset, "Material preset (default: weft's defaults)");
  check_range(
      cmd->add_option("--density", o->density_kg_m2, "Areal density, kg/m^2 (the start of a fit)"),
      Range::gt(0.0).le(100.0));
  check_range(
      cmd->add_option("--resolution", o->resolution, "Vertices along the longer side (default 32)"),
      Range::closed(3, 200));
  cmd->add_option("--fit", o->fit,
                  "What to fit to the outline: none, or a comma list of corners (their pixels, "
                  "within 3 px), depth, depth-difference, tilt, density (default: all five)");
  check_range(
      cmd->add_option("--max-evaluations", o->max_evaluations, "Fit evaluations (default 100)"),
      Range::closed(1, 10000));
  check_range(
      cmd->add_option("--tilt", o->tilt_deg, "Start: the camera's pitch, degrees down (default 0)"),
      Range::closed(-25.0, 25.0));
  check_range(cmd->add_option("--depth-scale", o->depth_scale,
                              "Start: the corners' depth relative to the width's (default 1)"),
              Range::closed(0.75, 4.0 / 3.0));
  check_range(cmd->add_option("--depth-difference", o->depth_difference_m,
                              "Start: right corner minus left corner depth, m (default 0)"),
              Range::closed(-10.0, 10.0));
  cmd->add_flag("--texture", o->texture,
                "Project the photo onto the settled cloth into DIR/texture.png and use it");
  cmd->add_option("--texture-photo", o->texture_photo,
                  "Take the texture from this photo instead: the same view at another size with "
                  "the same aspect ratio (e.g. the full-size frame); its mask is --mask scaled");
  check_range(cmd->add_option("--texture-size", o->texture_size,
                              "Texels along the longer side (default 512)"),
              Range::closed(8, 8192));
  cmd->add_option("--out", o->out, "Output folder (default: out/photo_scene)");
  cmd->add_flag("--json", o->json, "Print the summary as JSON");
  add_threads_option(*cmd, o->threads);
  return {cmd, [o] { return run_photo_scene(*o); }};
}

}  // namespace weft::app
