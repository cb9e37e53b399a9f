// Canvas: rectangles, lines, circles and text drawn straight into an Image. The hard-edged
// shapes use integer or round-half-up arithmetic only where it decides a pixel; the smooth ones
// and text blend by coverage. Either way the same calls give the same bits on every machine.
//
// Coordinates are pixel coordinates: (x, y) with integer values at pixel centres, x to the
// right, y down, (0, 0) the top-left pixel.

#include "render/canvas.h"

#include "render/font.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <utility>

namespace weft::render {

namespace {

// Nearest pixel index of a coordinate (halves round up), clamped far outside any canvas so the
// conversion to int is defined.
int nearest_pixel(double v) {
  constexpr double kFar = 1 << 24;
  return static_cast<int>(std::floor(std::clamp(v, -kFar, kFar) + 0.5));
}

// Liang–Barsky clipping of the segment p0→p1 to [lo_x, hi_x] × [lo_y, hi_y]; false when
// nothing of it is inside. On success p0 and p1 are moved to the clipped end points.
bool clip_segment(double& x0, double& y0, double& x1, double& y1, double lo_x, double lo_y,
                  double hi_x, double hi_y) {
  double t0 = 0.0, t1 = 1.0;
  const double dx = x1 - x0, dy = y1 - y0;
  // Each (p, q) pair: the segment is inside while p·t ≤ q.
  const std::array<std::array<double, 2>, 4> edges = {{
      {-dx, x0 - lo_x}, {dx, hi_x - x0}, {-dy, y0 - lo_y}, {dy, hi_y - y0}}};
  for (const auto& [p, q] : edges) {
    if (p == 0.0) {
      if (q < 0.0) return false;  // parallel to this edge and outside it
      continue;
    }
    const double t = q / p;
    if (p < 0.0) {
      t0 = std::max(t0, t);
    } else {
      t1 = std::min(t1, t);
    }
    if (t0 > t1) return false;
  }
  const double sx = x0, sy = y0;
  x0 = sx + t0 * dx;
  y0 = sy + t0 * dy;
  x1 = sx + t1 * dx;
  y1 = sy + t1 * dy;
  return true;
}

}  // namespace

Canvas::Canvas(int width, int height, Rgb8 background) : m_image(width, height, background) {}

Canvas::Canvas(Image image) : m_image(std::move(image)) {}

void Canvas::fill_rect(int x0, int y0, int x1, int y1, Rgb8 colour) {
  x0 = std::max(x0, 0);
  y0 = std::max(y0, 0);
  x1 = std::min(x1, width());
  y1 = std::min(y1, height());
  for (int y = y0; y < y1; ++y) {
    for (int x = x0; x < x1; ++x) m_image.set(x, y, colour);
  }
}

void Canvas::rect(int x0, int y0, int x1, int y1, Rgb8 colour) {
  if (x1 <= x0 || y1 <= y0) return;
  fill_rect(x0, y0, x1, y0 + 1, colour);
  fill_rect(x0, y1 - 1, x1, y1, colour);
  fill_rect(x0, y0, x0 + 1, y1, colour);
  fill_rect(x1 - 1, y0, x1, y1, colour);
}

void Canvas::line(double x0, double y0, double x1, double y1, Rgb8 colour, int thickness) {
  if (!(std::isfinite(x0) && std::isfinite(y0) && std::isfinite(x1) && std::isfinite(y1))) return;
  thickness = std::max(thickness, 1);
  // Each point of the line stamps a thickness × thickness square of pixels starting `before`
  // pixels up and left of it; clip to the canvas grown by that square so that the stamps
  // reaching in from outside are kept.
  const int before = (thickness - 1) / 2;
  const int after = thickness - 1 - before;
  const double margin = std::max(before, after) + 1.0;
  if (!clip_segment(x0, y0, x1, y1, -margin, -margin, width() - 1 + margin,
                    height() - 1 + margin)) {
    return;
  }
  // DDA: one point per pixel along the longer axis.
  const double dx = x1 - x0, dy = y1 - y0;
  const int steps = static_cast<int>(std::ceil(std::max(std::abs(dx), std::abs(dy))));
  for (int i = 0; i <= steps; ++i) {
    const double t = steps == 0 ? 0.0 : static_cast<double>(i) / steps;
    const int px = nearest_pixel(x0 + t * dx);
    const int py = nearest_pixel(y0 + t * dy);
    fill_rect(px - before, py - before, px + after + 1, py + after + 1, colour);
  }
}

double Canvas::dashed_line(double x0, double y0, double x1, double y1, Rgb8 colour,
                           int thickness, double dash, double gap, double phase) {
  const double period = dash + gap;
  const double length = std::hypot(x1 - x0, y1 - y0);
  if (!(std::isfinite(length) && dash > 0.0 && gap >= 0.0 && std::isfinite(period))) return phase;
  phase = std::fmod(std::max(phase, 0.0), period);
  const auto at = [&](double s) {
    const double t = length > 0.0 ? s / length : 0.0;
    return std::pair{x0 + t * (x1 - x0), y0 + t * (y1 - y0)};
  };
  double s = 0.0;
  while (s < length) {
    const bool on = phase < dash;
    const double step = std::min(length - s, on ? dash - phase : period - phase);
    if (on) {
      // The last pixel of a dash is its start plus dash − 1 pixels: `dash` pixels in all.
      const auto [ax, ay] = at(s);
      const auto [bx, by] = at(s + std::max(step - 1.0, 0.0));
      line(ax, ay, bx, by, colour, thickness);
    }
    s += step;
    phase = std::fmod(phase + step, period);
  }
  return phase;
}

void Canvas::circle(double cx, double cy, double r, Rgb8 colour, bool filled) {
  if (!(std::isfinite(cx) && std::isfinite(cy) && std::isfinite(r)) || r < 0.0) return;
  // Pixels whose centre lies in the disc (filled) or within half a pixel of the circle.
  const double reach = filled ? r : r + 0.5;
  const int x_lo = std::max(0, nearest_pixel(cx - reach) - 1);
  const int x_hi = std::min(width() - 1, nearest_pixel(cx + reach) + 1);
  const int y_lo = std::max(0, nearest_pixel(cy - reach) - 1);
  const int y_hi = std::min(height() - 1, nearest_pixel(cy + reach) + 1);
  for (int y = y_lo; y <= y_hi; ++y) {
    for (int x = x_lo; x <= x_hi; ++x) {
      const double d = std::hypot(x - cx, y - cy);
      if (filled ? d <= r : std::abs(d - r) <= 0.5) m_image.set(x, y, colour);
    }
  }
}

void Canvas::blend(int x, int y, Rgb8 colour, double alpha) {
  if (x < 0 || y < 0 || x >= width() || y >= height() || !(alpha > 0.0)) return;
  alpha = std::min(alpha, 1.0);
  const Rgb8 under = m_image.at(x, y);
  const auto mix = [alpha](std::uint8_t a, std::uint8_t b) {
    return static_cast<std::uint8_t>(std::lround(a + alpha * (b - a)));
  };
  m_image.set(x, y, {mix(under.r, colour.r), mix(under.g, colour.g), mix(under.b, colour.b)});
}

void Canvas::smooth_line(double x0, double y0, double x1, double y1, Rgb8 colour, double width) {
  if (!(std::isfinite(x0) && std::isfinite(y0) && std::isfinite(x1) && std::isfinite(y1))) return;
  // Coverage of each pixel centre by the capsule of half-width w/2 around the segment, with a
  // one-pixel ramp at its edge.
  const double half = 0.5 * std::max(width, 0.0), reach = half + 1.0;
  const double dx = x1 - x0, dy = y1 - y0, length2 = dx * dx + dy * dy;
  const int xa = std::max(0, nearest_pixel(std::min(x0, x1) - reach));
  const int xb = std::min(this->width() - 1, nearest_pixel(std::max(x0, x1) + reach));
  const int ya = std::max(0, nearest_pixel(std::min(y0, y1) - reach));
  const int yb = std::min(height() - 1, nearest_pixel(std::max(y0, y1) + reach));
  for (int y = ya; y <= yb; ++y) {
    for (int x = xa; x <= xb; ++x) {
      const double t = length2 > 0.0 ? std::clamp(((x - x0) * dx + (y - y0) * dy) / length2, 0.0, 1.0) : 0.0;
      const double d = std::hypot(x - (x0 + t * dx), y - (y0 + t * dy));
      blend(x, y, colour, std::clamp(half + 0.5 - d, 0.0, 1.0));
    }
  }
}

void Canvas::smooth_circle(double cx, double cy, double r, Rgb8 colour, bool filled,
                           double width) {
  if (!(std::isfinite(cx) && std::isfinite(cy) && std::isfinite(r)) || r < 0.0) return;
  const double half = 0.5 * std::max(width, 0.0), reach = r + half + 1.0;
  const int xa = std::max(0, nearest_pixel(cx - reach)), xb = std::min(this->width() - 1, nearest_pixel(cx + reach));
  const int ya = std::max(0, nearest_pixel(cy - reach)), yb = std::min(height() - 1, nearest_pixel(cy + reach));
  for (int y = ya; y <= yb; ++y) {
    for (int x = xa; x <= xb; ++x) {
      const double d = std::hypot(x - cx, y - cy);
      const double cover = filled ? r + 0.5 - d : half + 0.5 - std::abs(d - r);
      blend(x, y, colour, std::clamp(cover, 0.0, 1.0));
    }
  }
}

void Canvas::text(double x, double y, const std::string& s, Rgb8 colour, double size_px) {
  const Font& font = Font::chart_font();
  const double pen_x = x, baseline = y + font.ascent(size_px);
  const TextBitmap bitmap = font.rasterize(s, size_px, pen_x - std::floor(pen_x));
  const int left = static_cast<int>(std::floor(pen_x)) - bitmap.origin_x;
  const int top = nearest_pixel(baseline) - bitmap.baseline;
  for (int by = 0; by < bitmap.height; ++by)
    for (int bx = 0; bx < bitmap.width; ++bx)
      if (const std::uint8_t c = bitmap.at(bx, by)) blend(left + bx, top + by, colour, c / 255.0);
}

void Canvas::text_vertical(double x, double y, const std::string& s, Rgb8 colour,
                           double size_px) {
  // Rotating 90° counter-clockwise sends the text's rightward pen upward and its downward rows
  // rightward: bitmap pixel (bx, by) lands at (x + by', y − bx'), with (x, y) the bottom-left
  // corner of the text's box (its top-left before the rotation).
  const Font& font = Font::chart_font();
  const TextBitmap bitmap = font.rasterize(s, size_px);
  const int box_top = bitmap.baseline - nearest_pixel(font.ascent(size_px));
  const int x0 = nearest_pixel(x), y0 = nearest_pixel(y);
  for (int by = 0; by < bitmap.height; ++by)
    for (int bx = 0; bx < bitmap.width; ++bx)
      if (const std::uint8_t c = bitmap.at(bx, by))
        blend(x0 + (by - box_top), y0 - (bx - bitmap.origin_x), colour, c / 255.0);
}

int Canvas::text_width(const std::string& s, double size_px) {
  return static_cast<int>(std::ceil(Font::chart_font().width(s, size_px)));
}

int Canvas::text_height(double size_px) { return static_cast<int>(std::ceil(size_px)); }

}  // namespace weft::render
