#pragma once
// `weft compare PHOTO RENDER`: segments the cloth in a photo and a render (or
// takes mask images), aligns the render onto the photo, prints silhouette IoU, the Chamfer
// distance between the outlines, fold-line agreement and SSIM inside the overlap
// (render/photo_compare/), and writes DIR/overlay.png, DIR/folds.png, DIR/render_aligned.png,
// DIR/photo.png and DIR/report.html (relative links). Exit codes as the other commands: 0 ok,
// 1 bad input (missing or unreadable file, empty silhouette, bad --transform), 2 failure.

#include <filesystem>
#include <optional>
#include <string>

#include "app/cli/command.h"
#include "render/photo_compare/alignment.h"

namespace weft::app {

struct CompareOptions {
  std::filesystem::path photo, render;
  // white = cloth; when absent, a weft frame_NNNN.png's mask_NNNN.png beside it (weft run
  // --mask) is used unless `segment`. Segmented silhouettes that look doubtful (touching the
  // border, over 40 % of the image, or, with a transform, not within a factor 2 of the other's
  // area) are warned about on stderr and in the JSON ("warnings") and the report.
  std::optional<std::filesystem::path> mask_photo, mask_render;
  bool segment = false;
  std::optional<std::string> transform;   // "s,tx,ty[,deg]": render px → photo px
  std::filesystem::path out = "out/compare";
  bool json = false;
  double fold_sigma_px = 0.0;             // ≤ 0: the default (render/photo_compare/metrics.h)
};

// "s,tx,ty[,deg]" → p = s R(deg) r + (tx, ty). Throws std::invalid_argument naming --transform
// and what was expected.
render::Similarity parse_transform(const std::string& text);

// Returns an ExitCode (app/io/exit_code.h); errors go to stderr naming the file.
int run_compare(const CompareOptions& options);


// Adds `weft compare` to the command line.
Command register_compare(CLI::App& app, const std::string& command_line);

}  // namespace weft::app
