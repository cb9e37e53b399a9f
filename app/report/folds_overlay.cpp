// Predicted wrinkle lines over a photo (folds_overlay.h).

#include "app/report/folds_overlay.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <sstream>
#include <vector>

#include "app/io/input_error.h"
#include "render/canvas.h"

namespace weft::app {

namespace {

std::string pixel_text(const Eigen::Vector2d& p) {
  char text[64];
  std::snprintf(text, sizeof text, "(%g, %g)", p.x(), p.y());
  return text;
}

bool inside(const Eigen::Vector2d& p, int width, int height) {
  return p.x() >= 0.0 && p.y() >= 0.0 && p.x() <= width - 1 && p.y() <= height - 1;
}

}  // namespace

OverlayPlacement parse_supports(const std::string& text) {
  std::vector<double> values;
  std::stringstream in(text);
  for (std::string item; std::getline(in, item, ',');) {
    std::size_t used = 0;
    double v = 0.0;
    try {
      v = std::stod(item, &used);
    } catch (const std::exception&) {
      used = 0;
    }
    while (used < item.size() && std::isspace(static_cast<unsigned char>(item[used]))) ++used;
    if (used == 0 || used != item.size() || !std::isfinite(v))
      throw InputError("--supports: expected four numbers x1,y1,x2,y2 (pixels), got '" + text +
                       "' ('" + item + "' is not a number)");
    values.push_back(v);
  }
  if (values.size() != 4)
    throw InputError("--supports: expected four numbers x1,y1,x2,y2 (pixels), got '" + text + "'");
  OverlayPlacement p;
  p.left_support_px = {values[0], values[1]};
  p.right_support_px = {values[2], values[3]};
  return p;
}

OverlayMapping overlay_mapping(const sim::FoldPattern& pattern, const OverlayPlacement& placement,
                               int width, int height) {
  const std::string size = std::to_string(width) + "x" + std::to_string(height);
  for (const Eigen::Vector2d& s : {placement.left_support_px, placement.right_support_px})
    if (!inside(s, width, height))
      throw InputError("--supports: the support " + pixel_text(s) + " lies outside the " + size +
                       " photo");
  const Eigen::Vector2d span_px = placement.right_support_px - placement.left_support_px;
  if (!(span_px.norm() >= 1.0))
    throw InputError("--supports: the two supports " + pixel_text(placement.left_support_px) +
                     " and " + pixel_text(placement.right_support_px) +
                     " must be at least a pixel apart");
  OverlayMapping m;
  m.origin_px = 0.5 * (placement.left_support_px + placement.right_support_px);
  m.across_px_per_m = span_px / pattern.span_m;
  const Eigen::Vector2d down(-span_px.y(), span_px.x());  // the across direction turned 90°, y down
  m.down_px_per_m = down / pattern.span_m;
  if (placement.bottom_px) {
    const double bottom = *placement.bottom_px;
    const double depth_m = sim::fibre_point(pattern, 0.0, pattern.height_m).depth_m;
    const double rise = bottom - m.origin_px.y();  // rows from the supports' midpoint
    if (!(std::isfinite(bottom) && bottom >= 0.0 && bottom <= height - 1) || !(rise > 0.0) ||
        !(down.y() > 0.0))
      throw InputError("--bottom: expected a row of the " + size +
                       " photo below the supports' midpoint (y = " +
                       std::to_string(m.origin_px.y()) + "), got " + std::to_string(bottom));
    m.down_px_per_m = down * (rise / (down.y() * depth_m));
  }
  return m;
}

int overlay_line_width(const render::Image& photo) {
  return std::max(2, static_cast<int>(std::lround(std::max(photo.width(), photo.height()) / 300.0)));
}

render::Image draw_fold_overlay(render::Image photo, const sim::FoldPattern& pattern,
                                const OverlayMapping& mapping) {
  const int width = overlay_line_width(photo);
  render::Canvas canvas(std::move(photo));
  const render::Rgb8 black{0, 0, 0}, white{255, 255, 255};
  const double dash = 4.0 * width, gap = 3.0 * width;
  for (const sim::FoldLine& line : sim::fold_lines(pattern)) {
    double phase = 0.0;
    for (std::size_t k = 1; k < line.points.size(); ++k) {
      const Eigen::Vector2d a = mapping.to_pixel(line.points[k - 1].x(), line.points[k - 1].y());
      const Eigen::Vector2d b = mapping.to_pixel(line.points[k].x(), line.points[k].y());
      if (line.sign > 0)
        canvas.line(a.x(), a.y(), b.x(), b.y(), black, width);
      else
        phase = canvas.dashed_line(a.x(), a.y(), b.x(), b.y(), white, width, dash, gap, phase);
    }
  }
  return canvas.image();
}

}  // namespace weft::app
