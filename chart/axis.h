#pragma once
// The one axis type of weft's charts: a linear or logarithmic range with its ticks. The same
// axis places data in the PNG and in the SVG of a chart (chart/chart.h).

#include <string>
#include <utility>
#include <vector>

namespace weft::chart {

enum class Scale { linear, log };

struct Tick {
  Tick() = default;
  Tick(double v, std::string text = {}, bool is_major = true)
      : value(v), label(std::move(text)), major(is_major) {}
  double value = 0.0;
  std::string label;  // empty: an unlabelled (minor) tick
  bool major = true;  // longer, darker, and with a grid line when the axis has a grid
};

struct Axis {
  Axis() = default;
  Axis(std::string text, Scale s, double low, double high)
      : label(std::move(text)), scale(s), lo(low), hi(high) {}
  std::string label;  // e.g. "simulated time [s]"
  Scale scale = Scale::linear;
  double lo = 0.0, hi = 1.0;  // the range shown; 0 < lo < hi on a log axis
  std::vector<Tick> ticks;    // empty: automatic_ticks(*this)
  bool grid = false;          // light lines across the plot at the major ticks

  // Where v falls along the axis: 0 at lo, 1 at hi (linear in log v on a log axis). A value
  // ≤ 0 on a log axis falls on its low end.
  double fraction(double v) const;
  // The ticks drawn: `ticks`, or automatic_ticks when it is empty.
  std::vector<Tick> drawn_ticks() const;

  // A linear axis over the finite values, widened to whole tick steps (a single value gets
  // ±10 %, or ±1 when it is zero). With no finite value: 0 … 1.
  static Axis linear_fit(std::string label, const std::vector<double>& values);
  // A log axis over the positive finite values, at least 0.3 decades wide, with room on both
  // sides. With no positive value: 1e-3 … 1.
  static Axis log_fit(std::string label, const std::vector<double>& values);
};

// Linear: 1-2-5 steps (linear_ticks), labelled "%g". Log: m × 10^e for m = 1 … 9 inside the
// range; the decades major and labelled, 2 and 5 labelled too on axes under 2.6 decades, every
// tick on axes under 0.6 decades.
std::vector<Tick> automatic_ticks(const Axis& axis);

// Tick values for a linear axis covering [lo, hi]: about `target` steps of 1, 2 or 5 × 10^k.
std::vector<double> linear_ticks(double lo, double hi, int target = 5);

// A tick label for a value on a log axis: "0.001" … "1000", else "2e-5".
std::string log_tick_label(double value);

}  // namespace weft::chart
