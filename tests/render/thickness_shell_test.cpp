// The thickness shell (render/thickness_shell.h):
// - closed: every edge of the shell lies in exactly two triangles, for a sheet with a boundary
//   (the rim strip closes it) and for a closed surface (two separate closed sheets);
// - counts: 2V vertices and 2F + 2B triangles for B boundary edges;
// - offset: on a flat sheet the two sheets lie exactly t/2 above and below it, and the rim
//   faces outward, away from the sheet;
// - through prepare_cloth_mesh (render/cloth_surface.h) after subdivision.

#include "render/thickness_shell.h"

#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>
#include <map>
#include <stdexcept>
#include <utility>

#include "render/cloth_surface.h"
#include "render/primitives.h"

namespace weft::render {
namespace {

std::map<std::pair<std::uint32_t, std::uint32_t>, int> edge_counts(const RenderMesh& mesh) {
  std::map<std::pair<std::uint32_t, std::uint32_t>, int> count;
  for (const auto& t : mesh.triangles)
    for (int k = 0; k < 3; ++k) ++count[std::minmax(t[k], t[(k + 1) % 3])];
  return count;
}

int boundary_edge_count(const RenderMesh& mesh) {
  int b = 0;
  for (const auto& [e, n] : edge_counts(mesh)) b += n == 1;
  return b;
}

void expect_closed(const RenderMesh& shell) {
  for (const auto& [e, n] : edge_counts(shell))
    EXPECT_EQ(n, 2) << "edge " << e.first << "-" << e.second;
}

TEST(ThicknessShell, FlatSheetIsClosedWithSheetsAtHalfTheThickness) {
  const double t = 0.004;
  const RenderMesh sheet =
      make_grid_mesh(6, 4, [](double u, double v) { return Eigen::Vector3d(u, 0.5 * v, 0.3); });
  const RenderMesh shell = make_thickness_shell(sheet, t);
  const std::size_t v = sheet.positions.size(), f = sheet.triangles.size();
  const int b = boundary_edge_count(sheet);
  EXPECT_EQ(b, 2 * (5 + 3));
  EXPECT_EQ(shell.positions.size(), 2 * v);
  EXPECT_EQ(shell.triangles.size(), 2 * f + 2 * static_cast<std::size_t>(b));
  ASSERT_EQ(shell.uvs.size(), 2 * v);
  expect_closed(shell);
  for (std::size_t k = 0; k < v; ++k) {
    EXPECT_NEAR(shell.positions[k].z(), 0.3 + t / 2, 1e-7) << k;
    EXPECT_NEAR(shell.positions[v + k].z(), 0.3 - t / 2, 1e-7) << k;
    EXPECT_NEAR((shell.positions[k] - shell.positions[v + k]).head<2>().norm(), 0.0, 1e-7);
    EXPECT_EQ(shell.uvs[k], sheet.uvs[k]);
    EXPECT_EQ(shell.uvs[v + k], sheet.uvs[k]);
  }
  // Rim triangles face away from the sheet's centre.
  const Eigen::Vector3f centre(0.5f, 0.25f, 0.3f);
  for (std::size_t k = 2 * f; k < shell.triangles.size(); ++k) {
    const auto& tri = shell.triangles[k];
    const Eigen::Vector3f a = shell.positions[tri[0]], b2 = shell.positions[tri[1]],
                          c = shell.positions[tri[2]];
    const Eigen::Vector3f normal = (b2 - a).cross(c - a);
    EXPECT_GT(normal.dot((a + b2 + c) / 3.0f - centre), 0.0f) << "rim triangle " << k;
  }
}

TEST(ThicknessShell, CurvedSheetOffsetsAlongItsNormals) {
  const double t = 0.01;
  const RenderMesh sheet = make_grid_mesh(9, 9, [](double u, double v) {
    return Eigen::Vector3d(u, v, 0.2 * std::sin(3.0 * u) * std::cos(2.0 * v));
  });
  const RenderMesh shell = make_thickness_shell(sheet, t);
  expect_closed(shell);
  const std::size_t v = sheet.positions.size();
  for (std::size_t k = 0; k < v; ++k) {
    // Each sheet lies t/2 from the input along the input's unit normal.
    EXPECT_NEAR((shell.positions[k] - sheet.positions[k]).norm(), t / 2, 1e-6);
    EXPECT_NEAR((shell.positions[k] - sheet.positions[k]).dot(sheet.normals[k]), t / 2, 1e-6);
    EXPECT_NEAR((sheet.positions[k] - shell.positions[v + k]).dot(sheet.normals[k]), t / 2, 1e-6);
  }
}

TEST(ThicknessShell, ClosedSurfaceGivesTwoClosedSheets) {
  const RenderMesh sphere = make_sphere_mesh(Eigen::Vector3d::Zero(), 1.0, 12, 6);
  ASSERT_EQ(boundary_edge_count(sphere), 0);
  const RenderMesh shell = make_thickness_shell(sphere, 0.1);
  EXPECT_EQ(shell.triangles.size(), 2 * sphere.triangles.size());
  expect_closed(shell);
  EXPECT_NEAR(shell.positions[0].norm(), 1.05f, 1e-5f);
  EXPECT_NEAR(shell.positions[sphere.positions.size()].norm(), 0.95f, 1e-5f);
}

TEST(ThicknessShell, AppliedAfterSubdivisionByPrepareClothMesh) {
  const RenderMesh sheet =
      make_grid_mesh(4, 4, [](double u, double v) { return Eigen::Vector3d(u, v, 0.0); });
  ClothSurface surface;
  RenderMesh storage;
  EXPECT_EQ(&prepare_cloth_mesh(sheet, surface, storage), &sheet);  // nothing to do
  surface.subdivision_levels = 1;
  surface.thickness_m = 0.002;
  const RenderMesh& prepared = prepare_cloth_mesh(sheet, surface, storage);
  // 16 + 33 vertices after one level (E = V + F − 1 = 33), twice over; 4 · 18 triangles twice
  // plus two per boundary edge (24 after one level).
  EXPECT_EQ(prepared.positions.size(), 2u * (16 + 33));
  EXPECT_EQ(prepared.triangles.size(), 2u * 72 + 2u * 24);
  expect_closed(prepared);
  surface.thickness_m = -1.0;
  EXPECT_THROW(prepare_cloth_mesh(sheet, surface, storage), std::invalid_argument);
  EXPECT_THROW(make_thickness_shell(sheet, 0.0), std::invalid_argument);
}

// The wireframe's lines are drawn on both sheets: the upper sheet keeps the
// indices, the lower one has them offset by V.
TEST(ThicknessShell, WireframeEdgesOnBothSheets) {
  RenderMesh sheet =
      make_grid_mesh(3, 3, [](double u, double v) { return Eigen::Vector3d(u, v, 0); });
  sheet.edges = {{0, 1}, {1, 4}, {3, 4}};
  const RenderMesh shell = make_thickness_shell(sheet, 0.01);
  const auto v = static_cast<std::uint32_t>(sheet.positions.size());
  ASSERT_EQ(shell.edges.size(), 2 * sheet.edges.size());
  for (std::size_t e = 0; e < sheet.edges.size(); ++e) {
    EXPECT_EQ(shell.edges[e], sheet.edges[e]);
    EXPECT_EQ(shell.edges[sheet.edges.size() + e][0], sheet.edges[e][0] + v);
    EXPECT_EQ(shell.edges[sheet.edges.size() + e][1], sheet.edges[e][1] + v);
  }
}

}  // namespace
}  // namespace weft::render
