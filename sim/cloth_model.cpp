#include "sim/cloth_model.h"

#include <stdexcept>
#include <string>

#include "sim/continuum/bw_membrane.h"
#include "sim/continuum/hinge_bending.h"
#include "sim/mass_spring.h"
#include "sim/rft/rft.h"

namespace weft::sim {

ForceTerms make_force_terms(const ClothMesh& mesh, const Material& material, ClothModel model,
                            bool with_stretch, bool bending_in_time_step) {
  const bool grid_springs = model == ClothModel::mass_spring && mesh.has_grid();
  if ((material.bend_law_warp || material.bend_law_weft) && !grid_springs)
    throw MaterialError(std::string("a nonlinear bending law needs cloth.model mass_spring on a "
                                    "warp/weft grid (its angular bending along the lines); "
                                    "cloth.model is ") +
                        cloth_model_name(model) + (mesh.has_grid() ? "" : " on a mesh"));
  if ((material.stretch_law_warp || material.stretch_law_weft) && !(grid_springs && with_stretch))
    throw MaterialError(std::string("a nonlinear stretch law needs cloth.model mass_spring on a "
                                    "warp/weft grid with its structural springs (not "
                                    "inextensibility constraints); cloth.model is ") +
                        cloth_model_name(model) + (mesh.has_grid() ? "" : " on a mesh") +
                        (with_stretch ? "" : " with stretch left to constraints"));
  if (model == ClothModel::mass_spring)
    return MassSpringModel(mesh, material, with_stretch, bending_in_time_step).terms();
  ForceTerms terms;
  const bool bends = material.bend_warp_Nm > 0.0 || material.bend_weft_Nm > 0.0;
  switch (model) {
    case ClothModel::baraff_witkin:
      if (with_stretch || material.shear_N_m > 0.0)
        terms.push_back(std::make_shared<BwMembrane>(mesh, material, with_stretch));
      if (bends) terms.push_back(std::make_shared<HingeBending>(mesh, material));
      break;
    case ClothModel::rft3:
    case ClothModel::rft6: {
      Material membrane = material;  // stretch left to constraints: shear only
      if (!with_stretch) membrane.stretch_warp_N_m = membrane.stretch_weft_N_m = 0.0;
      if (with_stretch || material.shear_N_m > 0.0)
        terms.push_back(make_rft_membrane(
            mesh, membrane,
            model == ClothModel::rft3 ? RftMembrane::three_node : RftMembrane::six_node));
      if (bends) terms.push_back(make_rft_bending(mesh, material));
      break;
    }
    case ClothModel::mass_spring:
      break;
  }
  return terms;
}

}  // namespace weft::sim
