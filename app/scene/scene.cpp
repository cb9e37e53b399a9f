// Scene files → Scene, through ObjectReader (app/scene/json_reader.h). The format is documented, key
// by key, in docs/scene.md; keep the two in step.

#include "app/scene/scene.h"

#include "app/scene/scene_inputs.h"

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <limits>
#include <memory>
#include <optional>
#include <utility>

#include "app/scene/cloth_surface_scene.h"
#include "app/scene/data_dir.h"
#include "app/scene/environment_scene.h"
#include "app/scene/json_reader.h"
#include "app/io/mesh_file.h"
#include "app/scene/scene_bounds.h"
#include "app/scene/scene_cloth.h"
#include "app/scene/units.h"
#include "base/constants.h"
#include "sim/round_specimen.h"

// Defined in the .cpp that app/scene/embed_default_scene.cmake generates from
// assets/scenes/default.json.
const char* weft_default_scene_json();

namespace weft::app {
namespace {

constexpr const char* builtin_source = "<built-in default scene>";

// "mesh": a closed triangle mesh read from a file (app/io/mesh_file.h), its path relative to the
// scene file, scaled from the file's units to metres, turned about +z, then translated.
sim::MeshObstacle read_mesh_obstacle(ObjectReader& o) {
  const std::filesystem::path file = o.string("file", required);
  const double scale = o.number("scale", 1.0, Range::gt(0.0));
  sim::MeshObstacle mesh;
  mesh.pose.translation_m =
      o.quantity_vec3("translate", Quantity::length, Eigen::Vector3d::Zero());
  mesh.pose.yaw_rad = o.angle_deg("rotate_z", 0.0) * base::kPi / 180.0;
  const std::filesystem::path path = scene_relative(o.file(), file);
  try {
    TriangleMesh triangles = load_triangle_mesh(path);
    mesh.solid = std::make_shared<const sim::MeshSolid>(scale * triangles.vertices,
                                                        std::move(triangles.triangles));
  } catch (const MeshFileError& e) {
    o.fail("file", e.what());
  } catch (const std::invalid_argument& e) {
    o.fail("file", path.string() + ": " + e.what());
  }
  return mesh;
}

// An obstacle's optional "motion": keyframes {"time", "translate", "rotate_z"}
// (sim::ObstacleMotion).
sim::ObstacleMotion read_obstacle_motion(ObjectReader& r) {
  if (!r.has("motion")) return {};
  std::vector<ObjectReader> frames = r.objects("motion");
  if (frames.empty()) r.fail("motion", "expected at least one keyframe, got an empty list");
  std::vector<sim::ObstacleKeyframe> keyframes;
  for (ObjectReader& f : frames) {
    sim::ObstacleKeyframe frame;
    frame.time_s = f.quantity("time", Quantity::time, required);
    frame.translate_m = f.quantity_vec3("translate", Quantity::length, Eigen::Vector3d::Zero());
    frame.rotate_z_rad = f.angle_deg("rotate_z", 0.0) * base::kPi / 180.0;
    f.finish();
    keyframes.push_back(frame);
  }
  try {
    return sim::ObstacleMotion(std::move(keyframes));  // checks the order of the times
  } catch (const std::invalid_argument& e) {
    r.fail("motion", e.what());
  }
}

// One obstacle object: exactly one of "sphere", "plane", "box", "cylinder", "capsule", "mesh"
// (sim::Obstacle), and an optional "motion".
sim::Obstacle read_obstacle(ObjectReader r, sim::ObstacleMotion& motion,
                            std::vector<std::string>& warnings) {
  const std::vector<std::string> kinds = {"sphere", "plane", "box", "cylinder", "capsule", "mesh"};
  std::vector<std::string> present;
  for (const std::string& kind : kinds)
    if (r.has(kind)) present.push_back(kind);
  if (present.empty()) r.finish();  // a misspelt "sphere" gets its "did you mean"
  if (present.size() != 1) {
    throw_scene_error(r.file(), r.path(),
                      "expected exactly one of 'sphere', 'plane', 'box', 'cylinder', "
                      "'capsule' or 'mesh', got " +
                          (present.empty() ? std::string("none")
                                           : "'" + present[0] + "' and '" + present[1] + "'"));
  }
  const std::string& kind = present[0];
  ObjectReader o = r.required_object(kind);
  sim::Obstacle obstacle;
  if (kind == "sphere") {
    sim::SphereObstacle s;
    s.center_m = o.quantity_vec3("center", Quantity::length, required);
    s.radius_m = o.quantity("radius", Quantity::length, required, Range::gt(0.0));
    obstacle = s;
  } else if (kind == "plane") {
    sim::PlaneObstacle p;
    p.point_m = o.quantity_vec3("point", Quantity::length, required);
    p.normal = o.unit_vec3("normal", required);
    obstacle = p;
  } else if (kind == "box") {
    sim::BoxObstacle b;
    b.center_m = o.quantity_vec3("center", Quantity::length, required);
    const std::vector<double> half =
        o.quantities("half_size", Quantity::length, 3, required, Range::gt(0.0));
    b.half_size_m = Eigen::Vector3d(half[0], half[1], half[2]);
    b.yaw_rad = o.angle_deg("yaw", 0.0) * base::kPi / 180.0;
    obstacle = b;
  } else if (kind == "cylinder") {
    sim::CylinderObstacle c;
    c.center_m = o.quantity_vec3("center", Quantity::length, required);
    c.axis = o.unit_vec3("axis", required);
    c.radius_m = o.quantity("radius", Quantity::length, required, Range::gt(0.0));
    c.height_m = o.quantity("height", Quantity::length, required, Range::gt(0.0));
    obstacle = c;
  } else if (kind == "capsule") {
    sim::CapsuleObstacle c;
    c.a_m = o.quantity_vec3("a", Quantity::length, required);
    c.b_m = o.quantity_vec3("b", Quantity::length, required);
    c.radius_m = o.quantity("radius", Quantity::length, required, Range::gt(0.0));
    if (c.a_m == c.b_m)
      warnings.push_back(o.file() + ": " + o.path() +
                         ": 'a' and 'b' are the same point: a sphere (write it as one)");
    obstacle = c;
  } else {
    obstacle = read_mesh_obstacle(o);
  }
  o.finish();
  motion = read_obstacle_motion(r);
  r.finish();
  return obstacle;
}

// "simulation.constraints": inextensibility after the unconstrained step
// (sim::ProjectionSettings). A key the chosen method does not use is an error, not ignored.
sim::ProjectionSettings read_constraints(ObjectReader r) {
  using sim::ProjectionMethod;
  sim::ProjectionSettings p;
  p.method = r.enumeration("method", sim::projection_method_names, {p.method});
  p.edges = r.enumeration("edges", sim::constrained_edges_names, {p.edges});
  p.tolerance = r.number("tolerance", p.tolerance, Range::gt(0.0));
  p.max_iterations = static_cast<int>(r.integer("max_iterations", p.max_iterations,
                                                Range::closed(1, std::numeric_limits<int>::max())));
  p.max_stretch = r.number("max_stretch", p.max_stretch, Range::ge(0.0));
  p.reuse_iterations = static_cast<int>(
      r.integer("reuse_iterations", p.reuse_iterations, Range::closed(0, 1000)));
  r.finish();  // unknown keys first: a misspelt "method" gets its "did you mean"

  const std::string method_name = base::enum_name(sim::projection_method_names, p.method);
  const auto used_only_by = [&](const std::string& key, const std::string& users) {
    if (r.has(key)) {
      r.fail(key, "expected only with method " + users +
                      " (it has no effect otherwise), got method '" + method_name + "'");
    }
  };
  if (p.method == ProjectionMethod::none) {
    for (const char* key : {"edges", "tolerance", "max_iterations"})
      used_only_by(key, "'fast_projection' or 'pairwise'");
  }
  if (p.method != ProjectionMethod::pairwise) used_only_by("max_stretch", "'pairwise'");
  if (p.method != ProjectionMethod::fast_projection)
    used_only_by("reuse_iterations", "'fast_projection'");
  return p;
}

// "simulation.linear_solver": a sparse back-end this build has (sim::SparseBackend).
sim::SparseBackend read_linear_solver(ObjectReader& r, sim::SparseBackend fallback) {
  using sim::SparseBackend;
  const std::string key = "linear_solver";
  const SparseBackend backend = r.enumeration(key, sim::sparse_backend_names, {fallback});
  const std::vector<SparseBackend> available = sim::available_sparse_backends();
  if (std::find(available.begin(), available.end(), backend) == available.end()) {
    std::string names;
    for (SparseBackend b : available)
      names += std::string(names.empty() ? "'" : ", '") + sim::sparse_backend_name(b) + "'";
    r.fail(key, "expected a back-end this build has (" + names + "), got '" +
                    sim::sparse_backend_name(backend) + "', which it was built without");
  }
  return backend;
}

// "simulation.aerodynamics": air drag and wind (sim::AeroSettings); present means enabled.
sim::AeroSettings read_aerodynamics(ObjectReader r) {
  sim::AeroSettings a;
  a.enabled = true;
  a.drag_coefficient = r.number("drag_coefficient", a.drag_coefficient, Range::ge(0.0));
  a.air_density_kg_m3 = r.number("air_density", a.air_density_kg_m3, Range::gt(0.0));
  if (r.has("wind")) {
    ObjectReader wind = r.object("wind");
    a.wind.velocity_m_s = wind.quantity_vec3("velocity", Quantity::speed, required);
    if (wind.has("gust")) {
      ObjectReader gust = wind.object("gust");
      a.wind.gust.amplitude = gust.number("amplitude", required, Range::ge(0.0));
      a.wind.gust.period_s = gust.quantity("period", Quantity::time, required, Range::gt(0.0));
      a.wind.gust.wavelength_m =
          gust.quantity("wavelength", Quantity::length, a.wind.gust.wavelength_m, Range::ge(0.0));
      gust.finish();
    }
    wind.finish();
  }
  r.finish();
  return a;
}

// "simulation.self_collision": the cloth against itself (sim::SelfCollisionSettings);
// present means enabled unless "enabled": false.
sim::SelfCollisionSettings read_self_collision(ObjectReader r, Scene::CrossingPolicy& crossings) {
  sim::SelfCollisionSettings c;
  c.enabled = r.boolean("enabled", true);
  crossings = r.enumeration("crossings", Scene::crossing_policy_names, {crossings});
  c.thickness_m = r.quantity("thickness", Quantity::length, c.thickness_m, Range::gt(0.0));
  c.marble_radius_m =
      r.quantity("marble_radius", Quantity::length, c.marble_radius_m, Range::ge(0.0));
  c.iterations = static_cast<int>(r.integer("iterations", c.iterations, Range::closed(1, 100)));
  c.neighbourhood_edges =
      r.number("neighbourhood", c.neighbourhood_edges, Range::closed(0.0, 4.0));
  c.impact_zones = r.boolean("impact_zones", c.impact_zones);
  c.failsafe_interval_s =
      r.quantity("failsafe_interval", Quantity::time, c.failsafe_interval_s, Range::closed(0.0, 1.0));
  r.finish();
  return c;
}

// "simulation.adaptive_step" (sim/adaptive_step.h).
void read_adaptive_step(ObjectReader r, sim::AdaptiveStepSettings& a) {
  a.min_step_s = r.quantity("min_step", Quantity::time, a.min_step_s, Range::gt(0.0));
  a.max_step_s = r.quantity("max_step", Quantity::time, a.max_step_s, Range::gt(0.0));
  a.max_prediction_strain =
      r.number("max_prediction_strain", a.max_prediction_strain, Range::gt(0.0).le(1.0));
  if (a.max_step_s < a.min_step_s)
    r.fail("max_step", "expected at least min_step (" + std::to_string(a.min_step_s) +
                           " s), got " + std::to_string(a.max_step_s) + " s");
  r.finish();
}

// "simulation.remesh" (sim::RemeshSettings, docs/remeshing.md): present means enabled. Whether
// the cloth and the other settings allow it is the simulator's check (make_simulator names the
// key).
sim::RemeshSettings read_remesh(ObjectReader r) {
  sim::RemeshSettings m;
  m.enabled = true;
  m.every_steps = r.integer("every", m.every_steps, Range::closed(1, 1e9));
  m.c_m = r.quantity("c", Quantity::length, m.c_m, Range::gt(0.0));
  m.h_min_m = r.quantity("h_min", Quantity::length, m.h_min_m, Range::gt(0.0));
  m.h_max_m = r.quantity("h_max", Quantity::length, m.h_max_m, Range::gt(0.0));
  m.max_vertices = r.integer("max_vertices", m.max_vertices, Range::closed(3, static_cast<double>(max_remesh_vertices)));
  if (r.has("indicator")) {
    m.indicator = r.number("indicator", std::nullopt, Range::gt(0.0).lt(1e6));
    if (m.indicator <= 1.0)
      r.fail("indicator", "expected a multiple of c above 1 (max |κ|h² is about c where a "
                          "remeshed cloth is curved, so a threshold at c or below would remesh "
                          "at every check), got " + std::to_string(m.indicator));
  }
  if (r.has("coarsen")) {
    m.coarsen = r.number("coarsen", std::nullopt, Range::gt(0.0).lt(1e6));
    if (m.indicator <= 0.0)
      r.fail("coarsen", "needs \"indicator\": without it every check remeshes, which coarsens "
                        "flat regions already");
    if (m.coarsen <= 1.0)
      r.fail("coarsen", "expected a ratio above 1 (how many times finer than the curvature asks "
                        "the mesh may grow before it is coarsened), got " +
                            std::to_string(m.coarsen));
  }
  m.transfer = r.enumeration("transfer", sim::remesh::position_transfer_names, {m.transfer});
  m.relax_steps = r.integer("relax", m.relax_steps, Range::closed(0, 1000));
  if (m.h_max_m < m.h_min_m)
    r.fail("h_max", "expected at least h_min (" + std::to_string(m.h_min_m) + " m), got " +
                        std::to_string(m.h_max_m) + " m");
  r.finish();
  return m;
}

// A frame must take at most sim::max_substeps steps: of a fixed step, or of an adaptive step's
// max_step, its first and longest, and min_step, its shortest (a min_step of 1e-300 s used to run
// for a minute before failing). (The automatic step comes from the material: make_simulator
// checks it.)
void check_steps_per_frame(const Scene& scene) {
  const sim::TimeStep& t = scene.sim.time_step;
  if (t.kind == sim::TimeStep::Kind::automatic) return;
  const bool fixed = t.kind == sim::TimeStep::Kind::fixed;
  const std::string why =
      sim::too_many_steps(1.0 / scene.fps, fixed ? t.fixed_s : t.adaptive.max_step_s);
  if (!why.empty())
    throw InputError(scene.source + ": " +
                     (fixed ? "simulation.time_step: " : "simulation.adaptive_step.max_step: ") +
                     why);
  const std::string shortest = fixed ? "" : sim::too_many_steps(1.0 / scene.fps, t.adaptive.min_step_s);
  if (!shortest.empty())
    throw InputError(scene.source + ": simulation.adaptive_step.min_step: " + shortest +
                     " (were the step to shrink to it)");
}


// "simulation.time_step": "auto" (the default), "adaptive" (with "simulation.adaptive_step")
// or a time.
sim::TimeStep read_time_step(ObjectReader& r) {
  sim::TimeStep t;
  const std::optional<double> fixed_s =
      r.quantity_or_keyword("time_step", Quantity::time, {"auto", "adaptive"}, Range::gt(0.0));
  if (fixed_s) t = sim::fixed_time_step(*fixed_s);
  else if (r.holds_keyword("time_step", "adaptive")) t = sim::adaptive_time_step();
  if (r.has("adaptive_step")) {
    if (!t.is_adaptive()) r.fail("adaptive_step", "applies only with time_step \"adaptive\"");
    read_adaptive_step(r.object("adaptive_step"), t.adaptive);
  }
  return t;
}

// "simulation.static": how a static solve finds the rest shape (sim::StaticSettings).
sim::StaticSettings read_static(ObjectReader r) {
  sim::StaticSettings s;
  s.tolerance = r.number("tolerance", s.tolerance, Range::gt(0.0).lt(1.0));
  s.max_iterations = static_cast<int>(r.integer("max_iterations", s.max_iterations, Range::closed(1, 1e6)));
  s.contact_stiffness = r.number("contact_stiffness", s.contact_stiffness, Range::ge(1.0).le(1e9));
  s.imperfection = r.number("imperfection", s.imperfection, Range::ge(0.0).le(1.0));
  s.seed = static_cast<unsigned>(r.integer("seed", s.seed, Range::closed(0, 4294967295.0)));
  s.max_move = r.number("max_move", s.max_move, Range::gt(0.0).le(100.0));
  r.finish();
  return s;
}

// "simulation": integrator settings (sim::SimSettings).
void read_simulation(ObjectReader r, sim::SimSettings& s, bool& dynamics,
                     Scene::CrossingPolicy& crossings) {
  dynamics = r.boolean("dynamics", dynamics);
  s.model = r.enumeration("model", sim::cloth_model_names, {s.model});
  s.integrator = r.enumeration("integrator", sim::integrator_names, {s.integrator});
  s.sparse_backend = read_linear_solver(r, s.sparse_backend);
  s.implicit_solve = r.enumeration("implicit_solver", sim::implicit_solve_names, {s.implicit_solve});
  s.implicit_cg_tolerance =
      r.number("cg_tolerance", s.implicit_cg_tolerance, Range::gt(0.0).lt(1.0));
  s.implicit_cg_preconditioner = r.enumeration("cg_preconditioner", sim::cg_preconditioner_names,
                                               {s.implicit_cg_preconditioner});
  s.bending_in_step =
      r.enumeration("bending_in_step", sim::bending_in_step_names, {s.bending_in_step});
  if (s.bending_in_step == sim::BendingInStep::implicit &&
      s.integrator != sim::Integrator::implicit_euler)
    r.fail("bending_in_step", "\"implicit\" applies only with integrator \"implicit_euler\" "
                              "(the explicit integrators have no matrix to take it into)");
  s.gravity_m_s2 = r.quantity_vec3("gravity", Quantity::acceleration, s.gravity_m_s2);
  s.air_damping_1_s =
      r.quantity("air_damping", Quantity::inverse_time, s.air_damping_1_s, Range::ge(0.0));
  s.time_step = read_time_step(r);
  s.time_step_safety = r.number("time_step_safety", s.time_step_safety, Range::gt(0.0).le(1.0));
  s.max_speed_m_s = r.quantity("max_speed", Quantity::speed, s.max_speed_m_s, Range::gt(0.0));
  s.max_strain = r.number("max_strain", s.max_strain, Range::gt(0.0));
  s.projection = read_constraints(r.object("constraints"));
  s.collision_thickness_m =
      r.quantity("collision_thickness", Quantity::length, s.collision_thickness_m, Range::ge(0.0));
  s.collision_friction = r.number("collision_friction", s.collision_friction, Range::ge(0.0));
  s.resting_contacts = r.boolean("resting_contacts", s.resting_contacts);
  if (s.resting_contacts && s.integrator != sim::Integrator::implicit_euler)
    r.fail("resting_contacts", "applies only with integrator \"implicit_euler\" (it holds "
                               "contacts inside the implicit solve)");
  if (r.has("aerodynamics")) s.aero = read_aerodynamics(r.object("aerodynamics"));
  if (r.has("self_collision"))
    s.self_collision = read_self_collision(r.object("self_collision"), crossings);
  if (r.has("remesh")) s.remesh = read_remesh(r.object("remesh"));
  if (r.has("static")) s.statics = read_static(r.object("static"));
  if (s.time_step.is_adaptive() && (s.integrator != sim::Integrator::implicit_euler ||
                                    s.projection.method != sim::ProjectionMethod::fast_projection))
    r.fail("time_step", "\"adaptive\" follows fast projection's iterations: it needs integrator "
                        "implicit_euler and constraints.method fast_projection");
  r.finish();
}

void read_output(ObjectReader r, Scene& scene) {
  scene.fps = r.number("fps", scene.fps, Range::gt(0.0).le(1000.0));
  scene.frames = static_cast<int>(r.integer("frames", scene.frames, Range::closed(1, 100000)));
  scene.write_mask = r.boolean("mask", scene.write_mask);
  scene.write_alpha = r.boolean("alpha", scene.write_alpha);
  r.finish();
}

// "render.camera.intrinsics": a calibrated pinhole's fx, fy, cx, cy (pixels) and image size.
render::PinholeIntrinsics read_intrinsics(ObjectReader r) {
  render::PinholeIntrinsics k;
  k.fx_px = r.number("fx", required, Range::gt(0.0));
  k.fy_px = r.number("fy", required, Range::gt(0.0));
  k.cx_px = r.number("cx", required);
  k.cy_px = r.number("cy", required);
  const auto size = r.integers("size", 2, required, Range::closed(1, 100000));
  k.width_px = static_cast<int>(size[0]);
  k.height_px = static_cast<int>(size[1]);
  r.finish();
  return k;
}

// A calibrated camera: intrinsics and one pose, "position" + "rotation" (camera → world),
// "camera_to_world" or "world_to_camera" (4×4, OpenCV's [R | t] extrinsics); render/camera.h
// states the conventions. No look-at key may be given with it.
render::Camera read_calibrated_camera(ObjectReader& r) {
  for (const char* key : {"eye", "target", "up", "fov"}) {
    if (r.has(key))
      r.fail(key, "a calibrated camera (render.camera.intrinsics) takes no look-at key: give "
                  "its pose as position + rotation, camera_to_world or world_to_camera");
  }
  const render::PinholeIntrinsics k = read_intrinsics(r.object("intrinsics"));
  const bool has_position = r.has("position"), has_rotation = r.has("rotation");
  const int poses = int{has_position || has_rotation} + int{r.has("camera_to_world")} +
                    int{r.has("world_to_camera")};
  if (poses != 1 || has_position != has_rotation)
    r.fail("intrinsics", "expected exactly one pose beside the intrinsics: position and rotation "
                         "(camera to world), camera_to_world or world_to_camera (4x4)");
  const auto make = [&](const char* key, const auto& make_camera) {
    try {
      return make_camera();
    } catch (const std::invalid_argument& e) {
      r.fail(key, e.what());
    }
  };
  if (has_position) {
    const Eigen::Vector3d position = r.quantity_vec3("position", Quantity::length, required);
    const Eigen::Matrix3d rotation = r.matrix("rotation", 3, 3);
    return make("rotation", [&] { return render::Camera::calibrated(k, rotation, position); });
  }
  if (r.has("camera_to_world")) {
    const Eigen::Matrix4d pose = r.matrix("camera_to_world", 4, 4);
    return make("camera_to_world", [&] { return render::Camera::calibrated(k, pose); });
  }
  const Eigen::Matrix4d extrinsics = r.matrix("world_to_camera", 4, 4);
  return make("world_to_camera", [&] {
    const Eigen::Matrix3d rotation = render::checked_rotation(extrinsics.topLeftCorner<3, 3>());
    Eigen::Matrix4d pose = Eigen::Matrix4d::Identity();
    pose.topLeftCorner<3, 3>() = rotation.transpose();
    pose.topRightCorner<3, 1>() = -rotation.transpose() * extrinsics.topRightCorner<3, 1>();
    pose.row(3) = extrinsics.row(3);
    return render::Camera::calibrated(k, pose);
  });
}

render::Camera read_camera(ObjectReader r) {
  if (r.has("intrinsics")) {
    render::Camera c = read_calibrated_camera(r);
    c.near_m = r.quantity("near", Quantity::length, c.near_m, Range::gt(0.0));
    c.far_m = r.quantity("far", Quantity::length, c.far_m, Range::gt(c.near_m));
    r.finish();
    return c;
  }
  render::Camera c;
  c.eye = r.quantity_vec3("eye", Quantity::length, c.eye);
  c.target = r.quantity_vec3("target", Quantity::length, c.target);
  c.up = r.vec3("up", c.up);
  c.fov_y_deg = r.angle_deg("fov", c.fov_y_deg, Range::gt(0.0).lt(180.0));
  c.near_m = r.quantity("near", Quantity::length, c.near_m, Range::gt(0.0));
  c.far_m = r.quantity("far", Quantity::length, c.far_m, Range::gt(c.near_m));
  const Eigen::Vector3d view = c.target - c.eye;
  if (!(view.norm() > 0.0)) r.fail("target", "expected a target different from the eye");
  if (!(c.up.norm() > 0.0) || view.normalized().cross(c.up.normalized()).norm() < 1e-6)
    r.fail("up", "expected a direction that is not zero and not parallel to target - eye");
  r.finish();
  return c;
}

// "render.raytrace": the ray tracer's own settings (render::RayTraceSettings).
void read_raytrace(ObjectReader r, render::RayTraceSettings& t) {
  t.samples_per_pixel =
      static_cast<int>(r.integer("samples", t.samples_per_pixel, Range::closed(1, 65536)));
  t.adaptive_error = r.number("adaptive_error", t.adaptive_error, Range::closed(0.0, 255.0));
  t.adaptive_round =
      static_cast<int>(r.integer("adaptive_round", t.adaptive_round, Range::closed(1, 65536)));
  t.bounces = static_cast<int>(r.integer("bounces", t.bounces, Range::closed(0, 64)));
  t.ao_samples = static_cast<int>(r.integer("ao_samples", t.ao_samples, Range::closed(0, 1024)));
  t.ao_distance_m = r.quantity("ao_distance", Quantity::length, t.ao_distance_m, Range::gt(0.0));
  t.sun_angular_radius_deg =
      r.angle_deg("sun_radius", t.sun_angular_radius_deg, Range::closed(0.0, 45.0));
  for (const char* moved : {"sheen", "sheen_roughness"}) {
    if (r.has(moved))
      r.fail(moved, std::string("expected it in \"render\": render.") + moved +
                        " (the cloth's sheen is drawn by both renderers)");
  }
  t.seed = static_cast<std::uint32_t>(r.integer("seed", t.seed, Range::closed(0, 4294967295)));
  t.denoise = r.boolean("denoise", t.denoise);
  r.finish();
}

// "render": image size, camera, light, colours, ground, shading (render::RenderSettings).
// Also sets scene.camera_given and scene.ground_collider.
void read_render(ObjectReader r, Scene& scene) {
  render::RenderSettings& s = scene.render;
  scene.camera_given = r.has("camera");
  const auto size =
      r.integers("size", 2, std::vector<std::int64_t>{s.width, s.height}, Range::closed(16, 8192));
  s.width = static_cast<int>(size[0]);
  s.height = static_cast<int>(size[1]);
  s.camera = read_camera(r.object("camera"));
  if (s.camera.intrinsics) {
    try {
      s.camera.intrinsics->scaled_to(s.width, s.height);
    } catch (const std::invalid_argument& e) {
      r.fail("size", std::string(e.what()) + " (render.camera.intrinsics.size)");
    }
  }

  ObjectReader light = r.object("light");
  s.light_direction = light.vec3("direction", s.light_direction);
  if (!(s.light_direction.norm() > 0.0))
    light.fail("direction", "expected a non-zero vector towards the light, got [0, 0, 0]");
  s.light_intensity = light.number("intensity", s.light_intensity, Range::ge(0.0));
  s.ambient = light.number("ambient", s.ambient, Range::closed(0.0, 1.0));
  light.finish();

  ObjectReader colors = r.object("colors");
  s.front_color = read_color(colors, "front", s.front_color);
  if (colors.has("back")) s.back_color = read_color(colors, "back", s.front_color);
  s.background = read_color(colors, "background", s.background);
  s.obstacle_color = read_color(colors, "obstacle", s.obstacle_color);
  s.support_color = read_color(colors, "support", s.support_color);
  colors.finish();

  // "ground": false disables it, true keeps the defaults, an object sets them.
  if (r.holds_boolean("ground")) {
    s.ground = r.boolean("ground", required);
  } else {
    ObjectReader ground = r.object("ground");
    scene.ground_collider = ground.boolean("collider", scene.ground_collider);
    s.ground_z_m = ground.quantity("z", Quantity::length, s.ground_z_m);
    s.ground_half_size_m =
        ground.quantity("half_size", Quantity::length, s.ground_half_size_m, Range::gt(0.0));
    s.ground_color = read_color(ground, "color", s.ground_color);
    ground.finish();
  }

  s.supports = r.boolean("supports", s.supports);
  s.shading = r.enumeration("shading", render::shading_names, {s.shading});
  s.strain_full_scale = r.number("strain_scale", s.strain_full_scale, Range::gt(0.0).le(10.0));
  s.msaa_samples = static_cast<int>(r.integer("msaa", s.msaa_samples, Range::closed(1, 8)));
  if (s.msaa_samples & (s.msaa_samples - 1))
    r.fail("msaa", "expected 1, 2, 4 or 8 samples, got " + std::to_string(s.msaa_samples));
  s.renderer = r.enumeration("renderer", render::renderer_names, {s.renderer});
  s.gl = r.enumeration("gl", render::gl_backend_names, {s.gl});
  read_raytrace(r.object("raytrace"), s.raytrace);
  read_cloth_surface(r, s.cloth_surface);  // subdivision, thickness, texture
  read_environment(r, s.environment);       // image-based lighting
  r.finish();
}


}  // namespace

Scene parse_scene(const std::string& text, const std::string& source) {
  const Json document = parse_json(text, source);
  ObjectReader top = ObjectReader::root(document, source);

  Scene scene;
  scene.source = source;
  scene.name = std::filesystem::path(source).stem().string();
  scene.text = text;
  scene.input_files = scene_input_files(document, source);
  scene.description = top.string("description", required);
  if (scene.description.find_first_not_of(" \t\r\n") == std::string::npos)
    top.fail("description", "expected a non-empty string saying what the scene shows");
  read_cloth(top.required_object("cloth"), scene);
  if (const Json* list = document.contains("obstacles") ? &document.at("obstacles") : nullptr;
      list && list->is_array() && list->size() > max_obstacles)
    top.fail("obstacles", "expected at most " + std::to_string(max_obstacles) +
                              " obstacles (the limit: each is tested against every vertex in "
                              "every step), got " + std::to_string(list->size()));
  for (ObjectReader& obstacle : top.objects("obstacles")) {
    sim::ObstacleMotion motion;
    scene.sim.obstacles.push_back(read_obstacle(obstacle, motion, scene.warnings));
    scene.sim.obstacle_motions.push_back(std::move(motion));
  }
  read_simulation(top.object("simulation"), scene.sim, scene.dynamics, scene.crossings);
  if (scene.tension_field)
    check_tension_field_scene(*scene.tension_field, scene.grid, scene.material,
                              scene.sim.gravity_m_s2, source);
  read_output(top.object("output"), scene);
  read_render(top.object("render"), scene);
  top.finish();
  check_steps_per_frame(scene);
  return scene;
}

Scene load_scene(const std::filesystem::path& given) {
  const std::filesystem::path path = find_scene(given);  // a bare name: one of weft's scenes
  const std::unique_ptr<std::FILE, int (*)(std::FILE*)> file(std::fopen(path.c_str(), "rb"),
                                                             &std::fclose);
  const auto cannot_read = [&]() {
    const std::string reason = std::strerror(errno);
    std::string known;
    if (!path.has_parent_path()) {
      try {
        known = "; nor is it one of weft's scenes: " + known_scene_names();
      } catch (const InputError& e) {
        known = std::string("; nor could weft's own scenes be looked in: ") + e.what();
      }
    } else if (const std::filesystem::path own = find_scene(path.filename());
               own != path.filename()) {
      // assets/scenes/X.json typed outside the source tree: weft's own X is found by its name.
      known = "; weft's own scene " + path.stem().string() + " is " + own.string() +
              ": give its bare name, " + path.stem().string() + " (as in weft run " +
              path.stem().string() + ")";
    }
    throw InputError(path.string() + ": cannot read scene file (" + reason + ")" + known);
  };
  if (!file) cannot_read();
  std::string text;
  char buffer[65536];
  std::size_t n = 0;
  while ((n = std::fread(buffer, 1, sizeof buffer, file.get())) > 0) {
    text.append(buffer, n);
    if (text.size() > max_scene_file_bytes)  // e.g. /dev/zero: stop, do not read on
      throw InputError(path.string() + ": the scene file is larger than " +
                       std::to_string(max_scene_file_bytes >> 20) +
                       " MiB (the limit; meshes go in their own files)");
  }
  if (std::ferror(file.get())) cannot_read();
  return parse_scene(text, path.string());
}

const std::string& default_scene_text() {
  static const std::string text = weft_default_scene_json();
  return text;
}

Scene default_scene() {
  Scene scene = parse_scene(default_scene_text(), builtin_source);
  scene.name = "default";
  return scene;
}

// Unit normal components and metres: a plane this close to the drawn ground is the ground.
constexpr double ground_coincidence_tolerance = 1e-9;

bool is_rendered_ground(const sim::PlaneObstacle& plane, const render::RenderSettings& s) {
  return s.ground && plane.normal.z() >= 1.0 - ground_coincidence_tolerance &&
         std::fabs(plane.normal.dot(plane.point_m) - s.ground_z_m) <= ground_coincidence_tolerance;
}

sim::SimSettings simulated_settings(const Scene& scene) {
  sim::SimSettings settings = scene.sim;
  if (!scene.render.ground || !scene.ground_collider) return settings;
  for (const sim::Obstacle& obstacle : settings.obstacles)
    if (const auto* plane = std::get_if<sim::PlaneObstacle>(&obstacle);
        plane && is_rendered_ground(*plane, scene.render))
      return settings;  // the scene has the ground's plane already
  sim::PlaneObstacle ground;
  ground.point_m = {0.0, 0.0, scene.render.ground_z_m};
  settings.obstacles.push_back(ground);
  if (!settings.obstacle_motions.empty()) settings.obstacle_motions.emplace_back();
  return settings;
}

sim::ClothMesh cloth_mesh(const Scene& scene) {
  return scene.mesh ? *scene.mesh : sim::make_grid(scene.grid);
}

std::string cloth_size_text(const Scene& scene) {
  if (scene.mesh)
    return std::to_string(scene.mesh->used_vertex_count()) + " vertices (" + scene.mesh->source + ")";
  if (scene.grid.disc_edge == sim::DiscEdge::smooth)
    return std::to_string(cloth_mesh(scene).vertex_count()) + " vertices (a disc in " +
           std::to_string(sim::round_specimen_rings(scene.grid)) + " rings)";
  return std::to_string(scene.grid.nu) + "x" + std::to_string(scene.grid.nv) + " vertices";
}

std::unique_ptr<sim::Simulator> make_simulator(const Scene& scene) {
  sim::ClothMesh mesh = cloth_mesh(scene);
  std::vector<sim::Index> pinned = sim::resolve_pins(scene.pins, mesh);
  std::unique_ptr<sim::Simulator> simulator;
  try {
    simulator = std::make_unique<sim::Simulator>(std::move(mesh), scene.material, std::move(pinned),
                                                 simulated_settings(scene));
  } catch (const sim::MaterialError& e) {
    throw InputError(scene.source + ": cloth.material: " + e.what());
  } catch (const std::invalid_argument& e) {  // other settings the simulator cannot take
    throw InputError(scene.source + ": " + e.what());
  }
  if (scene.sim.time_step.kind == sim::TimeStep::Kind::automatic) {
    const std::string why = sim::too_many_steps(1.0 / scene.fps, simulator->time_step());
    if (!why.empty())
      throw InputError(scene.source + ": cloth.material: the automatic time step (from the "
                                      "density and stiffness) " + why);
  }
  check_scene_bounds(scene, *simulator);
  if (scene.tension_field)
    simulator->set_initial_positions(folded_start(*scene.tension_field, scene.grid, scene.material,
                                                  scene.sim.gravity_m_s2, simulator->mesh())
                                         .x);
  for (std::size_t k = 0; k < scene.pin_paths.size(); ++k) {
    if (scene.pin_paths[k].moves())
      simulator->set_pin_path(sim::resolve_pins({scene.pins[k]}, simulator->mesh()),
                              scene.pin_paths[k]);
  }
  return simulator;
}

void apply_threads(Scene& scene, std::optional<int> threads) {
  if (!threads) return;
  scene.render.raytrace.threads = *threads;
  scene.sim.self_collision.threads = *threads;
  scene.sim.solver_threads = *threads;
}

}  // namespace weft::app
