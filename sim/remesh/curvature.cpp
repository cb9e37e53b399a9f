#include "sim/remesh/curvature.h"

#include <Eigen/QR>
#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "base/check.h"
#include "sim/remesh/mesh_topology.h"

namespace weft::sim::remesh {

Eigen::Vector2d principal_curvatures(const Eigen::Matrix2d& first_form,
                                     const Eigen::Matrix2d& second_form) {
  const Eigen::Matrix2d& I = first_form;
  const Eigen::Matrix2d& II = second_form;
  const double det_I = I.determinant();
  WEFT_CHECK(det_I > 0.0, "first fundamental form not positive definite");
  // det(II − κ I) = 0: κ² det I − κ (I11 II22 + I22 II11 − 2 I12 II12) + det II = 0.
  const double mean =
      (I(0, 0) * II(1, 1) + I(1, 1) * II(0, 0) - 2.0 * I(0, 1) * II(0, 1)) / (2.0 * det_I);
  const double gauss = II.determinant() / det_I;
  const double root = std::sqrt(std::max(mean * mean - gauss, 0.0));
  return {mean + root, mean - root};
}

namespace {

// The vertices within `rings` edges of v, v itself excluded, sorted.
std::vector<Index> stencil(const std::vector<std::vector<Index>>& neighbours, Index v, int rings) {
  std::vector<Index> found{v};
  std::vector<Index> front{v};
  for (int r = 0; r < rings; ++r) {
    std::vector<Index> next;
    for (Index f : front)
      for (Index w : neighbours[static_cast<size_t>(f)])
        if (std::find(found.begin(), found.end(), w) == found.end()) {
          found.push_back(w);
          next.push_back(w);
        }
    front = std::move(next);
  }
  found.erase(found.begin());
  std::sort(found.begin(), found.end());
  return found;
}

// I = JᵀJ of a patch.
Eigen::Matrix2d patch_first_form(const VertexPatch& p) {
  Eigen::Matrix2d I;
  I << p.x_u.dot(p.x_u), p.x_u.dot(p.x_v), p.x_u.dot(p.x_v), p.x_v.dot(p.x_v);
  return I;
}

// The quadratic Taylor patch at vertex v fitted over `points` (invalid when the fit is
// rank-deficient or the fitted surface has no normal at v).
VertexPatch fitted_patch(const Matrix2X& material, const Matrix3X& positions, Index v,
                         const std::vector<Index>& points) {
  constexpr int kUnknowns = 5;  // x_u, x_v, ½x_uu, x_uv, ½x_vv per world component
  VertexPatch patch;
  if (static_cast<int>(points.size()) < kUnknowns) return patch;
  const Vec2 origin = material.row(v);
  double scale = 0.0;
  for (Index k : points) scale = std::max(scale, (Vec2(material.row(k)) - origin).norm());
  // Columns in units of the stencil radius, so the least-squares problem is well scaled.
  Eigen::MatrixXd A(points.size(), kUnknowns);
  Eigen::MatrixXd b(points.size(), 3);
  for (size_t r = 0; r < points.size(); ++r) {
    const Vec2 d = (Vec2(material.row(points[r])) - origin) / scale;
    A.row(static_cast<Eigen::Index>(r)) << d.x(), d.y(), d.x() * d.x(), d.x() * d.y(),
        d.y() * d.y();
    b.row(static_cast<Eigen::Index>(r)) = positions.row(points[r]) - positions.row(v);
  }
  Eigen::ColPivHouseholderQR<Eigen::MatrixXd> qr(A);
  qr.setThreshold(1e-8);
  if (qr.rank() < kUnknowns) return patch;
  const Eigen::MatrixXd c = qr.solve(b);  // 5×3, rows in scaled parameters
  patch.x_u = c.row(0).transpose() / scale;
  patch.x_v = c.row(1).transpose() / scale;
  patch.x_uu = 2.0 * c.row(2).transpose() / (scale * scale);
  patch.x_uv = c.row(3).transpose() / (scale * scale);
  patch.x_vv = 2.0 * c.row(4).transpose() / (scale * scale);
  patch.valid =
      patch.x_u.cross(patch.x_v).norm() > 0.0 && patch_first_form(patch).determinant() > 0.0;
  return patch;
}

}  // namespace

double patch_curvature(const VertexPatch& p) {
  if (!p.valid) return 0.0;
  const Vec3 n = p.x_u.cross(p.x_v).normalized();
  Eigen::Matrix2d II;
  II << n.dot(p.x_uu), n.dot(p.x_uv), n.dot(p.x_uv), n.dot(p.x_vv);
  const Eigen::Vector2d k = principal_curvatures(patch_first_form(p), II);
  return std::max(std::abs(k(0)), std::abs(k(1)));
}

Eigen::VectorXd patch_curvatures(const std::vector<VertexPatch>& patches) {
  Eigen::VectorXd kappa(static_cast<Eigen::Index>(patches.size()));
  for (size_t v = 0; v < patches.size(); ++v)
    kappa(static_cast<Eigen::Index>(v)) = patch_curvature(patches[v]);
  return kappa;
}

std::vector<VertexPatch> vertex_patches(const Matrix2X& material, const Triangles& triangles,
                                        const Matrix3X& positions) {
  check_mesh(material, triangles, "curvature");
  if (positions.rows() != material.rows())
    throw std::invalid_argument("curvature: " + std::to_string(positions.rows()) +
                                " positions for " + std::to_string(material.rows()) + " vertices");
  const Index nv = static_cast<Index>(material.rows());
  const auto neighbours = vertex_neighbours(nv, triangles);
  std::vector<VertexPatch> patches(static_cast<size_t>(nv));
  for (Index v = 0; v < nv; ++v) {
    if (neighbours[static_cast<size_t>(v)].empty()) continue;  // a vertex of no triangle
    // Two rings; three where a corner's two-ring is too small for the fit.
    for (int rings = 2; rings <= 3; ++rings) {
      VertexPatch p = fitted_patch(material, positions, v, stencil(neighbours, v, rings));
      if (p.valid) {
        patches[static_cast<size_t>(v)] = p;
        break;
      }
    }
  }
  return patches;
}

Eigen::VectorXd vertex_curvature(const Matrix2X& material, const Triangles& triangles,
                                 const Matrix3X& positions) {
  return patch_curvatures(vertex_patches(material, triangles, positions));
}

}  // namespace weft::sim::remesh
