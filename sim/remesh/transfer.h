#pragma once
// Transfer of per-vertex quantities (positions, velocities, anything) from an old mesh to a new
// mesh of the same material domain: barycentric interpolation in material coordinates (seed 002
// §5.2 f–h does the same through a background grid; here the old mesh itself is the grid).
// Linear in the values and exact for any field affine in (u, v). A new vertex that is an old
// vertex (kept boundary vertices and pins) gets that vertex's values bit for bit.

#include <vector>

#include "sim/remesh/point_locator.h"
#include "sim/remesh/remesh_types.h"

namespace weft::sim::remesh {

// Where each new vertex lies in the old mesh: the old triangle and weights, or, for a kept old
// vertex (new_to_old[i] ≥ 0), that vertex alone (triangle −1, weights unused).
struct TransferMap {
  std::vector<Location> location;  // per new vertex
  std::vector<Index> new_to_old;   // per new vertex: the old vertex it is, or −1
};

// new_to_old may be empty (no vertex kept) or have one entry per new vertex.
TransferMap make_transfer_map(const PointLocator& old_mesh, const Matrix2X& new_material,
                              const std::vector<Index>& new_to_old);

// The old mesh's #V_old×k values, evaluated at the new vertices: #V_new×k. `old_triangles`
// must be the triangles the locator was built on.
MatrixX transfer(const TransferMap& map, const Triangles& old_triangles, const MatrixX& values);

// The same for #V×3 arrays (positions, velocities).
Matrix3X transfer(const TransferMap& map, const Triangles& old_triangles, const Matrix3X& values);

}  // namespace weft::sim::remesh
