#include "sim/integrators/implicit_euler.h"

#include <algorithm>
#include <memory>
#include <string>
#include <vector>

#include "base/check.h"
#include "base/timer.h"
#include "sim/linear/block_conjugate_gradient.h"
#include "sim/linear/stiffness_assembly.h"

namespace weft::sim {

// The 3#V×3#V system A = M (1 + h α) + h² K (sim/linear/stiffness_assembly.h: its pattern is
// built and analysed once, each step refills the values). A pinned vertex's rows and columns
// are the identity with a zero right-hand side (its DOFs are eliminated: Δv = 0 there).
struct ImplicitEuler::Impl {
  StiffnessAssembly assembly;
  ImplicitSolveSettings solve_settings;
  std::unique_ptr<SparseSpdSolver> solver;  // direct
  std::unique_ptr<BlockConjugateGradient> cg;  // conjugate gradients
  Eigen::VectorXd last_dv;  // conjugate gradients' warm start
  Eigen::VectorXd diagonal; // #V, M (1 + h α) of the last fill, kg
  Matrix3X forces;          // #V×3 scratch, N
  Matrix3X velocity_forces; // #V×3 scratch, N
  Matrix3X kv;              // #V×3 scratch, K v_n, N/s

  Impl(const System& system, const ImplicitSolveSettings& solve);
  // WEFT_CHECKs that `system` has the structure this was built for.
  void check_structure(const System& system, const Matrix3X& x, const Matrix3X& v) const;
  // Δv = A⁻¹ rhs into dv; false when the solve failed.
  bool solve_system(const Eigen::VectorXd& rhs, Eigen::VectorXd& dv, StepReport& result);
  // h (f − h K v + M (g − α v)) on the free DOFs, 0 on the pinned ones, N·s.
  Eigen::VectorXd right_hand_side(const System& system, const Matrix3X& v, double h_s) const;
  // Holds the normal velocity of each resting contact of `system` that free flight would move
  // into its obstacle at zero: A and rhs as in implicit_euler.h. Returns how many it held.
  int hold_contacts(const System& system, const Matrix3X& v, double h_s, Eigen::VectorXd& rhs);
  bool pinned(Index i) const { return assembly.pinned(i); }
};

ImplicitEuler::Impl::Impl(const System& system, const ImplicitSolveSettings& solve)
    : assembly(system, StiffnessAssembly::Terms::time_step, "ImplicitEuler"), solve_settings(solve) {
  const Index n = system.vertex_count();
  forces = Matrix3X::Zero(n, 3);
  kv = Matrix3X::Zero(n, 3);
  if (solve.method == ImplicitSolve::direct) {
    solver = make_sparse_spd_solver(solve.backend);
    solver->analyze(assembly.matrix());
  } else {
    cg = std::make_unique<BlockConjugateGradient>(solve.threads);
    using Grid = BlockConjugateGradient::GridPreconditioner;
    const bool on_grid = uses_multigrid(solve) || uses_lines(solve);
    const Grid grid = !uses_lines(solve)     ? Grid::multigrid
                      : lines_when_slow(solve) ? Grid::lines_when_slow
                                               : Grid::lines;
    cg->analyze(assembly.matrix(), on_grid ? solve.grid_nu : 0, on_grid ? solve.grid_nv : 0, grid);
    last_dv = Eigen::VectorXd::Zero(3 * n);
  }
}

void ImplicitEuler::Impl::check_structure(const System& system, const Matrix3X& x,
                                          const Matrix3X& v) const {
  const Index n = system.vertex_count();
  WEFT_CHECK(x.rows() == n && v.rows() == n,
             "ImplicitEuler::step: positions or velocities have " +
                 std::to_string(std::min(x.rows(), v.rows())) + " rows, expected " +
                 std::to_string(n));
  assembly.check_structure(system, "ImplicitEuler::step");
}

bool ImplicitEuler::Impl::solve_system(const Eigen::VectorXd& rhs, Eigen::VectorXd& dv,
                                       StepReport& result) {
  const SparseMatrix& A = assembly.matrix();
  if (solver) {
    if (!solver->factorize(A)) return false;
    dv = solver->solve(rhs);
    return dv.allFinite();  // NaN/inf in, or a factorization that should have failed
  }
  cg->set_matrix(A);
  dv = last_dv;
  const BlockConjugateGradient::Result r =
      cg->solve(rhs, dv, solve_settings.cg_tolerance, solve_settings.cg_max_iterations);
  result.cg_iterations = r.iterations;
  // Not converging within the cap still leaves a usable (smaller-residual) Δv; a breakdown
  // (non-SPD A, non-finite input) does not.
  if (r.breakdown || !dv.allFinite()) return false;
  last_dv = dv;
  return true;
}

Eigen::VectorXd ImplicitEuler::Impl::right_hand_side(const System& system, const Matrix3X& v,
                                                     double h_s) const {
  const Index n = system.vertex_count();
  Eigen::VectorXd rhs(3 * n);  // N·s
  const Eigen::RowVector3d g = system.gravity_m_s2.transpose();
  const double alpha = system.damping_1_s;
  for (Index i = 0; i < n; ++i) {
    Eigen::RowVector3d bi = Eigen::RowVector3d::Zero();
    if (!pinned(i))
      bi = h_s * (forces.row(i) - h_s * kv.row(i) + system.mass_kg[i] * (g - alpha * v.row(i)));
    rhs.segment<3>(3 * i) = bi.transpose();
  }
  return rhs;
}

// Each held contact i with normal n adds κ n nᵀ to A's block (i, i) and κ n (−n·v_i) to rhs_i,
// κ = kContactWeight × the block's mean diagonal: row i then reads
//   n·Δv_i + (A Δv − rhs)_i·n / κ = −n·v_i,
// so n·v_{n+1} = 0 up to about 1/kContactWeight of the solve's own scale, while the tangential
// rows are unchanged (friction stays with the collide phase). A penalty on the diagonal keeps
// A's pattern and its SPD-ness; it is the limit of Baraff & Witkin's filtered constraint.
int ImplicitEuler::Impl::hold_contacts(const System& system, const Matrix3X& v, double h_s,
                                       Eigen::VectorXd& rhs) {
  constexpr double kContactWeight = 1e6;
  int held = 0;
  for (const ObstacleContact& c : system.contacts) {
    const Index i = c.vertex;
    WEFT_CHECK(i >= 0 && i < system.vertex_count(), "ImplicitEuler: contact vertex " +
                                                        std::to_string(i) + " of " +
                                                        std::to_string(system.vertex_count()));
    if (pinned(i)) continue;
    const Vec3& n = c.normal;
    // Free flight over the step: v + h (f/m + g − α v), along n.
    const Vec3 vi = v.row(i).transpose();
    const Vec3 accel = forces.row(i).transpose() / system.mass_kg[i] + system.gravity_m_s2 -
                       system.damping_1_s * vi;
    if (n.dot(vi + h_s * accel) >= 0.0) continue;  // leaving or sliding: not pressed in
    const int d = 3 * static_cast<int>(i);
    const double weight = kContactWeight *
                          (assembly.lower_entry(d, d) + assembly.lower_entry(d + 1, d + 1) +
                           assembly.lower_entry(d + 2, d + 2)) /
                          3.0;
    for (int r = 0; r < 3; ++r)
      for (int col = 0; col <= r; ++col)
        assembly.lower_entry(d + r, d + col) += weight * n[r] * n[col];
    rhs.segment<3>(d) -= weight * n.dot(vi) * n;
    ++held;
  }
  return held;
}

ImplicitEuler::ImplicitEuler(const System& system, const ImplicitSolveSettings& solve)
    : m_impl(std::make_unique<Impl>(system, solve)) {}

ImplicitEuler::~ImplicitEuler() = default;

// One Newton step of backward Euler (Baraff & Witkin 1998, with ∂f/∂x = −K, ∂f/∂v = −α M):
//   (M (1 + h α) + h² K) Δv = h (f(x_n) − α M v_n − h K v_n + M g),   v_{n+1} = v_n + Δv.
StepReport ImplicitEuler::step(const System& system, State& state, double h_s) {
  const base::Stopwatch watch;
  Impl& im = *m_impl;
  const Matrix3X& x = state.x;
  Matrix3X& v = state.v;
  im.check_structure(system, x, v);
  im.diagonal = system.mass_kg * (1.0 + h_s * system.damping_1_s);
  im.assembly.fill(x, im.diagonal, h_s * h_s, &v, &im.kv);
  im.forces.setZero();
  system.add_forces(x, im.forces);  // every term, N
  if (system.has_velocity_forces()) {  // explicitly, at (x_n, v_n)
    im.velocity_forces.setZero(x.rows(), 3);
    system.add_velocity_forces(x, v, state.time_s, im.velocity_forces);
    im.forces += im.velocity_forces;
  }
  Eigen::VectorXd rhs = im.right_hand_side(system, v, h_s);

  StepReport result;
  if (!system.contacts.empty()) result.held_contacts = im.hold_contacts(system, v, h_s, rhs);
  Eigen::VectorXd dv;  // m/s
  result.solved = im.solve_system(rhs, dv, result);
  if (result.solved) {
    for (Index i = 0; i < x.rows(); ++i)
      if (!im.pinned(i)) v.row(i) += dv.segment<3>(3 * i).transpose();
  }
  state.x += h_s * v;
  result.solve_s = watch.seconds();
  return result;
}

// The direct solver refactorizes every step; only conjugate gradients' warm start carries over.
void ImplicitEuler::save_state(StateWriter& out) const {
  out.section("implicit Euler");
  out.matrix(m_impl->last_dv);
}

void ImplicitEuler::restore_state(StateReader& in) {
  in.section("implicit Euler");
  in.matrix(m_impl->last_dv, m_impl->last_dv.size(), 1);
}

}  // namespace weft::sim
