#include "sim/bending_law.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "sim/material.h"

namespace weft::sim {
namespace {

void require(bool ok, const std::string& what) {
  if (!ok) throw MaterialError("bending law: " + what);
}

std::string number(double v) {
  char text[32];
  std::snprintf(text, sizeof text, "%.6g", v);
  return text;
}

// ln cosh(t) for any t without overflow: |t| + ln((1 + e^{−2|t|}) / 2).
double log_cosh(double t) {
  const double a = std::abs(t);
  return a + std::log1p(std::exp(-2.0 * a)) - std::log(2.0);
}

}  // namespace

BendingLaw BendingLaw::linear(double B_Nm) {
  require(std::isfinite(B_Nm) && B_Nm > 0.0, "linear B must be finite and > 0, got " + number(B_Nm));
  BendingLaw law;
  law.m_B = B_Nm;
  return law;
}

BendingLaw BendingLaw::frictional(double B_Nm, double M0_N, double kappa0_1_m) {
  require(std::isfinite(B_Nm) && B_Nm >= 0.0, "frictional B must be finite and >= 0, got " + number(B_Nm));
  require(std::isfinite(M0_N) && M0_N >= 0.0,
          "frictional couple M0 must be finite and >= 0, got " + number(M0_N));
  require(std::isfinite(kappa0_1_m) && kappa0_1_m > 0.0,
          "frictional curvature kappa0 must be finite and > 0, got " + number(kappa0_1_m));
  require(B_Nm + M0_N / kappa0_1_m > 0.0, "frictional law has no stiffness (B = M0 = 0)");
  BendingLaw law;
  law.m_form = Form::frictional;
  law.m_B = B_Nm;
  law.m_M0 = M0_N;
  law.m_kappa0 = kappa0_1_m;
  return law;
}

BendingLaw BendingLaw::cubic(double B_Nm, double C_Nm3) {
  require(std::isfinite(B_Nm) && B_Nm > 0.0, "cubic B must be finite and > 0, got " + number(B_Nm));
  require(std::isfinite(C_Nm3) && C_Nm3 >= 0.0, "cubic C must be finite and >= 0, got " + number(C_Nm3));
  BendingLaw law;
  law.m_form = Form::cubic;
  law.m_B = B_Nm;
  law.m_C = C_Nm3;
  return law;
}

BendingLaw BendingLaw::table(std::vector<std::pair<double, double>> points) {
  require(!points.empty(), "a table needs at least one (curvature, moment) point");
  BendingLaw law;
  law.m_form = Form::table;
  law.m_points.emplace_back(0.0, 0.0);
  for (std::size_t k = 0; k < points.size(); ++k) {
    const auto [kappa, M] = points[k];
    const auto [kappa_prev, M_prev] = law.m_points.back();
    const std::string where = "table point " + std::to_string(k + 1) + " (" + number(kappa) +
                              " 1/m, " + number(M) + " N)";
    require(std::isfinite(kappa) && std::isfinite(M), where + ": not finite");
    require(kappa > kappa_prev, where + ": curvatures must increase from 0");
    require(M > M_prev, where + ": moments must increase from 0 (a bending curve that does not "
                                "rise has no stable shape)");
    law.m_points.emplace_back(kappa, M);
  }
  law.m_energy_at.push_back(0.0);
  for (std::size_t k = 1; k < law.m_points.size(); ++k) {
    const auto [k0, m0] = law.m_points[k - 1];
    const auto [k1, m1] = law.m_points[k];
    law.m_energy_at.push_back(law.m_energy_at.back() + 0.5 * (m0 + m1) * (k1 - k0));
  }
  return law;
}

std::size_t BendingLaw::segment(double kappa) const {
  // The first point with curvature > κ closes the segment; beyond the table, the last segment.
  const auto it = std::upper_bound(m_points.begin(), m_points.end(), kappa,
                                   [](double k, const auto& p) { return k < p.first; });
  const std::size_t end = static_cast<std::size_t>(it - m_points.begin());
  return std::clamp<std::size_t>(end, 1, m_points.size() - 1) - 1;
}

double BendingLaw::moment(double kappa) const {
  const double a = std::abs(kappa), sign = kappa < 0.0 ? -1.0 : 1.0;
  switch (m_form) {
    case Form::linear: return m_B * kappa;
    case Form::frictional: return m_B * kappa + m_M0 * std::tanh(kappa / m_kappa0);
    case Form::cubic: return (m_B + m_C * kappa * kappa) * kappa;
    case Form::table: {
      const std::size_t s = segment(a);
      const auto [k0, m0] = m_points[s];
      return sign * (m0 + stiffness(a) * (a - k0));
    }
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
    case Form::table: {
      const std::size_t s = segment(std::abs(kappa));
      const auto [k0, m0] = m_points[s];
      const auto [k1, m1] = m_points[s + 1];
      return (m1 - m0) / (k1 - k0);
    }
  }
  return 0.0;
}

double BendingLaw::energy_density(double kappa) const {
  switch (m_form) {
    case Form::linear: return 0.5 * m_B * kappa * kappa;
    case Form::frictional:
      return 0.5 * m_B * kappa * kappa + m_M0 * m_kappa0 * log_cosh(kappa / m_kappa0);
    case Form::cubic: return (0.5 * m_B + 0.25 * m_C * kappa * kappa) * kappa * kappa;
    case Form::table: {
      const double a = std::abs(kappa);
      const std::size_t s = segment(a);
      const auto [k0, m0] = m_points[s];
      const double d = a - k0;
      return m_energy_at[s] + m0 * d + 0.5 * stiffness(a) * d * d;
    }
  }
  return 0.0;
}

std::string BendingLaw::describe() const {
  switch (m_form) {
    case Form::linear: return "linear: B " + number(m_B) + " N*m";
    case Form::frictional:
      return "frictional: B " + number(m_B) + " N*m, M0 " + number(m_M0) + " N, kappa0 " +
             number(m_kappa0) + " 1/m";
    case Form::cubic: return "cubic: B " + number(m_B) + " N*m, C " + number(m_C) + " N*m^3";
    case Form::table:
      return "table of " + std::to_string(m_points.size() - 1) + " points to " +
             number(m_points.back().first) + " 1/m";
  }
  return "";
}

}  // namespace weft::sim
