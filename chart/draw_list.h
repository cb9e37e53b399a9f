#pragma once
// A chart laid out: primitives in pixel coordinates, the one input of both back-ends (PNG and
// SVG). Coordinates follow SVG: pixel (i, j) covers [i, i+1) × [j, j+1), y down; crisp
// one-pixel lines sit on half-integers.

#include <string>
#include <variant>
#include <vector>

#include "chart/chart.h"

namespace weft::chart {

struct Point {
  double x = 0, y = 0;
};

struct LineItem {  // a polyline
  std::vector<Point> points;
  Rgb8 colour;
  double width = 1.0;
  bool dashed = false;   // 6 on, 4 off, times the width
  bool crisp = false;    // axis-aligned, 1 px: drawn without anti-aliasing
  std::string series;    // data-series name, or empty
  std::string role;      // "x-tick", "y-tick", "grid", "frame", "series", …
};

struct RectItem {
  double x0 = 0, y0 = 0, x1 = 0, y1 = 0;
  bool filled = true;  // else its 1-pixel outline
  Rgb8 colour;
  std::string role;
};

struct CircleItem {
  double cx = 0, cy = 0, r = 0;
  bool filled = true;  // else a 1.5-pixel ring
  Rgb8 colour;
};

enum class Anchor { start, middle, end };

struct TextItem {
  double x = 0, y = 0;  // the anchor point on the baseline (before rotation)
  std::string text;
  Rgb8 colour = kInk;
  double size_px = kBodyPx;
  Anchor anchor = Anchor::start;
  bool vertical = false;  // rotated 90° counter-clockwise about (x, y)
  std::string role;
};

using Item = std::variant<LineItem, RectItem, CircleItem, TextItem>;

struct DrawList {
  int width = 0, height = 0;
  std::vector<Item> items;  // in drawing order
};

DrawList lay_out(const Figure& figure);
render::Image rasterise(const DrawList& list);
std::string to_svg(const DrawList& list);

// The width of text in the chart font, pixels.
double text_width(const std::string& text, double size_px = kBodyPx);
// Text cut to at most max_width pixels, ending in "…" when cut.
std::string fit_text(const std::string& text, double max_width, double size_px = kBodyPx);

}  // namespace weft::chart
