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

Matrix3X transfer_quadratic(const TransferMap& map, const Matrix2X& old_material,
                            const Triangles& old_triangles, const Matrix3X& positions,
                            const SecondDerivatives& second_derivatives) {
  WEFT_CHECK(second_derivatives.rows() == positions.rows() &&
                 old_material.rows() == positions.rows(),
             "one second derivative and one material point per old vertex");
  Matrix3X out = transfer_rows(map, old_triangles, positions);
  for (Eigen::Index n = 0; n < out.rows(); ++n) {
    if (map.new_to_old[static_cast<size_t>(n)] >= 0) continue;  // a kept vertex: copied
    const Location& at = map.location[static_cast<size_t>(n)];
    Vec3 correction = Vec3::Zero();
    for (int k = 0; k < 3; ++k) {
      const Index i = old_triangles(at.triangle, k), j = old_triangles(at.triangle, (k + 1) % 3);
      const Vec2 E = Vec2(old_material.row(j)) - Vec2(old_material.row(i));
      // The edge's H: the mean of its two ends', so that a point on the edge gets the same
      // correction from both of its triangles.
      const auto H = 0.5 * (second_derivatives.row(i) + second_derivatives.row(j));
      correction += at.barycentric[static_cast<size_t>(k)] *
                    at.barycentric[static_cast<size_t>((k + 1) % 3)] *
                    (H.segment<3>(0).transpose() * (E.x() * E.x()) +
                     H.segment<3>(3).transpose() * (2.0 * E.x() * E.y()) +
                     H.segment<3>(6).transpose() * (E.y() * E.y()));
    }
    out.row(n) -= 0.5 * correction.transpose();
  }
  return out;
}

}  // namespace weft::sim::remesh
