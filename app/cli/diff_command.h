#pragma once
// `weft diff A B`: compares two images (render/image_diff.h) — per-channel mean, RMS and largest
// difference, PSNR, SSIM, the fraction of pixels over a threshold — against explicit warn and
// fail thresholds — by default the regression suite's (render::default_min_psnr_db, …) — and can
// write a heatmap of the differences. Exit codes: 0 pass, 1 warn,
// 2 fail, 3 size mismatch, 4 unreadable file, 5 bad arguments.

#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "app/cli/command.h"
#include "render/image_diff.h"

namespace weft::app {

enum DiffExit : int {
  diff_pass = 0,
  diff_warn = 1,
  diff_fail = 2,
  diff_size_mismatch = 3,
  diff_unreadable = 4,
  diff_bad_arguments = 5,
};

// One threshold: "METRIC<VALUE" or "METRIC>VALUE" — crossed when the metric is below, resp.
// above, the value. Metrics: mean, rms, max (0…255, all channels), psnr (dB), ssim, over (the
// fraction of pixels over the pixel threshold, 0…1).
struct DiffThreshold {
  std::string metric;
  bool below = true;  // '<'
  double value = 0.0;
  std::string text;   // as given
};

// Parses a comma-separated list of thresholds; throws std::invalid_argument naming `flag`
// and the bad item.
std::vector<DiffThreshold> parse_thresholds(const std::string& list, const std::string& flag);

// The metric's value for a comparison. Throws std::invalid_argument for an unknown name.
double metric_value(const render::ImageDifference& d, const std::string& metric);

struct DiffVerdict {
  DiffExit exit = diff_pass;
  std::vector<std::string> crossed;  // "psnr 38.2 < 40 (fail)", …
};

DiffVerdict judge(const render::ImageDifference& d, const std::vector<DiffThreshold>& warn,
                  const std::vector<DiffThreshold>& fail);

struct DiffOptions {
  std::filesystem::path a, b;
  std::optional<std::filesystem::path> heatmap;  // --heatmap D.png
  bool json = false;
  std::vector<std::string> warn, fail;  // threshold lists (--warn, --fail; repeatable)
  bool report_only = false;  // --report-only: no default fail thresholds, always pass
  int pixel_threshold = render::default_pixel_threshold;  // --pixel-threshold
};

// The fail thresholds without --fail: PSNR below 50 dB, over 0.05 % of pixels over the threshold.
std::string default_fail_thresholds();

// Prints the comparison (text or one JSON object on stdout), writes the heatmap if asked, and
// returns the exit code above; errors go to stderr.
int run_diff(const DiffOptions& options);


// Adds `weft diff` to the command line.
Command register_diff(CLI::App& app, const std::string& command_line);

}  // namespace weft::app
