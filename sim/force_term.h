#pragma once
// A cloth force model as a sum of elements over small vertex stencils: the one interface that
// every force of a System (sim/system.h) implements — the mass-spring model's springs and
// angular bending (sim/mass_spring.h), carried constraint tension
// (sim/constraints/carried_tension.h), the continuum models (Baraff–Witkin triangles,
// sim/continuum/; rotation-free triangles, sim/rft/) — so that the integrators need not know
// which model they step. Air drag, which depends on the velocity and the time too, is its
// velocity-dependent variant, VelocityForceTerm below.
//
// An element couples the vertices of its stencil (2 for a pair, 3 for a triangle, 4 for a
// hinge, 6 for a rotation-free patch). Its energy E_e(x) is a function of those vertices
// only; the term's energy is the sum. Implicit Euler needs each element's stiffness
// K_e = ∂²E_e/∂x² projected onto the positive semi-definite cone (so that the system matrix
// stays SPD); the explicit integrators need only the forces.
//
// Terms whose elements are vertex pairs (springs, carried tension) derive from PairForceTerm:
// implicit Euler assembles those by their 3×3 block, as fast as a dedicated spring path.

#include <algorithm>
#include <cstddef>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "sim/types.h"

namespace weft::sim {

inline constexpr int kMaxStencil = 6;
// An element's stiffness: (3s)×(3s) for a stencil of s vertices, ordered as the stencil
// (DOF 3k + c is coordinate c of stencil vertex k). Fixed capacity: no heap allocation.
using ElementMatrix =
    Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, 0, 3 * kMaxStencil, 3 * kMaxStencil>;

class ForceTerm {
 public:
  virtual ~ForceTerm() = default;

  // What the term is, for `weft run --explain`: e.g. "Baraff–Witkin stretch on 1922 triangles".
  virtual std::string describe() const = 0;

  virtual std::size_t element_count() const = 0;
  // The vertices of element e (stencil_size(e) of them, at most kMaxStencil).
  virtual int stencil_size(std::size_t e) const = 0;
  virtual void stencil(std::size_t e, Index* vertices) const = 0;

  // Σ_e E_e(x), J.
  virtual double energy(const Matrix3X& x) const = 0;
  // f += −∇E(x), N.
  virtual void add_forces(const Matrix3X& x, Matrix3X& f) const = 0;
  // K_e at x, N/m, into K (resized to 3s×3s): projected onto the PSD cone when project_psd
  // (what implicit Euler uses), else ∂²E_e/∂x² itself (what the finite-difference tests check;
  // a term that only has an approximation says so in its header and its tests). Terms without
  // stiffness (has_stiffness() false) enter implicit Euler through their forces only.
  virtual bool has_stiffness() const { return true; }
  // Whether implicit Euler assembles this stiffness into its step's matrix; false: the term's
  // forces stay explicit there (its right-hand side only), while a static solve still uses
  // its stiffness (sim/linear/stiffness_assembly.h).
  virtual bool stiffness_in_time_step() const { return has_stiffness(); }
  virtual void element_stiffness(const Matrix3X& x, std::size_t e, ElementMatrix& K,
                                 bool project_psd) const = 0;
  // K_e as implicit Euler's matrix takes it: the PSD-projected Hessian, unless the term says
  // otherwise in its header (an approximation that is PSD by construction; the forces stay
  // exact, so the step is still consistent).
  virtual void time_step_stiffness(const Matrix3X& x, std::size_t e, ElementMatrix& K) const {
    element_stiffness(x, e, K, true);
  }
  // bound[i] += an upper bound on Σ_j |K_ij| (3×3 block norms) over vertex i's block row of the
  // rest stiffness, N/m: with masses m, the largest eigenvalue of M⁻¹K is at most
  // max_i bound_i / m_i (Gershgorin), which sets the explicit integrators' critical step.
  virtual void add_stiffness_row_bound(Eigen::VectorXd& bound) const = 0;
};

using ForceTerms = std::vector<std::shared_ptr<const ForceTerm>>;

// A term of vertex pairs (a, b) whose stiffness is [H −H; −H H] for a symmetric 3×3 block H.
class PairForceTerm : public ForceTerm {
 public:
  // The two vertices of element e.
  virtual std::pair<Index, Index> pair(std::size_t e) const = 0;
  // H of element e at x, N/m: PSD-projected when project_psd.
  virtual Mat3 pair_stiffness(const Matrix3X& x, std::size_t e, bool project_psd) const = 0;

  int stencil_size(std::size_t) const final { return 2; }
  void stencil(std::size_t e, Index* vertices) const final {
    const auto [a, b] = pair(e);
    vertices[0] = a;
    vertices[1] = b;
  }
  void element_stiffness(const Matrix3X& x, std::size_t e, ElementMatrix& K,
                         bool project_psd) const final {
    const Mat3 H = pair_stiffness(x, e, project_psd);
    K.resize(6, 6);
    K << H, -H, -H, H;
  }
};

// The velocity-dependent variant: forces of positions, velocities and time (air drag and
// wind, sim/aerodynamics.h), without an energy or a stiffness. Every integrator takes them
// explicitly, at the step's start time.
class VelocityForceTerm {
 public:
  virtual ~VelocityForceTerm() = default;
  virtual std::string describe() const = 0;
  // f += the forces at positions x (m), velocities v (m/s) and time t (s), N.
  virtual void add_forces(const Matrix3X& x, const Matrix3X& v, double time_s,
                          Matrix3X& f) const = 0;
};

using VelocityForceTerms = std::vector<std::shared_ptr<const VelocityForceTerm>>;

// For add_stiffness_row_bound: bound[v] += Σ_c |K_e(r, c)| maximised over v's three rows r,
// for every element e, with K_e the projected stiffness at x (the rest positions, typically).
// Summing each element's row maxima bounds the assembled rows' sums, so Gershgorin holds.
inline void add_row_bound_from_stiffness(const ForceTerm& term, const Matrix3X& x,
                                         Eigen::VectorXd& bound) {
  ElementMatrix K;
  Index v[kMaxStencil];
  for (std::size_t e = 0; e < term.element_count(); ++e) {
    const int s = term.stencil_size(e);
    term.stencil(e, v);
    term.element_stiffness(x, e, K, true);
    for (int a = 0; a < s; ++a) {
      double row_max = 0.0;
      for (int r = 0; r < 3; ++r) row_max = std::max(row_max, K.row(3 * a + r).cwiseAbs().sum());
      bound[v[a]] += row_max;
    }
  }
}

}  // namespace weft::sim
