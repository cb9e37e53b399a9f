#pragma once
// Which cloth model a simulation steps (scene key cloth.model), and the force terms of the
// continuum ones. The mass-spring model (sim/mass_spring.h) is its own class; the continuum
// models are sums of ForceTerms (sim/force_term.h) that the integrators step alike.

#include <array>

#include "base/enum_names.h"
#include "sim/force_term.h"
#include "sim/grid.h"
#include "sim/material.h"

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

// The terms of a continuum model; empty for mass_spring. Only what the material needs is
// built: no bending term at zero bending rigidity, no membrane term when neither stretch (left
// to constraints: with_stretch false) nor shear remains.
ForceTerms make_force_terms(const ClothMesh& mesh, const Material& material, ClothModel model,
                            bool with_stretch);

}  // namespace weft::sim
