#pragma once
// Point location in the material domain of a triangle mesh: which triangle holds (u, v), and
// its barycentric coordinates there. A uniform grid of buckets over the bounding box; each
// bucket lists the triangles whose (slightly widened) bounding box meets it. Points on an edge
// or a vertex, inside or on the boundary, find a triangle that holds them; a point a rounding
// error outside the domain gets the triangle it is closest to being inside.

#include <array>
#include <vector>

#include "sim/remesh/remesh_types.h"

namespace weft::sim::remesh {

struct Location {
  Index triangle = -1;                  // −1: not in the domain (contains() only)
  std::array<double, 3> barycentric{};  // weights of the triangle's vertices, summing to 1
};

class PointLocator {
 public:
  // Keeps references to material and triangles: they must outlive the locator.
  PointLocator(const Matrix2X& material, const Triangles& triangles);

  // The triangle holding p, with barycentric weights (which may be a rounding error below 0 for
  // a point on the boundary; they are never clamped, so an affine field is reproduced exactly).
  // A point outside the domain gets the triangle whose smallest weight is largest among those
  // of its bucket, or, when its bucket is empty, among all triangles. A non-finite p throws
  // std::invalid_argument.
  Location locate(const Vec2& p) const;

  // Whether p lies in the closed domain, to a tolerance of 1e-10 of the local triangle's size.
  bool contains(const Vec2& p) const;

  // Barycentric weights of p in triangle t (unclamped).
  std::array<double, 3> barycentric(Index t, const Vec2& p) const;

 private:
  Location best_of(const Index* begin, const Index* end, const Vec2& p) const;
  Index bucket_of(const Vec2& p) const;

  const Matrix2X& m_material;
  const Triangles& m_triangles;
  Vec2 m_origin;
  double m_cell = 1.0;
  Index m_nx = 1, m_ny = 1;
  std::vector<Index> m_bucket_start;  // CSR: bucket b holds m_bucket_items[start[b], start[b+1])
  std::vector<Index> m_bucket_items;
};

}  // namespace weft::sim::remesh
