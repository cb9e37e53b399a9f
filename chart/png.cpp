// DrawList → Image through render::Canvas. Canvas puts integer coordinates at pixel centres,
// the draw list at pixel corners (SVG): smooth shapes shift by half a pixel, crisp lines and
// rectangles cover the pixels their edges enclose, text is placed by its box.

#include <algorithm>
#include <cmath>

#include "chart/draw_list.h"
#include "render/canvas.h"
#include "render/font.h"

namespace weft::chart {

namespace {

using render::Canvas;

int edge(double v) { return static_cast<int>(std::lround(v)); }

void draw(Canvas& c, const RectItem& r) {
  if (r.filled) {
    c.fill_rect(edge(r.x0), edge(r.y0), edge(r.x1), edge(r.y1), r.colour);
  } else {
    c.rect(edge(r.x0), edge(r.y0), edge(r.x1), edge(r.y1), r.colour);
  }
}

// Dashes of 6 × width on and 4 × width off along the polyline, one pattern across its joints.
void dashed(Canvas& c, const LineItem& l) {
  const double on = 6.0 * l.width, period = 10.0 * l.width;
  double phase = 0.0;
  for (std::size_t k = 1; k < l.points.size(); ++k) {
    const Point a = l.points[k - 1], b = l.points[k];
    const double length = std::hypot(b.x - a.x, b.y - a.y);
    for (double s = 0.0; s < length;) {
      const double p = std::fmod(phase + s, period);
      const double step = std::min(length - s, p < on ? on - p : period - p);
      if (p < on) {
        const double t0 = s / length, t1 = (s + step) / length;
        c.smooth_line(a.x + t0 * (b.x - a.x) - 0.5, a.y + t0 * (b.y - a.y) - 0.5,
                      a.x + t1 * (b.x - a.x) - 0.5, a.y + t1 * (b.y - a.y) - 0.5, l.colour, l.width);
      }
      s += step;
    }
    phase = std::fmod(phase + length, period);
  }
}

void draw(Canvas& c, const LineItem& l) {
  if (l.crisp && l.points.size() == 2) {  // axis-aligned: the pixels between the edges
    const Point a = l.points[0], b = l.points[1];
    const int x0 = static_cast<int>(std::floor(std::min(a.x, b.x)));
    const int y0 = static_cast<int>(std::floor(std::min(a.y, b.y)));
    if (a.x == b.x) c.fill_rect(x0, edge(std::min(a.y, b.y)), x0 + 1, edge(std::max(a.y, b.y)), l.colour);
    else c.fill_rect(edge(std::min(a.x, b.x)), y0, edge(std::max(a.x, b.x)), y0 + 1, l.colour);
    return;
  }
  if (l.dashed) return dashed(c, l);
  for (std::size_t k = 1; k < l.points.size(); ++k)
    c.smooth_line(l.points[k - 1].x - 0.5, l.points[k - 1].y - 0.5, l.points[k].x - 0.5,
                  l.points[k].y - 0.5, l.colour, l.width);
}

void draw(Canvas& c, const CircleItem& o) {
  c.smooth_circle(o.cx - 0.5, o.cy - 0.5, o.r, o.colour, o.filled, 1.5);
}

void draw(Canvas& c, const TextItem& t) {
  if (t.text.empty()) return;
  const render::Font& font = render::Font::chart_font();
  const double w = font.width(t.text, t.size_px);
  const double shift = t.anchor == Anchor::start ? 0.0 : t.anchor == Anchor::middle ? 0.5 * w : w;
  const double ascent = font.ascent(t.size_px);
  if (t.vertical) {
    c.text_vertical(t.x - ascent, t.y + shift, t.text, t.colour, t.size_px);
  } else {
    c.text(t.x - shift, t.y - ascent, t.text, t.colour, t.size_px);
  }
}

}  // namespace

render::Image rasterise(const DrawList& list) {
  Canvas canvas(list.width, list.height, kWhite);
  for (const Item& item : list.items) std::visit([&](const auto& i) { draw(canvas, i); }, item);
  return canvas.image();
}

render::Image draw_png(const Figure& figure) { return rasterise(lay_out(figure)); }

void write_png(const Figure& figure, const std::filesystem::path& path) {
  render::write_png(draw_png(figure), path);
}

}  // namespace weft::chart
