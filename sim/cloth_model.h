#pragma once
// Which cloth model a simulation steps (scene key cloth.model), and its force terms: every
// model is a sum of ForceTerms (sim/force_term.h) that the integrators step alike — springs
// and angular bending (sim/mass_spring.h), or continuum membranes and bending.

#include <array>

#include "base/enum_names.h"
#include "sim/force_term.h"
#include "sim/grid.h"
#include "sim/material/material.h"

namespace weft::sim {

enum class ClothModel {
  mass_spring,    // springs on warp/weft edges and quad diagonals, angular bending (seeds 003, 004)
  baraff_witkin,  // stretch and shear per triangle, dihedral bending per edge (seed 004)
  rft3,           // rotation-free triangles: six-node patch bending, constant-strain membrane
  rft6,           // the same bending, membrane strain from six-node interpolation (seed 002)
};

inline constexpr std::array<ClothModel, 4> all_cloth_models{
    ClothModel::mass_spring, ClothModel::baraff_witkin, ClothModel::rft3, ClothModel::rft6};

// The scene-file names (cloth.model), in all_cloth_models' order.
inline constexpr base::EnumNames<ClothModel, 4> cloth_model_names{
    {{ClothModel::mass_spring, "mass_spring"},
     {ClothModel::baraff_witkin, "baraff_witkin"},
     {ClothModel::rft3, "rft3"},
     {ClothModel::rft6, "rft6"}}};

inline const char* cloth_model_name(ClothModel model) {
  return base::enum_name(cloth_model_names, model);
}

// The terms of a model. Only what the material needs is built: no bending term at zero
// bending rigidity, no membrane term (mass-spring: no warp/weft springs) when stretch is left
// to constraints (with_stretch false), none at all when neither stretch nor shear remains.
// bending_in_time_step: the mass-spring grid's bending stiffness enters implicit Euler's matrix
// (the other models' bending always does).
ForceTerms make_force_terms(const ClothMesh& mesh, const Material& material, ClothModel model,
                            bool with_stretch, bool bending_in_time_step = false);

// Whether implicit Euler takes a mass-spring grid's bending into its matrix (simulation.bending_in_step):
// when explicit bending would be unstable at the step (automatic), always, or never.
enum class BendingInStep { automatic, explicit_forces, implicit };
inline constexpr base::EnumNames<BendingInStep, 3> bending_in_step_names{
    {{BendingInStep::automatic, "auto"},
     {BendingInStep::explicit_forces, "explicit"},
     {BendingInStep::implicit, "implicit"}}};

}  // namespace weft::sim
