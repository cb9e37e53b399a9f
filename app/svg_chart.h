#pragma once
// A small line chart as inline SVG text (weft run --report's plots of strain, energy and time
// per frame): linear axes with 1-2-5 ticks, one polyline per series, a legend. Numbers are
// printed with fixed precision, so the same data give the same text.

#include <string>
#include <vector>

namespace weft::app {

struct ChartSeries {
  std::string name;    // legend text, e.g. "kinetic"; also the polyline's data-series attribute
  std::string colour;  // SVG colour, e.g. "#d6541a"
  std::vector<double> y;  // one value per x; non-finite values are left out of the line
};

struct LineChart {
  std::string title;    // e.g. "Largest strain"
  std::string x_label;  // e.g. "simulated time [s]"
  std::string y_label;  // e.g. "strain [%]"
  std::vector<double> x;
  std::vector<ChartSeries> series;
  int width_px = 440, height_px = 240;
};

// The chart as an <svg> element. Each series is a <polyline data-series="NAME" points="x,y ...">
// with one point per finite value, in the order of `x`. Throws std::invalid_argument when a
// series' length differs from x's.
std::string svg_line_chart(const LineChart& chart);

// Tick values for a linear axis covering [lo, hi]: about `target` steps of 1, 2 or 5 × 10^k.
std::vector<double> linear_ticks(double lo, double hi, int target = 5);

}  // namespace weft::app
