// Area-weighted vertex normals.

#include "render/render_mesh.h"

#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>
#include <stdexcept>

namespace weft::render {
namespace {

void expect_near(const Eigen::Vector3f& actual, const Eigen::Vector3f& expected, float tol) {
  EXPECT_LT((actual - expected).norm(), tol)
      << "actual (" << actual.transpose() << "), expected (" << expected.transpose() << ")";
}

TEST(ComputeVertexNormals, FlatCounterClockwiseQuadPointsUp) {
  RenderMesh quad;
  quad.positions = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}};
  quad.triangles = {{0, 1, 2}, {0, 2, 3}};  // counter-clockwise seen from +z
  compute_vertex_normals(quad);
  ASSERT_EQ(quad.normals.size(), 4u);
  for (const auto& n : quad.normals) expect_near(n, Eigen::Vector3f::UnitZ(), 1e-6f);
}

TEST(ComputeVertexNormals, ClockwiseQuadPointsDown) {
  RenderMesh quad;
  quad.positions = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}};
  quad.triangles = {{0, 2, 1}, {0, 3, 2}};
  compute_vertex_normals(quad);
  for (const auto& n : quad.normals) expect_near(n, -Eigen::Vector3f::UnitZ(), 1e-6f);
}

TEST(ComputeVertexNormals, TetrahedronNormalsAreUnitAndPointOutwards) {
  RenderMesh tet;
  tet.positions = {{0, 0, 0}, {1.3f, 0, 0}, {0.2f, 0.9f, 0}, {0.4f, 0.3f, 1.1f}};
  // Outward (counter-clockwise seen from outside) faces.
  tet.triangles = {{0, 2, 1}, {0, 1, 3}, {1, 2, 3}, {2, 0, 3}};
  compute_vertex_normals(tet);
  Eigen::Vector3f centroid = Eigen::Vector3f::Zero();
  for (const auto& p : tet.positions) centroid += p / 4.0f;
  for (std::size_t v = 0; v < 4; ++v) {
    EXPECT_NEAR(tet.normals[v].norm(), 1.0f, 1e-6f) << "vertex " << v;
    EXPECT_GT(tet.normals[v].dot(tet.positions[v] - centroid), 0.0f) << "vertex " << v;
  }
}

TEST(ComputeVertexNormals, FacesAreWeightedByArea) {
  RenderMesh mesh;
  // Vertex 0 is shared by a triangle of area 2 facing +z and one of area 0.5 facing +y:
  // the normal is (0, 1, 4)/√17 (cross products 2A n summed).
  mesh.positions = {{0, 0, 0}, {2, 0, 0}, {0, 2, 0}, {0, 0, 1}, {1, 0, 0}};
  mesh.triangles = {{0, 1, 2}, {0, 3, 4}};
  compute_vertex_normals(mesh);
  expect_near(mesh.normals[0], Eigen::Vector3f(0, 1, 4) / std::sqrt(17.0f), 1e-6f);
}

TEST(ComputeVertexNormals, IsolatedVertexAndDegenerateFaceGivePlusZ) {
  RenderMesh mesh;
  mesh.positions = {{0, 0, 0}, {1, 0, 0}, {2, 0, 0}, {5, 5, 5}};
  mesh.triangles = {{0, 1, 2}};  // collinear: zero area
  compute_vertex_normals(mesh);
  for (const auto& n : mesh.normals) expect_near(n, Eigen::Vector3f::UnitZ(), 1e-7f);
}

TEST(ComputeVertexNormals, BadIndexNamesTheTriangle) {
  RenderMesh mesh;
  mesh.positions = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};
  mesh.triangles = {{0, 1, 2}, {0, 2, 7}};
  try {
    compute_vertex_normals(mesh);
    FAIL() << "no exception for an out-of-range vertex index";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("triangle 1"), std::string::npos) << e.what();
  }
}

TEST(ValidateRenderMesh, BadIndexNamesTheTriangleOrTheEdge) {
  RenderMesh mesh;
  mesh.positions = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};
  mesh.triangles = {{0, 1, 2}, {0, 2, 7}};
  const auto message = [&mesh] {
    try {
      validate(mesh, "cloth");
    } catch (const std::invalid_argument& e) {
      return std::string(e.what());
    }
    return std::string("no exception");
  };
  EXPECT_EQ(message(), "cloth: triangle 1 uses vertex 7 but the mesh has 3 vertices");
  mesh.triangles.pop_back();
  mesh.edges = {{0, 1}, {1, 2}, {3, 0}};  // the wireframe's lines: the last is out of range
  EXPECT_EQ(message(), "cloth: edge 2 uses vertex 3 but the mesh has 3 vertices");
  mesh.edges.pop_back();
  EXPECT_EQ(message(), "no exception");
}

}  // namespace
}  // namespace weft::render
