#pragma once
// Iterative pairwise projection: Provot's maximum stretch (seed 003, "Improvements") as a
// Gauss–Seidel sweep over the edges (position-based dynamics). Each edge whose strain lies
// outside [−max_stretch, +max_stretch] has its two ends moved along the edge, in proportion to
// their inverse masses, back to the limit; a fixed number of sweeps per step. Cheap per sweep,
// but information travels one edge per sweep, so long cloth converges slowly: that is the
// trade weft measures against fast projection.

#include "sim/constraints/projection.h"

namespace weft::sim {

class PairwiseProjection final : public ConstraintProjector {
 public:
  PairwiseProjection(std::vector<EdgeConstraint> constraints, Eigen::VectorXd inv_mass,
                     const ProjectionSettings& settings);
  ProjectionResult project(Matrix3X& x) override;
  const std::vector<EdgeConstraint>& constraints() const override { return m_constraints; }
  void set_inverse_masses(const Eigen::VectorXd& inv_mass, bool fresh) override;
  // Nothing carries over from one step to the next: an empty section.
  void save_state(StateWriter& out) const override { out.section("pairwise projection"); }
  void restore_state(StateReader& in) override { in.section("pairwise projection"); }

 private:
  std::vector<EdgeConstraint> m_constraints;
  Eigen::VectorXd m_inv_mass;
  Eigen::VectorXd m_inv_mass_made;  // at construction: its held vertices stay held
  ProjectionSettings m_settings;
};

}  // namespace weft::sim
