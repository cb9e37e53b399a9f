#pragma once
// Finite-difference checks for any ForceTerm: its forces against central differences of its
// energy, and an element's stiffness against central differences of its forces. Failures print
// both sides.

#include <gtest/gtest.h>

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <random>
#include <sstream>
#include <vector>

#include "sim/force_term.h"
#include "sim/grid.h"
#include "sim/material/material.h"

namespace weft::sim::fd {

// A clearly anisotropic fabric for the continuum terms' tests: warp ≠ weft in stretch and
// bending, non-zero shear.
inline Material anisotropic_fabric() {
  Material m;
  m.stretch_warp_N_m = 1000.0;
  m.stretch_weft_N_m = 600.0;
  m.shear_N_m = 40.0;
  m.bend_warp_Nm = 8e-6;
  m.bend_weft_Nm = 3e-6;
  return m;
}

// nu × nv vertices over size_u × size_v metres, flat in the world x–y plane at z = 0.
inline ClothMesh flat_sheet(Index nu, Index nv, double size_u_m, double size_v_m) {
  GridSpec spec;
  spec.nu = nu;
  spec.nv = nv;
  spec.size_u_m = size_u_m;
  spec.size_v_m = size_v_m;
  spec.origin = Vec3::Zero();
  return make_grid(spec);
}

// x with every coordinate moved by a uniform random amount in [−amplitude, amplitude] (seeded).
inline Matrix3X perturbed(const Matrix3X& x, double amplitude, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(-amplitude, amplitude);
  Matrix3X y = x;
  for (Eigen::Index i = 0; i < y.rows(); ++i)
    for (int c = 0; c < 3; ++c) y(i, c) += u(rng);
  return y;
}

// −∂E/∂x_ic by central differences with step eps (m), for every coordinate of every vertex.
inline Matrix3X fd_forces(const ForceTerm& term, const Matrix3X& x, double eps) {
  Matrix3X f(x.rows(), 3);
  Matrix3X y = x;
  for (Eigen::Index i = 0; i < x.rows(); ++i)
    for (int c = 0; c < 3; ++c) {
      y(i, c) = x(i, c) + eps;
      const double ep = term.energy(y);
      y(i, c) = x(i, c) - eps;
      const double em = term.energy(y);
      y(i, c) = x(i, c);
      f(i, c) = -(ep - em) / (2.0 * eps);
    }
  return f;
}

// Asserts add_forces == −∇E within rel_tol of the largest force (plus abs_tol_N).
inline void expect_forces_match_energy(const ForceTerm& term, const Matrix3X& x, double eps = 1e-7,
                                       double rel_tol = 1e-5, double abs_tol_N = 1e-12) {
  Matrix3X f = Matrix3X::Zero(x.rows(), 3);
  term.add_forces(x, f);
  const Matrix3X fd = fd_forces(term, x, eps);
  const double scale = std::max(f.cwiseAbs().maxCoeff(), fd.cwiseAbs().maxCoeff());
  const double err = (f - fd).cwiseAbs().maxCoeff();
  EXPECT_LE(err, rel_tol * scale + abs_tol_N)
      << term.describe() << ": analytic forces differ from −dE/dx by " << err << " N (largest "
      << scale << " N)\nanalytic:\n"
      << f.topRows(std::min<Eigen::Index>(6, f.rows())) << "\nfinite differences:\n"
      << fd.topRows(std::min<Eigen::Index>(6, fd.rows()));
}

// The term's stiffness assembled over all elements, dense 3#V×3#V (small meshes only).
inline Eigen::MatrixXd assembled_stiffness(const ForceTerm& term, const Matrix3X& x,
                                           bool project_psd) {
  const Eigen::Index n = x.rows();
  Eigen::MatrixXd K = Eigen::MatrixXd::Zero(3 * n, 3 * n);
  ElementMatrix Ke;
  Index v[kMaxStencil];
  for (std::size_t e = 0; e < term.element_count(); ++e) {
    const int s = term.stencil_size(e);
    term.stencil(e, v);
    term.element_stiffness(x, e, Ke, project_psd);
    for (int a = 0; a < s; ++a)
      for (int b = 0; b < s; ++b) K.block<3, 3>(3 * v[a], 3 * v[b]) += Ke.block<3, 3>(3 * a, 3 * b);
  }
  return K;
}

// −∂f/∂x of the whole term by central differences of add_forces, dense 3#V×3#V.
inline Eigen::MatrixXd fd_assembled_stiffness(const ForceTerm& term, const Matrix3X& x,
                                              double eps) {
  const Eigen::Index n = x.rows();
  Eigen::MatrixXd K(3 * n, 3 * n);
  Matrix3X y = x;
  for (Eigen::Index j = 0; j < n; ++j)
    for (int d = 0; d < 3; ++d) {
      Matrix3X fp = Matrix3X::Zero(n, 3), fm = Matrix3X::Zero(n, 3);
      y(j, d) = x(j, d) + eps;
      term.add_forces(y, fp);
      y(j, d) = x(j, d) - eps;
      term.add_forces(y, fm);
      y(j, d) = x(j, d);
      for (Eigen::Index i = 0; i < n; ++i)
        for (int c = 0; c < 3; ++c) K(3 * i + c, 3 * j + d) = -(fp(i, c) - fm(i, c)) / (2.0 * eps);
    }
  return K;
}

// Asserts that the unprojected assembled stiffness equals −∂f/∂x by finite differences within
// rel_tol of its largest entry.
inline void expect_assembled_stiffness_matches_forces(const ForceTerm& term, const Matrix3X& x,
                                                      double eps = 1e-6, double rel_tol = 1e-4) {
  const Eigen::MatrixXd K = assembled_stiffness(term, x, /*project_psd=*/false);
  const Eigen::MatrixXd fd = fd_assembled_stiffness(term, x, eps);
  const double scale = std::max(K.cwiseAbs().maxCoeff(), fd.cwiseAbs().maxCoeff());
  Eigen::Index r = 0, c = 0;
  const double err = (K - fd).cwiseAbs().maxCoeff(&r, &c);
  EXPECT_LE(err, rel_tol * scale) << term.describe() << ": stiffness entry (" << r << ", " << c
                                  << ") is " << K(r, c) << " N/m, finite differences give "
                                  << fd(r, c) << " (largest entry " << scale << " N/m)";
}

// Smallest eigenvalue of a symmetric stiffness (≥ −tolerance for a PSD-projected one).
inline double smallest_eigenvalue(const Eigen::MatrixXd& K) {
  Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eig(K, Eigen::EigenvaluesOnly);
  return eig.eigenvalues().minCoeff();
}

// Asserts K is positive semi-definite up to rounding (eigenvalues ≥ −1e-9 × the largest |K_ij|).
inline void expect_positive_semidefinite(const Eigen::MatrixXd& K) {
  const double scale = K.cwiseAbs().maxCoeff();
  EXPECT_GE(smallest_eigenvalue(K), -1e-9 * scale) << "the largest entry is " << scale << " N/m";
}

}  // namespace weft::sim::fd
