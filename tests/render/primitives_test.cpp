// Sphere and square-patch meshes: on the surface, closed, outward counter-clockwise triangles,
// unit outward normals.

#include "render/primitives.h"

#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>
#include <map>
#include <stdexcept>
#include <utility>

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
  const double sphere_area = 4.0 * 3.14159265358979323846 * 0.2 * 0.2;
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

TEST(Primitives, BadInputThrows) {
  EXPECT_THROW(make_sphere_mesh({0, 0, 0}, 0.0), std::invalid_argument);
  EXPECT_THROW(make_sphere_mesh({0, 0, 0}, -1.0), std::invalid_argument);
  EXPECT_THROW(make_sphere_mesh({0, 0, NAN}, 1.0), std::invalid_argument);
  EXPECT_THROW(make_sphere_mesh({0, 0, 0}, 1.0, 2, 8), std::invalid_argument);
  EXPECT_THROW(make_sphere_mesh({0, 0, 0}, 1.0, 8, 1), std::invalid_argument);
  EXPECT_THROW(make_square_patch({0, 0, 0}, {0, 0, 0}, 1.0), std::invalid_argument);
  EXPECT_THROW(make_square_patch({0, 0, 0}, {0, 0, 1}, 0.0), std::invalid_argument);
  EXPECT_THROW(make_square_patch({0, 0, INFINITY}, {0, 0, 1}, 1.0), std::invalid_argument);
}

}  // namespace
}  // namespace weft::render
