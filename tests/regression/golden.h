#pragma once
// Golden-image regression tests: key scenes rendered small by both renderers
// and compared with the PNGs in tests/data/golden through render/image_diff.h, with explicit
// thresholds per case. A failure writes the evidence — actual.png, expected.png, diff.png and
// index.html (side by side; click an image to swap actual and expected) — under
// BUILD/regression/<case>/ and names that page in the message. WEFT_REGRESSION_UPDATE=1 (the
// `regress-update` build target) writes the goldens instead of comparing.

#include <gtest/gtest.h>

#include <filesystem>
#include <string>
#include <utility>
#include <vector>

#include "render/image.h"
#include "render/image_diff.h"

namespace weft::test {

struct GoldenCase {
  std::string name;         // also the golden's file stem
  std::string scene;        // file in assets/scenes
  int resolution = 17;      // vertices per side of the coarse grid
  int frames = 12;          // frames of the scene's stream (0: the initial state)
  std::string renderer;     // "raster" or "raytrace"
  int width = 160, height = 120;
  int samples = 4;          // ray tracer samples per pixel
  // Fail when PSNR falls below this (dB) or more than max_over of the pixels differ by more
  // than pixel_threshold. The frames are deterministic, so an unchanged build gives the same
  // bytes (PSNR ∞); the margins allow for a different CPU's rounding in llvmpipe, and a cloth
  // 10 % heavier crosses them (regression_test.cpp).
  // --set KEY=VALUE overrides of the scene file (a mesh scene has no grid to make coarse).
  std::vector<std::pair<std::string, std::string>> settings{};
  double min_psnr_db = render::default_min_psnr_db;
  double max_over = render::default_max_over;
  int pixel_threshold = render::default_pixel_threshold;
};

// Simulates the case's scene on its coarse grid (cloth density × density_scale; with
// `settings`, the scene file with those overrides instead) through the frame stream of weft run
// (app/run/frame_stream.h) and renders its last frame; `remeshes`, when given, gets the number of
// times the cloth was remeshed. Throws what the scene or renderer throws.
render::Image render_case(const GoldenCase& c, double density_scale = 1.0,
                          long* remeshes = nullptr);

std::filesystem::path golden_path(const GoldenCase& c);

// Compares `actual` with the case's golden (or writes it, in update mode); on failure writes
// the evidence and says where. `evidence_folder` (default: the case's name) must differ for a
// test that compares a deliberately different image with the same golden: it must not clear
// the folder of the case's own test, which ctest may run at the same time.
::testing::AssertionResult matches_golden(const GoldenCase& c, const render::Image& actual,
                                          const std::string& evidence_folder = "");

// The evidence page of a case: BUILD/regression/<name>/index.html.
std::filesystem::path evidence_page(const GoldenCase& c, const std::string& evidence_folder = "");

}  // namespace weft::test
