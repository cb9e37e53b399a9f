// Remeshing during a simulation (simulation.remesh, Simulator::remesh_now, sim/cloth_remesh.h):
// a flat cloth at rest stays at rest, a hanging cloth is refined where it sags with its pins
// exactly where they were, the mass stays the cloth's, the same run gives the same bits, and the
// combinations that cannot be remeshed are errors naming the reason.

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <string>
#include <vector>

#include "sim/cloth_remesh.h"
#include "sim/simulator.h"
#include "sim/triangle_cloth.h"

namespace weft::sim {
namespace {

// A size_m square pattern of n × n vertices, each cell split into two triangles: a triangle mesh
// (no grid), laid at `origin` along `warp` (u) and `weft` (v).
ClothMesh triangle_square(double size_m, Index n, const Vec3& origin, const Vec3& warp,
                          const Vec3& weft) {
  ClothPattern p;
  p.origin = origin;
  p.warp_axis = warp;
  p.weft_axis = weft;
  const double h = size_m / static_cast<double>(n - 1);
  p.start_positions.resize(n * n, 3);
  for (Index j = 0; j < n; ++j)
    for (Index i = 0; i < n; ++i) {
      const Vec2 uv(h * static_cast<double>(i), h * static_cast<double>(j));
      p.material_coords.push_back(uv);
      p.start_positions.row(j * n + i) = (origin + uv.x() * warp + uv.y() * weft).transpose();
    }
  for (Index j = 0; j + 1 < n; ++j)
    for (Index i = 0; i + 1 < n; ++i) {
      const Index a = j * n + i, b = a + 1, c = a + n + 1, d = a + n;
      p.faces.push_back({a, b, c});
      p.faces.push_back({a, c, d});
    }
  return make_pattern_cloth(p);
}

SimSettings remeshing_settings(long every_steps) {
  SimSettings s;
  s.model = ClothModel::baraff_witkin;
  s.integrator = Integrator::implicit_euler;
  s.remesh.enabled = true;
  s.remesh.every_steps = every_steps;
  s.remesh.c_m = 1e-3;
  s.remesh.h_min_m = 0.01;
  s.remesh.h_max_m = 0.04;
  return s;
}

bool same_bits(const Matrix3X& a, const Matrix3X& b) {
  return a.rows() == b.rows() &&
         std::memcmp(a.data(), b.data(), sizeof(double) * static_cast<std::size_t>(a.size())) == 0;
}

// A 30 cm square on 2 cm cells lying on the ground under gravity: each remesh coarsens it (flat:
// h_max; 256 → 176 vertices), and nothing moves. Measured after ten remeshes and 1 s: in-plane
// displacement 3.4e-16 m, height change 4e-19 m, elastic energy 7e-29 J, speed 7e-15 m/s.
TEST(SimulatorRemesh, AClothLyingOnTheGroundStaysAtRestThroughRemeshes) {
  SimSettings s = remeshing_settings(12);
  PlaneObstacle ground;
  s.obstacles.push_back(ground);
  const double lift = s.collision_thickness_m;  // resting on the ground's skin
  ClothMesh mesh = triangle_square(0.3, 16, {0.0, 0.0, lift}, {1, 0, 0}, {0, 1, 0});
  const double area_m2 = mesh.vertex_area_m2.sum();
  Simulator sim(std::move(mesh), Material{}, {}, s);
  const Index before = sim.mesh().vertex_count();
  const double mass_kg = sim.masses_kg().sum();
  for (int frame = 0; frame < 10; ++frame) sim.advance(0.1);  // 120 steps, 10 remeshes
  EXPECT_EQ(sim.remesh_count(), 10);
  EXPECT_LT(sim.mesh().vertex_count(), before) << "a flat cloth is coarsened towards h_max";
  EXPECT_TRUE(sim.mesh().faces.size() > 0 && !sim.mesh().has_grid());
  const Matrix3X& x = sim.state().x;
  for (Index k = 0; k < x.rows(); ++k) {
    const Vec2& uv = sim.mesh().material_coords[static_cast<std::size_t>(k)];
    EXPECT_NEAR(x(k, 0), uv.x(), 1e-12) << k;
    EXPECT_NEAR(x(k, 1), uv.y(), 1e-12) << k;
    EXPECT_NEAR(x(k, 2), lift, 1e-12) << k;
  }
  const Diagnostics d = sim.diagnostics();
  EXPECT_LT(d.elastic_energy_J, 1e-26);
  EXPECT_LT(d.max_speed_m_s, 1e-12);
  const StepStatistics steps = sim.take_step_statistics();
  EXPECT_EQ(steps.remeshes, 10);
  // The transfer adds no energy: its change of the total (gravity's 3.4e-4 J with it) is
  // rounding (measured: 1.6e-18 J over the ten remeshes).
  EXPECT_LT(std::abs(steps.remesh_energy_J), 1e-15);
  // The lumped masses of every mesh add up to the cloth's: the domain is the same.
  EXPECT_NEAR(sim.masses_kg().sum(), mass_kg, 1e-12 * mass_kg);
  EXPECT_NEAR(sim.mesh().vertex_area_m2.sum(), area_m2, 1e-12 * area_m2);
}

// The same remesh, done by hand on a cloth at rest in its flat rest shape: the new mesh's
// energy (measured: 4.5e-29 J) and velocities are zero to rounding.
TEST(SimulatorRemesh, RemeshingAFlatClothAtRestKeepsItsEnergy) {
  SimSettings s = remeshing_settings(1000);
  s.gravity_m_s2.setZero();
  Simulator sim(triangle_square(0.3, 11, {0.0, 0.0, 1.0}, {1, 0, 0}, {0, 1, 0}), Material{}, {}, s);
  const double before_J = sim.diagnostics().total_energy_J();
  sim.remesh_now();
  EXPECT_EQ(sim.remesh_count(), 1);
  EXPECT_NEAR(sim.diagnostics().total_energy_J(), before_J, 1e-26);
  EXPECT_EQ(sim.state().v.cwiseAbs().maxCoeff(), 0.0);
  sim.advance(0.25);
  EXPECT_LT(sim.diagnostics().max_speed_m_s, 1e-12);
}

struct HangRun {
  std::vector<Index> vertex_counts;  // after each frame
  Matrix3X x;
  std::vector<Index> pinned;
  Matrix3X pinned_x;                 // the pinned vertices' positions, in pin order
  long remeshes = 0;
  bool finite = true;
};

// A 30 cm square on 3 cm cells hanging in the x–z plane from its two top corners, remeshed
// every 15 steps (8 frames of 1/24 s at h = 1/120 s: 40 steps), or never.
HangRun hang_with_remeshing(Matrix3X* pins_at_start = nullptr, bool remeshing = true) {
  const Index n = 11;
  ClothMesh mesh = triangle_square(0.3, n, {0.0, 0.0, 1.0}, {1, 0, 0}, {0, 0, -1});
  SimSettings settings = remeshing_settings(15);
  settings.remesh.enabled = remeshing;
  Simulator sim(std::move(mesh), Material{}, {0, n - 1}, settings);
  if (pins_at_start) {
    pins_at_start->resize(2, 3);
    for (int k = 0; k < 2; ++k) pins_at_start->row(k) = sim.state().x.row(sim.pinned()[static_cast<std::size_t>(k)]);
  }
  HangRun run;
  for (int frame = 0; frame < 8; ++frame) {
    sim.advance(1.0 / 24.0);
    run.vertex_counts.push_back(sim.mesh().vertex_count());
    run.finite = run.finite && sim.state().x.allFinite() && sim.state().v.allFinite();
  }
  run.x = sim.state().x;
  run.pinned = sim.pinned();
  run.pinned_x.resize(2, 3);
  for (int k = 0; k < 2; ++k) run.pinned_x.row(k) = sim.state().x.row(run.pinned[static_cast<std::size_t>(k)]);
  run.remeshes = sim.remesh_count();
  return run;
}

TEST(SimulatorRemesh, AHangingClothIsRemeshedWithItsPinsExactlyWhereTheyWere) {
  Matrix3X pins_at_start;
  const HangRun run = hang_with_remeshing(&pins_at_start);
  EXPECT_TRUE(run.finite);
  EXPECT_EQ(run.remeshes, 2);  // after steps 15 and 30
  EXPECT_NE(run.vertex_counts.front(), run.vertex_counts.back())
      << "the mesh changed between frames";
  EXPECT_TRUE(same_bits(run.pinned_x, pins_at_start)) << "pins kept bit for bit";
  // The pins are still the top corners of the pattern.
  EXPECT_EQ(run.pinned_x(0, 0), 0.0);
  EXPECT_EQ(run.pinned_x(1, 0), 0.3);
  // It hangs: everything else below the pins, the lowest point lower than the pins.
  EXPECT_LT(run.x.col(2).minCoeff(), 1.0 - 0.25);
  EXPECT_LE(run.x.col(2).maxCoeff(), 1.0 + 1e-9);
  // The same swing as on the mesh never remeshed: the lowest point within 1 mm (measured:
  // 0.1 mm; 121 vertices, then 167 and 168 after the two remeshes).
  const HangRun plain = hang_with_remeshing(nullptr, false);
  EXPECT_NEAR(run.x.col(2).minCoeff(), plain.x.col(2).minCoeff(), 1e-3);
}

// Dynamic relaxation (seed 002's own setting): its fictitious masses are made anew for each
// mesh; the relaxation goes on, finite, with its pins where they were.
TEST(SimulatorRemesh, DynamicRelaxationIsRemeshedWithItsPinsKept) {
  const Index n = 11;
  SimSettings s = remeshing_settings(40);
  s.integrator = Integrator::dynamic_relaxation;
  Simulator sim(triangle_square(0.3, n, {0.0, 0.0, 1.0}, {1, 0, 0}, {0, 0, -1}), Material{},
                {0, n - 1}, s);
  const Matrix3X pins = sim.state().x({0, n - 1}, Eigen::all);
  const Index before = sim.mesh().vertex_count();
  sim.advance(0.1);
  ASSERT_GT(sim.remesh_count(), 0);
  EXPECT_NE(sim.mesh().vertex_count(), before);
  EXPECT_TRUE(sim.state().x.allFinite());
  for (int k = 0; k < 2; ++k)
    EXPECT_EQ(sim.state().x.row(sim.pinned()[static_cast<std::size_t>(k)]), pins.row(k));
  EXPECT_LT(sim.state().x.col(2).minCoeff(), 1.0 - 0.05) << "it relaxes downwards";
}

TEST(SimulatorRemesh, TheSameRunGivesTheSameBits) {
  const HangRun a = hang_with_remeshing(), b = hang_with_remeshing();
  EXPECT_EQ(a.vertex_counts, b.vertex_counts);
  EXPECT_TRUE(same_bits(a.x, b.x));
}

// Seed 002's criterion (simulation.remesh.indicator), checked after every step: a cloth lying
// flat on the ground has max |κ|h² = 0 and is never remeshed.
TEST(SimulatorRemesh, UnderTheIndicatorAFlatClothIsNeverRemeshed) {
  SimSettings s = remeshing_settings(1);
  s.remesh.indicator = 2.0;
  PlaneObstacle ground;
  s.obstacles.push_back(ground);
  Simulator sim(triangle_square(0.3, 16, {0.0, 0.0, s.collision_thickness_m}, {1, 0, 0},
                                {0, 1, 0}),
                Material{}, {}, s);
  const Index before = sim.mesh().vertex_count();
  sim.advance(0.5);  // 60 steps, 60 checks
  EXPECT_EQ(sim.remesh_count(), 0);
  EXPECT_EQ(sim.mesh().vertex_count(), before);
  EXPECT_EQ(sim.take_step_statistics().remeshes, 0);
  EXPECT_LT(cloth_remesh_indicator_m(sim.mesh(), sim.state().x, s.remesh), 1e-12);
}

// A 30 cm square on 3 cm cells (c = 1 mm, h ∈ [1, 4] cm) lying horizontal, held at two
// adjacent corners: it falls and curls over the held edge. Checked after every step: flat at
// first (no remesh), remeshed once it curves enough that max |κ|h² passes 2c, and not at every
// check: a remesh brings the criterion back below the threshold. (Measured: remeshed at 7 of
// the 20 checks, 121 → 813 vertices; max |κ|h² at the end 1.0 c.)
TEST(SimulatorRemesh, UnderTheIndicatorAFoldingClothIsRemeshedWhenItCurves) {
  const Index n = 11;
  SimSettings s = remeshing_settings(1);
  s.remesh.indicator = 2.0;
  Simulator sim(triangle_square(0.3, n, {0.0, 0.0, 1.0}, {1, 0, 0}, {0, 1, 0}), Material{},
                {0, n - 1}, s);
  EXPECT_EQ(cloth_remesh_indicator_m(sim.mesh(), sim.state().x, s.remesh), 0.0);
  EXPECT_FALSE(sim.remesh_due());
  sim.advance(4.0 / 24.0);  // 20 steps, 20 checks
  const long checks = 20;
  EXPECT_GE(sim.remesh_count(), 1);
  EXPECT_LT(sim.remesh_count(), checks / 2);
  EXPECT_TRUE(sim.state().x.allFinite());
  EXPECT_LE(cloth_remesh_indicator_m(sim.mesh(), sim.state().x, s.remesh),
            s.remesh.indicator * s.remesh.c_m);
}

std::string remesh_error(const ClothMesh& mesh, const SimSettings& s) {
  try {
    check_remesh_settings(mesh, s);
  } catch (const std::invalid_argument& e) {
    return e.what();
  }
  return "";
}

TEST(SimulatorRemesh, WhatCannotBeRemeshedIsAnErrorNamingTheReason) {
  const ClothMesh triangles = triangle_square(0.3, 5, {0, 0, 1}, {1, 0, 0}, {0, 1, 0});
  SimSettings s = remeshing_settings(10);
  EXPECT_EQ(remesh_error(triangles, s), "");
  GridSpec g;
  g.nu = g.nv = 5;
  EXPECT_NE(remesh_error(make_grid(g), s).find("simulation.remesh: needs a triangle-mesh cloth"),
            std::string::npos);
  SimSettings springs = s;
  springs.model = ClothModel::mass_spring;
  EXPECT_NE(remesh_error(triangles, springs).find("mass_spring"), std::string::npos);
  SimSettings rft = s;
  rft.model = ClothModel::rft6;
  EXPECT_NE(remesh_error(triangles, rft).find("not with simulation.model \"rft6\": RFT bending"),
            std::string::npos);
  SimSettings explicit_step = s;
  explicit_step.integrator = Integrator::symplectic_euler;
  EXPECT_NE(remesh_error(triangles, explicit_step).find("implicit_euler or dynamic_relaxation"),
            std::string::npos);
  SimSettings projected = s;
  projected.projection.method = ProjectionMethod::fast_projection;
  EXPECT_NE(remesh_error(triangles, projected).find("fast projection needs warp/weft edges"),
            std::string::npos);
  // The simulator makes the same check; a state of a remeshed cloth is not saved.
  EXPECT_THROW(Simulator(make_grid(g), Material{}, {}, s), std::invalid_argument);
  Simulator sim(triangle_square(0.3, 5, {0, 0, 1}, {1, 0, 0}, {0, 1, 0}), Material{}, {}, s);
  StateWriter fresh;
  EXPECT_NO_THROW(sim.save_state(fresh));
  sim.remesh_now();
  StateWriter remeshed;
  EXPECT_THROW(sim.save_state(remeshed), std::logic_error);
  SimSettings off = s;
  off.remesh.enabled = false;
  Simulator plain(triangle_square(0.3, 5, {0, 0, 1}, {1, 0, 0}, {0, 1, 0}), Material{}, {}, off);
  EXPECT_THROW(plain.remesh_now(), std::invalid_argument);
}

}  // namespace
}  // namespace weft::sim
