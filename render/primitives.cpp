// Sphere and square-patch meshes for drawing analytic obstacles.

#include "render/primitives.h"

#include <Eigen/Geometry>
#include <cmath>
#include <stdexcept>
#include <string>

namespace weft::render {

RenderMesh make_sphere_mesh(const Eigen::Vector3d& center_m, double radius_m, int segments,
                            int rings) {
  if (!center_m.allFinite()) throw std::invalid_argument("make_sphere_mesh: centre not finite");
  if (!(radius_m > 0.0) || !std::isfinite(radius_m)) {
    throw std::invalid_argument("make_sphere_mesh: radius must be finite and > 0, got " +
                                std::to_string(radius_m));
  }
  if (segments < 3 || rings < 2 || segments > 4096 || rings > 4096) {
    throw std::invalid_argument(
        "make_sphere_mesh: expected 3..4096 segments and 2..4096 rings, got " +
        std::to_string(segments) + " and " + std::to_string(rings));
  }
  constexpr double pi = 3.14159265358979323846;
  RenderMesh mesh;
  const auto add_vertex = [&](const Eigen::Vector3d& unit) {
    mesh.positions.push_back((center_m + radius_m * unit).cast<float>());
    mesh.normals.push_back(unit.cast<float>());
  };
  // Vertex 0: north pole (+z); then ring k = 1 .. rings − 1 at polar angle π k / rings, vertex
  // j of a ring at azimuth 2π j / segments; last: south pole.
  add_vertex(Eigen::Vector3d::UnitZ());
  for (int k = 1; k < rings; ++k) {
    const double polar = pi * k / rings;
    for (int j = 0; j < segments; ++j) {
      const double azimuth = 2.0 * pi * j / segments;
      add_vertex({std::sin(polar) * std::cos(azimuth), std::sin(polar) * std::sin(azimuth),
                  std::cos(polar)});
    }
  }
  add_vertex(-Eigen::Vector3d::UnitZ());

  const auto u = [](int v) { return static_cast<std::uint32_t>(v); };
  const auto ring_vertex = [&](int k, int j) { return u(1 + (k - 1) * segments + j % segments); };
  const std::uint32_t south = u(static_cast<int>(mesh.positions.size()) - 1);
  // Seen from outside, azimuth increases counter-clockwise about +z; going down a ring is
  // going "south". Each triangle below is counter-clockwise seen from outside.
  for (int j = 0; j < segments; ++j)
    mesh.triangles.push_back({0, ring_vertex(1, j), ring_vertex(1, j + 1)});
  for (int k = 1; k + 1 < rings; ++k) {
    for (int j = 0; j < segments; ++j) {
      const std::uint32_t a = ring_vertex(k, j), b = ring_vertex(k, j + 1);
      const std::uint32_t c = ring_vertex(k + 1, j), d = ring_vertex(k + 1, j + 1);
      mesh.triangles.push_back({a, c, d});
      mesh.triangles.push_back({a, d, b});
    }
  }
  for (int j = 0; j < segments; ++j)
    mesh.triangles.push_back({south, ring_vertex(rings - 1, j + 1), ring_vertex(rings - 1, j)});
  return mesh;
}

RenderMesh make_square_patch(const Eigen::Vector3d& center_m, const Eigen::Vector3d& normal,
                             double half_size_m) {
  if (!center_m.allFinite() || !normal.allFinite())
    throw std::invalid_argument("make_square_patch: centre and normal must be finite");
  if (!(normal.norm() > 0.0)) throw std::invalid_argument("make_square_patch: zero normal");
  if (!(half_size_m > 0.0) || !std::isfinite(half_size_m)) {
    throw std::invalid_argument("make_square_patch: half size must be finite and > 0, got " +
                                std::to_string(half_size_m));
  }
  const Eigen::Vector3d n = normal.normalized();
  const Eigen::Vector3d e1 = n.unitOrthogonal();
  const Eigen::Vector3d e2 = n.cross(e1);  // (e1, e2, n) right-handed: e1 → e2 is CCW about n
  RenderMesh mesh;
  const double corners[4][2] = {{-1.0, -1.0}, {1.0, -1.0}, {1.0, 1.0}, {-1.0, 1.0}};
  for (const auto& c : corners) {
    mesh.positions.push_back((center_m + half_size_m * (c[0] * e1 + c[1] * e2)).cast<float>());
    mesh.normals.push_back(n.cast<float>());
  }
  mesh.triangles = {{0, 1, 2}, {0, 2, 3}};
  return mesh;
}

}  // namespace weft::render
