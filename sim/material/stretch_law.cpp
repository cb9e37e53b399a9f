#include "sim/material/stretch_law.h"

#include <cmath>
#include <cstdio>

#include "base/format.h"
#include "sim/material/material.h"

namespace weft::sim {
namespace {

const RisingTable::Names table_names{"stretch law", "strain", "", "tension", "N/m"};

}  // namespace

StretchLaw StretchLaw::linear(double Y_N_m) {
  if (!(std::isfinite(Y_N_m) && Y_N_m > 0.0))
    throw MaterialError("stretch law: linear Y must be finite and > 0, got " +
                        base::format("%.6g", Y_N_m));
  StretchLaw law;
  law.m_Y = Y_N_m;
  return law;
}

StretchLaw StretchLaw::table(std::vector<std::pair<double, double>> points) {
  StretchLaw law;
  law.m_form = Form::table;
  law.m_table = RisingTable(std::move(points), table_names);
  law.m_Y = law.m_table.slope(0.0);
  return law;
}

double StretchLaw::tension(double strain) const {
  if (m_form == Form::linear || strain <= 0.0) return m_Y * strain;
  return m_table.value(strain) - m_minus * strain;
}

double StretchLaw::stiffness(double strain) const {
  if (m_form == Form::linear || strain <= 0.0) return m_Y;
  return m_table.slope(strain) - m_minus;
}

double StretchLaw::energy_density(double strain) const {
  if (m_form == Form::linear || strain <= 0.0) return 0.5 * m_Y * strain * strain;
  return m_table.integral(strain) - 0.5 * m_minus * strain * strain;
}

StretchLaw StretchLaw::minus_linear(double c_N_m) const {
  const double least = m_form == Form::linear ? m_Y : m_table.least_slope() - m_minus;
  if (!(c_N_m < least))
    throw MaterialError("stretch law: its least stiffness " + base::format("%.6g", least) +
                        " N/m is not above the shear diagonals' " + base::format("%.6g", c_N_m) +
                        " N/m (the shear rigidity is too large for this law)");
  if (m_form == Form::linear) return linear(m_Y - c_N_m);
  StretchLaw law = *this;
  law.m_minus += c_N_m;
  law.m_Y -= c_N_m;
  return law;
}

std::string StretchLaw::describe() const {
  if (m_form == Form::linear) return "linear: Y " + base::format("%.6g", m_Y) + " N/m";
  return "table of " + std::to_string(m_table.size()) + " points to strain " +
         base::format("%.6g", m_table.last_x());
}

}  // namespace weft::sim
