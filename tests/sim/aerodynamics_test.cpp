// Air drag and wind (sim/aerodynamics.h): the flat-plate force, its independence of the
// triangle's orientation, the wind field, and a falling sheet's terminal speed.
#include "sim/aerodynamics.h"

#include <gtest/gtest.h>

#include <cmath>

#include "sim/simulator.h"

namespace weft::sim {
namespace {

constexpr double kRho = 1.2, kCd = 1.17;

// A 1 × 0.5 m panel in the xy plane falling at 2 m/s: ½ ρ C_d A v² upwards.
TEST(PanelDrag, FlatPlateNormalToTheFlow) {
  const Vec3 area =
      quad_area_vector(Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(1, 0.5, 0), Vec3(0, 0.5, 0));
  EXPECT_NEAR(area.z(), 0.5, 1e-15);
  const Vec3 f = panel_drag_force(area, Vec3(0, 0, -2), kRho, kCd);
  EXPECT_NEAR(f.z(), 0.5 * kRho * kCd * 0.5 * 4.0, 1e-12);
  EXPECT_NEAR(f.head<2>().norm(), 0.0, 1e-15);
  // The other orientation (normal flipped) gives the same force.
  EXPECT_LT((panel_drag_force(-area, Vec3(0, 0, -2), kRho, kCd) - f).norm(), 1e-15);
}

// Only the normal component of the relative velocity counts, quadratically.
TEST(PanelDrag, NormalComponentOnly) {
  const Vec3 area(0, 0, 0.5);
  EXPECT_EQ(panel_drag_force(area, Vec3(3, -2, 0), kRho, kCd).norm(), 0.0);
  const Vec3 oblique = panel_drag_force(area, Vec3(5, 0, -1), kRho, kCd);
  const Vec3 normal = panel_drag_force(area, Vec3(0, 0, -1), kRho, kCd);
  EXPECT_LT((oblique - normal).norm(), 1e-15);
  const Vec3 twice = panel_drag_force(area, Vec3(0, 0, -2), kRho, kCd);
  EXPECT_NEAR(twice.z() / normal.z(), 4.0, 1e-12);
}

TEST(WindField, UniformAndGusting) {
  WindField w;
  w.velocity_m_s = Vec3(4, 0, 0);
  EXPECT_EQ(w.at(Vec3(1, 2, 3), 7.0), Vec3(4, 0, 0));
  w.gust = {0.5, 2.0, 0.0};
  EXPECT_NEAR(w.at(Vec3::Zero(), 0.5).x(), 4.0 * 1.5, 1e-12);  // a quarter period: sin = 1
  EXPECT_NEAR(w.at(Vec3::Zero(), 1.5).x(), 4.0 * 0.5, 1e-12);
  w.gust.wavelength_m = 8.0;  // travels downwind: the crest at x = 2 m arrives T/4 later
  EXPECT_NEAR(w.at(Vec3(2, 0, 0), 1.0).x(), 4.0 * 1.5, 1e-12);
}

// A wind normal to a flat sheet pushes it with ½ ρ C_d A U² in the wind's direction.
TEST(Aerodynamics, WindOnASheetAtRest) {
  GridSpec g;
  g.nu = g.nv = 5;
  g.size_u_m = 0.8;
  g.size_v_m = 0.5;
  const ClothMesh mesh = make_grid(g);
  AeroSettings s;
  s.enabled = true;
  s.wind.velocity_m_s = Vec3(0, 0, 3);
  const Aerodynamics aero(mesh.quads, s);
  Matrix3X f = Matrix3X::Zero(mesh.vertex_count(), 3);
  aero.add_forces(mesh.rest_positions, Matrix3X::Zero(mesh.vertex_count(), 3), 0.0, f);
  const Vec3 total = f.colwise().sum().transpose();
  EXPECT_NEAR(total.z(), 0.5 * s.air_density_kg_m3 * s.drag_coefficient * 0.4 * 9.0, 1e-12);
  EXPECT_NEAR(total.head<2>().norm(), 0.0, 1e-12);
}

// A free horizontal sheet falls until drag carries its weight: v_t = √(2 ρ_A g / (ρ C_d)),
// 1.78 m/s for Kang & Yu's wool, reached within about 5 v_t/g ≈ 0.9 s. No mass damping.
TEST(Aerodynamics, FallingSheetReachesTerminalSpeed) {
  for (Integrator integrator : {Integrator::symplectic_euler, Integrator::implicit_euler}) {
    SCOPED_TRACE(integrator_name(integrator));
    GridSpec g;
    g.nu = g.nv = 9;
    g.size_u_m = g.size_v_m = 0.4;
    const Material wool;
    SimSettings s;
    s.integrator = integrator;
    s.air_damping_1_s = 0.0;
    s.aero.enabled = true;
    s.max_speed_m_s = 1e3;
    Simulator sim(make_grid(g), wool, {}, s);
    sim.advance(1.5);
    const Eigen::VectorXd& m = sim.masses_kg();
    const double v_com = (m.transpose() * sim.state().v.col(2)).value() / m.sum();
    const double v_t = std::sqrt(2.0 * wool.density_kg_m2 * s.gravity_m_s2.norm() /
                                 (s.aero.air_density_kg_m3 * s.aero.drag_coefficient));
    EXPECT_NEAR(-v_com / v_t, 1.0, 0.01) << "v_com " << v_com << " m/s, v_t " << v_t << " m/s";
  }
}

}  // namespace
}  // namespace weft::sim
