#pragma once
// Test support, part of no library: the two kinds of matrix weft hands to SparseSpdSolver, built
// on a perturbed cloth, for tests/sim/sparse_spd_solver_test and bench/sparse_solver_bench.
// Header-only, under tests/ so that production code cannot include it; it sits above the model
// (grid, pins, edge constraints, springs), whose kernels it reuses so that the matrices are the
// ones the simulator builds.
//
//   projection_matrix      J M⁻¹ Jᵀ of fast projection (Goldenthal et al. 2007, seed 000 §4),
//                          #C×#C over the warp and weft edge constraints C_e = |x_b − x_a|²/l − l.
//   implicit_euler_matrix  M (1 + h α) + h² K of backward Euler (Baraff & Witkin 1998),
//                          3#V×3#V over warp, weft and both shear diagonals.

#include <cstdint>
#include <random>
#include <tuple>
#include <utility>
#include <vector>

#include "sim/constraints/inextensibility.h"
#include "sim/constraints/projection.h"
#include "sim/energies/spring_hessian.h"
#include "sim/grid.h"
#include "sim/linear/sparse_spd_solver.h"
#include "sim/mass_spring.h"
#include "sim/material/material.h"
#include "sim/pins.h"

namespace weft::sim::test_matrices {

// An n×n vertex, 1 m × 1 m cloth of ρ = 0.2 kg/m² (lumped ρ·area masses) with corners u0v1 and
// u1v1 pinned, its vertices moved off the flat grid so that the matrices are generic.
struct ClothSample {
  ClothMesh mesh;
  Matrix3X x;                // #V×3 positions, m
  Eigen::VectorXd mass_kg;   // #V
  Eigen::VectorXd inv_mass;  // #V, 1/kg; 0 at the pins
};

// Each coordinate of each vertex moves by a uniform amount in ±perturbation × grid spacing,
// drawn from std::mt19937 seeded with `seed` (its output sequence is fixed by the standard; the
// mapping to [−1, 1] is done here, not by a library distribution, so samples are portable).
inline ClothSample make_cloth_sample(Index n, std::uint32_t seed, double perturbation = 0.2) {
  GridSpec spec;
  spec.nu = spec.nv = n;
  ClothSample sample;
  sample.mesh = make_grid(spec);
  const double density_kg_m2 = 0.2;
  sample.mass_kg = density_kg_m2 * sample.mesh.vertex_area_m2;
  sample.inv_mass = sample.mass_kg.cwiseInverse();
  for (Index pin : resolve_pins({PinCorner{"u0v1"}, PinCorner{"u1v1"}}, sample.mesh)) {
    sample.inv_mass[pin] = 0.0;
  }
  std::mt19937 random(seed);
  const double spacing_m = spec.size_u_m / static_cast<double>(n - 1);
  const double amplitude_m = perturbation * spacing_m;
  sample.x = sample.mesh.rest_positions;
  for (Index v = 0; v < sample.x.rows(); ++v) {
    for (int c = 0; c < 3; ++c) {
      const double unit = static_cast<double>(random()) / static_cast<double>(std::mt19937::max());
      sample.x(v, c) += amplitude_m * (2.0 * unit - 1.0);
    }
  }
  return sample;
}

// A = J M⁻¹ Jᵀ, #C×#C, both triangles stored, with J the #C×3#V Jacobian of the constraints at
// x (row e: ∇_b C_e in vertex b's columns, −∇_b C_e in a's). Pinned vertices (inv_mass 0) are
// left out of J's columns, so A's pattern is "constraints sharing a free vertex" — the pattern
// FastProjection analyses. A constraint between two pinned vertices gives an empty row and
// column: A is then singular (make_edge_constraints leaves such constraints out).
inline SparseMatrix projection_matrix(const std::vector<EdgeConstraint>& constraints,
                                      const Matrix3X& x, const Eigen::VectorXd& inv_mass) {
  std::vector<int> column_of(static_cast<std::size_t>(x.rows()), -1);  // free vertex → J block
  int free_count = 0;
  for (Index v = 0; v < x.rows(); ++v) {
    if (inv_mass[v] > 0.0) column_of[static_cast<std::size_t>(v)] = free_count++;
  }
  std::vector<Eigen::Triplet<double>> entries;
  entries.reserve(6 * constraints.size());
  for (std::size_t e = 0; e < constraints.size(); ++e) {
    const EdgeConstraint& c = constraints[e];
    const Vec3 gradient_b = edge_constraint_gradient_b(x.row(c.a), x.row(c.b), c.rest_m);
    for (const auto& [vertex, sign] : {std::pair{c.a, -1.0}, std::pair{c.b, 1.0}}) {
      const int block = column_of[static_cast<std::size_t>(vertex)];
      if (block < 0) continue;
      for (int k = 0; k < 3; ++k) {
        entries.emplace_back(static_cast<int>(e), 3 * block + k, sign * gradient_b[k]);
      }
    }
  }
  SparseMatrix J(static_cast<Eigen::Index>(constraints.size()), 3 * free_count);
  J.setFromTriplets(entries.begin(), entries.end());
  Eigen::VectorXd inv_mass_dof(3 * free_count);
  for (Index v = 0; v < x.rows(); ++v) {
    const int block = column_of[static_cast<std::size_t>(v)];
    if (block >= 0) inv_mass_dof.segment<3>(3 * block).setConstant(inv_mass[v]);
  }
  const SparseMatrix J_inv_mass = J * inv_mass_dof.asDiagonal();
  SparseMatrix A = J_inv_mass * SparseMatrix(J.transpose());
  A.makeCompressed();
  return A;
}

// The warp and weft constraints of the sample, as the simulator makes them.
inline std::vector<EdgeConstraint> warp_weft_constraints(const ClothSample& sample) {
  return make_edge_constraints(sample.mesh, ConstrainedEdges::warp_weft, sample.inv_mass);
}

inline SparseMatrix projection_matrix(const ClothSample& sample) {
  return projection_matrix(warp_weft_constraints(sample), sample.x, sample.inv_mass);
}

// A = M (1 + h α) + h² K, 3#V×3#V (DOF 3v + c is coordinate c of vertex v), both triangles
// stored, kg. K = Σ [H −H; −H H] over the mass-spring model's warp, weft and shear springs, each
// with stiffness k and H = spring_hessian_b_projected (k d̂d̂ᵀ plus the positive transverse part
// of a stretched spring). Every vertex keeps its mass, pinned or not: A is positive definite.
inline SparseMatrix implicit_euler_matrix(const ClothSample& sample, double h_s = 1.0 / 240.0,
                                          double damping_1_s = 1.0, double k_N_m = 1000.0) {
  const MassSpringModel model(sample.mesh, Material{});
  const Index n = sample.mesh.vertex_count();
  std::vector<Eigen::Triplet<double>> entries;
  entries.reserve(3 * static_cast<std::size_t>(n) + 36 * model.springs().size());
  for (Index v = 0; v < n; ++v) {
    for (int c = 0; c < 3; ++c) {
      entries.emplace_back(3 * v + c, 3 * v + c, sample.mass_kg[v] * (1.0 + h_s * damping_1_s));
    }
  }
  for (const Spring& s : model.springs()) {
    const Mat3 H =
        h_s * h_s *
        spring_hessian_b_projected(sample.x.row(s.a), sample.x.row(s.b), s.rest_m, k_N_m);
    for (const auto& [p, q, sign] : {std::tuple{s.a, s.a, 1.0}, std::tuple{s.b, s.b, 1.0},
                                     std::tuple{s.a, s.b, -1.0}, std::tuple{s.b, s.a, -1.0}}) {
      for (int r = 0; r < 3; ++r) {
        for (int c = 0; c < 3; ++c) entries.emplace_back(3 * p + r, 3 * q + c, sign * H(r, c));
      }
    }
  }
  SparseMatrix A(3 * n, 3 * n);
  A.setFromTriplets(entries.begin(), entries.end());  // sums the duplicates
  A.makeCompressed();
  return A;
}

}  // namespace weft::sim::test_matrices
