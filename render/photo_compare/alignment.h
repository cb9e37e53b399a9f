#pragma once
// Aligning a render to a photo: a similarity transform from render pixels to
// photo pixels, estimated from the two silhouettes or given, and the resampling of the render
// (and its mask) onto the photo's pixel grid through it.
//
// Pixel coordinates put pixel (x, y)'s centre at (x, y), (0, 0) the top-left pixel, y down.
// The transform maps a render point r to the photo point p = s · R(θ) · r + t, with R(θ) the
// rotation by θ (positive turns +x towards +y, i.e. clockwise on screen).
//
// Estimated alignment (no rotation): s = sqrt(A_photo / A_render) from the silhouette areas,
// t = c_photo − s · c_render from their centroids.
//
// Resampling: each photo pixel averages n × n bilinear samples of the render, n = ceil(1 / s)
// (n = 1 when the render is enlarged), so a render larger than the photo is box-filtered rather
// than aliased; samples outside the render take the nearest edge pixel (the image) or count as
// background (the mask, cloth where the averaged coverage is ≥ 1/2).

#include "render/image.h"
#include "render/photo_compare/silhouette.h"

namespace weft::render {

struct Similarity {
  double scale = 1.0;
  double tx_px = 0.0, ty_px = 0.0;
  double angle_rad = 0.0;
};

// Throws std::invalid_argument when either silhouette is empty.
Similarity align_silhouettes(const Mask& photo, const Mask& render);

// The render seen on a width × height photo grid through `t`.
Image warp_image(const Image& render, const Similarity& t, int width, int height);
Mask warp_mask(const Mask& render, const Similarity& t, int width, int height);

}  // namespace weft::render
