#pragma once
// Meshes and deformation maps shared by the remeshing tests.

#include <cmath>
#include <functional>

#include "sim/remesh/remesh_types.h"

namespace weft::sim::remesh::testing {

struct PlainMesh {
  Matrix2X material;
  Triangles triangles;
};

// A size_u × size_v rectangle at (u0, v0), nu × nv vertices (vertex (i, j) is j·nu + i), each
// cell split along the same diagonal: every interior vertex has a point-symmetric ring.
// keep_cell(i, j) = false drops cell (i, j) (holes, notches); vertices of no kept cell remain
// (unused), as in ClothMesh.
inline PlainMesh grid_mesh(double size_u, double size_v, Index nu, Index nv, double u0 = 0.0,
                           double v0 = 0.0,
                           const std::function<bool(Index, Index)>& keep_cell = nullptr) {
  PlainMesh m;
  m.material.resize(nu * nv, 2);
  for (Index j = 0; j < nv; ++j)
    for (Index i = 0; i < nu; ++i)
      m.material.row(j * nu + i) << u0 + size_u * i / (nu - 1), v0 + size_v * j / (nv - 1);
  std::vector<std::array<Index, 3>> tris;
  for (Index j = 0; j + 1 < nv; ++j)
    for (Index i = 0; i + 1 < nu; ++i) {
      if (keep_cell && !keep_cell(i, j)) continue;
      const Index a = j * nu + i, b = a + 1, c = a + nu + 1, d = a + nu;
      tris.push_back({a, b, c});
      tris.push_back({a, c, d});
    }
  m.triangles.resize(static_cast<Eigen::Index>(tris.size()), 3);
  for (size_t t = 0; t < tris.size(); ++t)
    m.triangles.row(static_cast<Eigen::Index>(t)) << tris[t][0], tris[t][1], tris[t][2];
  return m;
}

// World positions x(u, v) of every vertex under a map.
inline Matrix3X deform(const Matrix2X& material, const std::function<Vec3(double, double)>& map) {
  Matrix3X x(material.rows(), 3);
  for (Eigen::Index v = 0; v < material.rows(); ++v)
    x.row(v) = map(material(v, 0), material(v, 1)).transpose();
  return x;
}

// The flat sheet rolled onto a cylinder of radius R whose axis is along v (an isometry).
inline Vec3 on_cylinder(double u, double v, double R) {
  return {R * std::sin(u / R), v, R * (1.0 - std::cos(u / R))};
}

// The flat sheet laid on a sphere of radius R touching the plane z = 0 at the origin, centre
// (0, 0, R), by the azimuthal equidistant map (lengths along meridians kept, parallels
// stretched: the metric is not the identity).
inline Vec3 on_sphere(double u, double v, double R) {
  const double r = std::hypot(u, v), phi = std::atan2(v, u);
  return {R * std::sin(r / R) * std::cos(phi), R * std::sin(r / R) * std::sin(phi),
          R * (1.0 - std::cos(r / R))};
}

// Twice the total material area of a mesh's triangles (signed by orientation).
inline double area2(const Matrix2X& material, const Triangles& triangles) {
  double sum = 0.0;
  for (Eigen::Index t = 0; t < triangles.rows(); ++t) {
    const Vec2 a = material.row(triangles(t, 0)), b = material.row(triangles(t, 1)),
               c = material.row(triangles(t, 2));
    sum += (b - a).x() * (c - a).y() - (b - a).y() * (c - a).x();
  }
  return sum;
}

}  // namespace weft::sim::remesh::testing
