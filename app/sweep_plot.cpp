// The sweep chart, drawn with render::Canvas: a log–log frame with decade ticks, the runs as
// numbered markers, the Pareto front as a line, and a legend naming each run's settings.

#include "app/sweep_plot.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "render/canvas.h"

namespace weft::app {

namespace {

using render::Canvas;
using render::Rgb8;

constexpr int kWidth = 1100, kHeight = 620;
// The plot frame, pixels.
constexpr int kLeft = 90, kTop = 50, kRight = 600, kBottom = 540;
constexpr int kLegendX = kRight + 30;
constexpr int kLineHeight = 14;
constexpr int kMarkerRadius = 5;

const Rgb8 kBackground{255, 255, 255};
const Rgb8 kInk{20, 20, 20};
const Rgb8 kGrid{228, 228, 228};
const Rgb8 kMinorTick{150, 150, 150};
const Rgb8 kDominated{80, 105, 170};
const Rgb8 kPareto{214, 84, 26};
const Rgb8 kReference{20, 20, 20};
const Rgb8 kDiverged{160, 160, 160};

// A logarithmic axis: value lo at pixel p_lo, hi at p_hi.
struct LogAxis {
  double lo = 1e-3, hi = 1.0;
  double p_lo = 0.0, p_hi = 1.0;
  double pixel(double v) const {
    return p_lo + (std::log10(v) - std::log10(lo)) / (std::log10(hi) - std::log10(lo)) * (p_hi - p_lo);
  }
};

// A range holding every value with some room on both sides: at least 0.3 decades wide.
LogAxis axis_for(const std::vector<double>& values, double p_lo, double p_hi) {
  LogAxis axis;
  axis.p_lo = p_lo;
  axis.p_hi = p_hi;
  double l_min = INFINITY, l_max = -INFINITY;
  for (double v : values) {
    if (!(v > 0.0) || !std::isfinite(v)) continue;
    l_min = std::min(l_min, std::log10(v));
    l_max = std::max(l_max, std::log10(v));
  }
  if (!(l_max >= l_min)) return axis;  // nothing to show: 1e-3 … 1
  const double centre = 0.5 * (l_min + l_max);
  const double half = 0.5 * std::max(l_max - l_min, 0.3) * 1.12 + 0.04;
  axis.lo = std::pow(10.0, centre - half);
  axis.hi = std::pow(10.0, centre + half);
  return axis;
}

struct Tick {
  double value;
  bool major;  // a power of ten
  bool labelled;
};

// 1·10^e … 9·10^e inside the axis; every decade labelled, and 2 and 5 too on short axes.
std::vector<Tick> ticks(const LogAxis& axis) {
  const double decades = std::log10(axis.hi / axis.lo);
  std::vector<Tick> out;
  for (int e = static_cast<int>(std::floor(std::log10(axis.lo))); e <= std::ceil(std::log10(axis.hi)); ++e) {
    for (int m = 1; m <= 9; ++m) {
      const double v = m * std::pow(10.0, e);
      if (v < axis.lo || v > axis.hi) continue;
      const bool labelled = m == 1 || (decades < 2.6 && (m == 2 || m == 5)) || decades < 0.6;
      out.push_back({v, m == 1, labelled});
    }
  }
  return out;
}

// Shortens text to `max_chars` characters, ending in "..".
std::string fit(const std::string& text, std::size_t max_chars) {
  if (text.size() <= max_chars) return text;
  return text.substr(0, max_chars > 2 ? max_chars - 2 : 0) + "..";
}

void marker(Canvas& canvas, double x, double y, bool pareto) {
  if (pareto) {
    canvas.circle(x, y, kMarkerRadius, kPareto, true);
  } else {
    canvas.circle(x, y, kMarkerRadius, kBackground, true);
    canvas.circle(x, y, kMarkerRadius, kDominated, false);
  }
}

// 6-pixel dashes with 5-pixel gaps, 2 pixels wide.
void dashed_line(Canvas& canvas, double x0, double y0, double x1, double y1, Rgb8 colour) {
  const double length = std::hypot(x1 - x0, y1 - y0);
  for (double t = 0.0; t < length; t += 11.0) {
    const double a = t / length, b = std::min(t + 6.0, length) / length;
    canvas.line(x0 + a * (x1 - x0), y0 + a * (y1 - y0), x0 + b * (x1 - x0), y0 + b * (y1 - y0),
                colour, 2);
  }
}

void reference_marker(Canvas& canvas, double x, double y) {
  const int cx = static_cast<int>(std::lround(x)), cy = static_cast<int>(std::lround(y));
  canvas.fill_rect(cx - 4, cy - 4, cx + 5, cy + 5, kReference);
}

void draw_axes(Canvas& canvas, const LogAxis& x_axis, const LogAxis& y_axis) {
  for (const Tick& t : ticks(x_axis)) {
    const double px = x_axis.pixel(t.value);
    if (t.major) canvas.line(px, kTop + 1, px, kBottom - 1, kGrid);
    canvas.line(px, kBottom, px, kBottom + (t.major ? 6 : 3), t.major ? kInk : kMinorTick);
    if (t.labelled) {
      const std::string label = log_tick_label(t.value);
      canvas.text(static_cast<int>(std::lround(px)) - Canvas::text_width(label) / 2, kBottom + 10,
                  label, kInk);
    }
  }
  for (const Tick& t : ticks(y_axis)) {
    const double py = y_axis.pixel(t.value);
    if (t.major) canvas.line(kLeft + 1, py, kRight - 1, py, kGrid);
    canvas.line(kLeft - (t.major ? 6 : 3), py, kLeft, py, t.major ? kInk : kMinorTick);
    if (t.labelled) {
      const std::string label = log_tick_label(t.value);
      canvas.text(kLeft - 10 - Canvas::text_width(label),
                  static_cast<int>(std::lround(py)) - Canvas::text_height() / 2, label, kInk);
    }
  }
  canvas.rect(kLeft, kTop, kRight + 1, kBottom + 1, kInk);
  const std::string x_label = "simulation wall time [s]";
  canvas.text((kLeft + kRight - Canvas::text_width(x_label)) / 2, kBottom + 30, x_label, kInk);
  const std::string y_label = "RMS distance to the reference at the last frame [m]";
  canvas.text_vertical(14, (kTop + kBottom + Canvas::text_width(y_label)) / 2, y_label, kInk);
}

void draw_legend(Canvas& canvas, const std::vector<PlotRun>& runs) {
  int y = kTop;
  const int text_x = kLegendX + 16;
  const std::size_t max_chars = static_cast<std::size_t>((kWidth - 8 - text_x) / 6);
  marker(canvas, kLegendX + 5, y + 3, true);
  canvas.text(text_x, y, "Pareto-optimal (front connected; dashed to the reference)", kInk);
  y += kLineHeight;
  marker(canvas, kLegendX + 5, y + 3, false);
  canvas.text(text_x, y, "dominated: another run is faster and closer", kInk);
  y += kLineHeight;
  reference_marker(canvas, kLegendX + 5, y + 3);
  canvas.text(text_x, y, "reference (error 0): on the bottom edge", kInk);
  y += 2 * kLineHeight;
  canvas.text(kLegendX, y, "run  settings", kInk);
  y += kLineHeight + 2;
  const int max_rows = (kHeight - 20 - y) / kLineHeight;
  for (std::size_t k = 0; k < runs.size(); ++k) {
    if (static_cast<int>(k) == max_rows - 1 && runs.size() > k + 1) {
      canvas.text(kLegendX, y, "... " + std::to_string(runs.size() - k) + " more in sweep.csv", kInk);
      break;
    }
    const PlotRun& r = runs[k];
    std::string line = std::to_string(k + 1) + (k + 1 < 10 ? "    " : "   ") + r.label;
    if (r.reference) line += " (reference)";
    if (r.diverged) line += " (diverged)";
    const Rgb8 colour = r.diverged ? kDiverged : (r.pareto ? kPareto : kInk);
    canvas.text(kLegendX, y, fit(line, max_chars + 2), colour);
    y += kLineHeight;
  }
  y += kLineHeight;
  for (const char* note : {"error: RMS distance from the reference at the same",
                           "material points (bilinear), after the last frame",
                           "time: simulation steps only (no set-up, no rendering)"}) {
    if (y + kLineHeight > kHeight) break;
    canvas.text(kLegendX, y, note, kMinorTick);
    y += kLineHeight;
  }
}

}  // namespace

std::string log_tick_label(double value) {
  char text[32];
  const int e = static_cast<int>(std::floor(std::log10(value) + 1e-9));
  if (e >= -3 && e <= 3) {
    std::snprintf(text, sizeof text, "%g", value);
  } else {
    std::snprintf(text, sizeof text, "%ge%d", std::round(value / std::pow(10.0, e) * 1e3) / 1e3, e);
  }
  return text;
}

render::Image sweep_plot(const std::vector<PlotRun>& runs, const std::string& title) {
  Canvas canvas(kWidth, kHeight, kBackground);
  const int title_scale = Canvas::text_width(title, 2) <= kWidth - 20 ? 2 : 1;
  canvas.text(10, 14, title, kInk, title_scale);

  // Drawn: finished runs with a positive error. The reference (and any run that matches it
  // exactly) sits on the bottom edge at its time.
  std::vector<double> times, errors;
  for (const PlotRun& r : runs) {
    if (r.diverged) continue;
    times.push_back(r.time_s);
    if (r.error_m > 0.0) errors.push_back(r.error_m);
  }
  const LogAxis x_axis = axis_for(times, kLeft, kRight);
  const LogAxis y_axis = axis_for(errors, kBottom, kTop);
  draw_axes(canvas, x_axis, y_axis);

  const auto position = [&](const PlotRun& r) {
    const double px = x_axis.pixel(r.time_s);
    const double py = r.error_m > 0.0 ? y_axis.pixel(r.error_m) : kBottom;
    return std::pair<double, double>{px, py};
  };
  // The front, fastest first: a line through the Pareto-optimal runs.
  std::vector<std::size_t> front;
  for (std::size_t k = 0; k < runs.size(); ++k) {
    if (runs[k].pareto && !runs[k].diverged) front.push_back(k);
  }
  std::sort(front.begin(), front.end(),
            [&](std::size_t a, std::size_t b) { return runs[a].time_s < runs[b].time_s; });
  for (std::size_t k = 1; k < front.size(); ++k) {
    const auto [x0, y0] = position(runs[front[k - 1]]);
    const auto [x1, y1] = position(runs[front[k]]);
    // Towards a run drawn on the bottom edge (error 0, off the log axis): dashed.
    if (runs[front[k]].error_m > 0.0 && runs[front[k - 1]].error_m > 0.0) {
      canvas.line(x0, y0, x1, y1, kPareto, 2);
    } else {
      dashed_line(canvas, x0, y0, x1, y1, kPareto);
    }
  }
  // Dominated runs first, so that the front's markers stay on top.
  for (int pass = 0; pass < 2; ++pass) {
    for (std::size_t k = 0; k < runs.size(); ++k) {
      const PlotRun& r = runs[k];
      if (r.diverged || r.pareto != (pass == 1)) continue;
      const auto [px, py] = position(r);
      if (r.error_m > 0.0) {
        marker(canvas, px, py, r.pareto);
      } else {
        reference_marker(canvas, px, py);
      }
      canvas.text(static_cast<int>(std::lround(px)) + 7, static_cast<int>(std::lround(py)) - 11,
                  std::to_string(k + 1), r.pareto ? kPareto : kInk);
    }
  }
  draw_legend(canvas, runs);
  return canvas.image();
}

}  // namespace weft::app
