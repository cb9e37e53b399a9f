// Sphere, square-patch, box, cylinder and capsule meshes for drawing analytic obstacles, and
// parametric grid sheets.

#include "render/primitives.h"

#include <Eigen/Geometry>
#include <cmath>
#include <stdexcept>
#include <string>
#include <vector>

#include "base/constants.h"

namespace weft::render {
namespace {

void check_finite_positive(const char* function, const char* what, double value_m) {
  if (!(value_m > 0.0) || !std::isfinite(value_m)) {
    throw std::invalid_argument(std::string(function) + ": " + what +
                                " must be finite and > 0, got " + std::to_string(value_m));
  }
}

void check_segments(const char* function, int segments) {
  if (segments < 3 || segments > 4096) {
    throw std::invalid_argument(std::string(function) + ": expected 3..4096 segments, got " +
                                std::to_string(segments));
  }
}

// One point of a surface-of-revolution profile: distance r from the axis and height z along it
// (m), and the outward normal there as (radial, axial) components of a unit vector.
struct ProfilePoint {
  double r;
  double z;
  double normal_r;
  double normal_z;
};

// The surface swept by revolving `profile` about `axis` (unit) through `origin`: a profile point
// with r = 0 is one vertex (a pole), any other a ring of `segments` vertices at azimuths
// 2π j/segments from axis.unitOrthogonal() towards axis × that. Consecutive profile points are
// joined by a band (or a fan at a pole) unless they coincide — a repeated point with another
// normal makes a sharp edge (a cylinder's rim). The profile must run from the +axis end to the
// −axis end round the outside, so that each triangle is counter-clockwise seen from outside.
RenderMesh revolve(const Eigen::Vector3d& origin, const Eigen::Vector3d& axis,
                   const std::vector<ProfilePoint>& profile, int segments) {
  const Eigen::Vector3d e1 = axis.unitOrthogonal();
  const Eigen::Vector3d e2 = axis.cross(e1);
  RenderMesh mesh;
  std::vector<std::uint32_t> first;  // per profile point: index of its first vertex
  for (const ProfilePoint& q : profile) {
    first.push_back(static_cast<std::uint32_t>(mesh.positions.size()));
    const int count = q.r > 0.0 ? segments : 1;
    for (int j = 0; j < count; ++j) {
      const double azimuth = 2.0 * base::kPi * j / segments;
      const Eigen::Vector3d radial = std::cos(azimuth) * e1 + std::sin(azimuth) * e2;
      mesh.positions.push_back((origin + q.z * axis + q.r * radial).cast<float>());
      mesh.normals.push_back((q.normal_r * radial + q.normal_z * axis).cast<float>());
    }
  }
  const auto u = [](int j) { return static_cast<std::uint32_t>(j); };
  for (std::size_t k = 0; k + 1 < profile.size(); ++k) {
    const ProfilePoint &top = profile[k], &bottom = profile[k + 1];
    if (top.r == bottom.r && top.z == bottom.z) continue;  // a sharp edge, no band
    for (int j = 0; j < segments; ++j) {
      const int next = (j + 1) % segments;
      const std::uint32_t a = first[k] + (top.r > 0.0 ? u(j) : 0u);
      const std::uint32_t b = first[k] + (top.r > 0.0 ? u(next) : 0u);
      const std::uint32_t c = first[k + 1] + (bottom.r > 0.0 ? u(j) : 0u);
      const std::uint32_t d = first[k + 1] + (bottom.r > 0.0 ? u(next) : 0u);
      if (top.r == 0.0) {
        mesh.triangles.push_back({a, c, d});  // fan from the pole above (a = b)
      } else if (bottom.r == 0.0) {
        mesh.triangles.push_back({a, c, b});  // fan to the pole below (c = d)
      } else {
        mesh.triangles.push_back({a, c, d});
        mesh.triangles.push_back({a, d, b});
      }
    }
  }
  return mesh;
}

}  // namespace

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
  RenderMesh mesh;
  const auto add_vertex = [&](const Eigen::Vector3d& unit) {
    mesh.positions.push_back((center_m + radius_m * unit).cast<float>());
    mesh.normals.push_back(unit.cast<float>());
  };
  // Vertex 0: north pole (+z); then ring k = 1 .. rings − 1 at polar angle π k / rings, vertex
  // j of a ring at azimuth 2π j / segments; last: south pole.
  add_vertex(Eigen::Vector3d::UnitZ());
  for (int k = 1; k < rings; ++k) {
    const double polar = base::kPi * k / rings;
    for (int j = 0; j < segments; ++j) {
      const double azimuth = 2.0 * base::kPi * j / segments;
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

RenderMesh make_box_mesh(const Eigen::Vector3d& center_m, const Eigen::Vector3d& half_size_m,
                         double yaw_rad) {
  if (!center_m.allFinite() || !std::isfinite(yaw_rad))
    throw std::invalid_argument("make_box_mesh: centre and yaw must be finite");
  for (int i = 0; i < 3; ++i) check_finite_positive("make_box_mesh", "half size", half_size_m[i]);
  const Eigen::Matrix3d frame =
      Eigen::AngleAxisd(yaw_rad, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  RenderMesh mesh;
  // Face with outward local normal ±e_i: its corners in the plane of the other two axes
  // (j, k) = (i+1, i+2) mod 3, ordered counter-clockwise about the normal.
  for (int i = 0; i < 3; ++i) {
    for (const double sign : {1.0, -1.0}) {
      const int j = (i + 1) % 3, k = (i + 2) % 3;
      const auto base = static_cast<std::uint32_t>(mesh.positions.size());
      const double corners[4][2] = {{-1.0, -1.0}, {1.0, -1.0}, {1.0, 1.0}, {-1.0, 1.0}};
      for (const auto& c : corners) {
        Eigen::Vector3d local;
        local[i] = sign * half_size_m[i];
        // e_j × e_k = e_i: (j, k) is counter-clockwise about +e_i; flip j's order for −e_i.
        local[j] = sign * c[0] * half_size_m[j];
        local[k] = c[1] * half_size_m[k];
        mesh.positions.push_back((center_m + frame * local).cast<float>());
        mesh.normals.push_back((sign * frame.col(i)).cast<float>());
      }
      mesh.triangles.push_back({base, base + 1, base + 2});
      mesh.triangles.push_back({base, base + 2, base + 3});
    }
  }
  return mesh;
}

RenderMesh make_cylinder_mesh(const Eigen::Vector3d& center_m, const Eigen::Vector3d& axis,
                              double radius_m, double height_m, int segments) {
  if (!center_m.allFinite() || !axis.allFinite())
    throw std::invalid_argument("make_cylinder_mesh: centre and axis must be finite");
  if (!(axis.norm() > 0.0)) throw std::invalid_argument("make_cylinder_mesh: zero axis");
  check_finite_positive("make_cylinder_mesh", "radius", radius_m);
  check_finite_positive("make_cylinder_mesh", "height", height_m);
  check_segments("make_cylinder_mesh", segments);
  const double h = 0.5 * height_m, r = radius_m;
  return revolve(center_m, axis.normalized(),
                 {{0.0, h, 0.0, 1.0},
                  {r, h, 0.0, 1.0},
                  {r, h, 1.0, 0.0},
                  {r, -h, 1.0, 0.0},
                  {r, -h, 0.0, -1.0},
                  {0.0, -h, 0.0, -1.0}},
                 segments);
}

RenderMesh make_capsule_mesh(const Eigen::Vector3d& a_m, const Eigen::Vector3d& b_m,
                             double radius_m, int segments, int rings_per_cap) {
  if (!a_m.allFinite() || !b_m.allFinite())
    throw std::invalid_argument("make_capsule_mesh: endpoints must be finite");
  check_finite_positive("make_capsule_mesh", "radius", radius_m);
  check_segments("make_capsule_mesh", segments);
  if (rings_per_cap < 1 || rings_per_cap > 2048) {
    throw std::invalid_argument("make_capsule_mesh: expected 1..2048 rings per cap, got " +
                                std::to_string(rings_per_cap));
  }
  const Eigen::Vector3d ab = b_m - a_m;
  const double length = ab.norm();
  const Eigen::Vector3d axis =
      length > 0.0 ? Eigen::Vector3d(ab / length) : Eigen::Vector3d::UnitZ();
  // From the pole beyond b (polar angle 0) to b's equator, then a's equator to the pole beyond a.
  std::vector<ProfilePoint> profile;
  const double h = 0.5 * length;
  // Exact 0 and 1 at the pole and the equator, so that a zero-length capsule's two equators
  // coincide (no band between them) and the poles are single vertices.
  const auto sin_polar = [&](int k) {
    return k == 0 ? 0.0 : k == rings_per_cap ? 1.0 : std::sin(0.5 * base::kPi * k / rings_per_cap);
  };
  const auto cos_polar = [&](int k) {
    return k == 0 ? 1.0 : k == rings_per_cap ? 0.0 : std::cos(0.5 * base::kPi * k / rings_per_cap);
  };
  for (int k = 0; k <= rings_per_cap; ++k)
    profile.push_back(
        {radius_m * sin_polar(k), h + radius_m * cos_polar(k), sin_polar(k), cos_polar(k)});
  for (int k = rings_per_cap; k >= 0; --k)
    profile.push_back(
        {radius_m * sin_polar(k), -h - radius_m * cos_polar(k), sin_polar(k), -cos_polar(k)});
  return revolve(0.5 * (a_m + b_m), axis, profile, segments);
}

RenderMesh make_grid_mesh(int nu, int nv,
                          const std::function<Eigen::Vector3d(double u, double v)>& position) {
  if (nu < 2 || nv < 2 || static_cast<long long>(nu) * nv > 0xFFFFFFFFll) {
    throw std::invalid_argument("make_grid_mesh: expected at least 2×2 vertices (and fewer than "
                                "2^32), got " + std::to_string(nu) + "×" + std::to_string(nv));
  }
  RenderMesh mesh;
  for (int j = 0; j < nv; ++j) {
    for (int i = 0; i < nu; ++i) {
      const double u = static_cast<double>(i) / (nu - 1), v = static_cast<double>(j) / (nv - 1);
      mesh.positions.push_back(position(u, v).cast<float>());
      mesh.uvs.emplace_back(static_cast<float>(u), static_cast<float>(v));
    }
  }
  const auto row = static_cast<std::uint32_t>(nu);
  for (int j = 0; j + 1 < nv; ++j) {
    for (int i = 0; i + 1 < nu; ++i) {
      const auto k = static_cast<std::uint32_t>(j) * row + static_cast<std::uint32_t>(i);
      mesh.triangles.push_back({k, k + 1, k + row + 1});
      mesh.triangles.push_back({k, k + row + 1, k + row});
    }
  }
  compute_vertex_normals(mesh);
  return mesh;
}

}  // namespace weft::render
