#pragma once
// Comparing a render with a photo of real cloth (weft compare): the two silhouettes
// (silhouette.h), the alignment of the render onto the photo (alignment.h), and the metrics
// (metrics.h), plus the pictures `weft compare` writes: the outlines over the photo and the
// ridge/valley maps.

#include <optional>
#include <string>
#include <vector>

#include "render/image.h"
#include "render/photo_compare/alignment.h"
#include "render/photo_compare/appearance.h"
#include "render/photo_compare/metrics.h"
#include "render/photo_compare/silhouette.h"

namespace weft::render {

struct Silhouette {
  Mask mask;
  bool from_mask_image = false;
  Rgb8 background;          // segmentation only
  double threshold = 0.0;   // segmentation only
};

// The given mask (its size must match the image's), else segment_cloth(). Throws
// std::invalid_argument on a size mismatch or an empty silhouette, the message saying which.
Silhouette silhouette_of(const Image& image, const std::optional<Image>& mask_image);

// Why a segmented silhouette (not one from a mask) is doubtful, one sentence each; empty when
// none applies or it came from a mask:
// - it touches the image border (segmentation takes a background that differs from the border
//   median — a ground plane, a vignette — for cloth, and such a region runs into the border);
// - it covers more than 40 % of the image;
// - expected_area_px is given and the area is not within a factor 2 of it.
// `which` names the image in the sentences ("render").
std::vector<std::string> segmentation_doubts(const Silhouette& silhouette, const std::string& which,
                                             std::optional<double> expected_area_px = std::nullopt);

struct PhotoComparison {
  Similarity transform;     // render pixels → photo pixels
  bool transform_given = false;
  double iou = 0.0;
  ChamferDistance chamfer;
  FoldAgreement folds;
  double ssim = 0.0;        // inside the overlap (metrics.h's overlap_ssim)
  // Inside the photo's mask (appearance.h): none when no SSIM window fits inside it.
  std::optional<MaskedSsim> mask_ssim;
  ColourDifference delta_e;  // ΔE2000 over the photo's mask
  // On the photo's grid:
  Image render_aligned;
  Mask photo_mask, render_mask, overlap;
};

// Aligns (with `transform` if given, else from the silhouettes) and measures. Throws
// std::invalid_argument when the aligned silhouettes do not overlap.
PhotoComparison compare_with_photo(const Image& photo, const Silhouette& photo_silhouette,
                                   const Image& render, const Silhouette& render_silhouette,
                                   const std::optional<Similarity>& transform = std::nullopt,
                                   double fold_sigma_px = 0.0);

// The photo with the photo silhouette's outline (cyan) and the aligned render's (magenta),
// max(1, diagonal / 300) pixels thick, and a legend.
Image outline_overlay(const Image& photo, const PhotoComparison& c);
// The ridge (orange) / valley (blue) labels of the photo (left) and the render (right); the
// compared region is dark grey, the rest black.
Image fold_label_image(const PhotoComparison& c);

}  // namespace weft::render
