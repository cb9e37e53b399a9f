// The 3D Chamfer distance (see chamfer_3d.h).

#include "app/fit/chamfer_3d.h"

#include <cmath>
#include <limits>
#include <stdexcept>
#include <vector>

namespace weft::app {

Chamfer3d chamfer_3d(const Points& a, const Points& b) {
  if (a.rows() == 0 || b.rows() == 0) throw std::invalid_argument("3D Chamfer distance: a point set is empty");
  std::vector<double> b_nearest(static_cast<std::size_t>(b.rows()),
                                std::numeric_limits<double>::infinity());
  double a_sum = 0.0;
  for (Eigen::Index i = 0; i < a.rows(); ++i) {
    double nearest = std::numeric_limits<double>::infinity();
    for (Eigen::Index j = 0; j < b.rows(); ++j) {
      const double d2 = (a.row(i) - b.row(j)).squaredNorm();
      nearest = std::min(nearest, d2);
      double& bj = b_nearest[static_cast<std::size_t>(j)];
      bj = std::min(bj, d2);
    }
    a_sum += std::sqrt(nearest);
  }
  double b_sum = 0.0;
  for (const double d2 : b_nearest) b_sum += std::sqrt(d2);
  Chamfer3d c;
  c.a_to_b_m = a_sum / static_cast<double>(a.rows());
  c.b_to_a_m = b_sum / static_cast<double>(b.rows());
  c.symmetric_m = 0.5 * (c.a_to_b_m + c.b_to_a_m);
  return c;
}

Points cloth_points(const sim::ClothMesh& mesh, const sim::Matrix3X& x) {
  std::vector<sim::Index> used;
  for (sim::Index v = 0; v < mesh.vertex_count(); ++v)
    if (mesh.is_used(v)) used.push_back(v);
  Points p(static_cast<Eigen::Index>(used.size()), 3);
  for (std::size_t k = 0; k < used.size(); ++k) p.row(static_cast<Eigen::Index>(k)) = x.row(used[k]);
  return p;
}

}  // namespace weft::app
