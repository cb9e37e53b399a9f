// Backward Euler (one Newton step, Baraff & Witkin 1998) against its analytic recurrences and
// its invariants: exact free fall, the linear oscillator's amplification factor 1/(1 + h²ω²),
// unconditional stability far past the explicit limit with monotone energy loss, fixed pins,
// and a hanging cloth coming to rest. Each test runs on every sparse back-end of the build.
#include "sim/mass_spring.h"
#include "sim/integrators/implicit_euler.h"

#include <gtest/gtest.h>

#include <ostream>

#include "tests/sim/test_cloth.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <random>
#include <string>
#include <vector>

#include "sim/grid.h"
#include "sim/pins.h"
#include "sim/simulator.h"

namespace weft::sim {
namespace {

using test_cloth::fabric;
using test_cloth::square;

// A cloth advanced by ImplicitEuler: v_{n+1} from the integrator, then x_{n+1} = x_n + h v_{n+1}.
struct Cloth {
  ClothMesh mesh;
  MassSpringModel model;
  std::vector<Index> pinned;
  Eigen::VectorXd mass_kg, inv_mass;
  System system;
  ImplicitEuler integrator;
  Matrix3X x, v;  // #V×3, m and m/s

  static System make_system(const MassSpringModel& model, const Eigen::VectorXd& mass,
                            const Eigen::VectorXd& inv) {
    System s;
    s.mass_kg = mass;
    s.inv_mass = inv;
    s.terms = model.terms();
    return s;
  }

  static Eigen::VectorXd inverse_masses(const Eigen::VectorXd& mass,
                                        const std::vector<Index>& pins) {
    Eigen::VectorXd inv = mass.cwiseInverse();
    for (Index p : pins) inv[p] = 0.0;
    return inv;
  }

  Cloth(ClothMesh m, const Material& material, std::vector<Index> pins,
        const ImplicitSolveSettings& solve, bool bending_in_step = false)
      : mesh(std::move(m)),
        model(mesh, material, /*structural_springs=*/true, bending_in_step),
        pinned(std::move(pins)),
        mass_kg(material.density_kg_m2 * mesh.vertex_area_m2),
        inv_mass(inverse_masses(mass_kg, pinned)),
        system(make_system(model, mass_kg, inv_mass)),
        integrator(system, solve),
        x(mesh.rest_positions),
        v(Matrix3X::Zero(mesh.vertex_count(), 3)) {}

  void step(double h_s, const Vec3& g, double damping_1_s) {
    system.gravity_m_s2 = g;
    system.damping_1_s = damping_1_s;
    const StepReport r = integrator.step(system, x, v, h_s);  // and x += h v
    ASSERT_TRUE(r.solved);
    EXPECT_GE(r.solve_s, 0.0);
  }

  // Kinetic + elastic (springs and bending) + gravitational energy, J.
  double energy(const Vec3& g) const {
    double e = model.energy(x);
    for (Index i = 0; i < x.rows(); ++i)
      e += mass_kg[i] * (0.5 * v.row(i).squaredNorm() - x.row(i).dot(g.transpose()));
    return e;
  }

  // Largest |f_i + m_i g| over free vertices, divided by the largest weight m_i |g|: 0 at
  // static equilibrium.
  double relative_residual_force(const Vec3& g) const {
    Matrix3X f = Matrix3X::Zero(x.rows(), 3);
    model.add_forces(x, f);
    double worst = 0.0;
    for (Index i = 0; i < x.rows(); ++i)
      if (inv_mass[i] > 0.0)
        worst = std::max(worst, (f.row(i) + mass_kg[i] * g.transpose()).norm());
    return worst / (mass_kg.maxCoeff() * g.norm());
  }

