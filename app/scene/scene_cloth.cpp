// The `cloth` block of a scene file (see scene_cloth.h); docs/scene.md documents it key by key,
// docs/meshes.md the mesh file's keys.

#include "app/scene/scene_cloth.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <limits>
#include <map>
#include <memory>
#include <stdexcept>
#include <string>
#include <utility>
#include <variant>
#include <vector>

#include "app/io/cloth_mesh_file.h"
#include "app/io/mesh_file.h"
#include "app/scene/tension_field_scene.h"
#include "app/scene/units.h"
#include "base/constants.h"
#include "base/enum_names.h"
#include "sim/material/material_presets.h"

namespace weft::app {
namespace {

// One bending law (sim/material/bending_law.h): {"form": "frictional", "B": …, "M0": …, "kappa0": …},
// {"form": "cubic", "B": …, "C": …}, {"form": "linear", "B": …} or {"form": "table",
// "curvature": [κ…], "moment": [M…]} (the points after (0, 0)).
sim::BendingLaw read_bending_law(ObjectReader r) {
  using Form = sim::BendingLaw::Form;
  const Form form = r.enumeration<Form>("form", sim::BendingLaw::form_names, std::nullopt);
  const auto B = [&](Range range) { return r.quantity("B", Quantity::bending_rigidity, std::nullopt, range); };
  const std::string key = form == Form::table ? "moment" : form == Form::linear ? "B" : "form";
  try {
    std::optional<sim::BendingLaw> law;
    if (form == Form::linear) law = sim::BendingLaw::linear(B(Range::gt(0.0)));
    if (form == Form::frictional)
      law = sim::BendingLaw::frictional(
          B(Range::ge(0.0)), r.quantity("M0", Quantity::moment_per_width, std::nullopt, Range::ge(0.0)),
          r.quantity("kappa0", Quantity::curvature, std::nullopt, Range::gt(0.0)));
    if (form == Form::cubic)
      law = sim::BendingLaw::cubic(
          B(Range::gt(0.0)), r.quantity("C", Quantity::cubic_bending, std::nullopt, Range::ge(0.0)));
    if (form == Form::table) {
      const std::size_t n = r.array_length("curvature");
      const auto kappa = r.quantities("curvature", Quantity::curvature, n, std::nullopt);
      const auto moment = r.quantities("moment", Quantity::moment_per_width, n, std::nullopt);
      std::vector<std::pair<double, double>> points;
      for (std::size_t k = 0; k < n; ++k) points.emplace_back(kappa[k], moment[k]);
      law = sim::BendingLaw::table(std::move(points));
    }
    r.finish();
    return *law;
  } catch (const sim::MaterialError& e) {
    r.fail(key, e.what());
  }
}

// One stretch law (sim/material/stretch_law.h): {"form": "linear", "Y": …} or {"form": "table",
// "strain": [ε…], "tension": [T…]} (the points after (0, 0)).
sim::StretchLaw read_stretch_law(ObjectReader r) {
  using Form = sim::StretchLaw::Form;
  const Form form = r.enumeration<Form>("form", sim::StretchLaw::form_names, std::nullopt);
  try {
    std::optional<sim::StretchLaw> law;
    if (form == Form::linear)
      law = sim::StretchLaw::linear(r.quantity("Y", Quantity::force_per_length, std::nullopt, Range::gt(0.0)));
    if (form == Form::table) {
      const std::size_t n = r.array_length("strain");
      const auto strain = r.numbers("strain", n, std::nullopt);
      const auto tension = r.quantities("tension", Quantity::force_per_length, n, std::nullopt);
      std::vector<std::pair<double, double>> points;
      for (std::size_t k = 0; k < n; ++k) points.emplace_back(strain[k], tension[k]);
      law = sim::StretchLaw::table(std::move(points));
    }
    r.finish();
    return *law;
  } catch (const sim::MaterialError& e) {
    r.fail(form == Form::table ? "tension" : "Y", e.what());
  }
}

// A material law per direction, "cloth.material.<key>": one law for both directions, or
// {"warp": …, "weft": …}; a preset's laws stay unless replaced. A law sets its direction's
// rigidity (its slope at zero), so that rigidity's key may not be given beside it.
template <class Law, class ReadOne>
void read_laws(ObjectReader& material, const std::string& key,
               const std::array<std::string, 2>& rigidity_keys,
               const std::array<std::optional<Law>*, 2>& laws, ReadOne read_one) {
  if (material.has(key)) {
    ObjectReader given = material.object(key);
    if (given.has("form")) {
      *laws[0] = *laws[1] = read_one(material.object(key));
    } else {
      if (given.has("warp")) *laws[0] = read_one(given.object("warp"));
      if (given.has("weft")) *laws[1] = read_one(given.object("weft"));
      given.finish();
    }
  }
  std::string name = key;  // "bending law"
  std::replace(name.begin(), name.end(), '_', ' ');
  const std::string what = name.substr(0, name.find(' '));  // "bending"
  for (std::size_t d = 0; d < 2; ++d)
    if (*laws[d] && material.has(rigidity_keys[d]))
      material.fail(rigidity_keys[d],
                    (material.has(key) ? "the " + name : "the preset's measured " + name) +
                        " sets this direction's " + what + " rigidity (its slope at zero); " +
                        (material.has(key) ? "give it in the law, not here"
                                           : "replace the law with " + key +
                                                 ", or choose the preset without \"_curves\""));
}

void read_material_laws(ObjectReader& material, sim::Material& m) {
  read_laws<sim::BendingLaw>(material, "bending_law", {"bend_warp", "bend_weft"},
                             {&m.bend_law_warp, &m.bend_law_weft}, read_bending_law);
  read_laws<sim::StretchLaw>(material, "stretch_law", {"stretch_warp", "stretch_weft"},
                             {&m.stretch_law_warp, &m.stretch_law_weft}, read_stretch_law);
  if (m.bend_law_warp) m.bend_warp_Nm = m.bend_law_warp->initial_rigidity();
  if (m.bend_law_weft) m.bend_weft_Nm = m.bend_law_weft->initial_rigidity();
  if (m.stretch_law_warp) m.stretch_warp_N_m = m.stretch_law_warp->initial_stiffness();
  if (m.stretch_law_weft) m.stretch_weft_N_m = m.stretch_law_weft->initial_stiffness();
}

// "cloth.material": an optional "preset" (sim/material/material_presets.h) sets every value; each key
// given besides it overrides that one value.
sim::Material read_material(ObjectReader r) {
  std::vector<std::pair<std::string, sim::Material>> presets;
  for (const sim::MaterialPreset& p : sim::material_presets())
    presets.emplace_back(p.name, p.material);
  sim::Material m = r.choice<sim::Material>("preset", presets, sim::Material{});
  const Range positive = Range::gt(0.0);
  m.density_kg_m2 = r.quantity("density", Quantity::areal_density, m.density_kg_m2, positive);
  m.stretch_warp_N_m =
      r.quantity("stretch_warp", Quantity::force_per_length, m.stretch_warp_N_m, positive);
  m.stretch_weft_N_m =
      r.quantity("stretch_weft", Quantity::force_per_length, m.stretch_weft_N_m, positive);
  // Zero shear or bending rigidity is allowed: the term is then not built at all.
  const Range non_negative = Range::ge(0.0);
  m.shear_N_m = r.quantity("shear", Quantity::force_per_length, m.shear_N_m, non_negative);
  m.bend_warp_Nm =
      r.quantity("bend_warp", Quantity::bending_rigidity, m.bend_warp_Nm, non_negative);
  m.bend_weft_Nm =
      r.quantity("bend_weft", Quantity::bending_rigidity, m.bend_weft_Nm, non_negative);
  read_material_laws(r, m);
  r.finish();
  return m;
}

// A pin's optional "path": keyframes {"time", "offset"} that move it (sim::PinPath).
sim::PinPath read_pin_path(ObjectReader& pin) {
  if (!pin.has("path")) return {};
  std::vector<ObjectReader> frames = pin.objects("path");
  if (frames.empty()) pin.fail("path", "expected at least one keyframe, got an empty list");
  std::vector<sim::PinKeyframe> keyframes;
  for (std::size_t k = 0; k < frames.size(); ++k) {
    ObjectReader& f = frames[k];
    sim::PinKeyframe frame;
    frame.time_s = f.quantity("time", Quantity::time, required);
    frame.offset_m = f.quantity_vec3("offset", Quantity::length, required);
    f.finish();
    keyframes.push_back(frame);
  }
  try {
    return sim::PinPath(std::move(keyframes));  // checks the order of the times
  } catch (const std::invalid_argument& e) {
    pin.fail("path", e.what());
  }
}

// The cloth mesh file's vertex colours, for pins by colour: #V of the cloth, or empty.
struct MeshColours {
  std::string file;                      // cloth.mesh as given; empty: the built-in grid
  std::vector<Eigen::Vector3d> colour;
};

// A pin {"color": [r, g, b], "tolerance": t}: the mesh file's vertices whose colour is within t
// of it on every channel (docs/meshes.md).
sim::PinVertexSet read_colour_pin(ObjectReader& r, const MeshColours& colours) {
  if (colours.file.empty())
    r.fail("color", "a pin by vertex color needs a cloth mesh file (cloth.mesh) with vertex "
                    "colors; the built-in grid has none");
  if (colours.colour.empty())
    r.fail("color", "the mesh file " + colours.file + " has no vertex colors (on every mesh of "
                    "it), so no vertex can be pinned by its color");
  const auto c = r.numbers("color", 3, required, Range::closed(0, 1));
  const double tolerance = r.number("tolerance", 0.01, Range::ge(0.0));
  sim::PinVertexSet set;
  char what[96];
  std::snprintf(what, sizeof what, "color [%g, %g, %g] (tolerance %g)", c[0], c[1], c[2],
                tolerance);
  set.what = what;
  const Eigen::Vector3d wanted(c[0], c[1], c[2]);
  for (std::size_t v = 0; v < colours.colour.size(); ++v)
    if ((colours.colour[v] - wanted).cwiseAbs().maxCoeff() <= tolerance)
      set.indices.push_back(static_cast<sim::Index>(v));
  if (set.indices.empty())
    r.fail("color", "no vertex of " + colours.file + " has the " + set.what);
  return set;
}

// One pin object: exactly one of "corner", "vertex", "grid", "region", "box", "color", and an
// optional "path".
sim::PinSpec read_pin(ObjectReader r, sim::PinPath& path, const MeshColours& colours) {
  const std::vector<std::string> selectors{"corner", "vertex", "grid", "region", "box", "color"};
  std::vector<std::string> given;
  for (const auto& s : selectors)
    if (r.has(s)) given.push_back(s);
  if (given.size() != 1) {
    const std::string got =
        given.empty() ? "none of them" : "both '" + given[0] + "' and '" + given[1] + "'";
    throw_scene_error(r.file(), r.path(),
                      "expected exactly " + base::choices_text(selectors) + ", got " + got);
  }
  const Range index_range = Range::closed(0, std::numeric_limits<sim::Index>::max());
  sim::PinSpec pin;
  if (given[0] == "corner") {
    // resolve_pins checks the name and lists the choices.
    pin = sim::PinCorner{r.string("corner", required)};
  } else if (given[0] == "vertex") {
    pin = sim::PinVertex{static_cast<sim::Index>(r.integer("vertex", required, index_range))};
  } else if (given[0] == "grid") {
    const auto ij = r.integers("grid", 2, required, index_range);
    pin = sim::PinGrid{static_cast<sim::Index>(ij[0]), static_cast<sim::Index>(ij[1])};
  } else if (given[0] == "region") {
    ObjectReader region = r.required_object("region");
    const auto u = region.numbers("u", 2, required, Range::closed(0, 1));
    const auto v = region.numbers("v", 2, required, Range::closed(0, 1));
    if (u[0] > u[1]) region.fail("u", "expected [min, max] with min ≤ max, got a reversed range");
    if (v[0] > v[1]) region.fail("v", "expected [min, max] with min ≤ max, got a reversed range");
    region.finish();
    pin = sim::PinRegion{u[0], u[1], v[0], v[1]};
  } else if (given[0] == "color") {
    pin = read_colour_pin(r, colours);
  } else {
    // A box in material coordinates (u, v: two values each) or in the world (x, y, z).
    ObjectReader box = r.required_object("box");
    sim::PinBox b;
    b.world = box.choice<bool>("space", {{"material", false}, {"world", true}}, false);
    const std::size_t n = b.world ? 3 : 2;
    const auto lo = box.quantities("min", Quantity::length, n, required);
    const auto hi = box.quantities("max", Quantity::length, n, required);
    b.lo.setZero();
    b.hi.setZero();
    for (std::size_t k = 0; k < n; ++k) {
      b.lo[static_cast<int>(k)] = lo[k];
      b.hi[static_cast<int>(k)] = hi[k];
      if (lo[k] > hi[k]) box.fail("max", "expected max ≥ min on every axis, got a reversed range");
    }
    box.finish();
    pin = b;
  }
  path = read_pin_path(r);
  r.finish();
  return pin;
}

// Resolves each pin against the grid alone, so that an error names its own key path; warns of
// a vertex pinned twice and of a cloth pinned everywhere.
void check_pins(const std::vector<sim::PinSpec>& pins, const sim::ClothMesh& mesh,
                const std::string& file, const std::string& pins_path,
                std::vector<std::string>& warnings) {
  if (pins.empty()) return;  // no pins: the cloth falls freely
  std::map<sim::Index, std::size_t> pinned_by;  // vertex → the first pin holding it
  for (std::size_t k = 0; k < pins.size(); ++k) {
    const std::string path = pins_path + "[" + std::to_string(k) + "]";
    try {
      std::size_t twice = 0, first = 0;
      for (const sim::Index v : sim::resolve_pins({pins[k]}, mesh)) {
        const auto [at, added] = pinned_by.emplace(v, k);
        if (!added && twice++ == 0) first = at->second;
      }
      if (twice)
        warnings.push_back(file + ": " + path + ": " + std::to_string(twice) +
                           " of its vertices are pinned already by " + pins_path + "[" +
                           std::to_string(first) + "]");
    } catch (const std::invalid_argument& e) {
      std::string what = e.what();
      const std::string prefix = "pin 0: ";  // resolve_pins names the pin by its index, here 0
      if (what.compare(0, prefix.size(), prefix) == 0) what.erase(0, prefix.size());
      throw_scene_error(file, path, what);
    }
  }
  sim::Index used = 0;
  for (sim::Index v = 0; v < mesh.vertex_count(); ++v) used += mesh.is_used(v) ? 1 : 0;
  if (static_cast<sim::Index>(pinned_by.size()) >= used)
    warnings.push_back(file + ": " + pins_path + ": every vertex of the cloth is pinned: nothing " +
                       "moves but what a pin path moves");
}

// "mesh": the cloth from a mesh file (app/io/cloth_mesh_file.h), its path relative to the scene
// file; its placement from "origin", "warp_axis", "weft_axis" (default: as the file gives it).
void read_cloth_mesh(ObjectReader& r, Scene& scene, MeshColours& colours) {
  for (const char* key : {"size", "resolution", "shape", "edge"})
    if (r.has(key))
      r.fail(key, "the cloth comes from the mesh file in cloth.mesh; a grid key does not apply");
  ClothMeshFileSpec spec;
  const std::filesystem::path file = r.string("mesh", required);
  spec.path = file.is_absolute() ? file : std::filesystem::path(r.file()).parent_path() / file;
  spec.pattern = r.enumeration("pattern", pattern_source_names, {PatternSource::automatic});
  spec.uv_scale_m = r.quantity("uv_scale", Quantity::length, 1.0, Range::gt(0.0));
  spec.warp_angle_rad = r.angle_deg("warp_angle", 0.0) * base::kPi / 180.0;
  spec.scale = r.number("scale", 1.0, Range::gt(0.0));
  spec.origin = r.quantity_vec3("origin", Quantity::length, sim::Vec3::Zero());
  spec.warp_axis = r.unit_vec3("warp_axis", spec.warp_axis);
  spec.weft_axis = r.unit_vec3("weft_axis", spec.weft_axis);
  if (std::fabs(spec.warp_axis.dot(spec.weft_axis)) > ObjectReader::unit_tolerance)
    r.fail("weft_axis", "expected a unit vector orthogonal to warp_axis");
  if (r.has("initial_shape"))
    r.fail("initial_shape", "the tension-field start needs the warp/weft grid of cloth.size and "
                            "cloth.resolution, not a mesh file");
  try {
    scene.mesh = std::make_shared<const sim::ClothMesh>(load_cloth_mesh(spec, &colours.colour));
    colours.file = file.string();
  } catch (const MeshFileError& e) {
    r.fail("mesh", e.what());
  }
  // The grid's placement keys, for what reads them (the measures' weft axis).
  scene.grid.origin = spec.origin;
  scene.grid.warp_axis = spec.warp_axis;
  scene.grid.weft_axis = spec.weft_axis;
}

// The grid keys of "cloth".
void read_cloth_grid(ObjectReader& r, Scene& scene) {
  sim::GridSpec& g = scene.grid;
  const auto size = r.quantities("size", Quantity::length, 2, required, Range::gt(0.0));
  g.size_u_m = size[0];
  g.size_v_m = size[1];
  const auto n = r.integers("resolution", 2, required, Range::closed(2, 4096));
  g.nu = static_cast<sim::Index>(n[0]);
  g.nv = static_cast<sim::Index>(n[1]);
  g.shape = r.enumeration("shape", sim::specimen_shape_names, {g.shape});
  if (r.has("edge") && g.shape != sim::SpecimenShape::disc)
    r.fail("edge", "applies to a disc (\"shape\": \"disc\"); a rectangle's edges are straight "
                   "grid lines");
  g.disc_edge = r.enumeration("edge", sim::disc_edge_names, {g.disc_edge});
  g.origin = r.quantity_vec3("origin", Quantity::length, g.origin);
  g.warp_axis = r.unit_vec3("warp_axis", g.warp_axis);
  g.weft_axis = r.unit_vec3("weft_axis", g.weft_axis);
  if (std::fabs(g.warp_axis.dot(g.weft_axis)) > ObjectReader::unit_tolerance) {
    char got[64];
    std::snprintf(got, sizeof got, "one at %.6g deg to it",
                  std::acos(g.warp_axis.dot(g.weft_axis)) * 180.0 / base::kPi);
    r.fail("weft_axis", std::string("expected a unit vector orthogonal to warp_axis, got ") + got);
  }
  if (r.has("initial_shape")) {
    ObjectReader shape = r.object("initial_shape");
    scene.tension_field = read_tension_field_shape(shape.required_object("tension_field"));
    shape.finish();
  }
}

// A disc with a smooth edge is a ring mesh without a grid (sim/round_specimen.h): a pin by grid
// vertex or corner is an error naming the pin and the ways to pin it instead.
void check_round_specimen_pins(const std::vector<sim::PinSpec>& pins, const ObjectReader& r) {
  for (std::size_t k = 0; k < pins.size(); ++k) {
    const char* by = std::holds_alternative<sim::PinGrid>(pins[k])     ? "grid vertex"
                     : std::holds_alternative<sim::PinCorner>(pins[k]) ? "corner"
                                                                       : nullptr;
    if (by)
      throw_scene_error(r.file(), r.path_of("pins") + "[" + std::to_string(k) + "]",
                        std::string("a pin by ") + by + " needs the warp/weft grid, and a disc "
                        "with \"edge\": \"smooth\" is meshed in rings of triangles without one: "
                        "pin by \"vertex\" (0 is the centre), \"region\" (fractions of the "
                        "disc's box: {\"u\": [0.5, 0.5], \"v\": [0.5, 0.5]} is the centre) or "
                        "\"box\"");
  }
}

}  // namespace

void read_cloth(ObjectReader r, Scene& scene) {
  MeshColours colours;
  if (r.has("mesh")) {
    read_cloth_mesh(r, scene, colours);
  } else {
    read_cloth_grid(r, scene);
  }
  scene.material = read_material(r.object("material"));
  for (ObjectReader& pin : r.objects("pins")) {
    sim::PinPath path;
    scene.pins.push_back(read_pin(pin, path, colours));
    scene.pin_paths.push_back(std::move(path));
  }
  r.finish();
  if (!scene.mesh && scene.grid.disc_edge == sim::DiscEdge::smooth)
    check_round_specimen_pins(scene.pins, r);
  if (!scene.pins.empty())
    check_pins(scene.pins, cloth_mesh(scene), r.file(), r.path_of("pins"), scene.warnings);
}

}  // namespace weft::app
