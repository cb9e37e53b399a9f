#pragma once
// How well an aligned render matches a photo. All on the photo's pixel grid,
// after the render and its silhouette were resampled onto it (alignment.h).
//
// - Silhouette IoU: |P ∩ R| / |P ∪ R| of the two masks.
// - Chamfer distance between the outlines (silhouette.h's outline()): the mean, over one
//   outline's pixels, of the Euclidean distance to the nearest pixel of the other, in both
//   directions; the symmetric distance is the mean of the two, also given in % of the image
//   diagonal.
// - Fold-line agreement: the luminance, smoothed by a Gaussian of σ pixels, has the Hessian
//   H = [Ixx Ixy; Ixy Iyy] (central differences); its eigenvalue λ of largest magnitude says
//   ridge (λ < 0: a bright crest across the fold) or valley (λ > 0: a dark trough). A pixel is
//   labelled ridge/valley when |λ| is at least the median |λ| of the compared region (and above
//   1e-3 grey levels per px², so flat areas stay unlabelled); the others are unlabelled.
//   The region is the overlap P ∩ R less a band of ceil(3σ) pixels along its edge and the image
//   edge, where the cloth/background edge would dominate the Hessian. Precision: the fraction
//   of the render's labelled pixels where the photo has the same label; recall: the fraction
//   of the photo's labelled pixels where the render has the same label; F = 2PR / (P + R)
//   (1 when neither image has a labelled pixel, 0 when only one has). Labels depend only on the
//   sign and relative size of λ, so a brightness change or colour cast leaves them unchanged.
// - SSIM inside the overlap: image_diff.h's ssim() of the two luminances on the bounding box of
//   P ∩ R, with the render's pixels outside the overlap set equal to the photo's.

#include <cstdint>
#include <vector>

#include "render/image.h"
#include "render/photo_compare/silhouette.h"

namespace weft::render {

double silhouette_iou(const Mask& a, const Mask& b);

struct ChamferDistance {
  double a_to_b_px = 0.0, b_to_a_px = 0.0;
  double symmetric_px = 0.0;          // (a_to_b + b_to_a) / 2
  double percent_of_diagonal = 0.0;   // 100 · symmetric / sqrt(w² + h²)
};
// Throws std::invalid_argument when a mask is empty or the sizes differ.
ChamferDistance chamfer_distance(const Mask& a, const Mask& b);

// Euclidean distance of every pixel to the nearest pixel set in `features` (+∞ when none),
// exact (Felzenszwalb & Huttenlocher 2012, separable squared-distance transform).
std::vector<double> distance_transform(const Mask& features);

// Fold labels: +1 ridge, −1 valley, 0 unlabelled (outside `region` too).
std::vector<std::int8_t> fold_labels(const std::vector<double>& luminance, int width, int height,
                                     double sigma_px, const Mask& region);

struct FoldAgreement {
  double precision = 0.0, recall = 0.0, f_score = 0.0;
  double sigma_px = 0.0;
  long compared_px = 0;  // pixels of the region
  std::vector<std::int8_t> photo_labels, render_labels;
};
// σ ≤ 0 picks the default: 1 % of the image diagonal, at least 1.5 px.
FoldAgreement fold_agreement(const std::vector<double>& photo_luminance,
                             const std::vector<double>& render_luminance, int width, int height,
                             const Mask& overlap, double sigma_px = 0.0);

// SSIM inside the overlap as above; throws std::invalid_argument on an empty overlap.
double overlap_ssim(const std::vector<double>& photo_luminance,
                    const std::vector<double>& render_luminance, int width, int height,
                    const Mask& overlap);

}  // namespace weft::render
