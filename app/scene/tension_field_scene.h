#pragma once
// The tension-field fold pattern (seed 001, sim/folds/) as a scene's initial shape: the key
// `cloth.initial_shape.tension_field` lays the flat cloth onto Conci's folds before the first
// frame. With `simulation.dynamics: false` every frame shows that shape (the fold generator as a
// scene model, drawn by the usual renderers); otherwise the dynamic simulation starts from it.
//
// The cloth hangs from its top edge: weft_axis points along gravity (down), the warp edge at
// v = 0 is the top, and its two corners are the supports, already brought together by the
// support shift d (so pins on them hold them there). Height h and width L are cloth.size
// (weft and warp), the weight per area w is the material's density times |gravity|; the other
// inputs are the tension_field object's keys (docs/scene.md, docs/folds.md).

#include <optional>

#include "app/scene/json_reader.h"
#include "sim/folds/fold_geometry.h"
#include "sim/folds/tension_field.h"
#include "sim/grid.h"
#include "sim/material/material.h"

namespace weft::app {

struct TensionFieldShape {
  double support_shift_m = 0.0;  // d
  double thickness_m = 0.0;      // t
  double youngs_modulus_Pa = 0.0;
  double poisson_ratio = 0.3;
  double load_constant = sim::conci_table1_load_constant;
  double tolerance = 0.05;
  std::optional<double> ratio;   // Q given instead of eq. (7)'s
  sim::FoldInterpolation interpolation = sim::FoldInterpolation::cosine;
  sim::MembraneShape shape = sim::MembraneShape::rectangle;
};

// Reads the `tension_field` object (its keys: support_shift, thickness, youngs_modulus,
// poisson_ratio, load_constant, ratio, tolerance, interpolation, shape). Throws InputError.
TensionFieldShape read_tension_field_shape(ObjectReader r);

// The solver's inputs for this cloth. gravity_m_s2: the scene's gravity vector.
sim::TensionFieldInputs tension_field_inputs(const TensionFieldShape& shape,
                                             const sim::GridSpec& grid,
                                             const sim::Material& material,
                                             const sim::Vec3& gravity_m_s2);

// Checks that the cloth can carry the shape — it hangs (weft_axis along gravity), is a
// rectangle, and the solver accepts the inputs — throwing InputError "SOURCE: KEY: …" naming
// the scene key at fault.
void check_tension_field_scene(const TensionFieldShape& shape, const sim::GridSpec& grid,
                               const sim::Material& material, const sim::Vec3& gravity_m_s2,
                               const std::string& source);

struct FoldedStart {
  sim::TensionFieldResult result;
  sim::Matrix3X x;  // #V×3 world positions, m
};

// Solves the tension field and lays the mesh (made from `grid`) onto its folds.
FoldedStart folded_start(const TensionFieldShape& shape, const sim::GridSpec& grid,
                         const sim::Material& material, const sim::Vec3& gravity_m_s2,
                         const sim::ClothMesh& mesh);

}  // namespace weft::app
