// `weft diff`: see diff_command.h.

#include "app/cli/diff_command.h"

#include <CLI/CLI.hpp>
#include <memory>

#include <cmath>
#include <tuple>
#include <cstdio>
#include <sstream>
#include <stdexcept>

#include <nlohmann/json.hpp>

#include "app/io/finite_outputs.h"
#include "app/scene/json_reader.h"
#include "app/io/output_files.h"

namespace weft::app {
namespace {

std::string number_text(double v) {
  if (std::isinf(v)) return v > 0 ? "inf" : "-inf";
  char buffer[32];
  std::snprintf(buffer, sizeof buffer, "%.6g", v);
  return buffer;
}

void print_text(const DiffOptions& o, const render::ImageDifference& d, const DiffVerdict& v) {
  std::printf("weft diff: %s vs %s (%dx%d)\n", o.a.c_str(), o.b.c_str(), d.width, d.height);
  std::printf("  %-8s %10s %10s %6s\n", "channel", "mean", "rms", "max");
  const char* names[4] = {"R", "G", "B", "A"};
  for (int c = 0; c < (d.has_alpha ? 4 : 3); ++c) {
    const auto& ch = d.channels[static_cast<std::size_t>(c)];
    std::printf("  %-8s %10.4f %10.4f %6d\n", names[c], ch.mean_abs, ch.rms, ch.max_abs);
  }
  std::printf("  %-8s %10.4f %10.4f %6d\n", "all", d.mean_abs, d.rms, d.max_abs);
  std::printf("  PSNR %s dB, SSIM %.6f, pixels differing by more than %d: %.4f %%\n",
              number_text(d.psnr_db).c_str(), d.ssim, d.pixel_threshold, 100.0 * d.fraction_over);
  for (const std::string& c : v.crossed) std::printf("  crossed: %s\n", c.c_str());
  static const char* results[] = {"pass", "warn", "fail"};
  std::printf("  result: %s%s\n", results[v.exit], o.report_only ? " (--report-only)" : "");
}

void print_json(const DiffOptions& o, const render::ImageDifference& d, const DiffVerdict& v) {
  nlohmann::json j;
  j["a"] = o.a.string();
  j["b"] = o.b.string();
  j["width"] = d.width;
  j["height"] = d.height;
  const char* names[4] = {"r", "g", "b", "a"};
  for (int c = 0; c < (d.has_alpha ? 4 : 3); ++c) {
    const auto& ch = d.channels[static_cast<std::size_t>(c)];
    j["channels"][names[c]] = {{"mean", ch.mean_abs}, {"rms", ch.rms}, {"max", ch.max_abs}};
  }
  j["mean"] = d.mean_abs;
  j["rms"] = d.rms;
  j["max"] = d.max_abs;
  // JSON has no infinity: identical images give "psnr": null with "identical": true.
  j["psnr"] = std::isinf(d.psnr_db) ? nlohmann::json(nullptr) : nlohmann::json(d.psnr_db);
  j["identical"] = d.max_abs == 0;
  j["ssim"] = d.ssim;
  j["pixel_threshold"] = d.pixel_threshold;
  j["over"] = d.fraction_over;
  j["crossed"] = v.crossed;
  static const char* results[] = {"pass", "warn", "fail"};
  j["result"] = results[v.exit];
  std::printf("%s\n", finite_json_text(j, "weft diff's result").c_str());
}

// Writes the heatmap as PNG or JPEG by the file's extension.
void write_heatmap(const render::Image& heatmap, const std::filesystem::path& path) {
  if (lower_extension(path) == ".png") render::write_png(heatmap, path);
  else render::write_jpg(heatmap, path);
}

// --warn and --fail as thresholds; without --fail (and without --report-only) the defaults.
std::pair<std::vector<DiffThreshold>, std::vector<DiffThreshold>> thresholds_of(const DiffOptions& o) {
  std::vector<DiffThreshold> warn, fail;
  for (const std::string& w : o.warn) {
    const auto t = parse_thresholds(w, "--warn");
    warn.insert(warn.end(), t.begin(), t.end());
  }
  for (const std::string& f : o.fail) {
    const auto t = parse_thresholds(f, "--fail");
    fail.insert(fail.end(), t.begin(), t.end());
  }
  if (o.fail.empty() && !o.report_only) fail = parse_thresholds(default_fail_thresholds(), "default");
  if (o.heatmap) {
    const std::string ext = lower_extension(*o.heatmap);
    if (ext != ".png" && ext != ".jpg" && ext != ".jpeg")
      throw std::invalid_argument("--heatmap: " + o.heatmap->string() +
                                  ": expected a .png, .jpg or .jpeg file name");
  }
  return {warn, fail};
}

}  // namespace

std::string default_fail_thresholds() {
  return "psnr<" + number_text(render::default_min_psnr_db) + ",over>" +
         number_text(render::default_max_over);
}

std::vector<DiffThreshold> parse_thresholds(const std::string& list, const std::string& flag) {
  std::vector<DiffThreshold> out;
  std::stringstream items(list);
  std::string item;
  while (std::getline(items, item, ',')) {
    const auto fail = [&](const std::string& why) {
      throw std::invalid_argument(flag + ": '" + item + "': " + why +
                                  " (expected METRIC<VALUE or METRIC>VALUE, METRIC one of mean, "
                                  "rms, max, psnr, ssim, over)");
    };
    const std::size_t op = item.find_first_of("<>");
    if (op == std::string::npos || op == 0) fail("no comparison");
    DiffThreshold t;
    t.text = item;
    t.metric = item.substr(0, op);
    t.below = item[op] == '<';
    std::size_t used = 0;
    try {
      t.value = std::stod(item.substr(op + 1), &used);
    } catch (const std::logic_error&) {
      fail("not a number");
    }
    if (used != item.size() - op - 1 || !std::isfinite(t.value)) fail("not a finite number");
    try {
      (void)metric_value(render::ImageDifference{}, t.metric);
    } catch (const std::invalid_argument&) {
      fail("unknown metric '" + t.metric + "'");
    }
    out.push_back(t);
  }
  return out;
}

double metric_value(const render::ImageDifference& d, const std::string& metric) {
  if (metric == "mean") return d.mean_abs;
  if (metric == "rms") return d.rms;
  if (metric == "max") return d.max_abs;
  if (metric == "psnr") return d.psnr_db;
  if (metric == "ssim") return d.ssim;
  if (metric == "over") return d.fraction_over;
  throw std::invalid_argument("unknown image-difference metric '" + metric + "'");
}

DiffVerdict judge(const render::ImageDifference& d, const std::vector<DiffThreshold>& warn,
                  const std::vector<DiffThreshold>& fail) {
  DiffVerdict v;
  const auto check = [&](const std::vector<DiffThreshold>& list, DiffExit level, const char* name) {
    for (const DiffThreshold& t : list) {
      const double x = metric_value(d, t.metric);
      if (t.below ? x < t.value : x > t.value) {
        v.crossed.push_back(t.metric + " " + number_text(x) + (t.below ? " < " : " > ") +
                            number_text(t.value) + " (" + name + ")");
        if (level > v.exit) v.exit = level;
      }
    }
  };
  check(fail, diff_fail, "fail");
  check(warn, diff_warn, "warn");
  return v;
}

int run_diff(const DiffOptions& o) {
  std::vector<DiffThreshold> warn, fail;
  try {
    std::tie(warn, fail) = thresholds_of(o);
    // (--pixel-threshold is bounded by its option, check_range in app/cli/command.h.)
    for (const std::filesystem::path& input : {o.a, o.b})
      if (o.heatmap && same_file(*o.heatmap, input))
        throw std::invalid_argument("--heatmap: " + o.heatmap->string() + " is the input " +
                                    input.string() + "; write the heatmap to another file");
  } catch (const std::invalid_argument& e) {
    std::fprintf(stderr, "weft diff: error: %s\n", e.what());
    return diff_bad_arguments;
  }
  render::Image a, b;
  std::vector<std::uint8_t> alpha_a, alpha_b;  // empty: the file has no alpha
  try {
    a = render::read_image(o.a);
    b = render::read_image(o.b);
    alpha_a = render::read_alpha(o.a);
    alpha_b = render::read_alpha(o.b);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "weft diff: error: %s\n", e.what());
    return diff_unreadable;
  }
  if (a.width() != b.width() || a.height() != b.height()) {
    std::fprintf(stderr, "weft diff: error: sizes differ: %s is %dx%d, %s is %dx%d\n", o.a.c_str(),
                 a.width(), a.height(), o.b.c_str(), b.width(), b.height());
    return diff_size_mismatch;
  }
  const render::ImageDifference d =
      render::compare_images(a, b, o.pixel_threshold, alpha_a, alpha_b);
  const DiffVerdict v = judge(d, warn, fail);
  if (o.heatmap) {
    write_heatmap(render::difference_heatmap(a, b, o.pixel_threshold), *o.heatmap);
    std::fprintf(stderr, "weft diff: wrote %s\n", o.heatmap->c_str());
  }
  if (o.json) print_json(o, d, v);
  else print_text(o, d, v);
  return v.exit;
}

