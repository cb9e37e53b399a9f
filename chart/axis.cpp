#include "chart/axis.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace weft::chart {

namespace {

double nice_step(double span, int target) {
  const double raw = span / std::max(target, 1);
  const double decade = std::pow(10.0, std::floor(std::log10(raw)));
  for (const double m : {1.0, 2.0, 5.0})
    if (m * decade >= raw) return m * decade;
  return 10.0 * decade;
}

std::string format_g(double v) {
  char text[32];
  std::snprintf(text, sizeof text, "%g", v);
  return text;
}

std::vector<Tick> log_ticks(const Axis& axis) {
  const double decades = std::log10(axis.hi / axis.lo);
  std::vector<Tick> out;
  const int e_lo = static_cast<int>(std::floor(std::log10(axis.lo)));
  const int e_hi = static_cast<int>(std::ceil(std::log10(axis.hi)));
  for (int e = e_lo; e <= e_hi; ++e) {
    for (int m = 1; m <= 9; ++m) {
      const double v = m * std::pow(10.0, e);
      if (v < axis.lo * (1 - 1e-9) || v > axis.hi * (1 + 1e-9)) continue;
      const bool labelled = m == 1 || (decades < 2.6 && (m == 2 || m == 5)) || decades < 0.6;
      out.push_back({v, labelled ? log_tick_label(v) : std::string(), m == 1});
    }
  }
  return out;
}

}  // namespace

double Axis::fraction(double v) const {
  if (scale == Scale::log) {
    if (!(v > 0.0)) return 0.0;
    return (std::log10(v) - std::log10(lo)) / (std::log10(hi) - std::log10(lo));
  }
  return (v - lo) / (hi - lo);
}

std::vector<Tick> Axis::drawn_ticks() const { return ticks.empty() ? automatic_ticks(*this) : ticks; }

Axis Axis::linear_fit(std::string label, const std::vector<double>& values) {
  Axis axis;
  axis.label = std::move(label);
  double lo = INFINITY, hi = -INFINITY;
  for (const double v : values) {
    if (!std::isfinite(v)) continue;
    lo = std::min(lo, v);
    hi = std::max(hi, v);
  }
  if (!(hi >= lo)) return axis;
  if (hi == lo) {
    const double pad = lo == 0.0 ? 1.0 : 0.1 * std::abs(lo);
    lo -= pad;
    hi += pad;
  }
  const double step = nice_step(hi - lo, 5);
  axis.lo = std::floor(lo / step) * step;
  axis.hi = std::ceil(hi / step) * step;
  return axis;
}

Axis Axis::log_fit(std::string label, const std::vector<double>& values) {
  Axis axis;
  axis.label = std::move(label);
  axis.scale = Scale::log;
  axis.lo = 1e-3;
  axis.hi = 1.0;
  double l_min = INFINITY, l_max = -INFINITY;
  for (const double v : values) {
    if (!(v > 0.0) || !std::isfinite(v)) continue;
    l_min = std::min(l_min, std::log10(v));
    l_max = std::max(l_max, std::log10(v));
  }
  if (!(l_max >= l_min)) return axis;
  const double centre = 0.5 * (l_min + l_max);
  const double half = 0.5 * std::max(l_max - l_min, 0.3) * 1.12 + 0.04;
  axis.lo = std::pow(10.0, centre - half);
  axis.hi = std::pow(10.0, centre + half);
  return axis;
}

std::vector<Tick> automatic_ticks(const Axis& axis) {
  if (axis.scale == Scale::log) return log_ticks(axis);
  std::vector<Tick> out;
  for (const double v : linear_ticks(axis.lo, axis.hi)) out.push_back({v, format_g(v), true});
  return out;
}

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

}  // namespace weft::chart
