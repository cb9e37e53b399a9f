#pragma once
// Plain arrays of the remeshing module: a triangle mesh of the cloth's
// material domain and per-vertex quantities on it. The module knows nothing of ClothMesh or the
// simulator; the caller copies its arrays in and out.

#include <Eigen/Core>

#include "sim/types.h"

namespace weft::sim::remesh {

// #V×2 material coordinates (u, v) in metres: the flat rest pattern of the cloth.
using Matrix2X = Eigen::Matrix<double, Eigen::Dynamic, 2, Eigen::RowMajor>;
// #T×3 vertex indices of the triangles, 0-based.
using Triangles = Eigen::Matrix<Index, Eigen::Dynamic, 3, Eigen::RowMajor>;
// #V×k per-vertex quantities of any width (positions, velocities, ...).
using MatrixX = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;

}  // namespace weft::sim::remesh
