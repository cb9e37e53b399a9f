#pragma once
// Position-level constraint solvers that run after an integrator's unconstrained step (the
// "project" phase). The simulator then sets v = (x_{n+1} − x_n) / h: a velocity filter.

#include <memory>
#include <string>
#include <vector>

#include "base/enum_names.h"
#include "sim/grid.h"
#include "sim/linear/sparse_spd_solver.h"
#include "sim/state_archive.h"
#include "sim/types.h"

namespace weft::sim {

struct EdgeConstraint {
  Index a, b;
  double rest_m;
};

// Which edges carry inextensibility constraints: the warp and weft edges of the quad grid
// (seed 000), or additionally the diagonal that triangulates each quad, so that every edge of
// the triangle mesh is constrained (the "locking" configuration of seed 000 §3).
enum class ConstrainedEdges { warp_weft, triangle_edges };

inline constexpr base::EnumNames<ConstrainedEdges, 2> constrained_edges_names{
    {{ConstrainedEdges::warp_weft, "warp_weft"}, {ConstrainedEdges::triangle_edges, "triangle_edges"}}};

// The constrained edges of the grid, without edges whose two ends are both pinned (nothing can
// change their length: a redundant, all-zero row of the Jacobian).
std::vector<EdgeConstraint> make_edge_constraints(const ClothMesh& mesh, ConstrainedEdges which,
                                                  const Eigen::VectorXd& inv_mass);

// Largest |length / rest − 1| over the constraints.
double max_edge_strain(const std::vector<EdgeConstraint>& constraints, const Matrix3X& x);
// The same over the constraints with an end whose inverse mass is not 0 (the others cannot
// be corrected).
double max_edge_strain(const std::vector<EdgeConstraint>& constraints, const Matrix3X& x,
                       const Eigen::VectorXd& inv_mass);
// Throws std::invalid_argument (set_inverse_masses) unless `now` has the size of `made` and
// is 0 wherever `made` is.
void require_held_kept(const Eigen::VectorXd& made, const Eigen::VectorXd& now);
double mean_edge_strain(const std::vector<EdgeConstraint>& constraints, const Matrix3X& x);

enum class ProjectionMethod { none, fast_projection, pairwise };

// The scene-file names (simulation.constraints.method), also used by the step explanations.
inline constexpr base::EnumNames<ProjectionMethod, 3> projection_method_names{
    {{ProjectionMethod::none, "none"},
     {ProjectionMethod::fast_projection, "fast_projection"},
     {ProjectionMethod::pairwise, "pairwise"}}};

struct ProjectionSettings {
  ProjectionMethod method = ProjectionMethod::none;
  ConstrainedEdges edges = ConstrainedEdges::warp_weft;
  double tolerance = 1e-3;   // fast projection: stop when max strain ≤ tolerance
  // Fast projection: iteration cap. Most steps take 1–3 iterations; the few near a singular
  // configuration (quads sheared almost flat beside a pin, a chain pulled taut) converge only
  // linearly and took up to ~65 on a 2 s 64² two-corner hang. Pairwise: sweeps per step.
  int max_iterations = 100;
  double max_stretch = 0.0;  // pairwise: Provot's limit, |strain| allowed before correcting
  // Fast projection: carry each step's constraint force into the next step's prediction
  // (carried_tension.h). Off only to measure what it buys.
  bool carry_tension = true;
  // Fast projection: hold the vertices of chains pulled straight between still pins at their
  // rest length, which have no other shape (taut_chains.h), instead of projecting them. Off
  // only to measure what it buys.
  bool hold_taut_chains = true;
  // Fast projection: conjugate-gradient iterations allowed per Newton system on the last
  // factorization (an earlier iterate's or step's matrix, used as preconditioner) before
  // refactorizing; 0 refactorizes every iteration (the paper's iteration). 8, the default since
  // taut chains are held: on the two-corner hang it takes 0.81–0.95 of the CPU time of 0 at
  // 64² and 0.88–1.02 at 128² (tol 1e-2 to 1e-4, docs/benchmarks.md). Before, the 128² hang's
  // near-singular top edge needed more CG iterations than a factorization costs and doubled it.
  int reuse_iterations = 8;
  // Fast projection: stop, unconverged, when an iteration whose step the line search shortened
  // leaves Σ C² above this fraction of its value before (0: never; the iteration cap alone).
  // Where no shape meets the tolerance (the failsafe's projections with impact zones held: two
  // held zones pulling the cloth between them apart) the line search keeps taking ever shorter
  // steps that each remove a percent or less.
  double stall_fraction = 0.0;
};

struct [[nodiscard]] ProjectionResult {
  bool converged = true;   // the tolerance was met (pairwise: always reports its sweeps)
  int iterations = 0;
  double max_strain = 0.0;  // after the projection
  double solve_s = 0.0;     // wall time in factorizations and solves
  int factorizations = 0;   // numeric factorizations of J M⁻¹ Jᵀ (fast projection)
  int reuse_iterations = 0;  // conjugate-gradient iterations on a reused factorization
};

class ConstraintProjector {
 public:
  virtual ~ConstraintProjector() = default;
  // Moves x (#V×3, m) onto the constraints, changing only vertices with inv_mass > 0.
  virtual ProjectionResult project(Matrix3X& x) = 0;
  virtual const std::vector<EdgeConstraint>& constraints() const = 0;
  // Per constraint, the multipliers μ (kg·m) of the last project(): it moved x by −M⁻¹ Jᵀ μ,
  // so −Jᵀ μ / h² is the constraint force of a step of h seconds. Empty when the method has
  // no multipliers (pairwise projection).
  virtual const Eigen::VectorXd& multipliers() const;
  // Projects from now on with these inverse masses (#V): a vertex whose inverse mass is 0 is
  // held, and a constraint between two held vertices is left out. The vertices held when the
  // projector was made must stay held (std::invalid_argument otherwise): their constraints,
  // and fast projection's sparsity pattern and its analysis, are kept, so that holding other
  // vertices costs no new analysis (the impact zones' projections). fresh: forget
  // what earlier projections carry over (fast projection: the factorization it reuses), so
  // that the next result depends on this projector's input alone.
  virtual void set_inverse_masses(const Eigen::VectorXd& inv_mass, bool fresh) = 0;
  // What the projector carries from one step to the next (fast projection: the factorization
  // it may reuse), for a checkpoint; restore_state() reads it into a projector made alike.
  virtual void save_state(StateWriter& out) const = 0;
  virtual void restore_state(StateReader& in) = 0;
};

// nullptr for ProjectionMethod::none.
std::unique_ptr<ConstraintProjector> make_projector(const ClothMesh& mesh,
                                                    const Eigen::VectorXd& inv_mass,
                                                    const ProjectionSettings& settings,
                                                    SparseBackend backend);

}  // namespace weft::sim
