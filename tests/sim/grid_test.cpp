#include "sim/grid.h"

#include <gtest/gtest.h>

#include "sim/mass_spring.h"

namespace weft::sim {
namespace {

TEST(Grid, CountsOfVerticesQuadsAndTriangles) {
  GridSpec spec;
  spec.nu = 7;
  spec.nv = 4;
  const ClothMesh mesh = make_grid(spec);
  EXPECT_EQ(mesh.vertex_count(), 28);
  EXPECT_EQ(mesh.quads.size(), 6u * 3u);
  EXPECT_EQ(mesh.triangles().size(), 2u * 6u * 3u);
  EXPECT_EQ(mesh.material_coords.size(), 28u);
}

TEST(Grid, SpringAndBendCounts) {
  GridSpec spec;
  spec.nu = 7;
  spec.nv = 4;
  const MassSpringModel model(make_grid(spec), Material{});
  const auto count = [&](SpringKind kind) {
    return std::count_if(model.springs().begin(), model.springs().end(),
                         [&](const Spring& s) { return s.kind == kind; });
  };
  EXPECT_EQ(count(SpringKind::warp), 6 * 4);
  EXPECT_EQ(count(SpringKind::weft), 7 * 3);
  EXPECT_EQ(count(SpringKind::shear), 2 * 6 * 3);
  EXPECT_EQ(model.bends().size(), 5u * 4u + 7u * 2u);
}

TEST(Grid, LumpedAreaSumsToSheetAreaForAnyResolutionAndAspect) {
  for (auto [nu, nv] : {std::pair{2, 2}, {3, 17}, {64, 64}, {101, 33}}) {
    GridSpec spec;
    spec.size_u_m = 0.37;
    spec.size_v_m = 1.9;
    spec.nu = nu;
    spec.nv = nv;
    const ClothMesh mesh = make_grid(spec);
    const double area = spec.size_u_m * spec.size_v_m;
    EXPECT_NEAR(mesh.vertex_area_m2.sum() / area, 1.0, 1e-12) << nu << "×" << nv;
    // Area-weighted: a corner has a quarter cell, an edge vertex half, an interior vertex one.
    const double cell = area / ((nu - 1) * (nv - 1));
    EXPECT_NEAR(mesh.vertex_area_m2[0], 0.25 * cell, 1e-15);
    if (nu > 2 && nv > 2) {
      EXPECT_NEAR(mesh.vertex_area_m2[mesh.index(1, 1)], cell, 1e-15);
    }
  }
}

TEST(Grid, PlacesVerticesAlongTheWarpAndWeftAxes) {
  GridSpec spec;
  spec.size_u_m = 2.0;
  spec.size_v_m = 1.0;
  spec.nu = 3;
  spec.nv = 2;
  spec.origin = Vec3(1, 2, 3);
  spec.warp_axis = Vec3(0, 1, 0);
  spec.weft_axis = Vec3(0, 0, -1);
  const ClothMesh mesh = make_grid(spec);
  EXPECT_EQ(Vec3(mesh.rest_positions.row(mesh.index(2, 1))), Vec3(1, 4, 2));
  EXPECT_EQ(mesh.material_coords[mesh.index(2, 1)], Vec2(2, 1));
}

TEST(Grid, RejectsDegenerateResolutionAndSize) {
  GridSpec spec;
  spec.nu = 1;
  EXPECT_THROW(make_grid(spec), std::invalid_argument);
  spec.nu = 4;
  spec.size_v_m = 0.0;
  EXPECT_THROW(make_grid(spec), std::invalid_argument);
}

}  // namespace
}  // namespace weft::sim
