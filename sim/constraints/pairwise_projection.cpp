#include "sim/constraints/pairwise_projection.h"

#include <algorithm>

namespace weft::sim {

PairwiseProjection::PairwiseProjection(std::vector<EdgeConstraint> constraints,
                                       Eigen::VectorXd inv_mass, const ProjectionSettings& settings)
    : m_constraints(std::move(constraints)),
      m_inv_mass(std::move(inv_mass)),
      m_inv_mass_made(m_inv_mass),
      m_settings(settings) {}

void PairwiseProjection::set_inverse_masses(const Eigen::VectorXd& inv_mass, bool /*fresh*/) {
  require_held_kept(m_inv_mass_made, inv_mass);
  m_inv_mass = inv_mass;
}

ProjectionResult PairwiseProjection::project(Matrix3X& x) {
  ProjectionResult result;
  const double limit = m_settings.max_stretch;
  for (int sweep = 0; sweep < m_settings.max_iterations; ++sweep) {
    ++result.iterations;
    for (const EdgeConstraint& c : m_constraints) {
      const double wa = m_inv_mass[c.a], wb = m_inv_mass[c.b];
      if (wa + wb == 0.0) continue;  // both ends held
      const Eigen::RowVector3d d = x.row(c.b) - x.row(c.a);
      const double len = d.norm();
      if (len == 0.0) continue;
      const double target = std::clamp(len, (1.0 - limit) * c.rest_m, (1.0 + limit) * c.rest_m);
      if (target == len) continue;
      const Eigen::RowVector3d correction = ((len - target) / (len * (wa + wb))) * d;
      x.row(c.a) += wa * correction;
      x.row(c.b) -= wb * correction;
    }
  }
  result.max_strain = max_edge_strain(m_constraints, x, m_inv_mass);
  result.converged = result.max_strain <= std::max(limit, m_settings.tolerance);
  return result;
}

}  // namespace weft::sim