Command register_diff(CLI::App& app, const std::string& /*command_line*/) {
  const auto o = std::make_shared<DiffOptions>();
  CLI::App* cmd = app.add_subcommand(
      "diff", "Compare two images: mean/RMS/max difference, PSNR, SSIM, pixels over a threshold "
              "(alpha too when either image has it). Without --fail it fails as the regression "
              "suite does: PSNR below 50 dB or more than 0.05 % of pixels differing by more than "
              "16 (--fail '" + default_fail_thresholds() + "'); --report-only never fails. Exit 0 "
              "pass, 1 warn, 2 fail, 3 size mismatch, 4 unreadable file, 5 bad arguments");
  cmd->add_option("a", o->a, "First image (PNG or JPG)")->required();
  cmd->add_option("b", o->b, "Second image (PNG or JPG)")->required();
  cmd->add_option("--heatmap", o->heatmap,
                  "Write a heatmap of the differences to this PNG or JPEG (by extension)");
  cmd->add_flag("--json", o->json, "Print the comparison as one JSON object");
  cmd->add_option("--warn", o->warn,
                  "Thresholds that warn, e.g. 'psnr<40,ssim<0.99' (metrics: mean, rms, max, "
                  "psnr, ssim, over); repeatable")
      ->expected(1)
      ->multi_option_policy(CLI::MultiOptionPolicy::TakeAll);
  CLI::Option* fail =
      cmd->add_option("--fail", o->fail,
                      "Thresholds that fail, e.g. 'ssim<0.95,over>0.01' (replace the default "
                      "'" + default_fail_thresholds() + "'); repeatable")
          ->expected(1)
          ->multi_option_policy(CLI::MultiOptionPolicy::TakeAll);
  cmd->add_flag("--report-only", o->report_only,
                "Print the comparison and pass whatever it shows (no default thresholds)")
      ->excludes(fail);
  check_range(cmd->add_option("--pixel-threshold", o->pixel_threshold,
                              "A pixel differs when a channel differs by more than this (0..255, "
                              "default 16)"),
              Range::closed(0, 255));
  // Its exit code 1 means "warn": a command-line error is diff_bad_arguments.
  return {cmd, [o] { return run_diff(*o); }, diff_bad_arguments};
}

}  // namespace weft::app
