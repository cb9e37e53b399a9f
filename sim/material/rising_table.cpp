#include "sim/material/rising_table.h"

#include <algorithm>
#include <cmath>

#include "base/format.h"
#include "sim/material/material.h"

namespace weft::sim {
namespace {

// The Hermite cubic on a segment of width h from (y0, slope d0) to (y1, d1), at t = (x − x0)/h.
struct HermiteSegment {
  double h, y0, y1, d0, d1;
  double value(double t) const {
    const double t2 = t * t, t3 = t2 * t;
    return y0 * (2 * t3 - 3 * t2 + 1) + h * d0 * (t3 - 2 * t2 + t) + y1 * (3 * t2 - 2 * t3) +
           h * d1 * (t3 - t2);
  }
  double slope(double t) const {
    const double t2 = t * t;
    return (y0 - y1) * (6 * t2 - 6 * t) / h + d0 * (3 * t2 - 4 * t + 1) + d1 * (3 * t2 - 2 * t);
  }
  // ∫ from x0 to x0 + t h.
  double integral(double t) const {
    const double t2 = t * t, t3 = t2 * t, t4 = t3 * t;
    return h * (y0 * (t - t3 + 0.5 * t4) + h * d0 * (0.25 * t4 - 2.0 * t3 / 3.0 + 0.5 * t2) +
                y1 * (t3 - 0.5 * t4) + h * d1 * (0.25 * t4 - t3 / 3.0));
  }
  // The least slope on the segment: at an end, or where the quadratic slope(t) turns.
  double least_slope() const {
    double least = std::min(d0, d1);
    const double a = 6 * (y0 - y1) / h + 3 * (d0 + d1), b = -6 * (y0 - y1) / h - 4 * d0 - 2 * d1;
    if (a > 0.0) {
      const double t = -b / (2 * a);
      if (t > 0.0 && t < 1.0) least = std::min(least, slope(t));
    }
    return least;
  }
};

// The Hermite cubic of segment k of a table's points and slopes.
HermiteSegment hermite(const std::vector<std::pair<double, double>>& points,
                       const std::vector<double>& slopes, std::size_t k) {
  return {points[k + 1].first - points[k].first, points[k].second, points[k + 1].second,
          slopes[k], slopes[k + 1]};
}

}  // namespace

RisingTable::RisingTable(std::vector<std::pair<double, double>> points, const Names& names) {
  const auto require = [&](bool ok, const std::string& what) {
    if (!ok) throw MaterialError(names.law + ": " + what);
  };
  const auto where = [&](std::size_t k) {
    const auto [x, y] = m_points[k];
    return "table point " + std::to_string(k) + " (" + base::format("%.6g", x) +
           (names.x_unit.empty() ? "" : " " + names.x_unit) + ", " + base::format("%.6g", y) +
           " " + names.y_unit + ")";
  };
  require(!points.empty(), "a table needs at least one (" + names.x + ", " + names.y + ") point");
  for (const auto& [x, y] : points) {
    const auto [x_prev, y_prev] = m_points.back();
    m_points.emplace_back(x, y);
    const std::size_t k = m_points.size() - 1;
    require(std::isfinite(x) && std::isfinite(y), where(k) + ": not finite");
    require(x > x_prev, where(k) + ": " + names.x + "s must increase from 0");
    require(y > y_prev, where(k) + ": " + names.y + "s must increase from 0 (a curve that does "
                                                    "not rise has no stable shape)");
  }
  // Slopes at the points: the weighted harmonic mean of the two segments' mean slopes inside,
  // which keeps each cubic monotone; the end segments' mean slopes at the ends.
  const std::size_t n = m_points.size();
  std::vector<double> h(n - 1), mean(n - 1);
  for (std::size_t k = 0; k + 1 < n; ++k) {
    h[k] = m_points[k + 1].first - m_points[k].first;
    mean[k] = (m_points[k + 1].second - m_points[k].second) / h[k];
  }
  m_slope_at.assign(n, 0.0);
  m_slope_at.front() = mean.front();
  m_slope_at.back() = mean.back();
  for (std::size_t k = 1; k + 1 < n; ++k) {
    const double w1 = 2 * h[k] + h[k - 1], w2 = h[k] + 2 * h[k - 1];
    m_slope_at[k] = (w1 + w2) / (w1 / mean[k - 1] + w2 / mean[k]);
  }
  m_integral_at.assign(1, 0.0);
  m_least_slope = m_slope_at.back();
  for (std::size_t k = 0; k + 1 < n; ++k) {
    const HermiteSegment s = hermite(m_points, m_slope_at, k);
    m_least_slope = std::min(m_least_slope, s.least_slope());
    require(s.least_slope() > 0.0, where(k + 1) + ": the curve through the points flattens");
    m_integral_at.push_back(m_integral_at.back() + s.integral(1.0));
  }
}

std::size_t RisingTable::segment(double x) const {
  // The first point with abscissa > x closes the segment; beyond the table, the last segment.
  const auto it = std::upper_bound(m_points.begin(), m_points.end(), x,
                                   [](double v, const auto& p) { return v < p.first; });
  const std::size_t end = static_cast<std::size_t>(it - m_points.begin());
  return std::clamp<std::size_t>(end, 1, m_points.size() - 1) - 1;
}

double RisingTable::value(double x) const {
  if (x >= m_points.back().first)
    return m_points.back().second + m_slope_at.back() * (x - m_points.back().first);
  const std::size_t k = segment(x);
  const HermiteSegment s = hermite(m_points, m_slope_at, k);
  return s.value((x - m_points[k].first) / s.h);
}

double RisingTable::slope(double x) const {
  if (x >= m_points.back().first) return m_slope_at.back();
  const std::size_t k = segment(x);
  const HermiteSegment s = hermite(m_points, m_slope_at, k);
  return s.slope((x - m_points[k].first) / s.h);
}

double RisingTable::integral(double x) const {
  const auto [xn, yn] = m_points.back();
  if (x >= xn) {
    const double d = x - xn;
    return m_integral_at.back() + yn * d + 0.5 * m_slope_at.back() * d * d;
  }
  const std::size_t k = segment(x);
  const HermiteSegment s = hermite(m_points, m_slope_at, k);
  return m_integral_at[k] + s.integral((x - m_points[k].first) / s.h);
}

std::vector<std::pair<double, double>> RisingTable::points() const {
  return {m_points.begin() + 1, m_points.end()};
}

}  // namespace weft::sim
