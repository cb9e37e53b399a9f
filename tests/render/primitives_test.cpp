// Sphere, square-patch, box, cylinder and capsule meshes: on the surface, closed, outward
// counter-clockwise triangles, unit outward normals.

#include "render/primitives.h"

#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <array>
#include <cmath>
#include <map>
#include <stdexcept>
#include <utility>

#include "base/constants.h"

namespace weft::render {
namespace {

Eigen::Vector3d at(const RenderMesh& mesh, std::uint32_t v) {
  return mesh.positions[v].cast<double>();
}

// (b − a) × (c − a): twice the area, pointing to the side the triangle is CCW from.
Eigen::Vector3d face_normal(const RenderMesh& mesh, const std::array<std::uint32_t, 3>& t) {
  return (at(mesh, t[1]) - at(mesh, t[0])).cross(at(mesh, t[2]) - at(mesh, t[0]));
}

TEST(Primitives, SphereVerticesAndNormalsLieOnTheSphere) {
  const Eigen::Vector3d centre(0.3, -0.2, 0.6);
  const double radius = 0.25;
  const RenderMesh mesh = make_sphere_mesh(centre, radius, 24, 12);
  EXPECT_EQ(mesh.positions.size(), 2u + 11u * 24u);
  ASSERT_EQ(mesh.normals.size(), mesh.positions.size());
  for (std::size_t v = 0; v < mesh.positions.size(); ++v) {
    const Eigen::Vector3d p = mesh.positions[v].cast<double>();
    EXPECT_NEAR((p - centre).norm(), radius, 1e-6);
    EXPECT_NEAR(mesh.normals[v].norm(), 1.0f, 1e-6f);
    EXPECT_GT(mesh.normals[v].cast<double>().dot((p - centre).normalized()), 1.0 - 1e-6);
  }
  // Poles first and last.
  EXPECT_NEAR(mesh.positions.front().z(), 0.85f, 1e-6f);
  EXPECT_NEAR(mesh.positions.back().z(), 0.35f, 1e-6f);
}

TEST(Primitives, SphereIsClosedWithOutwardCounterClockwiseTriangles) {
  const Eigen::Vector3d centre(0.0, 0.0, 0.5);
  const RenderMesh mesh = make_sphere_mesh(centre, 0.2, 16, 8);
  EXPECT_EQ(mesh.triangles.size(), 2u * 16u * (8u - 1u));
  // Closed and consistently oriented: every directed edge appears once, and its reverse once.
  std::map<std::pair<std::uint32_t, std::uint32_t>, int> directed;
  double area = 0.0;
  for (const auto& t : mesh.triangles) {
    for (int k = 0; k < 3; ++k) ++directed[{t[k], t[(k + 1) % 3]}];
    const Eigen::Vector3d n = face_normal(mesh, t);
    const Eigen::Vector3d centroid = (at(mesh, t[0]) + at(mesh, t[1]) + at(mesh, t[2])) / 3.0;
    EXPECT_GT(n.dot(centroid - centre), 0.0) << "inward triangle";
    area += 0.5 * n.norm();
  }
  for (const auto& [edge, count] : directed) {
    EXPECT_EQ(count, 1);
    EXPECT_EQ(directed.count({edge.second, edge.first}), 1u) << "open edge";
  }
  // Euler characteristic of a sphere: V − E + F = 2.
  const auto V = static_cast<long>(mesh.positions.size());
  const auto E = static_cast<long>(directed.size() / 2);
  const auto F = static_cast<long>(mesh.triangles.size());
  EXPECT_EQ(V - E + F, 2);
  // The inscribed polyhedron's area is a little below 4πr².
  const double sphere_area = 4.0 * base::kPi * 0.2 * 0.2;
  EXPECT_LT(area, sphere_area);
  EXPECT_GT(area, 0.95 * sphere_area);
}

TEST(Primitives, SquarePatchFacesItsNormal) {
  const Eigen::Vector3d centre(1.0, 2.0, 3.0);
  const Eigen::Vector3d normal(0.0, 3.0, 4.0);  // any length
  const RenderMesh mesh = make_square_patch(centre, normal, 2.0);
  ASSERT_EQ(mesh.positions.size(), 4u);
  ASSERT_EQ(mesh.triangles.size(), 2u);
  const Eigen::Vector3d unit = normal.normalized();
  double area = 0.0;
  for (const auto& t : mesh.triangles) {
    const Eigen::Vector3d n = face_normal(mesh, t);
    EXPECT_GT(n.normalized().dot(unit), 1.0 - 1e-6);
    area += 0.5 * n.norm();
  }
  EXPECT_NEAR(area, 16.0, 1e-5);  // (2 · 2 m)²
  Eigen::Vector3d mean = Eigen::Vector3d::Zero();
  for (std::size_t v = 0; v < 4; ++v) {
    EXPECT_NEAR((at(mesh, static_cast<std::uint32_t>(v)) - centre).dot(unit), 0.0, 1e-6);
    EXPECT_NEAR((at(mesh, static_cast<std::uint32_t>(v)) - centre).norm(), 2.0 * std::sqrt(2.0),
                1e-5);
    EXPECT_TRUE(mesh.normals[v].cast<double>().isApprox(unit, 1e-6));
    mean += at(mesh, static_cast<std::uint32_t>(v)) / 4.0;
  }
  EXPECT_TRUE(mean.isApprox(centre, 1e-6));
}

// Closed and consistently oriented as a surface, whatever vertices are duplicated for sharp
// edges: every directed edge between positions (to 1e-6 m) appears once, and its reverse once.
// Each triangle faces the way of its vertices' normals. Returns the enclosed volume (divergence
// theorem: Σ a·(b × c)/6), positive when the triangles face outward.
double closed_volume(const RenderMesh& mesh) {
  const auto key = [&](std::uint32_t v) {
    const Eigen::Vector3d p = at(mesh, v) * 1e6;
    return std::array<long, 3>{std::lround(p.x()), std::lround(p.y()), std::lround(p.z())};
  };
  std::map<std::pair<std::array<long, 3>, std::array<long, 3>>, int> directed;
  double volume = 0.0;
  for (const auto& t : mesh.triangles) {
    for (int k = 0; k < 3; ++k) ++directed[{key(t[k]), key(t[(k + 1) % 3])}];
    const Eigen::Vector3d n = face_normal(mesh, t);
    EXPECT_GT(n.norm(), 0.0) << "degenerate triangle";
    for (int k = 0; k < 3; ++k) {
      EXPECT_NEAR(mesh.normals[t[k]].norm(), 1.0f, 1e-6f);
      EXPECT_GT(n.dot(mesh.normals[t[k]].cast<double>()), 0.0) << "triangle against its normals";
    }
    volume += at(mesh, t[0]).dot(at(mesh, t[1]).cross(at(mesh, t[2]))) / 6.0;
  }
  for (const auto& [edge, count] : directed) {
    EXPECT_EQ(count, 1);
    EXPECT_EQ(directed.count({edge.second, edge.first}), 1u) << "open edge";
  }
  return volume;
}

TEST(Primitives, BoxIsClosedFlatShadedAndHasItsVolume) {
  const Eigen::Vector3d centre(0.2, -0.1, 0.05), half(0.05, 0.04, 0.03);
  const double yaw = 0.5;
  const RenderMesh mesh = make_box_mesh(centre, half, yaw);
  EXPECT_EQ(mesh.positions.size(), 24u);
  EXPECT_EQ(mesh.triangles.size(), 12u);
  EXPECT_NEAR(closed_volume(mesh), 8.0 * half.prod(), 1e-9);
  // Every vertex is a corner: ±half along the turned axes; its normal is a face's.
  const Eigen::Vector3d ex(std::cos(yaw), std::sin(yaw), 0), ey(-std::sin(yaw), std::cos(yaw), 0);
  for (std::size_t v = 0; v < mesh.positions.size(); ++v) {
    const Eigen::Vector3d d = at(mesh, static_cast<std::uint32_t>(v)) - centre;
    EXPECT_NEAR(std::fabs(d.dot(ex)), half.x(), 1e-7);
    EXPECT_NEAR(std::fabs(d.dot(ey)), half.y(), 1e-7);
    EXPECT_NEAR(std::fabs(d.z()), half.z(), 1e-7);
    const Eigen::Vector3d n = mesh.normals[v].cast<double>();
    EXPECT_NEAR(std::fabs(n.dot(ex)) + std::fabs(n.dot(ey)) + std::fabs(n.z()), 1.0, 1e-6);
  }
}

TEST(Primitives, CylinderIsClosedOnItsSurfaceAndHasItsPrismVolume) {
  const Eigen::Vector3d centre(-0.1, 0.2, 0.3), axis = Eigen::Vector3d(1, 2, 2) / 3.0;
  const double radius = 0.09, height = 0.02;
  const int segments = 24;
  const RenderMesh mesh = make_cylinder_mesh(centre, 3.0 * axis, radius, height, segments);
  // Inscribed prism: a regular 24-gon of area (n/2) R² sin(2π/n) times the height.
  const double polygon =
      0.5 * segments * radius * radius * std::sin(2.0 * 3.14159265358979 / segments);
  EXPECT_NEAR(closed_volume(mesh), polygon * height, 1e-9);
  for (std::size_t v = 0; v < mesh.positions.size(); ++v) {
    const Eigen::Vector3d d = at(mesh, static_cast<std::uint32_t>(v)) - centre;
    const double z = d.dot(axis), r = (d - z * axis).norm();
    const Eigen::Vector3d n = mesh.normals[v].cast<double>();
    if (std::fabs(n.dot(axis)) > 0.5) {  // a cap vertex: on the cap, normal ±axis
      EXPECT_NEAR(std::fabs(z), 0.5 * height, 1e-7);
      EXPECT_NEAR(n.dot(axis), z > 0 ? 1.0 : -1.0, 1e-6);
      EXPECT_LE(r, radius + 1e-7);
    } else {  // a side vertex: on the rim, normal radial
      EXPECT_NEAR(r, radius, 1e-7);
      EXPECT_NEAR(n.dot((d - z * axis) / r), 1.0, 1e-6);
    }
  }
}

TEST(Primitives, CapsuleIsClosedOnItsSurfaceWithNearlyItsVolume) {
  const Eigen::Vector3d a(0.0, -0.1, 0.3), b(0.05, 0.1, 0.3);
  const double radius = 0.03;
  const RenderMesh mesh = make_capsule_mesh(a, b, radius, 32, 8);
  const double length = (b - a).norm();
  const double exact = base::kPi * radius * radius * length + 4.0 / 3.0 * base::kPi * std::pow(radius, 3);
  const double volume = closed_volume(mesh);
  EXPECT_LT(volume, exact);  // inscribed
  EXPECT_GT(volume, 0.97 * exact);
  for (std::size_t v = 0; v < mesh.positions.size(); ++v) {
    const Eigen::Vector3d p = at(mesh, static_cast<std::uint32_t>(v));
    const double s = std::clamp((p - a).dot(b - a) / (b - a).squaredNorm(), 0.0, 1.0);
    const Eigen::Vector3d off = p - (a + s * (b - a));
    EXPECT_NEAR(off.norm(), radius, 1e-7);
    EXPECT_NEAR(mesh.normals[v].cast<double>().dot(off / off.norm()), 1.0, 1e-6);
  }
  // a = b: a closed sphere.
  const RenderMesh ball = make_capsule_mesh(a, a, radius, 32, 8);
  EXPECT_GT(closed_volume(ball), 0.97 * 4.0 / 3.0 * base::kPi * std::pow(radius, 3));
}

TEST(Primitives, BadInputThrows) {
  EXPECT_THROW(make_sphere_mesh({0, 0, 0}, 0.0), std::invalid_argument);
  EXPECT_THROW(make_sphere_mesh({0, 0, 0}, -1.0), std::invalid_argument);
  EXPECT_THROW(make_sphere_mesh({0, 0, NAN}, 1.0), std::invalid_argument);
  EXPECT_THROW(make_sphere_mesh({0, 0, 0}, 1.0, 2, 8), std::invalid_argument);
  EXPECT_THROW(make_sphere_mesh({0, 0, 0}, 1.0, 8, 1), std::invalid_argument);
  EXPECT_THROW(make_square_patch({0, 0, 0}, {0, 0, 0}, 1.0), std::invalid_argument);
  EXPECT_THROW(make_square_patch({0, 0, 0}, {0, 0, 1}, 0.0), std::invalid_argument);
  EXPECT_THROW(make_square_patch({0, 0, INFINITY}, {0, 0, 1}, 1.0), std::invalid_argument);
  EXPECT_THROW(make_box_mesh({0, 0, 0}, {1, 0, 1}, 0.0), std::invalid_argument);
  EXPECT_THROW(make_box_mesh({0, 0, 0}, {1, 1, 1}, NAN), std::invalid_argument);
  EXPECT_THROW(make_cylinder_mesh({0, 0, 0}, {0, 0, 0}, 1.0, 1.0), std::invalid_argument);
  EXPECT_THROW(make_cylinder_mesh({0, 0, 0}, {0, 0, 1}, 1.0, -1.0), std::invalid_argument);
  EXPECT_THROW(make_cylinder_mesh({0, 0, 0}, {0, 0, 1}, 1.0, 1.0, 2), std::invalid_argument);
  EXPECT_THROW(make_capsule_mesh({0, 0, 0}, {0, 0, 1}, 0.0), std::invalid_argument);
  EXPECT_THROW(make_capsule_mesh({0, 0, 0}, {0, 0, 1}, 1.0, 8, 0), std::invalid_argument);
}

// A flat 4×3 grid: 12 vertices, 2·3·2 = 12 triangles, uv = the grid parameters, every normal
// ∂p/∂u × ∂p/∂v = +z for p = (2u, v, 0), and the triangles tile the 2 m² rectangle exactly.
TEST(Primitives, GridMeshCountsUvsNormalsAndArea) {
  const RenderMesh grid =
      make_grid_mesh(4, 3, [](double u, double v) { return Eigen::Vector3d(2.0 * u, v, 0.5); });
  ASSERT_EQ(grid.positions.size(), 12u);
  ASSERT_EQ(grid.triangles.size(), 12u);
  ASSERT_EQ(grid.uvs.size(), 12u);
  EXPECT_FLOAT_EQ(grid.uvs[5].x(), 1.0f / 3.0f);  // vertex (1, 1)
  EXPECT_FLOAT_EQ(grid.uvs[5].y(), 0.5f);
  double area = 0.0;
  for (const auto& t : grid.triangles) {
    const Eigen::Vector3f n = (grid.positions[t[1]] - grid.positions[t[0]])
                                  .cross(grid.positions[t[2]] - grid.positions[t[0]]);
    EXPECT_GT(n.z(), 0.0f);  // counter-clockwise seen from +z
    area += 0.5 * n.norm();
  }
  EXPECT_NEAR(area, 2.0, 1e-6);
  for (const Eigen::Vector3f& n : grid.normals)
    EXPECT_NEAR((n - Eigen::Vector3f::UnitZ()).norm(), 0.0, 1e-6);
  EXPECT_THROW(make_grid_mesh(1, 3, [](double, double) { return Eigen::Vector3d::Zero(); }),
               std::invalid_argument);
}

}  // namespace
}  // namespace weft::render
