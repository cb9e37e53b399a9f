#pragma once
// Shared Eigen aliases: one storage layout for per-vertex data.

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <cstdint>
#include <vector>

namespace weft::sim {

using Vec2 = Eigen::Vector2d;
using Vec3 = Eigen::Vector3d;
using Mat3 = Eigen::Matrix3d;
// #V×3 per-vertex vectors (positions in m, velocities in m/s, forces in N), row-major so that a
// vertex's x, y, z are contiguous and the whole block maps to a 3#V vector.
using Matrix3X = Eigen::Matrix<double, Eigen::Dynamic, 3, Eigen::RowMajor>;
using Index = std::int32_t;

// Vertex v of a #V×3 block, as a column vector.
inline Vec3 vertex(const Matrix3X& x, Index v) { return x.row(v).transpose(); }

}  // namespace weft::sim
