#pragma once
// How much a render looks like a photo inside the photo's cloth mask (weft compare), both on
// the photo's pixel grid (the render aligned onto it, alignment.h):
//
// - Masked SSIM: the SSIM map of the two luminances (image_diff.h's ssim_map(): Wang et al.
//   2004, BT.601 luminance, 11 × 11 Gaussian window of σ = 1.5, K1 = 0.01, K2 = 0.03, L = 255)
//   averaged over the windows that lie wholly inside the mask — the window centres of the mask
//   eroded by the window's 5-pixel radius (silhouette.h's eroded_mask) (a square erosion, so every
//   pixel a window weighs is cloth in the photo). The background never enters it, so a render on
//   another background scores the same; where the render's cloth does not cover the photo's, the
//   render's background is compared with the photo's cloth and lowers it.
// - ΔE2000: the CIEDE2000 colour difference (Sharma, Wu & Dalal 2005, kL = kC = kH = 1) of every
//   mask pixel, both images read as sRGB (IEC 61966-2-1: its transfer curve and its XYZ matrix)
//   → CIELAB with the D65 white of that matrix, (Xn, Yn, Zn) = (0.9505, 1, 1.0890), so sRGB
//   white is L* = 100, a* = b* = 0; the mean and the 95th percentile (nearest rank) over the
//   mask's pixels.

#include <array>
#include <optional>
#include <vector>

#include "render/image.h"
#include "render/photo_compare/silhouette.h"

namespace weft::render {

using Lab = std::array<double, 3>;  // L*, a*, b*

// An 8-bit sRGB colour in CIELAB (D65).
Lab srgb_to_lab(Rgb8 c);

// CIEDE2000 ΔE between two CIELAB colours (symmetric, 0 for equal colours, never NaN).
double ciede2000(const Lab& a, const Lab& b);

struct MaskedSsim {
  double mean = 0.0;
  long windows = 0;  // window centres averaged over
};
// Masked SSIM as above; none when no 11 × 11 window fits inside the mask. Throws
// std::invalid_argument when the sizes differ.
std::optional<MaskedSsim> masked_ssim(const std::vector<double>& photo_luminance,
                                      const std::vector<double>& render_luminance, int width,
                                      int height, const Mask& mask);

struct ColourDifference {
  double mean = 0.0;
  double p95 = 0.0;
  long pixels = 0;
};
// ΔE2000 over the mask's pixels as above. Throws std::invalid_argument when the sizes differ
// or the mask is empty.
ColourDifference mask_colour_difference(const Image& photo, const Image& render, const Mask& mask);

}  // namespace weft::render
