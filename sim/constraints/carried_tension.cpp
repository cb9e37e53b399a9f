#include "sim/constraints/carried_tension.h"

#include <algorithm>

namespace weft::sim {

void add_tension_forces(const std::vector<EdgeConstraint>& edges, const Eigen::VectorXd& k,
                        const Matrix3X& x, Matrix3X& forces) {
  if (k.size() == 0) return;
  for (std::size_t e = 0; e < edges.size(); ++e) {
    const EdgeConstraint& c = edges[e];
    const Eigen::RowVector3d f = k[static_cast<Eigen::Index>(e)] * (x.row(c.b) - x.row(c.a));
    forces.row(c.b) -= f;
    forces.row(c.a) += f;
  }
}

void accumulate_tension(const std::vector<EdgeConstraint>& edges, const Eigen::VectorXd& mu,
                        double h_s, Eigen::VectorXd& k) {
  if (mu.size() == 0) return;
  if (k.size() != mu.size()) k = Eigen::VectorXd::Zero(mu.size());
  for (std::size_t e = 0; e < edges.size(); ++e) {
    const auto i = static_cast<Eigen::Index>(e);
    k[i] = std::max(0.0, k[i] + 2.0 * mu[i] / (edges[e].rest_m * h_s * h_s));
  }
}

}  // namespace weft::sim
