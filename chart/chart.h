#pragma once
// weft's charts: one description, drawn as a PNG or as SVG text with the same layout (weft
// sweep's error-vs-time plot, weft stability's heatmaps, weft run --report's line charts).
//
// A Figure is a title, a grid of Plots and a legend. A Plot has two Axes (chart/axis.h), heat
// cells drawn first and data series over them. lay_out() turns a Figure into a DrawList of
// pixel-placed primitives (chart/draw_list.h); draw_png() rasterises that list (render::Canvas,
// anti-aliased text in DejaVu Sans) and draw_svg() writes it as SVG, so both agree on every
// position. Colours: chart/palette.h.

#include <filesystem>
#include <string>
#include <utility>
#include <vector>

#include "chart/axis.h"
#include "chart/palette.h"
#include "render/image.h"

namespace weft::chart {

enum class Marker { none, disc, ring, square };

struct Series {
  Series() = default;
  Series(std::string series_name, Rgb8 c, std::vector<double> xs, std::vector<double> ys,
         double width = 1.5)
      : name(std::move(series_name)), colour(c), x(std::move(xs)), y(std::move(ys)),
        line_width(width) {}
  std::string name;  // the SVG polyline's data-series attribute
  Rgb8 colour = okabe_ito::black;
  std::vector<double> x, y;  // same length; points with a non-finite value are left out
  double line_width = 1.5;   // pixels; 0 draws no line
  bool dashed = false;
  Marker marker = Marker::none;
  double marker_radius = 4.0;
  Rgb8 marker_fill = kWhite;               // inside a ring
  std::vector<std::string> point_labels;   // empty, or one per point: text beside it
  Rgb8 label_colour = kInk;
};

// A rectangle of the plot in data coordinates, filled (a heatmap cell).
struct Cell {
  double x0 = 0, x1 = 0, y0 = 0, y1 = 0;
  Rgb8 fill;
};

struct Plot {
  std::string title;  // above the frame, larger
  std::string note;   // after the title, body size
  Axis x, y;
  std::vector<Cell> cells;
  std::vector<Series> series;
};

enum class Swatch { none, line, dashed_line, disc, ring, square, box };

struct LegendEntry {
  LegendEntry() = default;
  LegendEntry(std::string t, Swatch s = Swatch::none, Rgb8 c = okabe_ito::black, Rgb8 tc = kInk)
      : text(std::move(t)), swatch(s), colour(c), text_colour(tc) {}
  std::string text;
  Swatch swatch = Swatch::none;
  Rgb8 colour = okabe_ito::black;  // of the swatch
  Rgb8 text_colour = kInk;
};

enum class LegendPlace {
  top_right,  // one row in the title's line, ending at the right edge
  right,      // one entry per line, right of the plots (legend_width pixels wide)
  below,      // one row under the plots
};

struct Figure {
  std::string title, subtitle;
  std::vector<Plot> plots;
  int columns = 1;
  int plot_width = 360, plot_height = 200;  // each plot's frame, pixels
  std::vector<LegendEntry> legend;
  LegendPlace legend_place = LegendPlace::below;
  int legend_width = 300;  // LegendPlace::right only; longer entries are cut with "…"
};

// Text sizes, pixels (render/font.h).
constexpr double kTitlePx = 16.0, kPlotTitlePx = 14.0, kBodyPx = 12.0;

// Throws std::invalid_argument when a series' x and y (or point_labels) lengths differ, a log
// axis has lo ≤ 0, or an axis is empty (hi ≤ lo).
void check(const Figure& figure);

render::Image draw_png(const Figure& figure);
std::string draw_svg(const Figure& figure);
void write_png(const Figure& figure, const std::filesystem::path& path);

}  // namespace weft::chart
