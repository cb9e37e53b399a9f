#pragma once
// Where a cloth hung by two corners is held, found in its mask (weft photo-scene,
// docs/photos.md "A scene from a photo"): the top-left and top-right corners of the cloth's
// silhouette.
//
// 1. The silhouette is cleaned: its largest 4-connected component, holes filled, then opened
//    (eroded, then dilated) by a square of half-side r = max(1, round(1 % of √area)) pixels,
//    which removes loose fibres, noise and thin spurs narrower than 2r + 1 (a keyed background's
//    specks are other components).
// 2. Each held corner is the extremal point of the cleaned silhouette along a direction: the
//    top-left one minimises v + k·u, the top-right one v − k·u (u right, v down, pixel
//    centres), k = 1 by default: the corners of a hanging cloth are its highest points at its
//    left and right, and 45° tolerates a top edge that sags or sides that bulge by less than they
//    drop. The corner is the mean of the pixels within ½ px of the extremum (a flat top edge at
//    45° picks one pixel; the mean keeps ties symmetric).

#include <Eigen/Core>
#include <array>

#include "render/mask.h"

namespace weft::render {

struct HeldCorners {
  std::array<Eigen::Vector2d, 2> px;  // (u, v): top-left, top-right
  Mask cleaned;                       // the silhouette they were found on
  int opening_radius_px = 0;
};

// Throws std::invalid_argument when the mask is empty or both corners fall on one pixel.
HeldCorners find_held_corners(const Mask& mask, double k = 1.0);

}  // namespace weft::render
