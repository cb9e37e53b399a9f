// weft sweep's pieces: the errors between two cloths (interpolation at material points,
// silhouettes), the Pareto front, and --set parsing and scene patching with their messages.

#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <string>
#include <utility>
#include <vector>

#include "app/scene/scene.h"
#include "app/scene/scene_patch.h"
#include "analysis/sweep_metrics.h"
#include "sim/grid.h"
#include "tests/app/scene_test_support.h"

namespace weft::app {
namespace {

// A flat nu × nv sheet of size_u × size_v metres in the plane z = 0, from the origin.
sim::ClothMesh sheet(int nu, int nv, double size_u = 1.0, double size_v = 1.0) {
  sim::GridSpec spec;
  spec.nu = nu;
  spec.nv = nv;
  spec.size_u_m = size_u;
  spec.size_v_m = size_v;
  spec.origin = sim::Vec3::Zero();
  return sim::make_grid(spec);
}

// Positions f(u, v) at every vertex's material coordinates.
template <class F>
sim::Matrix3X positions(const sim::ClothMesh& mesh, F f) {
  sim::Matrix3X x(mesh.vertex_count(), 3);
  for (sim::Index k = 0; k < mesh.vertex_count(); ++k)
    x.row(k) = f(mesh.material_coords[static_cast<std::size_t>(k)]).transpose();
  return x;
}

// ---- interpolation and RMS distance ----

// Bilinear interpolation reproduces any function a + b u + c v + d u v exactly.
TEST(SweepMetrics, InterpolationIsExactForBilinearFunctions) {
  const sim::ClothMesh mesh = sheet(5, 4, 2.0, 1.5);
  const auto f = [](const sim::Vec2& uv) {
    return sim::Vec3(0.3 + 2.0 * uv.x() - uv.y(), -1.0 + 0.5 * uv.x() * uv.y(), 4.0 * uv.y());
  };
  const sim::Matrix3X x = positions(mesh, f);
  for (const sim::Vec2& uv : {sim::Vec2(0.0, 0.0), sim::Vec2(2.0, 1.5), sim::Vec2(0.37, 1.21),
                             sim::Vec2(1.5, 0.5), sim::Vec2(1.999, 0.001)}) {
    EXPECT_LT((analysis::position_at_material_point(mesh, x, uv) - f(uv)).norm(), 1e-12)
        << "at (" << uv.x() << ", " << uv.y() << ")";
  }
  // Outside the cloth: clamped to its edge.
  EXPECT_LT((analysis::position_at_material_point(mesh, x, {3.0, -1.0}) - f({2.0, 0.0})).norm(),
            1e-12);
}

TEST(SweepMetrics, IdenticalClothsAreZeroApart) {
  const sim::ClothMesh mesh = sheet(7, 6);
  const sim::Matrix3X x = positions(mesh, [](const sim::Vec2& uv) {
    return sim::Vec3(uv.x(), 0.2 * std::sin(3 * uv.y()), std::cos(uv.x() * uv.y()));
  });
  EXPECT_EQ(analysis::rms_distance_m(mesh, x, mesh, x), 0.0);
}

TEST(SweepMetrics, TranslatedSheetIsItsShiftApart) {
  const sim::ClothMesh mesh = sheet(9, 9);
  const sim::Matrix3X x = mesh.rest_positions;
  sim::Matrix3X moved = x;
  moved.rowwise() += Eigen::RowVector3d(0.03, -0.04, 0.0);  // |shift| = 5 cm
  EXPECT_NEAR(analysis::rms_distance_m(mesh, x, mesh, moved), 0.05, 1e-12);
  // The same with a coarser run: the flat sheet is bilinear, so resolution adds nothing.
  const sim::ClothMesh coarse = sheet(4, 3);
  sim::Matrix3X coarse_moved = coarse.rest_positions;
  coarse_moved.rowwise() += Eigen::RowVector3d(0.03, -0.04, 0.0);
  EXPECT_NEAR(analysis::rms_distance_m(mesh, x, coarse, coarse_moved), 0.05, 1e-12);
}

// A parabola z = u² sampled on a reference with spacing h = 0.5 is off by a(1−a)h² at the
// fraction a of a cell: a finer run exactly on the parabola differs by h²/4 = 0.0625 m at
// u = 0.25 and 0.75, and not at all at u = 0, 0.5, 1.
TEST(SweepMetrics, DifferentResolutionsCompareThroughInterpolation) {
  const auto parabola = [](const sim::Vec2& uv) { return sim::Vec3(uv.x(), uv.y(), uv.x() * uv.x()); };
  const sim::ClothMesh reference = sheet(3, 2), run = sheet(5, 2);
  const double expected = 0.0625 * std::sqrt(4.0 / 10.0);  // 4 of 10 vertices off by 0.0625
  EXPECT_NEAR(analysis::rms_distance_m(reference, positions(reference, parabola), run,
                                       positions(run, parabola)),
              expected, 1e-12);
}

// ---- silhouettes ----

// Looking down −z with +y up on the image, x is to the right.
analysis::OrthoView top_view() {
  return analysis::ortho_view({0.0, 0.0, -1.0}, {0.0, 1.0, 0.0});
}

TEST(SweepMetrics, OrthoViewIsOrthonormalAndRejectsParallelUp) {
  const analysis::OrthoView view = analysis::ortho_view({1.0, 2.0, -0.5}, {0.0, 0.0, 3.0});
  EXPECT_NEAR(view.right.norm(), 1.0, 1e-12);
  EXPECT_NEAR(view.up.norm(), 1.0, 1e-12);
  EXPECT_NEAR(view.right.dot(view.up), 0.0, 1e-12);
  EXPECT_NEAR(view.right.dot(sim::Vec3(1.0, 2.0, -0.5)), 0.0, 1e-12);
  EXPECT_GT(view.up.z(), 0.0);  // up stays up
  const analysis::OrthoView top = top_view();
  EXPECT_NEAR((top.right - sim::Vec3(1, 0, 0)).norm(), 0.0, 1e-12);
  EXPECT_THROW(analysis::ortho_view({0, 0, 1}, {0, 0, 2}), std::invalid_argument);
}

TEST(SweepMetrics, SheetFillsItsOwnWindowAndHalfASheetGivesOneHalf) {
  const sim::ClothMesh full = sheet(5, 5);                  // [0, 1]²
  const sim::ClothMesh half = sheet(3, 5, 0.5, 1.0);        // [0, 0.5] × [0, 1]
  const analysis::Window window{0.0, 0.0, 1.0};
  const int n = 64;
  const analysis::Mask a =
      analysis::silhouette(full.triangles(), full.rest_positions, top_view(), window, n);
  const analysis::Mask b =
      analysis::silhouette(half.triangles(), half.rest_positions, top_view(), window, n);
  EXPECT_EQ(a.count(), n * n);
  EXPECT_EQ(b.count(), n * n / 2);
  EXPECT_TRUE(b.at(0, 0) && b.at(n / 2 - 1, n - 1) && !b.at(n / 2, 0));  // the left half
  EXPECT_DOUBLE_EQ(analysis::silhouette_difference(a, b), 0.5);
  EXPECT_DOUBLE_EQ(analysis::silhouette_difference(a, a), 0.0);
}

TEST(SweepMetrics, ShiftedSheetsOverlapByTheirCommonPart) {
  // Two unit squares, one shifted by half its width: |A xor B| = 1, |A or B| = 1.5.
  const sim::ClothMesh mesh = sheet(3, 3);
  sim::Matrix3X shifted = mesh.rest_positions;
  shifted.col(0).array() += 0.5;
  const analysis::Window window =
      analysis::joint_window(top_view(), mesh.rest_positions, shifted, 0.0);
  EXPECT_NEAR(window.side_m, 1.5, 1e-12);  // square: the larger side of the 1.5 × 1 box
  const analysis::Mask a =
      analysis::silhouette(mesh.triangles(), mesh.rest_positions, top_view(), window, 120);
  const analysis::Mask b = analysis::silhouette(mesh.triangles(), shifted, top_view(), window, 120);
  EXPECT_NEAR(analysis::silhouette_difference(a, b), 1.0 / 1.5, 0.02);
}

TEST(SweepMetrics, SilhouetteIgnoresFacingAndEdgeOnTriangles) {
  const sim::ClothMesh mesh = sheet(2, 2);
  auto flipped = mesh.triangles();
  for (auto& t : flipped) std::swap(t[1], t[2]);  // clockwise seen from above
  const analysis::Window window{0.0, 0.0, 1.0};
  EXPECT_EQ(analysis::silhouette(flipped, mesh.rest_positions, top_view(), window, 16).count(),
            256);
  // The same sheet seen edge-on (looking along +y) covers no area.
  const analysis::OrthoView side = analysis::ortho_view({0.0, 1.0, 0.0}, {0.0, 0.0, 1.0});
  EXPECT_EQ(analysis::silhouette(
                mesh.triangles(), mesh.rest_positions, side,
                analysis::joint_window(side, mesh.rest_positions, mesh.rest_positions), 16)
                .count(),
            0);
}

// ---- Pareto front ----

TEST(SweepMetrics, ParetoFrontKeepsRunsNoOtherBeatsInBoth) {
  //                       time  1    2    3    4    0.5
  const std::vector<double> time{1.0, 2.0, 3.0, 4.0, 0.5};
  const std::vector<double> error{4.0, 3.0, 5.0, 0.0, 0.1};
  // Run 5 diverged: it neither counts nor dominates the others.
  const std::vector<bool> eligible{true, true, true, true, false};
  const std::vector<bool> front = analysis::pareto_optimal(time, error, eligible);
  EXPECT_EQ(front, (std::vector<bool>{true, true, false, true, false}));
  // Ties: two equal runs are both optimal; a run equal in time but worse in error is not.
  EXPECT_EQ(analysis::pareto_optimal({1, 1, 1}, {2, 2, 3}, {true, true, true}),
            (std::vector<bool>{true, true, false}));
}


// ---- --set parsing and scene patching ----

std::string error_of(const std::function<void()>& f) {
  try {
    f();
  } catch (const InputError& e) {
    return e.what();
  }
  return "no error";
}

TEST(ScenePatch, ValuesSplitAtTopLevelCommas) {
  const SettingValues r = parse_set_option("cloth.resolution=[8,8],[12, 12]");
  EXPECT_EQ(r.key, "cloth.resolution");
  EXPECT_EQ(r.values, (std::vector<std::string>{"[8,8]", "[12, 12]"}));
  EXPECT_EQ(parse_set_option("simulation.time_step=1 ms, auto").values,
            (std::vector<std::string>{"1 ms", "auto"}));
  EXPECT_EQ(parse_set_option(R"(description="a, b",c)").values,
            (std::vector<std::string>{"\"a, b\"", "c"}));
}

TEST(ScenePatch, MalformedOptionsNameSet) {
  for (const char* bad : {"cloth.resolution", "=3", "cloth.resolution=", "a=1,,2", "a=[1,2", "a=1,1",
                          "a..b=1", "obstacles[x].sphere=1"}) {
    const std::string message = error_of([&] { parse_set_option(bad); });
    EXPECT_CONTAINS(message, "--set '" + std::string(bad) + "'");
  }
}

TEST(ScenePatch, ValuesAreJsonWhenTheyParseElseStrings) {
  EXPECT_EQ(setting_json("12"), Json(12));
  EXPECT_EQ(setting_json("1e-3"), Json(1e-3));
  EXPECT_EQ(setting_json("[8,8]"), Json::parse("[8,8]"));
  EXPECT_EQ(setting_json("true"), Json(true));
  EXPECT_EQ(setting_json("\"rk4\""), Json("rk4"));
  EXPECT_EQ(setting_json("rk4"), Json("rk4"));
  EXPECT_EQ(setting_json("1 ms"), Json("1 ms"));
}

TEST(ScenePatch, PatchedSceneTakesTheValuesAndLeavesTheBase) {
  const Scene base = default_scene();
  const Scene patched = patched_scene(base, {{"cloth.resolution", "[8,12]"},
                                             {"simulation.time_step", "0.5 ms"},
                                             {"simulation.integrator", "rk4"}});
  EXPECT_EQ(patched.grid.nu, 8);
  EXPECT_EQ(patched.grid.nv, 12);
  ASSERT_EQ(patched.sim.time_step.kind, sim::TimeStep::Kind::fixed);
  EXPECT_DOUBLE_EQ(patched.sim.time_step.fixed_s, 5e-4);
  EXPECT_EQ(patched.sim.integrator, sim::Integrator::rk4);
  EXPECT_EQ(patched.name, "default");
  EXPECT_EQ(patched.source, base.source);
  // Everything else as in the base scene.
  EXPECT_EQ(patched.material.density_kg_m2, base.material.density_kg_m2);
  EXPECT_EQ(patched.frames, base.frames);
  EXPECT_EQ(base.grid.nu, 41);
}

TEST(ScenePatch, MissingObjectsOnThePathAreCreated) {
  // The default scene has no simulation.constraints block.
  const Scene patched = patched_scene(default_scene(), {{"simulation.constraints.method", "fast_projection"},
                                                        {"simulation.constraints.tolerance", "1e-2"}});
  EXPECT_EQ(patched.sim.projection.method, sim::ProjectionMethod::fast_projection);
  EXPECT_DOUBLE_EQ(patched.sim.projection.tolerance, 1e-2);
}

TEST(ScenePatch, UnknownKeyNamesSetAndTheKey) {
  const std::string message =
      error_of([] { patched_scene(default_scene(), {{"simulation.time_stp", "1 ms"}}); });
  EXPECT_CONTAINS(message, "--set simulation.time_stp=1 ms: ");
  EXPECT_CONTAINS(message, "simulation.time_stp");
  EXPECT_CONTAINS(message, "time_step");  // the "did you mean"
}

TEST(ScenePatch, BadValueNamesSetTheKeyAndWhatWasExpected) {
  const std::string resolution =
      error_of([] { patched_scene(default_scene(), {{"cloth.resolution", "[1,8]"}}); });
  EXPECT_CONTAINS(resolution, "--set cloth.resolution=[1,8]: ");
  EXPECT_CONTAINS(resolution, "cloth.resolution");
  const std::string integrator = error_of([] {
    patched_scene(default_scene(), {{"cloth.resolution", "[9,9]"}, {"simulation.integrator", "leapfrog"}});
  });
  // Only the culprit is named, and the choices are listed.
  EXPECT_EQ(integrator.find("--set cloth.resolution"), std::string::npos) << integrator;
  EXPECT_CONTAINS(integrator, "--set simulation.integrator=leapfrog: ");
  EXPECT_CONTAINS(integrator, "rk4");
  const std::string through =
      error_of([] { patched_scene(default_scene(), {{"cloth.size.warp", "1"}}); });
  EXPECT_CONTAINS(through, "--set cloth.size.warp=1");
  EXPECT_CONTAINS(through, "'cloth.size' is not an object");
}

TEST(ScenePatch, GridIsTheCartesianProductLastKeyFastest) {
  const auto grid = setting_grid({{"a", {"1", "2"}}, {"b", {"x", "y", "z"}}});
  ASSERT_EQ(grid.size(), 6u);
  EXPECT_EQ(describe(grid[0]), "a=1 b=x");
  EXPECT_EQ(describe(grid[1]), "a=1 b=y");
  EXPECT_EQ(describe(grid[5]), "a=2 b=z");
  EXPECT_CONTAINS(error_of([] { setting_grid({{"a", {"1"}}, {"a", {"2"}}}); }), "'a' is given twice");
}

}  // namespace
}  // namespace weft::app
