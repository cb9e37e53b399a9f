// Line charts as inline SVG (see svg_chart.h).

#include "app/svg_chart.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <sstream>
#include <stdexcept>

#include "app/html_escape.h"

namespace weft::app {
namespace {

// The plot frame inside the chart, pixels from the chart's edges.
constexpr int kLeft = 66, kRight = 14, kTop = 30, kBottom = 42;

struct Range {
  double lo = 0.0, hi = 1.0;
};

// The finite values' range; a single value gets ±10 % (or ±1 for zero) of room.
Range range_of(const std::vector<double>& values) {
  Range r{INFINITY, -INFINITY};
  for (const double v : values) {
    if (!std::isfinite(v)) continue;
    r.lo = std::min(r.lo, v);
    r.hi = std::max(r.hi, v);
  }
  if (!(r.hi >= r.lo)) return {0.0, 1.0};
  if (r.hi == r.lo) {
    const double pad = r.lo == 0.0 ? 1.0 : 0.1 * std::abs(r.lo);
    return {r.lo - pad, r.hi + pad};
  }
  return r;
}

double nice_step(double span, int target) {
  const double raw = span / std::max(target, 1);
  const double decade = std::pow(10.0, std::floor(std::log10(raw)));
  for (const double m : {1.0, 2.0, 5.0})
    if (m * decade >= raw) return m * decade;
  return 10.0 * decade;
}

std::string number(double v) {
  char text[32];
  std::snprintf(text, sizeof text, "%g", v);
  return text;
}

std::string pixel(double v) {
  char text[32];
  std::snprintf(text, sizeof text, "%.1f", v);
  return text;
}

}  // namespace

std::vector<double> linear_ticks(double lo, double hi, int target) {
  if (!(hi > lo) || !std::isfinite(lo) || !std::isfinite(hi)) return {lo};
  const double step = nice_step(hi - lo, target);
  std::vector<double> ticks;
  for (double k = std::ceil(lo / step - 1e-9); k * step <= hi + 1e-9 * step; k += 1.0) {
    const double v = k * step;
    ticks.push_back(std::abs(v) < 1e-12 * step ? 0.0 : v);
  }
  return ticks;
}

std::string svg_line_chart(const LineChart& chart) {
  std::vector<double> all_y;
  for (const ChartSeries& s : chart.series) {
    if (s.y.size() != chart.x.size())
      throw std::invalid_argument("svg_line_chart: series '" + s.name + "' has " +
                                  std::to_string(s.y.size()) + " values for " +
                                  std::to_string(chart.x.size()) + " x values");
    all_y.insert(all_y.end(), s.y.begin(), s.y.end());
  }
  const Range xr = range_of(chart.x);
  Range yr = range_of(all_y);
  // The y axis starts and ends on a tick.
  const double y_step = nice_step(yr.hi - yr.lo, 5);
  yr = {std::floor(yr.lo / y_step) * y_step, std::ceil(yr.hi / y_step) * y_step};

  const double x0 = kLeft, x1 = chart.width_px - kRight;
  const double y0 = chart.height_px - kBottom, y1 = kTop;  // y0: bottom of the frame
  const auto px = [&](double x) { return x0 + (x - xr.lo) / (xr.hi - xr.lo) * (x1 - x0); };
  const auto py = [&](double y) { return y0 + (y - yr.lo) / (yr.hi - yr.lo) * (y1 - y0); };

  std::ostringstream svg;
  svg << "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"" << chart.width_px << "\" height=\""
      << chart.height_px << "\" viewBox=\"0 0 " << chart.width_px << ' ' << chart.height_px
      << "\" font-family=\"sans-serif\" font-size=\"11\">\n";
  svg << "<rect width=\"100%\" height=\"100%\" fill=\"white\"/>\n";
  svg << "<text x=\"" << kLeft << "\" y=\"16\" font-size=\"13\" font-weight=\"bold\">"
      << html_escape(chart.title) << "</text>\n";
  for (const double t : linear_ticks(yr.lo, yr.hi)) {
    svg << "<line x1=\"" << pixel(x0) << "\" x2=\"" << pixel(x1) << "\" y1=\"" << pixel(py(t))
        << "\" y2=\"" << pixel(py(t)) << "\" stroke=\"#e4e4e4\"/>"
        << "<text x=\"" << pixel(x0 - 5) << "\" y=\"" << pixel(py(t) + 4)
        << "\" text-anchor=\"end\">" << number(t) << "</text>\n";
  }
  for (const double t : linear_ticks(xr.lo, xr.hi)) {
    svg << "<line x1=\"" << pixel(px(t)) << "\" x2=\"" << pixel(px(t)) << "\" y1=\"" << pixel(y0)
        << "\" y2=\"" << pixel(y0 + 5) << "\" stroke=\"#333\"/>"
        << "<text x=\"" << pixel(px(t)) << "\" y=\"" << pixel(y0 + 17)
        << "\" text-anchor=\"middle\">" << number(t) << "</text>\n";
  }
  svg << "<rect x=\"" << pixel(x0) << "\" y=\"" << pixel(y1) << "\" width=\"" << pixel(x1 - x0)
      << "\" height=\"" << pixel(y0 - y1) << "\" fill=\"none\" stroke=\"#333\"/>\n";
  svg << "<text x=\"" << pixel(0.5 * (x0 + x1)) << "\" y=\"" << chart.height_px - 6
      << "\" text-anchor=\"middle\">" << html_escape(chart.x_label) << "</text>\n";
  svg << "<text transform=\"translate(13 " << pixel(0.5 * (y0 + y1))
      << ") rotate(-90)\" text-anchor=\"middle\">" << html_escape(chart.y_label) << "</text>\n";

  double legend_x = x1;
  for (auto s = chart.series.rbegin(); s != chart.series.rend(); ++s) {
    legend_x -= 7.0 * static_cast<double>(s->name.size()) + 28.0;
    svg << "<line x1=\"" << pixel(legend_x) << "\" x2=\"" << pixel(legend_x + 16)
        << "\" y1=\"12\" y2=\"12\" stroke=\"" << s->colour << "\" stroke-width=\"2\"/>"
        << "<text x=\"" << pixel(legend_x + 20) << "\" y=\"16\">" << html_escape(s->name)
        << "</text>\n";
  }
  for (const ChartSeries& s : chart.series) {
    svg << "<polyline data-series=\"" << html_escape(s.name) << "\" fill=\"none\" stroke=\""
        << s.colour << "\" stroke-width=\"1.5\" points=\"";
    bool first = true;
    for (std::size_t k = 0; k < chart.x.size(); ++k) {
      if (!std::isfinite(s.y[k]) || !std::isfinite(chart.x[k])) continue;
      svg << (first ? "" : " ") << pixel(px(chart.x[k])) << ',' << pixel(py(s.y[k]));
      first = false;
    }
    svg << "\"/>\n";
  }
  svg << "</svg>";
  return svg.str();
}

}  // namespace weft::app
