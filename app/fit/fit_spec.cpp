// The fit-spec file of `weft fit` (see fit_spec.h).

#include "app/fit/fit_spec.h"

#include <fstream>
#include <sstream>

#include "app/scene/json_reader.h"
#include "app/io/npy_file.h"
#include "base/file_read.h"
#include "sim/simulator.h"

namespace weft::app {
namespace {

namespace fs = std::filesystem;

struct ParameterKind {
  std::string name;
  std::vector<std::string> keys;
  std::optional<Quantity> kind;  // none: a plain number
  std::string unit;
};

const std::vector<ParameterKind>& parameter_kinds() {
  static const std::vector<ParameterKind> kinds = {
      {"bend", {"cloth.material.bend_warp", "cloth.material.bend_weft"},
       Quantity::bending_rigidity, "N*m"},
      {"bend_warp", {"cloth.material.bend_warp"}, Quantity::bending_rigidity, "N*m"},
      {"bend_weft", {"cloth.material.bend_weft"}, Quantity::bending_rigidity, "N*m"},
      {"shear", {"cloth.material.shear"}, Quantity::force_per_length, "N/m"},
      {"density", {"cloth.material.density"}, Quantity::areal_density, "kg/m^2"},
      {"friction", {"simulation.collision_friction"}, std::nullopt, ""},
      // The coefficients of cloth.material.bending_law (one law for both directions, whose form
      // the fit file's "set" gives): sim/material/bending_law.h.
      {"bend_law_B", {"cloth.material.bending_law.B"}, Quantity::bending_rigidity, "N*m"},
      {"bend_law_M0", {"cloth.material.bending_law.M0"}, Quantity::moment_per_width, "N"},
      {"bend_law_kappa0", {"cloth.material.bending_law.kappa0"}, Quantity::curvature, "1/m"},
      {"bend_law_C", {"cloth.material.bending_law.C"}, Quantity::cubic_bending, "N*m^3"},
  };
  return kinds;
}

FitParameter read_parameter(ObjectReader r) {
  const std::string name = r.string("name", required);
  const ParameterKind* kind = nullptr;
  for (const ParameterKind& k : parameter_kinds())
    if (k.name == name) kind = &k;
  if (!kind) {
    std::string choices;
    for (const std::string& n : fit_parameter_names()) choices += (choices.empty() ? "'" : ", '") + n + "'";
    r.fail("name", "expected one of " + choices + ", got '" + name + "'");
  }
  const auto value = [&](const std::string& key, std::optional<double> fallback) {
    return kind->kind ? r.quantity(key, *kind->kind, fallback, Range::gt(0.0))
                      : r.number(key, fallback, Range::gt(0.0));
  };
  FitParameter p{kind->name, kind->keys, kind->unit};
  p.start = value("start", required);
  p.min = value("min", p.start / 10.0);
  p.max = value("max", p.start * 10.0);
  if (!(p.min <= p.start && p.start <= p.max))
    r.fail("start", "expected min ≤ start ≤ max, got " + std::to_string(p.min) + ", " +
                        std::to_string(p.start) + ", " + std::to_string(p.max));
  r.finish();
  return p;
}

MeasuredTarget read_measured(ObjectReader r) {
  MeasuredTarget t;
  if (r.has("overhang")) t.overhang_m = r.quantity("overhang", Quantity::length, required, Range::gt(0.0));
  if (r.has("drop")) t.drop_m = r.quantity("drop", Quantity::length, required, Range::gt(0.0));
  if (r.has("drape_coefficient"))
    t.drape_coefficient = r.number("drape_coefficient", required, Range::gt(0.0).le(1.0));
  if (r.has("folds")) t.folds = r.number("folds", required, Range::ge(1.0));
  if (!t.overhang_m && !t.drop_m && !t.drape_coefficient && !t.folds)
    throw_scene_error(r.file(), r.path(), "expected at least one of 'overhang', 'drop', 'drape_coefficient', 'folds'");
  r.finish();
  return t;
}

PointCloudTarget read_point_cloud(ObjectReader r) {
  PointCloudTarget t;
  t.file = fit_file_path(r.file(), r.string("file", required));
  r.finish();
  try {
    t.points = read_npy_points(t.file);
  } catch (const NpyError& e) {
    r.fail("file", e.what());
  }
  return t;
}

PhotoTarget read_photo(ObjectReader r) {
  PhotoTarget t;
  t.image_path = fit_file_path(r.file(), r.string("image", required));
  if (r.has("mask")) t.mask_path = fit_file_path(r.file(), r.string("mask", required));
  t.metric = r.enumeration("metric", photo_metric_names, {PhotoMetric::chamfer});
  if (r.has("mm_per_px")) t.mm_per_px = r.number("mm_per_px", required, Range::gt(0.0));
  r.finish();
  try {
    t.photo = render::read_image(t.image_path);
    std::optional<render::Image> mask_image;
    if (t.mask_path) mask_image = render::read_image(*t.mask_path);
    t.mask = render::silhouette_of(t.photo, mask_image).mask;
  } catch (const std::exception& e) {
    r.fail(t.mask_path ? "mask" : "image", e.what());
  }
  return t;
}

// `object`: the target's JSON, which `r` reads.
FitTarget read_target(ObjectReader r, const Json& object) {
  const int given = int(r.has("measured")) + int(r.has("point_cloud")) + int(r.has("photo")) +
                    int(r.has("drape_photos"));
  if (given != 1)
    throw_scene_error(r.file(), r.path(), "expected exactly one of 'measured', 'point_cloud', 'photo', "
                                          "'drape_photos', got " + std::to_string(given));
  FitTarget target;
  if (r.has("measured")) target = read_measured(r.required_object("measured"));
  if (r.has("point_cloud")) target = read_point_cloud(r.required_object("point_cloud"));
  if (r.has("photo")) target = read_photo(r.required_object("photo"));
  if (r.has("drape_photos")) {
    r.required_object("drape_photos");  // marks it read, an error unless an object
    target = read_drape_photos(object.at("drape_photos"), r.file(), r.path_of("drape_photos"));
  }
  r.finish();
  return target;
}

void read_options(ObjectReader& root, FitSpec& spec) {
  ObjectReader s = root.object("settle");
  spec.settle.method = s.enumeration("method", settle_method_names, {spec.settle.method});
  if (spec.settle.method == SettleMethod::static_solve) {
    for (const char* key : {"tolerance", "still", "check_every", "max_iterations"})
      if (s.has(key))
        s.fail(key, "applies to method \"dynamic_relaxation\"; a static solve takes the scene's "
                    "simulation.static settings");
    if (const std::string why = sim::static_solve_refusal(spec.base.sim); !why.empty())
      s.fail("method", "the scene cannot be solved statically (" + why +
                           "): give \"method\": \"dynamic_relaxation\"");
  }
  spec.settle.seeds = static_cast<int>(s.integer("seeds", spec.settle.seeds, Range::closed(1, 100)));
  if (spec.settle.seeds > 1 && spec.settle.method != SettleMethod::static_solve)
    s.fail("seeds", "applies to method \"static\" (dynamic relaxation has no imperfection seed)");
  spec.settle.tolerance = s.number("tolerance", spec.settle.tolerance, Range::gt(0.0));
  spec.settle.still_m = s.quantity("still", Quantity::length, spec.settle.still_m, Range::ge(0.0));
  spec.settle.check_every = s.integer("check_every", spec.settle.check_every, Range::ge(1));
  spec.settle.max_iterations = s.integer("max_iterations", spec.settle.max_iterations, Range::ge(1));
  s.finish();
  ObjectReader o = root.object("optimizer");
  spec.optimizer.method = o.enumeration("method", fit_method_names, {spec.optimizer.method});
  spec.optimizer.max_evaluations =
      static_cast<int>(o.integer("max_evaluations", spec.optimizer.max_evaluations, Range::ge(1)));
  spec.optimizer.initial_step = o.number("initial_step", spec.optimizer.initial_step, Range::gt(0.0));
  spec.optimizer.x_tolerance = o.number("x_tolerance", spec.optimizer.x_tolerance, Range::gt(0.0));
  o.finish();
  ObjectReader p = root.object("profile");
  spec.profile.points = static_cast<int>(p.integer("points", spec.profile.points, Range::closed(0, 50)));
  spec.profile.span = p.number("span", spec.profile.span, Range::gt(0.0).le(10.0));
  if (p.has("band")) spec.profile.band = p.number("band", required, Range::gt(0.0));
  p.finish();
}

// The "set" object: scene key paths and JSON values, applied to the scene like --set.
std::vector<Setting> read_set(const Json& document, const std::string& source) {
  std::vector<Setting> set;
  if (!document.contains("set")) return set;
  const Json& object = document.at("set");
  if (!object.is_object()) throw_scene_error(source, "set", "expected an object of scene keys and values");
  for (const auto& [key, value] : object.items())
    set.push_back({key, value.dump(), source + ": set." + key});
  return set;
}

}  // namespace

fs::path fit_file_path(const std::string& fit_file, const std::string& file) {
  const fs::path p(file);
  return p.is_absolute() ? p : fs::path(fit_file).parent_path() / p;
}

const std::vector<std::string>& fit_parameter_names() {
  static const std::vector<std::string> names = [] {
    std::vector<std::string> n;
    for (const ParameterKind& k : parameter_kinds()) n.push_back(k.name);
    return n;
  }();
  return names;
}

double default_band(const FitTarget& target) {
  if (std::holds_alternative<MeasuredTarget>(target)) return 1e-4;
  if (std::holds_alternative<PointCloudTarget>(target)) return 0.5;
  if (std::holds_alternative<DrapePhotosTarget>(target)) return 1.0;
  return std::get<PhotoTarget>(target).metric == PhotoMetric::chamfer ? 0.5 : 0.01;
}

std::string objective_label(const FitTarget& target) {
  if (std::holds_alternative<MeasuredTarget>(target)) return "Σ relative misfit²";
  if (std::holds_alternative<PointCloudTarget>(target)) return "3D Chamfer [mm]";
  if (std::holds_alternative<DrapePhotosTarget>(target)) return "drape photos misfit";
  return std::get<PhotoTarget>(target).metric == PhotoMetric::chamfer ? "outline Chamfer [px]"
                                                                       : "1 − IoU";
}

FitSpec parse_fit_spec(const std::string& text, const std::string& source) {
  const Json document = parse_json(text, source);
  ObjectReader root = ObjectReader::root(document, source);
  FitSpec spec;
  spec.source = source;
  spec.name = fs::path(source).stem().string();
  spec.description = root.string("description", "");
  const fs::path scene_path = fit_file_path(source, root.string("scene", required));
  root.object("set");  // marks it read; its keys are scene keys, checked by the scene reader
  spec.set = read_set(document, source);
  try {
    spec.base = load_scene(scene_path);
  } catch (const InputError& e) {
    throw_scene_error(source, "scene", e.what());
  }
  if (!spec.set.empty()) spec.base = patched_scene(spec.base, spec.set);
  for (ObjectReader& p : root.objects("parameters")) spec.parameters.push_back(read_parameter(p));
  if (spec.parameters.empty()) root.fail("parameters", "expected at least one parameter to fit");
  for (std::size_t i = 0; i < spec.parameters.size(); ++i)
    for (std::size_t j = 0; j < i; ++j)
      for (const std::string& key : spec.parameters[i].keys)
        for (const std::string& other : spec.parameters[j].keys)
          if (key == other)
            root.fail("parameters[" + std::to_string(i) + "]",
                      "sets " + key + ", which parameters[" + std::to_string(j) + "] sets too");
  spec.target = read_target(root.required_object("target"), document.at("target"));
  read_options(root, spec);
  root.finish();
  if (const auto* drape = std::get_if<DrapePhotosTarget>(&spec.target))
    check_drape_photos_scene(*drape, spec.base, source);
  if (const auto* photo = std::get_if<PhotoTarget>(&spec.target))
    if (photo->photo.width() != spec.base.render.width || photo->photo.height() != spec.base.render.height)
      root.fail("target", "the photo " + photo->image_path.string() + " is " +
                              std::to_string(photo->photo.width()) + "×" + std::to_string(photo->photo.height()) +
                              " px but the scene renders " + std::to_string(spec.base.render.width) + "×" +
                              std::to_string(spec.base.render.height) + " (render.size must match it)");
  return spec;
}

FitSpec load_fit_spec(const fs::path& path) {
  try {  // as large as a scene file may be
    return parse_fit_spec(base::read_file_capped(path, max_scene_file_bytes, "a fit file"),
                          path.string());
  } catch (const base::FileReadError& e) {
    throw InputError(e.what());
  }
}

}  // namespace weft::app
