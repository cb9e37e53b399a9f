#include "sim/material/bending_law.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "base/format.h"
#include "sim/material/material.h"

namespace weft::sim {
namespace {

void require(bool ok, const std::string& what) {
  if (!ok) throw MaterialError("bending law: " + what);
}

// ln cosh(t) for any t without overflow: |t| + ln((1 + e^{−2|t|}) / 2).
double log_cosh(double t) {
  const double a = std::abs(t);
  return a + std::log1p(std::exp(-2.0 * a)) - std::log(2.0);
}

}  // namespace

BendingLaw BendingLaw::linear(double B_Nm) {
  require(std::isfinite(B_Nm) && B_Nm > 0.0, "linear B must be finite and > 0, got " + base::format("%.6g", B_Nm));
  BendingLaw law;
  law.m_B = B_Nm;
  return law;
}

BendingLaw BendingLaw::frictional(double B_Nm, double M0_N, double kappa0_1_m) {
  require(std::isfinite(B_Nm) && B_Nm >= 0.0, "frictional B must be finite and >= 0, got " + base::format("%.6g", B_Nm));
  require(std::isfinite(M0_N) && M0_N >= 0.0,
          "frictional couple M0 must be finite and >= 0, got " + base::format("%.6g", M0_N));
  require(std::isfinite(kappa0_1_m) && kappa0_1_m > 0.0,
          "frictional curvature kappa0 must be finite and > 0, got " + base::format("%.6g", kappa0_1_m));
  require(B_Nm + M0_N / kappa0_1_m > 0.0, "frictional law has no stiffness (B = M0 = 0)");
  BendingLaw law;
  law.m_form = Form::frictional;
  law.m_B = B_Nm;
  law.m_M0 = M0_N;
  law.m_kappa0 = kappa0_1_m;
  return law;
}

BendingLaw BendingLaw::cubic(double B_Nm, double C_Nm3) {
  require(std::isfinite(B_Nm) && B_Nm > 0.0, "cubic B must be finite and > 0, got " + base::format("%.6g", B_Nm));
  require(std::isfinite(C_Nm3) && C_Nm3 >= 0.0, "cubic C must be finite and >= 0, got " + base::format("%.6g", C_Nm3));
  BendingLaw law;
  law.m_form = Form::cubic;
  law.m_B = B_Nm;
  law.m_C = C_Nm3;
  return law;
}

BendingLaw BendingLaw::table(std::vector<std::pair<double, double>> points) {
  BendingLaw law;
  law.m_form = Form::table;
  law.m_table = RisingTable(std::move(points), {"bending law", "curvature", "1/m", "moment", "N"});
  return law;
}

double BendingLaw::moment(double kappa) const {
  const double a = std::abs(kappa), sign = kappa < 0.0 ? -1.0 : 1.0;
  switch (m_form) {
    case Form::linear: return m_B * kappa;
    case Form::frictional: return m_B * kappa + m_M0 * std::tanh(kappa / m_kappa0);
    case Form::cubic: return (m_B + m_C * kappa * kappa) * kappa;
    case Form::table: return sign * m_table.value(a);
  }
  return 0.0;
}

double BendingLaw::stiffness(double kappa) const {
  switch (m_form) {
    case Form::linear: return m_B;
    case Form::frictional: {
      const double t = std::tanh(kappa / m_kappa0);
      return m_B + m_M0 / m_kappa0 * (1.0 - t * t);
    }
    case Form::cubic: return m_B + 3.0 * m_C * kappa * kappa;
    case Form::table: return m_table.slope(std::abs(kappa));
  }
  return 0.0;
}

double BendingLaw::energy_density(double kappa) const {
  switch (m_form) {
    case Form::linear: return 0.5 * m_B * kappa * kappa;
    case Form::frictional:
      return 0.5 * m_B * kappa * kappa + m_M0 * m_kappa0 * log_cosh(kappa / m_kappa0);
    case Form::cubic: return (0.5 * m_B + 0.25 * m_C * kappa * kappa) * kappa * kappa;
    case Form::table: return m_table.integral(std::abs(kappa));
  }
  return 0.0;
}

std::string BendingLaw::describe() const {
  switch (m_form) {
    case Form::linear: return "linear: B " + base::format("%.6g", m_B) + " N*m";
    case Form::frictional:
      return "frictional: B " + base::format("%.6g", m_B) + " N*m, M0 " + base::format("%.6g", m_M0) + " N, kappa0 " +
             base::format("%.6g", m_kappa0) + " 1/m";
    case Form::cubic: return "cubic: B " + base::format("%.6g", m_B) + " N*m, C " + base::format("%.6g", m_C) + " N*m^3";
    case Form::table:
      return "table of " + std::to_string(m_table.size()) + " points to " +
             base::format("%.6g", m_table.last_x()) + " 1/m";
  }
  return "";
}

}  // namespace weft::sim
