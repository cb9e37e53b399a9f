#pragma once
// The 3D Chamfer distance between two point sets (a settled cloth's vertices and a depth
// camera's point cloud, for weft fit): the mean distance from each point of one set to the nearest
// point of the other, in both directions, and their mean. Brute force, O(#a · #b): meant for
// clouds of thousands of points against a cloth of about a thousand vertices.

#include <Eigen/Core>

#include "sim/grid.h"
#include "sim/types.h"

namespace weft::app {

using Points = Eigen::Matrix<double, Eigen::Dynamic, 3, Eigen::RowMajor>;  // #N×3, metres

struct Chamfer3d {
  double a_to_b_m = 0.0, b_to_a_m = 0.0;
  double symmetric_m = 0.0;  // (a_to_b + b_to_a) / 2
};

// Throws std::invalid_argument when a set is empty.
Chamfer3d chamfer_3d(const Points& a, const Points& b);

// The used vertices of `mesh` at positions x (#V×3, m), as points.
Points cloth_points(const sim::ClothMesh& mesh, const sim::Matrix3X& x);

}  // namespace weft::app
