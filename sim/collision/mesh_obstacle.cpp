// Mesh obstacles: an Embree BVH over the triangles answers closest-point queries
// (rtcPointQuery calls our callback for each triangle whose bounds meet the query sphere; the
// callback computes the exact point–triangle distance in double and shrinks the sphere), and
// the angle-weighted pseudonormal of the closest feature gives the sign (Bærentzen & Aanæs
// 2005, Theorem 1: for a closed, oriented mesh, (p − q)·n_pseudo > 0 exactly when p is outside).

#include "sim/collision/mesh_obstacle.h"

#include <embree3/rtcore.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <map>
#include <stdexcept>
#include <string>
#include <utility>

#include "base/embree.h"
#include "sim/collision/proximity.h"

namespace weft::sim {
namespace {

using GeometryOwner = std::unique_ptr<RTCGeometryTy, decltype(&rtcReleaseGeometry)>;

// The running best of one point query, shared with the Embree callback.
struct Query {
  Vec3 p;                                   // query point, mesh coordinates, m
  const Matrix3X* vertices;
  const std::vector<std::array<Index, 3>>* triangles;
  double margin_m;                          // slack added to the shrunk radius
  double best_d2 = std::numeric_limits<double>::infinity();
  Index best = -1;
  TrianglePoint best_point{Vec3::Zero(), TriangleFeature::face};

