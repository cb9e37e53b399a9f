#pragma once
// Analytic shapes as RenderMeshes: what obstacles (spheres, planes) are drawn with.

#include <Eigen/Core>

#include "render/render_mesh.h"

namespace weft::render {

// A UV sphere: a vertex at each pole and rings − 1 rings of `segments` vertices between;
// triangles counter-clockwise seen from outside, normals the exact outward unit vectors.
// centre_m and radius_m in metres; segments ≥ 3 around, rings ≥ 2 from pole to pole.
// Throws std::invalid_argument for a non-finite centre, a radius not finite and > 0, or too
// few segments or rings.
RenderMesh make_sphere_mesh(const Eigen::Vector3d& center_m, double radius_m, int segments = 64,
                            int rings = 32);

// A square of side 2·half_size_m centred on center_m in the plane with the given normal (any
// non-zero length): two triangles, counter-clockwise seen from the side the normal points to,
// every vertex normal the unit normal. Throws std::invalid_argument for non-finite input, a
// zero normal or half_size_m ≤ 0.
RenderMesh make_square_patch(const Eigen::Vector3d& center_m, const Eigen::Vector3d& normal,
                             double half_size_m);

}  // namespace weft::render
