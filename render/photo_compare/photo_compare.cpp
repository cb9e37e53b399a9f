// Photo comparison and its pictures; see photo_compare.h.

#include "render/photo_compare/photo_compare.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <stdexcept>
#include <string>

#include "render/canvas.h"
#include "render/image_diff.h"

namespace weft::render {

Silhouette silhouette_of(const Image& image, const std::optional<Image>& mask_image) {
  Silhouette s;
  if (mask_image) {
    if (mask_image->width() != image.width() || mask_image->height() != image.height())
      throw std::invalid_argument("the mask is " + std::to_string(mask_image->width()) + "x" +
                                  std::to_string(mask_image->height()) + " but the image is " +
                                  std::to_string(image.width()) + "x" + std::to_string(image.height()));
    s.mask = mask_from_image(*mask_image);
    s.from_mask_image = true;
    if (moments(s.mask).area_px <= 0)
      throw std::invalid_argument("empty silhouette: the mask has no white (cloth) pixel");
    return s;
  }
  Segmentation seg = segment_cloth(image);
  s.mask = std::move(seg.mask);
  s.background = seg.background;
  s.threshold = seg.threshold;
  if (moments(s.mask).area_px <= 0)
    throw std::invalid_argument("empty silhouette: no pixel stands out of the background");
  return s;
}

std::vector<std::string> segmentation_doubts(const Silhouette& silhouette, const std::string& which,
                                             std::optional<double> expected_area_px) {
  std::vector<std::string> doubts;
  if (silhouette.from_mask_image) return doubts;
  const Mask& m = silhouette.mask;
  const long border = m.border_pixels();
  const auto percent = [](double part, double whole) {
    char text[32];
    std::snprintf(text, sizeof text, "%.1f %%", 100.0 * part / whole);
    return std::string(text);
  };
  const double area = moments(m).area_px;
  const double image_area = static_cast<double>(m.width) * m.height;
  if (border > 0)
    doubts.push_back("the " + which + "'s segmented silhouette touches the image border (" +
                     std::to_string(border) + " border pixels): it may hold background, e.g. a "
                     "ground plane; give a mask (a weft render's mask_NNNN.png, --mask-" + which +
                     ")");
  if (area > 0.4 * image_area)
    doubts.push_back("the " + which + "'s segmented silhouette covers " +
                     percent(area, image_area) + " of the image: more than 40 %");
  if (expected_area_px && !(area <= 2.0 * *expected_area_px && area >= 0.5 * *expected_area_px)) {
    char text[160];
    std::snprintf(text, sizeof text, "%.0f px, %.2f times the %.0f px expected",
                  area, area / *expected_area_px, *expected_area_px);
    doubts.push_back("the " + which + "'s segmented silhouette has " + text +
                     " from the other silhouette and --transform (not within a factor 2)");
  }
  return doubts;
}

PhotoComparison compare_with_photo(const Image& photo, const Silhouette& photo_silhouette,
                                   const Image& render, const Silhouette& render_silhouette,
                                   const std::optional<Similarity>& transform, double fold_sigma_px) {
  PhotoComparison c;
  const int w = photo.width(), h = photo.height();
  c.transform_given = transform.has_value();
  c.transform = transform ? *transform : align_silhouettes(photo_silhouette.mask, render_silhouette.mask);
  c.render_aligned = warp_image(render, c.transform, w, h);
  c.photo_mask = photo_silhouette.mask;
  c.render_mask = warp_mask(render_silhouette.mask, c.transform, w, h);
  c.overlap = Mask(w, h);
  long overlap_px = 0;
  for (std::size_t i = 0; i < c.overlap.in.size(); ++i) {
    c.overlap.in[i] = c.photo_mask.in[i] && c.render_mask.in[i];
    overlap_px += c.overlap.in[i];
  }
  if (overlap_px == 0)
    throw std::invalid_argument("the aligned silhouettes do not overlap (check --transform)");
  c.iou = silhouette_iou(c.photo_mask, c.render_mask);
  c.chamfer = chamfer_distance(c.photo_mask, c.render_mask);
  const std::vector<double> yp = luminance(photo), yr = luminance(c.render_aligned);
  c.folds = fold_agreement(yp, yr, w, h, c.overlap, fold_sigma_px);
  c.ssim = overlap_ssim(yp, yr, w, h, c.overlap);
  c.mask_ssim = masked_ssim(yp, yr, w, h, c.photo_mask);
  c.delta_e = mask_colour_difference(photo, c.render_aligned, c.photo_mask);
  return c;
}

Image outline_overlay(const Image& photo, const PhotoComparison& c) {
  const int w = photo.width(), h = photo.height();
  const int thick = std::max(1, static_cast<int>(std::lround(std::hypot(w, h) / 300.0)));
  Image out = photo;
  const auto draw = [&](const Mask& m, Rgb8 colour) {
    const Mask o = outline(m);
    for (int y = 0; y < h; ++y)
      for (int x = 0; x < w; ++x) {
        if (!o.at(x, y)) continue;
        for (int dy = 0; dy < thick; ++dy)
          for (int dx = 0; dx < thick; ++dx) {
            const int px = x + dx - thick / 2, py = y + dy - thick / 2;
            if (px >= 0 && py >= 0 && px < w && py < h) out.set(px, py, colour);
          }
      }
  };
  const Rgb8 cyan{0, 220, 255}, magenta{255, 0, 200};
  draw(c.photo_mask, cyan);
  draw(c.render_mask, magenta);
  Canvas canvas(std::move(out));
  const int scale = std::max(1, std::min(w, h) / 300);
  const double size = Canvas::kTextPx * scale;
  const int lh = Canvas::text_height(size) + 2 * scale;
  if (w >= Canvas::text_width("render", size) + 8 && h >= 2 * lh + 8) {
    canvas.fill_rect(2, 2, 6 + Canvas::text_width("render", size), 4 + 2 * lh, {0, 0, 0});
    canvas.text(4, 4, "photo", cyan, size);
    canvas.text(4, 4 + lh, "render", magenta, size);
  }
  return canvas.image();
}

Image fold_label_image(const PhotoComparison& c) {
  const int w = c.photo_mask.width, h = c.photo_mask.height;
  Image out(2 * w + 4, h, {255, 255, 255});
  const auto paint = [&](const std::vector<std::int8_t>& labels, int x_offset) {
    for (int y = 0; y < h; ++y)
      for (int x = 0; x < w; ++x) {
        const std::size_t i = static_cast<std::size_t>(y) * w + x;
        Rgb8 colour{0, 0, 0};
        if (labels[i] > 0) colour = {255, 150, 30};
        else if (labels[i] < 0) colour = {40, 110, 255};
        else if (c.overlap.in[i]) colour = {60, 60, 60};
        out.set(x + x_offset, y, colour);
      }
  };
  paint(c.folds.photo_labels, 0);
  paint(c.folds.render_labels, w + 4);
  return out;
}

}  // namespace weft::render