  void consider(Index f) {
    const auto& t = (*triangles)[f];
    const TrianglePoint q = closest_point_on_triangle(p, vertices->row(t[0]).transpose(),
                                                      vertices->row(t[1]).transpose(),
                                                      vertices->row(t[2]).transpose());
    const double d2 = (p - q.point).squaredNorm();
    // (distance, index) order: the result is the same whatever order triangles arrive in.
    if (d2 < best_d2 || (d2 == best_d2 && f < best)) {
      best_d2 = d2;
      best = f;
      best_point = q;
    }
  }
};

// rtcPointQuery's callback, once per triangle whose (float) bounds meet the query sphere.
// The radius shrinks to the best distance plus the margin, never below: every triangle within
// the margin of the final best is still visited, so ties are broken by index, not by order.
bool visit_triangle(RTCPointQueryFunctionArguments* args) {
  auto* query = static_cast<Query*>(args->userPtr);
  query->consider(static_cast<Index>(args->primID));
  const double radius = std::sqrt(query->best_d2) + query->margin_m;
  const float radius_f =
      std::nextafter(static_cast<float>(radius), std::numeric_limits<float>::infinity());
  if (radius_f < args->query->radius) {
    args->query->radius = radius_f;
    return true;
  }
  return false;
}

std::string triangle_name(std::size_t f) { return "mesh obstacle: triangle " + std::to_string(f); }

}  // namespace

Vec3 RigidPose::rotate(const Vec3& d) const {
  const double c = std::cos(yaw_rad), s = std::sin(yaw_rad);
  return {c * d.x() - s * d.y(), s * d.x() + c * d.y(), d.z()};
}

Vec3 RigidPose::unrotate(const Vec3& d) const {
  const double c = std::cos(yaw_rad), s = std::sin(yaw_rad);
  return {c * d.x() + s * d.y(), -s * d.x() + c * d.y(), d.z()};
}

RigidPose compose(const RigidPose& outer, const RigidPose& inner) {
  return {outer.rotate(inner.translation_m) + outer.translation_m, outer.yaw_rad + inner.yaw_rad};
}

RigidPose inverse(const RigidPose& pose) {
  return {-pose.unrotate(pose.translation_m), -pose.yaw_rad};
}

TrianglePoint closest_point_on_triangle(const Vec3& p, const Vec3& a, const Vec3& b,
                                        const Vec3& c) {
  // The shared kernel (proximity.h) sets the weights of the corners off the nearest feature to
  // exactly 0, so the feature is read off them.
  const Vec3 w = closest_point_on_triangle_weights(p, a, b, c);
  const Vec3 point = w[0] * a + w[1] * b + w[2] * c;
  const bool on_a = w[0] != 0.0, on_b = w[1] != 0.0, on_c = w[2] != 0.0;
  if (on_a && !on_b && !on_c) return {a, TriangleFeature::vertex_a};
  if (!on_a && on_b && !on_c) return {b, TriangleFeature::vertex_b};
  if (!on_a && !on_b && on_c) return {c, TriangleFeature::vertex_c};
  if (!on_c) return {point, TriangleFeature::edge_ab};
  if (!on_a) return {point, TriangleFeature::edge_bc};
  if (!on_b) return {point, TriangleFeature::edge_ca};
  return {point, TriangleFeature::face};
}

// One build thread (base::EmbreeDevice): the meshes are small and the machine is shared; queries
// run on the caller's thread anyway. The scene is released before its device (member order).
struct MeshSolid::Bvh {
  base::EmbreeDevice device;
  base::EmbreeScene scene{device};
};

MeshSolid::MeshSolid(Matrix3X vertices_m, std::vector<std::array<Index, 3>> triangles)
    : m_vertices_m(std::move(vertices_m)), m_triangles(std::move(triangles)) {
  const Index n = static_cast<Index>(m_vertices_m.rows());
  if (!m_vertices_m.allFinite()) {
    for (Index i = 0; i < n; ++i)
      if (!m_vertices_m.row(i).allFinite())
        throw std::invalid_argument("mesh obstacle: vertex " + std::to_string(i) +
                                    " is not finite");
  }
  if (m_triangles.empty()) throw std::invalid_argument("mesh obstacle: no triangles");
  for (std::size_t f = 0; f < m_triangles.size(); ++f) {
    const auto& t = m_triangles[f];
    for (Index i : t)
      if (i < 0 || i >= n)
        throw std::invalid_argument(triangle_name(f) + " has vertex index " + std::to_string(i) +
                                    ", outside 0.." + std::to_string(n - 1));
    if (t[0] == t[1] || t[1] == t[2] || t[2] == t[0])
      throw std::invalid_argument(triangle_name(f) + " repeats a vertex (" +
                                  std::to_string(t[0]) + ", " + std::to_string(t[1]) + ", " +
                                  std::to_string(t[2]) + ")");
  }

  // Pseudonormals: faces, vertices (angle-weighted), edges (sum of the adjacent faces).
  m_face_normals.assign(m_triangles.size(), Vec3::Zero());
  m_vertex_normals.assign(static_cast<std::size_t>(n), Vec3::Zero());
  m_triangle_edges.resize(m_triangles.size());
  std::map<std::pair<Index, Index>, int> edge_index;
  std::vector<int> edge_uses;
  for (std::size_t f = 0; f < m_triangles.size(); ++f) {
    const auto& t = m_triangles[f];
    const Vec3 x[3] = {m_vertices_m.row(t[0]).transpose(), m_vertices_m.row(t[1]).transpose(),
                       m_vertices_m.row(t[2]).transpose()};
    const Vec3 cross = (x[1] - x[0]).cross(x[2] - x[0]);
    const double length = cross.norm();
    const Vec3 normal = length > 0.0 ? Vec3(cross / length) : Vec3::Zero();
    m_face_normals[f] = normal;
    for (int k = 0; k < 3; ++k) {
      const Vec3 u = x[(k + 1) % 3] - x[k], w = x[(k + 2) % 3] - x[k];
      const double angle = std::atan2(u.cross(w).norm(), u.dot(w));  // interior angle at k
      m_vertex_normals[t[k]] += angle * normal;
      const std::pair<Index, Index> key = std::minmax(t[k], t[(k + 1) % 3]);
      const auto [it, inserted] = edge_index.emplace(key, static_cast<int>(edge_uses.size()));
      if (inserted) {
        edge_uses.push_back(0);
        m_edge_normals.push_back(Vec3::Zero());
      }
      ++edge_uses[it->second];
      m_edge_normals[it->second] += normal;
      m_triangle_edges[f][k] = it->second;
    }
  }
  for (int uses : edge_uses) {
    if (uses == 1) ++m_border_edges;
    if (uses > 2) ++m_non_manifold_edges;
  }

  // The BVH is built from float copies of the vertices, so its bounds and the float query
  // point are off by about 6e-8 of the coordinates: the margin keeps those triangles in.
  m_query_margin_m = 1e-5 * m_vertices_m.cwiseAbs().maxCoeff();

  m_bvh = std::make_unique<Bvh>();
  base::EmbreeDevice& device = m_bvh->device;
  GeometryOwner geometry(rtcNewGeometry(device.get(), RTC_GEOMETRY_TYPE_TRIANGLE),
                         &rtcReleaseGeometry);
  device.check("creating the triangle geometry");
  auto* vertex = static_cast<float*>(rtcSetNewGeometryBuffer(
      geometry.get(), RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3, 3 * sizeof(float),
      static_cast<std::size_t>(n)));
  auto* index = static_cast<std::uint32_t*>(
      rtcSetNewGeometryBuffer(geometry.get(), RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3,
                              3 * sizeof(std::uint32_t), m_triangles.size()));
  device.check("allocating the mesh buffers");
  for (Index i = 0; i < n; ++i)
    for (int k = 0; k < 3; ++k) vertex[3 * i + k] = static_cast<float>(m_vertices_m(i, k));
  for (std::size_t f = 0; f < m_triangles.size(); ++f)
    for (int k = 0; k < 3; ++k) index[3 * f + k] = static_cast<std::uint32_t>(m_triangles[f][k]);
  rtcCommitGeometry(geometry.get());
  rtcAttachGeometry(m_bvh->scene.get(), geometry.get());
  m_bvh->scene.commit(device);
}

MeshSolid::~MeshSolid() = default;

Vec3 MeshSolid::pseudonormal(Index f, TriangleFeature feature) const {
  const auto& t = m_triangles[f];
  switch (feature) {
    case TriangleFeature::vertex_a: return m_vertex_normals[t[0]];
    case TriangleFeature::vertex_b: return m_vertex_normals[t[1]];
    case TriangleFeature::vertex_c: return m_vertex_normals[t[2]];
    case TriangleFeature::edge_ab: return m_edge_normals[m_triangle_edges[f][0]];
    case TriangleFeature::edge_bc: return m_edge_normals[m_triangle_edges[f][1]];
    case TriangleFeature::edge_ca: return m_edge_normals[m_triangle_edges[f][2]];
    case TriangleFeature::face: break;
  }
  return m_face_normals[f];
}

MeshPoint MeshSolid::closest_point(const Vec3& p) const {
  Query query{p, &m_vertices_m, &m_triangles, m_query_margin_m + 1e-5 * p.cwiseAbs().maxCoeff()};
  RTCPointQuery sphere;
  sphere.x = static_cast<float>(p.x());
  sphere.y = static_cast<float>(p.y());
  sphere.z = static_cast<float>(p.z());
  sphere.time = 0.0f;
  sphere.radius = std::numeric_limits<float>::infinity();
  RTCPointQueryContext context;
  rtcInitPointQueryContext(&context);
  rtcPointQuery(m_bvh->scene.get(), &sphere, &context, &visit_triangle, &query);
  if (query.best < 0) {  // not expected (a non-finite p): look at every triangle
    for (std::size_t f = 0; f < m_triangles.size(); ++f) query.consider(static_cast<Index>(f));
    if (query.best < 0)
      return {p, Vec3::UnitZ(), std::numeric_limits<double>::quiet_NaN(), -1};
  }
  const Vec3& q = query.best_point.point;
  const Vec3 n = pseudonormal(query.best, query.best_point.feature);
  const double distance = std::sqrt(query.best_d2);
  if (distance > 0.0) {
    const Vec3 away = (p - q) / distance;
    const bool inside = away.dot(n) < 0.0;
    return {q, inside ? Vec3(-away) : away, inside ? -distance : distance, query.best};
  }
  const double length = n.norm();
  Vec3 normal = length > 0.0 ? Vec3(n / length) : m_face_normals[query.best];
  if (!(normal.squaredNorm() > 0.0)) normal = Vec3::UnitZ();
  return {q, normal, 0.0, query.best};
}

double signed_distance(const MeshObstacle& mesh, const Vec3& p) {
  return mesh.solid->signed_distance(mesh.pose.apply_inverse(p));
}

SurfacePoint closest_surface_point(const MeshObstacle& mesh, const Vec3& p) {
  const MeshPoint q = mesh.solid->closest_point(mesh.pose.apply_inverse(p));
  return {mesh.pose.apply(q.point_m), mesh.pose.rotate(q.normal)};
}

}  // namespace weft::sim
