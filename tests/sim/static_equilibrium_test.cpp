// The static equilibrium solver (sim/statics/static_equilibrium.h): a spring's static extension
// (analytic); the Peirce cantilever's chord angle (elastica) and its agreement with implicit
// Euler's damped solve; a cantilever bending by a nonlinear law against the nonlinear elastica
// solved by shooting; a sheet resting on a plane inside the contact layer; the same seed giving
// the same bits and every solve lowering the energy.
#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <functional>

#include "sim/mass_spring.h"
#include "sim/simulator.h"
#include "sim/statics/static_equilibrium.h"
#include "tests/sim/cantilever_support.h"
#include "tests/sim/test_cloth.h"

namespace weft::sim {
namespace {

using namespace cantilever;  // NOLINT: the strip and its helpers (cantilever_support.h)

TEST(StaticEquilibrium, HangingSpringReachesTheStaticExtensionInAFewNewtonSteps) {
  const double m = 0.01, k = 100.0, L = 0.2, g = 9.81;  // kg, N/m, m, m/s²
  const System system = test_cloth::hanging_spring(m, k, L, g);  // vertex 0 pinned
  StaticSettings settings;
  settings.tolerance = 1e-12;
  const StaticEquilibrium statics(system, {}, 0.0, L, L, settings);
  Matrix3X x(2, 3);
  x << 0.0, 0.0, 0.0, 0.0, 0.0, -L;
  const StaticResult r = statics.solve(x);
  EXPECT_TRUE(r.converged) << r.stopped;
  EXPECT_LE(r.residual, 1e-12);
  EXPECT_NEAR(-x(1, 2) - L, m * g / k, 1e-9 * m * g / k);
  EXPECT_NEAR(x(1, 0), 0.0, 1e-12);  // the imperfection swung back under the pin
  EXPECT_EQ(Vec3(x.row(0)), Vec3::Zero());
  EXPECT_LE(r.iterations, 10);
}

// The strip of cantilever_support.h solved statically.
Bent solve_strip(const Material& material, StripAlong along, double overhang_m, Index segments,
                 StaticResult* result = nullptr) {
  const Strip strip = make_strip(along, overhang_m, segments);
  SimSettings settings;
  Simulator sim(strip.mesh, material, strip.clamped, settings);
  StaticSettings s;
  s.tolerance = 1e-7;
  const StaticResult r = sim.solve_static(s);
  EXPECT_TRUE(r.converged) << r.stopped;
  if (result) *result = r;
  return measure(strip, sim.state().x);
}

// Peirce: at O = 2c the chord makes 41.5° (the elastica, cantilever_test.cpp); and the same
// strip's rest shape agrees with implicit Euler's damped solve to rest.
TEST(StaticEquilibrium, PeirceCantileverMatchesTheElasticaAndTheDampedSolve) {
  const double overhang = 2.0 * bending_length(kWool, StripAlong::warp);
  StaticResult r;
  const auto start = std::chrono::steady_clock::now();
  const Bent statics = solve_strip(kWool, StripAlong::warp, overhang, 24, &r);
  const double static_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  const Bent damped = hang_strip(kWool, StripAlong::warp, overhang, 24);
  std::printf("Peirce O = 2c: static chord %.3f deg (%d Newton iterations, %.3f s), damped implicit "
              "Euler %.3f deg; elastica 41.5\n",
              statics.chord_deg(), r.iterations, static_s, damped.chord_deg());
  EXPECT_NEAR(statics.chord_deg(), 41.5, 1.0);
  EXPECT_NEAR(statics.drop_m / damped.drop_m, 1.0, 2e-3);
}

// The nonlinear elastica: θ' = κ(s) with M(κ(s)) = m(s), m' = −w (O − s) cos θ, θ(0) = 0,
// m(O) = 0; m(0) found by bisection (shooting), RK4 on n steps. Returns the tip drop, m.
double nonlinear_elastica_drop(const BendingLaw& law, double w, double O, int n = 2000) {
  const auto curvature = [&](double moment) {  // M⁻¹ by bisection (M rises)
    double lo = 0.0, hi = 1.0;
    while (law.moment(hi) < moment) hi *= 2.0;
    for (int k = 0; k < 60; ++k) {
      const double mid = 0.5 * (lo + hi);
      (law.moment(mid) < moment ? lo : hi) = mid;
    }
    return 0.5 * (lo + hi);
  };
  // State (θ, m, y); returns m(O) and the drop.
  const auto shoot = [&](double m0, double& drop) {
    const double h = O / n;
    double theta = 0.0, m = m0, y = 0.0;
    const auto rhs = [&](double s, double th, double mm, double out[3]) {
      out[0] = curvature(std::max(mm, 0.0));
      out[1] = -w * (O - s) * std::cos(th);
      out[2] = std::sin(th);
    };
    for (int i = 0; i < n; ++i) {
      const double s = i * h;
      double k1[3], k2[3], k3[3], k4[3];
      rhs(s, theta, m, k1);
      rhs(s + h / 2, theta + h / 2 * k1[0], m + h / 2 * k1[1], k2);
      rhs(s + h / 2, theta + h / 2 * k2[0], m + h / 2 * k2[1], k3);
      rhs(s + h, theta + h * k3[0], m + h * k3[1], k4);
      theta += h / 6 * (k1[0] + 2 * k2[0] + 2 * k3[0] + k4[0]);
      m += h / 6 * (k1[1] + 2 * k2[1] + 2 * k3[1] + k4[1]);
      y += h / 6 * (k1[2] + 2 * k2[2] + 2 * k3[2] + k4[2]);
    }
    drop = y;
    return m;
  };
  double lo = 0.0, hi = w * O * O;  // m(0) ≤ w O² / 2 < hi
  double drop = 0.0;
  for (int k = 0; k < 60; ++k) {
    const double mid = 0.5 * (lo + hi);
    (shoot(mid, drop) < 0.0 ? lo : hi) = mid;
  }
  shoot(0.5 * (lo + hi), drop);
  return drop;
}

// A strip whose bending curve is Grosberg's (stiff, then soft beyond κ₀): its static shape
// against the nonlinear elastica's tip drop, and against the linear strip of the same initial
// rigidity, which it must droop well below.
TEST(StaticEquilibrium, CantileverWithAFrictionalBendingLawMatchesTheNonlinearElastica) {
  Material m = kWool;
  const double w = m.density_kg_m2 * 9.81;
  const BendingLaw law = BendingLaw::frictional(2e-6, 1.2e-4, 15.0);  // N·m, N, 1/m
  m.bend_law_warp = law;
  m.bend_warp_Nm = law.initial_rigidity();
  const double overhang = 0.025;
  const double reference = nonlinear_elastica_drop(law, w, overhang);
  const Bent bent = solve_strip(m, StripAlong::warp, overhang, 48);
  Material linear = kWool;
  linear.bend_warp_Nm = law.initial_rigidity();
  const Bent stiff = solve_strip(linear, StripAlong::warp, overhang, 48);
  std::printf("frictional law (%s): tip drop %.3f mm, nonlinear elastica %.3f mm; linear at the "
              "initial rigidity %.3f mm\n",
              law.describe().c_str(), bent.drop_m * 1e3, reference * 1e3, stiff.drop_m * 1e3);
  EXPECT_NEAR(bent.drop_m / reference, 1.0, 0.01);
  EXPECT_GT(bent.drop_m, 1.5 * stiff.drop_m);
}

TEST(StaticEquilibrium, SheetRestsOnAPlaneInsideTheContactLayerAndTheSameSeedGivesTheSameBits) {
  GridSpec grid;
  grid.nu = grid.nv = 9;
  grid.size_u_m = grid.size_v_m = 0.2;
  grid.origin = Vec3(-0.1, -0.1, 0.01);
  const ClothMesh mesh = make_grid(grid);
  SimSettings settings;
  settings.obstacles = {PlaneObstacle{Vec3::Zero(), Vec3::UnitZ()}};
  const double thickness = settings.collision_thickness_m;
  const auto solve = [&](unsigned seed, double* energy_drop) {
    Simulator sim(mesh, kWool, {}, settings);
    StaticSettings s;
    s.seed = seed;
    const StaticEquilibrium statics(sim.system(), settings.obstacles, thickness, 0.025, 0.025, s);
    Matrix3X x = sim.state().x;
    const double before = statics.energy(x);
    const StaticResult r = sim.solve_static(s);
    EXPECT_TRUE(r.converged) << r.stopped;
    EXPECT_EQ(r.contacts, 81);
    if (energy_drop) *energy_drop = before - r.energy_J;
    return sim.state().x;
  };
  double drop = 0.0;
  const Matrix3X a = solve(1, &drop), b = solve(1, nullptr), c = solve(2, nullptr);
  EXPECT_GT(drop, 0.0);
  EXPECT_EQ(a, b);
  EXPECT_NE(a, c);
  // Each vertex carries its own weight: it sinks δ / 1000 into the layer, nothing more.
  EXPECT_LT(a.col(2).maxCoeff(), thickness);
  EXPECT_GT(a.col(2).minCoeff(), thickness * (1.0 - 2e-3));
}

TEST(StaticEquilibrium, RefusesWhatHasNoStaticPotential) {
  const Strip strip = make_strip(StripAlong::warp, 0.05, 8);
  SimSettings settings;
  settings.aero.enabled = true;
  EXPECT_NE(static_solve_refusal(settings).find("simulation.air"), std::string::npos);
  settings.aero.enabled = false;
  settings.projection.method = ProjectionMethod::fast_projection;
  Simulator sim(strip.mesh, kWool, strip.clamped, settings);
  EXPECT_THROW(sim.solve_static({}), std::invalid_argument);
}

}  // namespace
}  // namespace weft::sim
