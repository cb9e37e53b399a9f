#pragma once
// Shared by the preconditioner tests: a 33² mass-spring hang (the default material, corners
// u0v1 and u1v1 pinned) stepped for 0.1 s by implicit Euler, h = 1/120 s, with conjugate
// gradients to 1e-9 under a given preconditioner, so tight that the positions do not depend on
// the preconditioner.

#include <gtest/gtest.h>

#include <cstdio>

#include "sim/grid.h"
#include "sim/integrators/time_integrator.h"
#include "sim/pins.h"
#include "sim/simulator.h"

namespace weft::sim::test_cloth {

struct CgHang {
  Matrix3X x;             // the positions after 0.1 s
  long cg_iterations = 0;  // over the 12 steps
};

inline CgHang cg_hang(CgPreconditioner preconditioner) {
  GridSpec grid;
  grid.nu = grid.nv = 33;
  grid.origin = Vec3(-0.5, 0.0, 1.6);
  const ClothMesh mesh = make_grid(grid);
  const auto pins = resolve_pins({PinCorner{"u0v1"}, PinCorner{"u1v1"}}, mesh);
  SimSettings s;
  s.integrator = Integrator::implicit_euler;
  s.time_step = fixed_time_step(1.0 / 120.0);
  s.implicit_solve = ImplicitSolve::conjugate_gradient;
  s.implicit_cg_tolerance = 1e-9;
  s.implicit_cg_preconditioner = preconditioner;
  Simulator sim(mesh, Material{}, pins, s);
  sim.advance(0.1);
  return {sim.state().x, sim.take_step_statistics().cg_iterations};
}

// The hang with `preconditioner` moves as with block Jacobi (to 1e-6 m: the solution does not
// depend on the path to it) in fewer than half block Jacobi's iterations.
inline void expect_same_steps_in_fewer_iterations(CgPreconditioner preconditioner,
                                                  const char* name) {
  const CgHang jacobi = cg_hang(CgPreconditioner::block_jacobi);
  const CgHang other = cg_hang(preconditioner);
  std::printf("33² hang, 12 steps: block Jacobi %ld, %s %ld CG iterations\n",
              jacobi.cg_iterations, name, other.cg_iterations);
  EXPECT_LT((jacobi.x - other.x).cwiseAbs().maxCoeff(), 1e-6);
  EXPECT_LT(2 * other.cg_iterations, jacobi.cg_iterations);
}

}  // namespace weft::sim::test_cloth
