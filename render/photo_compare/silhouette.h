#pragma once
// The cloth's silhouette in a photo or a render: a binary mask, found by
// segmenting the cloth from the background, or read from a mask image that overrides it.
//
// Segmentation (segment_cloth):
//  1. Background colour: the per-channel median of the pixels in a border band of
//     max(1, round(1 % of the shorter side)) pixels.
//  2. Each pixel's distance to it in a chroma-weighted space: BT.601 Y, Cb, Cr (0…255 scale),
//     d = sqrt(ΔCb² + ΔCr² + (luma_weight · ΔY)²), luma_weight = 0.25 by default, so that
//     shading and shadows on the background count less than a change of colour.
//  3. Threshold by Otsu (1979) on the 256-bin histogram of d over [0, max d]: pixels with d above
//     the threshold are cloth.
//  4. Keep the largest 4-connected component, then fill its holes (background pixels not
//     4-connected to the image border).
// Throws std::invalid_argument when nothing stands out of the background (a uniform image).

#include <cstdint>
#include <vector>

#include "render/image.h"
#include "render/mask.h"

namespace weft::render {

struct SegmentationSettings {
  double luma_weight = 0.25;  // weight of ΔY against the chroma differences
};

struct Segmentation {
  Mask mask;
  Rgb8 background;          // the border median
  double threshold = 0.0;   // Otsu's threshold on d
};

Segmentation segment_cloth(const Image& image, const SegmentationSettings& settings = {});

// A mask image: white (luminance ≥ 128) is cloth, taken as it is (no component filtering).
Mask mask_from_image(const Image& image);

// The largest 4-connected component of `mask` (the first in row order on a tie).
Mask largest_component(const Mask& mask);
// Background pixels not 4-connected to the image border become cloth.
Mask fill_holes(const Mask& mask);
// Cloth pixels with a 4-neighbour outside the cloth (or outside the image).
Mask outline(const Mask& mask);
// Square morphology with a (2 radius + 1)² window: eroded keeps the pixels whose whole window
// lies inside the mask and the image (so pixels within `radius` of the image edge never stay),
// dilated sets the pixels whose window (clipped to the image) holds a mask pixel.
Mask eroded_mask(const Mask& mask, int radius);
Mask dilated_mask(const Mask& mask, int radius);

struct SilhouetteMoments {
  double area_px = 0.0;          // number of cloth pixels
  double cx = 0.0, cy = 0.0;     // centroid of the pixel centres, pixels ((0, 0) = top-left centre)
};
SilhouetteMoments moments(const Mask& mask);

}  // namespace weft::render
