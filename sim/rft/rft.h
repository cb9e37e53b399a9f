#pragma once
// Rotation-free triangles (seed 002, Zhou & Sze): the cloth model choices "rft3" and "rft6" are
//   bending  make_rft_bending (rft_bending.h; the same for both), and
//   membrane make_rft_membrane with RftMembrane::three_node (RFT3, constant-strain triangle) or
//            RftMembrane::six_node (RFT6, six-node interpolation).
// Formulas, boundary treatment and measured patch tests: docs/models.md, "Rotation-free
// triangles (RFT3/RFT6)".

#include <memory>

#include "sim/force_term.h"
#include "sim/grid.h"
#include "sim/material/material.h"

namespace weft::sim {

enum class RftMembrane { three_node, six_node };  // RFT3 (constant strain) or RFT6

// Bending of the rotation-free triangles (seed 002 §2), anisotropic from material.bend_warp_Nm
// and bend_weft_Nm (N·m), Poisson 0, twist ½ √(B_warp B_weft) (rft_bending_kernel.h).
// Throws std::invalid_argument on a negative or non-finite rigidity or a degenerate patch.
std::unique_ptr<ForceTerm> make_rft_bending(const ClothMesh& mesh, const Material& material);

// Membrane (stretch + shear), orthotropic from material.stretch_warp_N_m, stretch_weft_N_m and
// shear_N_m (N/m) (rft_membrane_kernel.h). Throws as make_rft_bending.
std::unique_ptr<ForceTerm> make_rft_membrane(const ClothMesh& mesh, const Material& material,
                                             RftMembrane kind);

}  // namespace weft::sim
