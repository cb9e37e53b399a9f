#pragma once
// A closed triangle mesh as a rigid solid obstacle: exact closest surface points through an
// Embree BVH (rtcPointQuery with our own point–triangle distance), and the inside/outside sign
// from the angle-weighted pseudonormal of the closest feature (Bærentzen & Aanæs 2005, "Signed
// distance computation using the angle weighted pseudonormal", IEEE TVCG 11(3)).
//
// The mesh must be CLOSED (every edge shared by exactly two triangles) and CONSISTENTLY
// ORIENTED with outward normals (triangles counter-clockwise seen from outside). Then the
// signed distance is exact (up to rounding) everywhere. Otherwise the unsigned distance and the
// closest point are still exact, but the sign is only local: a point counts as inside when it
// lies behind the pseudonormal of its closest feature. An open sheet then acts as a one-sided
// wall (its back side is "inside", which is wrong past its border edges), and a flipped
// triangle makes the region in front of it count as inside, so the cloth is pushed into it.

#include <array>
#include <memory>
#include <vector>

#include "sim/collision/obstacle_shapes.h"
#include "sim/types.h"

namespace weft::sim {

// A rotation by yaw_rad about +z followed by a translation: x ↦ Rz(yaw)·x + translation_m.
// Places a mesh in the world, and is the pose of a moving obstacle (obstacle_motion.h).
struct RigidPose {
  Vec3 translation_m{0.0, 0.0, 0.0};
  double yaw_rad = 0.0;  // counter-clockwise seen from above

  Vec3 rotate(const Vec3& direction) const;    // Rz(yaw)·direction
  Vec3 unrotate(const Vec3& direction) const;  // Rz(−yaw)·direction
  Vec3 apply(const Vec3& x) const { return rotate(x) + translation_m; }
  Vec3 apply_inverse(const Vec3& x) const { return unrotate(x - translation_m); }
};

// outer ∘ inner: x ↦ outer.apply(inner.apply(x)).
RigidPose compose(const RigidPose& outer, const RigidPose& inner);
// The pose p⁻¹ with p⁻¹.apply(p.apply(x)) = x.
RigidPose inverse(const RigidPose& pose);

// The triangle features a closest point can lie on.
enum class TriangleFeature { vertex_a, vertex_b, vertex_c, edge_ab, edge_bc, edge_ca, face };

struct TrianglePoint {
  Vec3 point;
  TriangleFeature feature;
};

// The point of triangle abc nearest p, and the feature (vertex, edge or interior) it lies on,
// by the triangle's Voronoi regions (closest_point_on_triangle_weights, proximity.h). A
// degenerate (zero-area) triangle gives the nearest point of its longest edge.
TrianglePoint closest_point_on_triangle(const Vec3& p, const Vec3& a, const Vec3& b, const Vec3& c);

// The closest surface point of a mesh solid to a query point.
struct MeshPoint {
  Vec3 point_m;            // nearest surface point
  Vec3 normal;             // outward unit normal there, as SurfacePoint (see closest_point)
  double signed_distance_m;  // |p − point|, negative inside
  Index triangle;          // the triangle it lies on (the lowest index among equally near ones)
};

// An immutable triangle mesh with its BVH. Owns an Embree device and scene (one thread, built
// once in the constructor, released in the destructor); not copyable: share it through
// std::shared_ptr<const MeshSolid>. Queries are const and deterministic.
class MeshSolid {
 public:
  // vertices_m: #V×3 positions, m; triangles: #F index triples into them, counter-clockwise
  // seen from outside. Throws std::invalid_argument unless every vertex is finite, there is
  // at least one triangle, and every triangle has three distinct indices in 0..#V−1. Zero-area
  // triangles (distinct but collinear vertices) are allowed and contribute no normal.
  MeshSolid(Matrix3X vertices_m, std::vector<std::array<Index, 3>> triangles);
  ~MeshSolid();
  MeshSolid(const MeshSolid&) = delete;
  MeshSolid& operator=(const MeshSolid&) = delete;

  const Matrix3X& vertices_m() const { return m_vertices_m; }
  const std::vector<std::array<Index, 3>>& triangles() const { return m_triangles; }
  // Edges used by one triangle only (0 for a closed mesh), and by more than two.
  int border_edge_count() const { return m_border_edges; }
  int non_manifold_edge_count() const { return m_non_manifold_edges; }

  // The exact nearest surface point to p (m, in the mesh's coordinates). Among triangles at
  // exactly the same distance the lowest index wins, whatever the BVH's traversal order. The
  // normal: outside, (p − point)/|p − point| (the signed distance's gradient); inside,
  // (point − p)/|point − p|; on the surface, the closest feature's pseudonormal.
  MeshPoint closest_point(const Vec3& p) const;
  double signed_distance(const Vec3& p) const { return closest_point(p).signed_distance_m; }

 private:
  struct Bvh;  // the Embree device and scene (mesh_obstacle.cpp)
  Matrix3X m_vertices_m;
  std::vector<std::array<Index, 3>> m_triangles;
  std::vector<Vec3> m_face_normals;    // #F unit normals (zero for a zero-area triangle)
  std::vector<Vec3> m_vertex_normals;  // #V angle-weighted pseudonormals (Σ angle · face normal)
  std::vector<Vec3> m_edge_normals;    // per edge: Σ of its triangles' normals
  std::vector<std::array<int, 3>> m_triangle_edges;  // #F: edges ab, bc, ca as indices
  int m_border_edges = 0;
  int m_non_manifold_edges = 0;
  double m_query_margin_m = 0.0;  // absolute slack of the BVH's float bounds (see .cpp)
  std::unique_ptr<Bvh> m_bvh;

  Vec3 pseudonormal(Index triangle, TriangleFeature feature) const;
};

// A mesh solid placed in the world: world = pose.apply(mesh coordinates). Copies share the
// solid. Pushed out of like a box (obstacle.h): closest surface point + thickness · normal.
struct MeshObstacle {
  std::shared_ptr<const MeshSolid> solid;  // not null
  RigidPose pose;
};

// Signed distance from p (m) to the surface, positive outside, m.
double signed_distance(const MeshObstacle& mesh, const Vec3& p);
// The closest surface point to p and the outward normal there (MeshSolid::closest_point).
SurfacePoint closest_surface_point(const MeshObstacle& mesh, const Vec3& p);

}  // namespace weft::sim
