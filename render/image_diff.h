#pragma once
// Image comparison (weft diff): per-channel mean, RMS and largest absolute difference,
// PSNR, SSIM and the fraction of pixels that differ by more than a threshold, and a heatmap of
// where they differ. Pixel values are in 0…255 throughout.
//
// SSIM (Wang, Bovik, Sheikh & Simoncelli 2004, "Image quality assessment: from error
// visibility to structural similarity") on the luminance Y = 0.299 R + 0.587 G + 0.114 B
// (ITU-R BT.601), with the paper's 11 × 11 circular-symmetric Gaussian window of σ = 1.5
// (normalised to sum 1), K1 = 0.01, K2 = 0.03 and L = 255, averaged over every window position
// that lies wholly inside the image (the reference implementation's 'valid' filtering). An image
// smaller than the window in either direction is compared as one window of equal weights.

#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "render/image.h"

namespace weft::render {

struct ChannelDifference {
  double mean_abs = 0.0;  // mean |a − b|
  double rms = 0.0;       // sqrt(mean (a − b)²)
  int max_abs = 0;        // largest |a − b|
};

struct ImageDifference {
  int width = 0, height = 0;
  std::array<ChannelDifference, 4> channels;  // R, G, B and, when has_alpha, A
  bool has_alpha = false;  // alpha compared too (then mean, rms, max, psnr, over cover 4 channels)
  double mean_abs = 0.0;  // over every channel of every pixel
  double rms = 0.0;
  int max_abs = 0;
  double psnr_db = 0.0;   // 10 log10(255² / MSE) over all channels; +∞ when identical
  double ssim = 1.0;      // mean SSIM of the luminance; 1 when identical
  int pixel_threshold = 0;        // a pixel "differs" when some channel differs by more
  double fraction_over = 0.0;     // of the pixels, in [0, 1]
};

// The regression suite's tolerance (tests/regression/golden.h) and `weft diff`'s default: an
// image fails when its PSNR is below 50 dB or more than 0.05 % of its pixels differ by more
// than 16 in some channel.
inline constexpr double default_min_psnr_db = 50.0;
inline constexpr double default_max_over = 0.0005;
inline constexpr int default_pixel_threshold = 16;

// Throws std::invalid_argument when the sizes differ (naming both) or an image is empty.
ImageDifference compare_images(const Image& a, const Image& b, int pixel_threshold = 8);
// The same with alpha channels (one byte per pixel; empty = opaque, e.g. an RGB file): when
// either is given, alpha is a fourth channel of every metric but SSIM (luminance only).
ImageDifference compare_images(const Image& a, const Image& b, int pixel_threshold,
                               const std::vector<std::uint8_t>& alpha_a,
                               const std::vector<std::uint8_t>& alpha_b);

// Mean SSIM of two luminance images (width × height, row-major, values 0…255) as above.
double ssim(const std::vector<double>& a, const std::vector<double>& b, int width, int height);
// The SSIM of every window wholly inside the image: (width − 10) × (height − 10) values,
// row-major, value (x, y) that of the window centred on pixel (x + 5, y + 5). Throws
// std::invalid_argument when the image is smaller than the window or the sizes differ.
std::vector<double> ssim_map(const std::vector<double>& a, const std::vector<double>& b, int width,
                             int height);

// BT.601 luminance of every pixel, row-major.
std::vector<double> luminance(const Image& image);

// Where the images differ: each pixel's largest channel difference d through a colour ramp of
// sqrt(d / 255), black → blue → red → yellow → white, so small differences stay visible; a pixel
// with d ≤ pixel_threshold is drawn as b's grey value at a quarter of its brightness, so the
// picture stays recognisable. Sizes must match (std::invalid_argument).
Image difference_heatmap(const Image& a, const Image& b, int pixel_threshold = 8);

}  // namespace weft::render
