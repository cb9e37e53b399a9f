#pragma once
// Analytic shapes as RenderMeshes: what obstacles (spheres, planes, boxes, cylinders, capsules)
// are drawn with.

#include <Eigen/Core>
#include <functional>

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

// A box with half extents half_size_m (all > 0), m, centred on center_m and turned by yaw_rad
// about +z (its local x axis along (cos yaw, sin yaw, 0)): six faces of two triangles each,
// counter-clockwise seen from outside, each face with its own four vertices carrying the face's
// outward normal (flat shading). Throws std::invalid_argument for non-finite input or a half
// size ≤ 0.
RenderMesh make_box_mesh(const Eigen::Vector3d& center_m, const Eigen::Vector3d& half_size_m,
                         double yaw_rad);

// A closed finite cylinder of radius_m and full length height_m about the axis (any non-zero
// length) through center_m, its middle: a side of `segments` quads with the exact
// outward radial normals, and two flat caps (a centre vertex and a rim ring each) with normals
// ±axis. Triangles counter-clockwise seen from outside. Throws std::invalid_argument for
// non-finite input, a zero axis, a radius or height ≤ 0, or segments outside 3..4096.
RenderMesh make_cylinder_mesh(const Eigen::Vector3d& center_m, const Eigen::Vector3d& axis,
                              double radius_m, double height_m, int segments = 64);

// A capsule: the points within radius_m of the segment a_m–b_m, drawn as two UV hemispheres of
// rings_per_cap rings (pole included) about a_m and b_m joined by a cylinder band; normals the
// exact outward unit vectors, triangles counter-clockwise seen from outside. a_m = b_m gives a
// sphere (drawn with its axis along +z). Throws std::invalid_argument for non-finite input, a
// radius ≤ 0, segments outside 3..4096 or rings_per_cap outside 1..2048.
RenderMesh make_capsule_mesh(const Eigen::Vector3d& a_m, const Eigen::Vector3d& b_m,
                             double radius_m, int segments = 64, int rings_per_cap = 16);

// A sheet of nu×nv vertices: vertex (i, j), index j·nu + i, at position(u, v) with
// u = i/(nu − 1), v = j/(nv − 1) (metres), uv (u, v); each cell split into the triangles
// (i, j)(i+1, j)(i+1, j+1) and (i, j)(i+1, j+1)(i, j+1), counter-clockwise seen from the side
// ∂p/∂u × ∂p/∂v points to; vertex normals computed. Throws std::invalid_argument unless
// nu, nv ≥ 2 and nu·nv fits 32-bit indices.
RenderMesh make_grid_mesh(int nu, int nv,
                          const std::function<Eigen::Vector3d(double u, double v)>& position);

}  // namespace weft::render
