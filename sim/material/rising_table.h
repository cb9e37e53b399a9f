#pragma once
// A measured curve y(x) for x ≥ 0, as a material law's table gives it: through (0, 0) and
// points whose x and y both increase, by monotone cubic Hermite interpolation (Fritsch & Carlson
// 1980, "Monotone piecewise cubic interpolation", SIAM J. Numer. Anal. 17; the weighted harmonic
// mean slopes of Fritsch & Butland 1984), extended beyond the last point with the last
// segment's mean slope; with its integral ∫₀^x y. The slope at 0 is the first segment's mean
// slope. Its slope dy/dx is continuous, so Newton's method on an energy whose derivative is this
// curve sees no jumps in its Hessian (a piecewise-linear table would have one at every point),
// and positive everywhere (checked). The table forms of the bending law (moment against
// curvature) and of the stretch law (tension against strain) are this curve.

#include <string>
#include <utility>
#include <vector>

namespace weft::sim {

class RisingTable {
 public:
  // How messages name the curve: law "bending law", x "curvature" in "1/m", y "moment" in "N".
  struct Names {
    std::string law, x, x_unit, y, y_unit;
  };

  // Points (x, y) after (0, 0). Throws MaterialError (sim/material/material.h), starting with
  // names.law, naming the point, when there is none, a value is not finite, or x or y does not
  // increase from 0 ("bending law: table point 2 (20 1/m, 0.001 N): moments must increase…").
  RisingTable(std::vector<std::pair<double, double>> points, const Names& names);
  RisingTable() = default;

  // y(x) for x ≥ 0.
  double value(double x) const;
  // dy/dx at x ≥ 0 (the first segment's mean slope at 0, the last's beyond the table).
  double slope(double x) const;
  // ∫₀^x y for x ≥ 0.
  double integral(double x) const;

  // The points after (0, 0).
  std::vector<std::pair<double, double>> points() const;
  std::size_t size() const { return m_points.size() - 1; }
  // The least slope anywhere (> 0).
  double least_slope() const { return m_least_slope; }
  double last_x() const { return m_points.back().first; }

 private:
  // The segment holding x: its index, the last one beyond the table.
  std::size_t segment(double x) const;
  std::vector<std::pair<double, double>> m_points{{0.0, 0.0}};  // with (0, 0) first
  std::vector<double> m_slope_at{0.0};                           // dy/dx at each point
  std::vector<double> m_integral_at{0.0};                        // ∫₀ y at each point
  double m_least_slope = 0.0;
};

}  // namespace weft::sim
