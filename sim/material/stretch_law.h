#pragma once
// A fabric's tension per unit width as a function of its strain along one yarn direction:
// T(ε), N/m, for the engineering strain ε = l/l₀ − 1; what a strip tensile test (KES-FB1, or
// Wang et al. 2011's stretching rig) measures along warp or weft. Real fabrics are not linear:
// knits and stretch wovens are soft while the yarns straighten and stiffen many times once they
// carry the load (Wang et al. 2011's knits stiffen up to ~90× by 17 % strain). Two forms:
//   linear  T = Y ε                      (the default: Material's stretch_*_N_m)
//   table   T through measured (εᵢ, Tᵢ), 0 < ε₁ < ε₂ < …, from (0, 0): a monotone cubic with a
//           continuous slope (sim/material/rising_table.h), extended beyond the last point with
//           the last segment's mean slope
// In compression (ε < 0) a table continues with its slope at 0, the first segment's mean slope:
// a fabric buckles out
// of plane long before it compresses, and the measurements are all in tension.
// The energy per area is W(ε) = ∫₀^ε T, J/m²; dT/dε > 0 everywhere (checked), so W is convex.

#include <string>
#include <utility>
#include <vector>

#include "base/enum_names.h"
#include "sim/material/rising_table.h"

namespace weft::sim {

class StretchLaw {
 public:
  enum class Form { linear, table };

  // Throw MaterialError (sim/material/material.h) naming the bad value: Y not finite or ≤ 0; a
  // table with no point, a value not finite, a strain or tension not increasing from 0.
  static StretchLaw linear(double Y_N_m);
  // Points (ε, T N/m), without (0, 0).
  static StretchLaw table(std::vector<std::pair<double, double>> points);

  static constexpr base::EnumNames<Form, 2> form_names{
      {{Form::linear, "linear"}, {Form::table, "table"}}};

  Form form() const { return m_form; }
  // T(ε), N/m.
  double tension(double strain) const;
  // dT/dε at ε, N/m (> 0).
  double stiffness(double strain) const;
  // W(ε) = ∫₀^ε T, J/m².
  double energy_density(double strain) const;
  // dT/dε at ε = 0: the rigidity that sets the time step and the stability bounds, N/m.
  double initial_stiffness() const { return stiffness(0.0); }
  // The law T(ε) − c ε: what is left for a warp or weft edge when the shear diagonals carry the
  // linear part c (sim/mass_spring.h). Throws MaterialError when that would not rise everywhere.
  StretchLaw minus_linear(double c_N_m) const;
  // "table of 15 points to 0.5".
  std::string describe() const;

  double Y() const { return m_Y; }
  // Table: its points (ε, T) after (0, 0).
  std::vector<std::pair<double, double>> points() const { return m_table.points(); }

 private:
  StretchLaw() = default;
  Form m_form = Form::linear;
  double m_Y = 0.0;      // the slope at zero (and in compression)
  RisingTable m_table;
  double m_minus = 0.0;  // table: the linear part c taken off, T = table(ε) − c ε
};

}  // namespace weft::sim
