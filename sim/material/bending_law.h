#pragma once
// A fabric's bending moment as a function of curvature, per unit width: M(κ), N·m/m (= N), for
// κ in 1/m; what a cantilever or a drape tester measures along one direction (warp or weft).
// Real fabrics are not linear: their bending curve is stiff at small curvature, where the
// fibres' friction holds the yarns together, and much softer beyond (Grosberg 1966, "The
// mechanical properties of woven fabrics, part II: the bending of woven fabrics", Textile
// Research Journal 36; Kawabata's KES-FB2 reports both the slope B and the hysteresis 2HB of
// that curve). Four forms:
//   linear      M = B κ                                    (the default: Material's bend_*_Nm)
//   frictional  M = B κ + M₀ tanh(κ / κ₀)                  Grosberg's frictional couple M₀ on an
//               elastic slope B, smoothed over the curvature κ₀ (slope at 0: B + M₀/κ₀)
//   cubic       M = B κ + C κ³                              (C ≥ 0: stiffening; the low-order
//               polynomial of drape-tester and cantilever fits)
//   table       M through measured (κᵢ, Mᵢ), 0 < κ₁ < κ₂ < …, from (0, 0): a monotone cubic
//               with a continuous slope (sim/material/rising_table.h), extended beyond the last
//               point with the last segment's mean slope
// The energy per area is W(κ) = ∫₀^κ M, J/m². Every form is odd in κ (W even) and has
// dM/dκ > 0 everywhere (checked), so W is convex: the bending energy keeps one minimum.

#include <string>

#include <utility>
#include <vector>

#include "base/enum_names.h"
#include "sim/material/rising_table.h"

namespace weft::sim {

class BendingLaw {
 public:
  enum class Form { linear, frictional, cubic, table };

  // Each throws MaterialError (sim/material/material.h) naming the bad value: B ≤ 0 (linear), B < 0,
  // M₀ < 0 or κ₀ ≤ 0 or B + M₀/κ₀ ≤ 0 (frictional), B ≤ 0 or C < 0 (cubic); a table with fewer
  // than one point, a curvature not increasing from > 0, a moment not increasing from > 0, or
  // any value not finite.
  static BendingLaw linear(double B_Nm);
  static BendingLaw frictional(double B_Nm, double M0_N, double kappa0_1_m);
  static BendingLaw cubic(double B_Nm, double C_Nm3);
  // Points (κ 1/m, M N·m/m), without (0, 0).
  static BendingLaw table(std::vector<std::pair<double, double>> points);

  static constexpr base::EnumNames<Form, 4> form_names{{{Form::linear, "linear"},
                                                       {Form::frictional, "frictional"},
                                                       {Form::cubic, "cubic"},
                                                       {Form::table, "table"}}};

  Form form() const { return m_form; }
  // M(κ), N·m/m.
  double moment(double kappa_1_m) const;
  // dM/dκ at κ, N·m (> 0).
  double stiffness(double kappa_1_m) const;
  // W(κ) = ∫₀^κ M, J/m².
  double energy_density(double kappa_1_m) const;
  // dM/dκ at κ = 0: the rigidity that sets the time step and the stability bounds, N·m.
  double initial_rigidity() const { return stiffness(0.0); }
  // "frictional: B 0.0088 N*m, M0 0.22 N, kappa0 0.46 1/m".
  std::string describe() const;

  double B() const { return m_B; }
  double M0() const { return m_M0; }
  double kappa0() const { return m_kappa0; }
  double C() const { return m_C; }
  // Table: its points (κ, M) after (0, 0).
  std::vector<std::pair<double, double>> points() const { return m_table.points(); }

 private:
  BendingLaw() = default;
  Form m_form = Form::linear;
  double m_B = 0.0, m_M0 = 0.0, m_kappa0 = 1.0, m_C = 0.0;
  RisingTable m_table;  // table: M(|κ|)
};

}  // namespace weft::sim
