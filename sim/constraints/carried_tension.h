#pragma once
// Constraint forces carried from one step to the next.
//
// Fast projection corrects the unconstrained prediction x̃ by −M⁻¹ Jᵀ μ: over a step of h
// seconds that is the constraint force f = −Jᵀ μ / h², along each constrained edge
// f_b = −(2 μ / (l h²)) (x_b − x_a) = −f_a, since ∇_b C = 2 (x_b − x_a) / l. A hanging cloth
// needs that force every step; leaving it out of the prediction lets gravity pull the cloth
// off the constraints each step and projection pull it back — from a nearly flat sheet or a
// chain pulled taut between pins, a correction along directions where C is only quadratic
// (a singular root), which Newton-type iterations cannot finish in a few iterations.
// Carrying the tension k = Σ 2 μ / (l h²) (N/m per edge, the stiffness of a zero-rest-length
// spring) into the next prediction, with its stiffness k I in the implicit matrix (the string
// stiffness of a taut thread), leaves projection only the change of tension to find.

#include <vector>

#include "sim/constraints/projection.h"
#include "sim/types.h"

namespace weft::sim {

// forces (#V×3, N) += the tension forces of k (#edges, N/m) at positions x. An empty k adds none.
void add_tension_forces(const std::vector<EdgeConstraint>& edges, const Eigen::VectorXd& k,
                        const Matrix3X& x, Matrix3X& forces);

// k += 2 μ / (l h²): the tension implied by a projection's multipliers μ (kg·m) over h seconds.
void accumulate_tension(const std::vector<EdgeConstraint>& edges, const Eigen::VectorXd& mu,
                        double h_s, Eigen::VectorXd& k);

}  // namespace weft::sim
