#pragma once
// A flat grid rolled onto a cylinder of curvature κ along the warp (u) or the weft (v), arc
// length preserved: the analytic bend of the hinge tests (bw_continuum_test,
// material_presets_test).
#include <cmath>

#include "sim/grid.h"

namespace weft::sim::test {

// #V×3 positions, metres: material coordinate s along the bend goes to (sin κs / κ, 0,
// (1 − cos κs) / κ), the other one stays straight.
inline Matrix3X bent_into_cylinder(const ClothMesh& mesh, double kappa_1_m, bool along_warp) {
  Matrix3X x = mesh.rest_positions;
  for (Eigen::Index i = 0; i < x.rows(); ++i) {
    const Vec2 uv = mesh.material_coords[static_cast<std::size_t>(i)];
    const double s = along_warp ? uv.x() : uv.y();
    const Vec3 across = along_warp ? Vec3(0, uv.y(), 0) : Vec3(uv.x(), 0, 0);
    const Vec3 along = along_warp ? Vec3::UnitX() : Vec3::UnitY();
    x.row(i) = (across + std::sin(kappa_1_m * s) / kappa_1_m * along +
                (1.0 - std::cos(kappa_1_m * s)) / kappa_1_m * Vec3::UnitZ())
                   .transpose();
  }
  return x;
}

}  // namespace weft::sim::test