  double max_speed() const { return v.rowwise().norm().maxCoeff(); }
};

class ImplicitEulerTest : public testing::TestWithParam<ImplicitSolveSettings> {};

}  // namespace

// How GoogleTest names a parameter in its output (instead of a byte dump).
void PrintTo(const ImplicitSolveSettings& solve, std::ostream* out) {
  if (solve.method == ImplicitSolve::direct)
    *out << "direct " << sparse_backend_name(solve.backend);
  else
    *out << "conjugate gradients to " << solve.cg_tolerance;
}

namespace {

// With no spring stretched, K annihilates the uniform Δv and the system is M(1 + hα) Δv =
// h M (g − α v): v_{n+1} = (v_n + h g)/(1 + hα) for every vertex. With α = 0, v_n = n h g and
// x_n = x_0 + h² g n(n+1)/2 — the same as symplectic Euler, to round-off.
TEST_P(ImplicitEulerTest, FreeFallFollowsTheDiscreteRecurrenceExactly) {
  const Vec3 g(0.0, 0.0, -9.81);
  const double h = 0.01;
  for (double alpha : {0.0, 0.8}) {
    Cloth cloth(square(9, 1.0, Vec3(0, 0, 1)), fabric(500.0), {}, GetParam());
    double c = 0.0;  // v_n = c_n g
    for (int n = 1; n <= 60; ++n) {
      cloth.step(h, g, alpha);
      c = (c + h) / (1.0 + h * alpha);
      for (Index i = 0; i < cloth.x.rows(); ++i)
        ASSERT_LT((Vec3(cloth.v.row(i)) - c * g).norm(), 1e-12 * g.norm())
            << "alpha " << alpha << " step " << n << " vertex " << i;
      if (alpha == 0.0) {
        EXPECT_NEAR(c, n * h, 1e-15);
      }
    }
    if (alpha == 0.0) {
      const Vec3 drop = g * h * h * 0.5 * 60.0 * 61.0;
      for (Index i = 0; i < cloth.x.rows(); ++i)
        EXPECT_LT((Vec3(cloth.x.row(i)) - Vec3(cloth.mesh.rest_positions.row(i)) - drop).norm(),
                  1e-12)
            << "vertex " << i;
    }
  }
}

// A 1-D linear oscillator: a 2×2 grid without shear springs, its u = 0 edge pinned, the free
// edge displaced along the warp. Each free vertex hangs on one warp spring (k, mass m; the weft
// spring between them and the zero-stiffness diagonals do not act on a common x displacement),
// ω² = k/m. Backward Euler's recurrence for ü = −ω²u − αu̇:
//   v_{n+1} (1 + hα + h²ω²) = v_n − hω² u_n,   u_{n+1} = u_n + h v_{n+1},
// and without damping ω²u² + v² shrinks by exactly 1/(1 + h²ω²) per step (the amplification
// factor |1/(1 ± i hω)|²), for any h.
TEST_P(ImplicitEulerTest, LinearOscillatorFollowsTheBackwardEulerRecurrence) {
  Material m;
  m.density_kg_m2 = 0.2;
  m.stretch_warp_N_m = m.stretch_weft_N_m = 1000.0;
  m.shear_N_m = 0.0;
  m.bend_warp_Nm = m.bend_weft_Nm = 0.0;
  const ClothMesh mesh = square(2, 0.1, Vec3(0, 0, 1));
  const std::vector<Index> pins{mesh.index(0, 0), mesh.index(0, 1)};
  const Index free_vertices[] = {mesh.index(1, 0), mesh.index(1, 1)};
  const Vec3 no_gravity = Vec3::Zero();

  for (double h_omega : {0.05, 1.0, 20.0}) {
    for (double alpha : {0.0, 70.0}) {
      Cloth cloth(mesh, m, pins, GetParam());
      const Spring& warp = cloth.model.springs().front();
      ASSERT_EQ(warp.kind, SpringKind::warp);
      const double omega2 = warp.k_N_m / cloth.mass_kg[warp.b];
      const double h = h_omega / std::sqrt(omega2);
      const double u0 = 0.02;  // m, a 20 % stretch
      for (Index i : free_vertices) cloth.x(i, 0) += u0;

      // ω²u² + v² of the cloth's first free vertex.
      const auto oscillator_energy = [&] {
        const double disp =
            cloth.x(free_vertices[0], 0) - cloth.mesh.rest_positions(free_vertices[0], 0);
        return omega2 * disp * disp + cloth.v(free_vertices[0], 0) * cloth.v(free_vertices[0], 0);
      };
      double u = u0, vel = 0.0;
      for (int n = 1; n <= 100; ++n) {
        const double before = oscillator_energy();
        cloth.step(h, no_gravity, alpha);
        vel = (vel - h * omega2 * u) / (1.0 + h * alpha + h * h * omega2);
        u += h * vel;
        const std::string where = "hω " + std::to_string(h_omega) + " α " + std::to_string(alpha) +
                                  " step " + std::to_string(n);
        for (Index i : free_vertices) {
          const Vec3 disp = cloth.x.row(i) - cloth.mesh.rest_positions.row(i);
          ASSERT_NEAR(disp.x(), u, 1e-9 * u0) << where;
          ASSERT_NEAR(cloth.v(i, 0), vel, 1e-9 * u0 * std::sqrt(omega2)) << where;
          ASSERT_LT(disp.tail<2>().norm() + cloth.v.row(i).tail<2>().norm(), 1e-12) << where;
        }
        // While the displacement is well above the round-off of x − x_rest (~1e-17 m).
        if (alpha == 0.0 && std::abs(u) > 1e-4 * u0) {
          EXPECT_NEAR(oscillator_energy() / before, 1.0 / (1.0 + h_omega * h_omega), 1e-9) << where;
        }
      }
    }
  }
}

// A stiff cloth (Y = 1e5 N/m) with h = 1/24 s, more than a hundred times the explicit critical
// step of the same mesh and material, displaced in its plane (the stiff stretch and shear modes
// that set the explicit limit): without damping its energy still falls at every step, to
// round-off. In the linear regime one Newton step is exact backward Euler, whose energy change
// per step is −½|Δv|²_M − ½h²|v_{n+1}|²_K ≤ 0: it dissipates, it never injects energy.
TEST_P(ImplicitEulerTest, StiffClothFarPastTheExplicitLimitLosesEnergyEveryStep) {
  const ClothMesh mesh = square(16, 1.0, Vec3(0, 0, 1));
  const Material stiff = fabric(1e5);
  const auto pins = resolve_pins({PinCorner{"u0v1"}, PinCorner{"u1v1"}}, mesh);
  const double h = 1.0 / 24.0;
  const double critical = Simulator(mesh, stiff, pins, SimSettings{}).critical_time_step();
  ASSERT_GT(h / critical, 100.0) << "critical step " << critical << " s";

  Cloth cloth(mesh, stiff, pins, GetParam());
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> offset(-1e-2 / 15.0, 1e-2 / 15.0);  // 1 % of an edge
  for (Index i = 0; i < cloth.x.rows(); ++i)
    if (cloth.inv_mass[i] > 0.0)
      cloth.x.row(i).head<2>() += Eigen::RowVector2d(offset(rng), offset(rng));
  const Vec3 no_gravity = Vec3::Zero();
  const double initial = cloth.energy(no_gravity);
  ASSERT_GT(initial, 0.0);
  double energy = initial;
  for (int n = 1; n <= 48; ++n) {
    cloth.step(h, no_gravity, 0.0);
    ASSERT_TRUE(cloth.x.allFinite() && cloth.v.allFinite()) << "step " << n;
    const double next = cloth.energy(no_gravity);
    ASSERT_LE(next, energy + 1e-12 * initial) << "step " << n;
    energy = next;
  }
  EXPECT_LT(energy, 1e-12 * initial);
}

// The Gershgorin bound max_i bound_i / m_i over the stiffness a mass-spring grid leaves out of
// implicit Euler's matrix (its bending, explicit): an upper bound on that part's ω².
double explicit_bending_omega2(const ClothMesh& mesh, const Material& material) {
  const MassSpringModel model(mesh, material);
  Eigen::VectorXd bound = Eigen::VectorXd::Zero(mesh.vertex_count());
  for (const auto& term : model.terms())
    if (!term->stiffness_in_time_step()) term->add_stiffness_row_bound(bound);
  const Eigen::VectorXd mass = material.density_kg_m2 * mesh.vertex_area_m2;
  return (bound.array() / mass.array()).maxCoeff();
}

// Explicit bending inside the implicit step is stable only while h² ω_bend² stays small. On a
// fine sheet (4 mm edges) at h = 1/120 s the bending's Gershgorin bound gives h² ω² ≈ 450: a
// small out-of-plane checkerboard, free of gravity and damping, grows when the bending is
// left explicit (a hundredfold within a step), and never gains energy with the bending's
// near-flat stiffness in the matrix.
TEST_P(ImplicitEulerTest, BendingInTheMatrixKeepsAFineSheetStableWhereExplicitBendingGrows) {
  const ClothMesh mesh = square(64, 0.25, Vec3(0, 0, 1));
  const Material material = fabric(1e3);
  const double h = 1.0 / 120.0;
  ASSERT_GT(h * h * explicit_bending_omega2(mesh, material), 100.0);
  const Vec3 no_gravity = Vec3::Zero();
  const double amplitude = 1e-2 * 0.25 / 63.0;  // 1 % of an edge
  const auto perturbed = [&](Cloth& cloth) {
    for (Index j = 0; j < mesh.nv; ++j)
      for (Index i = 0; i < mesh.nu; ++i)
        cloth.x(mesh.index(i, j), 2) += (i + j) % 2 == 0 ? amplitude : -amplitude;
  };
  Cloth explicit_bending(mesh, material, {}, GetParam());
  perturbed(explicit_bending);
  const double start = explicit_bending.energy(no_gravity);
  ASSERT_GT(start, 0.0);
  double largest = start;  // it grows hundredfold within a step, then swings (θ saturates)
  for (int n = 0; n < 10; ++n) {
    explicit_bending.step(h, no_gravity, 0.0);
    largest = std::max(largest, explicit_bending.energy(no_gravity));
  }
  EXPECT_GT(largest, 100.0 * start);

  Cloth implicit_bending(mesh, material, {}, GetParam(), /*bending_in_step=*/true);
  perturbed(implicit_bending);
  double energy = implicit_bending.energy(no_gravity);
  EXPECT_DOUBLE_EQ(energy, start);
  for (int n = 1; n <= 10; ++n) {
    implicit_bending.step(h, no_gravity, 0.0);
    const double next = implicit_bending.energy(no_gravity);
    ASSERT_LE(next, energy * (1.0 + 1e-9)) << "step " << n;
    energy = next;
  }
  EXPECT_LT(energy, 0.5 * start);
}

// Bending left out of the matrix steps as in symplectic Euler: stable for h ω < 2, with ω² at
// most max_i bound_i / m_i (Gershgorin), which the out-of-plane checkerboard mode reaches (a
// stencil's row bound is its own mode's). On a flat sheet without tension (springs at rest
// have no transverse stiffness) that mode's energy, perturbed, swings but stops growing at
// 0.8 × 2/ω_G (the simulator's safety factor) and grows a hundredfold at 1.3 × (where h² ω² > 4
// even for the interior's ω² = 0.8 ω_G²).
TEST_P(ImplicitEulerTest, ExplicitBendingIsStableBelowTwoOverOmegaAndGrowsAbove) {
  const ClothMesh mesh = square(24, 0.25, Vec3(0, 0, 1));
  const Material material = fabric(1e3);
  const Vec3 no_gravity = Vec3::Zero();
  const double omega2 = explicit_bending_omega2(mesh, material);
  // The largest energy over the first and the second 60 steps, over the start's.
  const auto largest = [&](double h_s) {
    Cloth cloth(mesh, material, {}, GetParam());
    const double amplitude = 1e-3 * 0.25 / 23.0;  // 0.1 % of an edge
    for (Index j = 0; j < mesh.nv; ++j)
      for (Index i = 0; i < mesh.nu; ++i)
        cloth.x(mesh.index(i, j), 2) += (i + j) % 2 == 0 ? amplitude : -amplitude;
    const double start = cloth.energy(no_gravity);
    std::array<double, 2> most = {start, start};
    for (int n = 0; n < 120; ++n) {
      cloth.step(h_s, no_gravity, 0.0);
      most[n / 60] = std::max(most[n / 60], cloth.energy(no_gravity));
    }
    return std::array<double, 2>{most[0] / start, most[1] / start};
  };
  const double limit_s = 2.0 / std::sqrt(omega2);
  const std::array<double, 2> safe = largest(0.8 * limit_s), past = largest(1.3 * limit_s);
  std::printf("2/omega_G = %.3g ms; largest energy / start over steps 1-60, 61-120: at 0.8x "
              "%.3g, %.3g; at 1.3x %.3g, %.3g\n",
              1e3 * limit_s, safe[0], safe[1], past[0], past[1]);
  EXPECT_LE(safe[1], safe[0] * (1.0 + 1e-6));  // no growth
  EXPECT_LT(safe[0], 10.0);
  EXPECT_GT(past[0], 100.0);
}

// The same stiff cloth falling from horizontal, hanging from two corners, h = 1/24 s: far from
// the linear regime (the first steps overshoot: one Newton step does not see the stretch its
// large vertical Δv causes next to the pins, up to ~15 % strain at step 2) it stays finite,
// comes to rest, and hangs with its edges nearly inextensible; the pins never move.
TEST_P(ImplicitEulerTest, StiffHangingClothStaysFiniteAndComesToRestNearlyInextensible) {
  const ClothMesh mesh = square(16, 1.0, Vec3(0, 0, 1));
  const Material stiff = fabric(1e5);
  const auto pins = resolve_pins({PinCorner{"u0v1"}, PinCorner{"u1v1"}}, mesh);
  const Vec3 g(0.0, 0.0, -9.81);
  Cloth cloth(mesh, stiff, pins, GetParam());
  const double initial = cloth.energy(g);
  for (int n = 1; n <= 240; ++n) {  // 10 s
    cloth.step(1.0 / 24.0, g, 0.0);
    ASSERT_TRUE(cloth.x.allFinite() && cloth.v.allFinite()) << "step " << n;
  }
  EXPECT_LT(cloth.max_speed(), 1e-2);
  EXPECT_LT(cloth.energy(g), 0.6 * initial);  // the centre of mass has dropped by ~½ m from 1 m
  double max_strain = 0.0;
  for (const Spring& s : cloth.model.springs())
    if (s.kind != SpringKind::shear)
      max_strain = std::max(
          max_strain, std::abs((cloth.x.row(s.b) - cloth.x.row(s.a)).norm() / s.rest_m - 1.0));
  EXPECT_LT(max_strain, 1e-3);
  for (Index p : pins) EXPECT_EQ(Vec3(cloth.x.row(p)), Vec3(mesh.rest_positions.row(p)));
}

// Pins are eliminated from the system, whatever the neighbours do: a cloth thrown with random,
// large velocities keeps its pinned vertices exactly in place with exactly zero velocity.
TEST_P(ImplicitEulerTest, PinnedVerticesNeverMove) {
  const ClothMesh mesh = square(12, 1.0, Vec3(0, 0, 1));
  const auto pins = resolve_pins({PinCorner{"u0v0"}, PinGrid{6, 6}, PinGrid{11, 3}}, mesh);
  Cloth cloth(mesh, fabric(2000.0), pins, GetParam());
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> speed(-3.0, 3.0);
  for (Index i = 0; i < cloth.v.rows(); ++i)
    if (cloth.inv_mass[i] > 0.0)
      cloth.v.row(i) = Eigen::RowVector3d(speed(rng), speed(rng), speed(rng));
  for (int n = 0; n < 100; ++n) cloth.step(1.0 / 60.0, Vec3(0, 0, -9.81), 0.3);
  for (Index p : pins) {
    EXPECT_EQ(Vec3(cloth.x.row(p)), Vec3(mesh.rest_positions.row(p))) << "vertex " << p;
    EXPECT_EQ(Vec3(cloth.v.row(p)), Vec3::Zero()) << "vertex " << p;
  }
}

// The wool of sim::Material hanging from two corners comes to static equilibrium with and
// without air damping (backward Euler's own dissipation suffices), and both reach the same
// equilibrium: damping changes the path, not the rest state. The hanging sheet buckles to one
// side or the other of the vertical plane through the pins (y = y_pin), so "the same" is up to
// that mirror symmetry of the problem.
TEST_P(ImplicitEulerTest, HangingClothComesToRestWithAndWithoutDamping) {
  const ClothMesh mesh = square(12, 0.5, Vec3(0, 0, 1));
  const auto pins = resolve_pins({PinCorner{"u0v1"}, PinCorner{"u1v1"}}, mesh);
  const double y_pin = mesh.rest_positions(pins[0], 1);
  const Vec3 g(0.0, 0.0, -9.81);
  std::vector<Matrix3X> rest_shapes;
  std::vector<double> rest_energies;
  for (double alpha : {0.0, 0.5}) {
    Cloth cloth(mesh, Material{}, pins, GetParam());
    for (int n = 0; n < 720; ++n) cloth.step(1.0 / 24.0, g, alpha);  // 30 s
    EXPECT_LT(cloth.max_speed(), 1e-5) << "alpha " << alpha;
    EXPECT_LT(cloth.relative_residual_force(g), 1e-5) << "alpha " << alpha;
    rest_shapes.push_back(cloth.x);
    rest_energies.push_back(cloth.energy(g));
  }
  Matrix3X mirrored = rest_shapes[1];
  mirrored.col(1) = (2.0 * y_pin) - mirrored.col(1).array();
  const double same = (rest_shapes[0] - rest_shapes[1]).rowwise().norm().maxCoeff();
  const double mirror = (rest_shapes[0] - mirrored).rowwise().norm().maxCoeff();
  EXPECT_LT(std::min(same, mirror), 1e-6) << "same " << same << " m, mirrored " << mirror << " m";
  EXPECT_NEAR(rest_energies[0], rest_energies[1], 1e-9 * std::abs(rest_energies[0]));
}

// The numerical-trouble tier: a system that cannot be factorized (here, from a non-finite
// position) reports solved = false and leaves the velocities as they were.
TEST_P(ImplicitEulerTest, FailedFactorizationLeavesTheVelocitiesUnchanged) {
  Cloth cloth(square(5, 1.0, Vec3(0, 0, 1)), fabric(500.0), {}, GetParam());
  cloth.v.setConstant(0.25);
  cloth.x(7, 1) = std::numeric_limits<double>::quiet_NaN();
  const Matrix3X before = cloth.v;
  cloth.system.gravity_m_s2 = Vec3(0, 0, -9.81);
  const StepReport r = cloth.integrator.step(cloth.system, cloth.x, cloth.v, 0.01);
  EXPECT_FALSE(r.solved);
  EXPECT_EQ(cloth.v, before);
}

// Every direct back-end, and conjugate gradients converged to round-off (so that the same
// recurrences and equilibria hold).
std::vector<ImplicitSolveSettings> solves() {
  std::vector<ImplicitSolveSettings> out;
  for (SparseBackend b : available_sparse_backends()) {
    ImplicitSolveSettings direct;
    direct.backend = b;
    out.push_back(direct);
  }
  ImplicitSolveSettings cg;
  cg.method = ImplicitSolve::conjugate_gradient;
  cg.cg_tolerance = 1e-13;
  cg.cg_max_iterations = 5000;
  out.push_back(cg);
  return out;
}

std::string solve_test_name(const testing::TestParamInfo<ImplicitSolveSettings>& info) {
  return info.param.method == ImplicitSolve::direct ? sparse_backend_name(info.param.backend)
                                                    : "conjugate_gradient";
}

INSTANTIATE_TEST_SUITE_P(ImplicitEuler, ImplicitEulerTest, testing::ValuesIn(solves()),
                         solve_test_name);

}  // namespace
}  // namespace weft::sim
