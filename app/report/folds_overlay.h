#pragma once
// The predicted wrinkle lines of a tension-field solution drawn over a photo of the real cloth,
// as seed 001's Figures 6–7 do: positive folds solid black, negative folds dashed white
// (sim/folds/fold_geometry.h's signs). The photo is placed by its two supports in pixels and,
// optionally, the row of the cloth's bottom.

#include <optional>
#include <string>

#include <Eigen/Core>

#include "render/image.h"
#include "sim/folds/fold_geometry.h"

namespace weft::app {

// Where the cloth is in the photo, pixels ((0, 0) the top-left pixel, y down).
struct OverlayPlacement {
  Eigen::Vector2d left_support_px{0.0, 0.0};   // the support at x = −l/2
  Eigen::Vector2d right_support_px{0.0, 0.0};  // the support at x = +l/2
  std::optional<double> bottom_px;  // row of the cloth's lowest point at the middle
};

// "x1,y1,x2,y2" → the two supports. Throws InputError naming --supports unless it is four
// finite comma-separated numbers.
OverlayPlacement parse_supports(const std::string& text);

// The map from the fold frame (x across, depth down, m) to photo pixels: across along the
// supports' line at |right − left| / l pixels per metre; depth perpendicular to it, downwards,
// at the same scale, or — with bottom_px — at the scale that puts the centre fibre's lowest
// point (sim::fibre_point(pattern, 0, h)) on that row.
struct OverlayMapping {
  Eigen::Vector2d origin_px;          // the midpoint between the supports
  Eigen::Vector2d across_px_per_m;    // d(pixel)/dx
  Eigen::Vector2d down_px_per_m;      // d(pixel)/d(depth)

  Eigen::Vector2d to_pixel(double x_m, double depth_m) const {
    return origin_px + x_m * across_px_per_m + depth_m * down_px_per_m;
  }
};

// Throws InputError when a support lies outside a width × height photo (naming --supports and
// the photo's size), the supports coincide, or bottom_px is outside the photo or not below the
// supports (naming --bottom).
OverlayMapping overlay_mapping(const sim::FoldPattern& pattern, const OverlayPlacement& placement,
                               int width, int height);

// Line width in pixels for a photo: about 1/300 of its larger side, at least 2.
int overlay_line_width(const render::Image& photo);

// The photo with wrinkle lines 0 … n drawn on it (a pattern without wrinkles draws nothing).
render::Image draw_fold_overlay(render::Image photo, const sim::FoldPattern& pattern,
                                const OverlayMapping& mapping);

}  // namespace weft::app
