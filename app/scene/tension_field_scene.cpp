// A tension-field fold pattern as a scene's initial shape; see tension_field_scene.h.

#include "app/scene/tension_field_scene.h"

#include <cmath>
#include <string>

#include "app/io/input_error.h"
#include "app/scene/units.h"

namespace weft::app {
namespace {

const std::string shape_key = "cloth.initial_shape.tension_field";

// The scene key behind each of the solver's inputs (TensionFieldInputError::field).
std::string key_of(const std::string& field) {
  if (field == "h" || field == "L") return "cloth.size";
  if (field == "w") return "cloth.material.density";
  if (field == "d") return shape_key + ".support_shift";
  if (field == "t") return shape_key + ".thickness";
  if (field == "E") return shape_key + ".youngs_modulus";
  if (field == "nu") return shape_key + ".poisson_ratio";
  if (field == "c") return shape_key + ".load_constant";
  if (field == "Q") return shape_key + ".ratio";
  return shape_key + "." + field;
}

}  // namespace

TensionFieldShape read_tension_field_shape(ObjectReader r) {
  TensionFieldShape s;
  s.support_shift_m = r.quantity("support_shift", Quantity::length, required, Range::ge(0.0));
  s.thickness_m = r.quantity("thickness", Quantity::length, required, Range::gt(0.0));
  s.youngs_modulus_Pa = r.quantity("youngs_modulus", Quantity::stress, required, Range::gt(0.0));
  s.poisson_ratio = r.number("poisson_ratio", s.poisson_ratio, Range::gt(-1.0).le(0.5));
  s.load_constant = r.number("load_constant", s.load_constant, Range::gt(0.0));
  s.tolerance = r.number("tolerance", s.tolerance, Range::gt(0.0).lt(1.0));
  if (r.has("ratio")) s.ratio = r.number("ratio", required, Range::gt(1.0));
  s.interpolation = r.enumeration("interpolation", sim::fold_interpolation_names, {s.interpolation});
  s.shape = r.enumeration("shape", sim::membrane_shape_names, {s.shape});
  r.finish();
  return s;
}

sim::TensionFieldInputs tension_field_inputs(const TensionFieldShape& shape,
                                             const sim::GridSpec& grid,
                                             const sim::Material& material,
                                             const sim::Vec3& gravity_m_s2) {
  sim::TensionFieldInputs in;
  in.height_m = grid.size_v_m;
  in.width_m = grid.size_u_m;
  in.support_shift_m = shape.support_shift_m;
  in.thickness_m = shape.thickness_m;
  in.youngs_modulus_Pa = shape.youngs_modulus_Pa;
  in.poisson_ratio = shape.poisson_ratio;
  in.weight_N_m2 = material.density_kg_m2 * gravity_m_s2.norm();
  in.load_constant = shape.load_constant;
  in.tolerance = shape.tolerance;
  in.ratio = shape.ratio;
  return in;
}

void check_tension_field_scene(const TensionFieldShape& shape, const sim::GridSpec& grid,
                               const sim::Material& material, const sim::Vec3& gravity_m_s2,
                               const std::string& source) {
  const auto fail = [&](const std::string& key, const std::string& what) {
    throw InputError(source + ": " + key + ": " + what);
  };
  if (grid.shape != sim::SpecimenShape::rectangle)
    fail("cloth.shape", "the tension-field shape needs a rectangle, got a disc");
  if (!(gravity_m_s2.norm() > 0.0))
    fail("simulation.gravity", "the tension-field shape hangs the cloth: expected gravity ≠ 0");
  if (grid.weft_axis.normalized().dot(gravity_m_s2.normalized()) < 1.0 - 1e-9)
    fail("cloth.weft_axis",
         "the tension-field shape hangs the cloth from its top edge (v = 0): expected weft_axis "
         "along gravity, e.g. [0, 0, -1]");
  try {
    sim::validate(tension_field_inputs(shape, grid, material, gravity_m_s2));
  } catch (const sim::TensionFieldInputError& e) {
    fail(key_of(e.field()), e.what());
  }
}

FoldedStart folded_start(const TensionFieldShape& shape, const sim::GridSpec& grid,
                         const sim::Material& material, const sim::Vec3& gravity_m_s2,
                         const sim::ClothMesh& mesh) {
  const sim::TensionFieldInputs in = tension_field_inputs(shape, grid, material, gravity_m_s2);
  FoldedStart out;
  out.result = sim::solve_tension_field(in);
  const sim::FoldPattern pattern = sim::make_fold_pattern(in, out.result, shape.interpolation);
  // The fold frame (fold_geometry.h): warp across (+x), weft down (−z), the top edge's middle
  // at the origin, and the sheet's normal warp × weft along +y.
  const sim::Vec3 warp = grid.warp_axis.normalized(), weft = grid.weft_axis.normalized();
  const sim::Vec3 normal = warp.cross(weft);
  const sim::Vec3 top = grid.origin + 0.5 * grid.size_u_m * warp;
  sim::Matrix3X local(mesh.vertex_count(), 3);
  for (sim::Index v = 0; v < mesh.vertex_count(); ++v) {
    const sim::Vec3 d = mesh.rest_positions.row(v).transpose() - top;
    local.row(v) = Eigen::RowVector3d(d.dot(warp), d.dot(normal), -d.dot(weft));
  }
  const sim::Matrix3X folded =
      sim::fold_rest_positions(pattern, local, sim::Vec3::Zero(), shape.shape);
  out.x.resize(mesh.vertex_count(), 3);
  for (sim::Index v = 0; v < mesh.vertex_count(); ++v)
    out.x.row(v) = (top + folded(v, 0) * warp + folded(v, 1) * normal - folded(v, 2) * weft).transpose();
  return out;
}

}  // namespace weft::app
