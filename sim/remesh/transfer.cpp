#include "sim/remesh/transfer.h"

#include "base/check.h"

namespace weft::sim::remesh {

TransferMap make_transfer_map(const PointLocator& old_mesh, const Matrix2X& new_material,
                              const std::vector<Index>& new_to_old) {
  const auto n = static_cast<size_t>(new_material.rows());
  WEFT_CHECK(new_to_old.empty() || new_to_old.size() == n, "new_to_old has the wrong size");
  TransferMap map;
  map.location.resize(n);
  map.new_to_old = new_to_old.empty() ? std::vector<Index>(n, -1) : new_to_old;
  for (size_t i = 0; i < n; ++i)
    if (map.new_to_old[i] < 0)
      map.location[i] = old_mesh.locate(new_material.row(static_cast<Eigen::Index>(i)));
  return map;
}

namespace {

template <class Matrix>
Matrix transfer_rows(const TransferMap& map, const Triangles& old_triangles, const Matrix& values) {
  const auto n = static_cast<Eigen::Index>(map.location.size());
  Matrix out(n, values.cols());
  for (Eigen::Index i = 0; i < n; ++i) {
    const Index old = map.new_to_old[static_cast<size_t>(i)];
    if (old >= 0) {
      WEFT_CHECK(old < values.rows(), "kept vertex beyond the old values");
      out.row(i) = values.row(old);
      continue;
    }
    const Location& at = map.location[static_cast<size_t>(i)];
    WEFT_CHECK(at.triangle >= 0 && at.triangle < old_triangles.rows(), "vertex not located");
    out.row(i) = at.barycentric[0] * values.row(old_triangles(at.triangle, 0)) +
                 at.barycentric[1] * values.row(old_triangles(at.triangle, 1)) +
                 at.barycentric[2] * values.row(old_triangles(at.triangle, 2));
  }
  return out;
}

}  // namespace

MatrixX transfer(const TransferMap& map, const Triangles& old_triangles, const MatrixX& values) {
  return transfer_rows(map, old_triangles, values);
}

Matrix3X transfer(const TransferMap& map, const Triangles& old_triangles, const Matrix3X& values) {
  return transfer_rows(map, old_triangles, values);
}

}  // namespace weft::sim::remesh
