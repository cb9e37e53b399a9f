#pragma once
// A cloth's texture taken from a photo of it (weft photo-scene --texture, docs/photos.md
// "A texture from the photo"): the photo projected through its calibrated camera onto the
// cloth's shape at rest, into an image in material coordinates for render.texture.
//
// The cloth is a grid of nu × nv vertices (vertex (i, j) at index j·nu + i, material point
// (i·W/(nu − 1), j·H/(nv − 1)) for a W × H piece), each with its world position at rest.
// Texel (x, y) of a tw × th texture (y = 0 the top row) is the material point
// ((x + ½) W / tw, (th − y − ½) H / th): the image spans the piece once, its bottom-left corner
// at material (0, 0) and its top-right at (W, H) — render.texture with scale [W, H] (one
// repeat), or the "piece" mapping. For each texel:
//
// 1. Its world position: bilinear in the grid cell that holds it; its normal: the cell's
//    (the cross product of its diagonals), oriented as warp × weft (the front).
// 2. Its pixel (u, v) and depth Z through the camera (`project`, OpenCV pixel centres).
// 3. It is seen when Z > 0, (u, v) lies inside the image, the front faces the camera
//    (n · (eye − p) > 0), nothing of the cloth is in front of it (a depth buffer of the
//    cloth's triangles at the photo's pixel centres, Z within 0.5 % + 2 mm of the nearest), and
//    the four photo pixels around (u, v) are all inside the mask (so no background bleeds in).
//    Then its colour is the photo's, bilinear at (u, v).
// 4. Texels not seen (hidden, facing away, outside the mask or the image) take the colour of
//    the nearest seen texel, found by a breadth-first flood over 4-neighbours (city-block
//    distance; ties in the order the flood reaches them), so the texture covers the whole
//    piece without holes or background colour.

#include <Eigen/Core>
#include <functional>
#include <vector>

#include "render/image.h"
#include "render/mask.h"

namespace weft::render {

struct ClothGridShape {
  int nu = 0, nv = 0;                      // vertices along warp, weft (≥ 2 each)
  double width_m = 0.0, height_m = 0.0;    // the piece's material size W × H
  std::vector<Eigen::Vector3d> positions;  // world, nu·nv
};

// (u, v, Z): the pixel where a world point appears in the photo and its depth (Z ≤ 0 behind).
using PhotoProjection = std::function<Eigen::Vector3d(const Eigen::Vector3d&)>;

struct PhotoTexture {
  Image texture;
  Mask seen;  // texels coloured from the photo (the others filled)
  double seen_fraction = 0.0;
};

// Throws std::invalid_argument when the grid is malformed, the photo and mask differ in size,
// the texture size is not positive, or no texel is seen.
PhotoTexture project_photo_texture(const Image& photo, const Mask& mask,
                                   const ClothGridShape& cloth, const PhotoProjection& project,
                                   const Eigen::Vector3d& eye, int texture_width,
                                   int texture_height);

}  // namespace weft::render
