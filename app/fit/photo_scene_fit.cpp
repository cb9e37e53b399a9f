// Evaluating and fitting a scene from a photo; see photo_scene_fit.h.

#include "app/fit/photo_scene_fit.h"

#include <chrono>
#include <cmath>
#include <nlopt.hpp>

#include "app/fit/fit_optimizer.h"
#include "app/run/frame_mesh.h"
#include "app/run/obstacle_meshes.h"
#include "app/run/renderer_choice.h"
#include "render/photo_compare/metrics.h"

namespace weft::app {
namespace {

constexpr double kDivergedObjective = 1e12;
constexpr double kTiltDegree = 3.14159265358979323846 / 180.0;
// The coarse scan of the camera's pitch before the local fit, degrees down.
constexpr double kTiltScanDeg[] = {-10.0, 10.0, 20.0};

// The settle of every evaluation: dynamic relaxation (the pin path rules out a static solve).
SettleSettings photo_scene_settle() {
  SettleSettings s;
  s.method = SettleMethod::dynamic_relaxation;
  return s;
}

// One freed parameter of the fit: its optimiser coordinate ↔ the placement.
struct FreedParameter {
  double lo, hi, step;
  std::function<double(const Placement&)> get;  // optimiser coordinate
  std::function<void(Placement&, double)> set;
};

std::vector<FreedParameter> freed_parameters(const PlacementFitSettings& s, double depth_m) {
  std::vector<FreedParameter> out;
  if (s.corners)
    for (std::size_t c = 0; c < 2; ++c)
      for (int axis = 0; axis < 2; ++axis)
        out.push_back({-3.0, 3.0, 0.5,
                       [c, axis](const Placement& p) { return p.corner_shift_px[c][axis]; },
                       [c, axis](Placement& p, double x) { p.corner_shift_px[c][axis] = x; }});
  if (s.depth)
    out.push_back({std::log10(0.75), std::log10(4.0 / 3.0), 0.01,
                   [](const Placement& p) { return std::log10(p.depth_scale); },
                   [](Placement& p, double x) { p.depth_scale = std::pow(10.0, x); }});
  if (s.depth_difference)
    out.push_back({-0.25 * depth_m, 0.25 * depth_m, 0.02 * depth_m,
                   [](const Placement& p) { return p.depth_difference_m; },
                   [](Placement& p, double x) { p.depth_difference_m = x; }});
  if (s.tilt) {
    const double deg = 3.14159265358979323846 / 180.0;
    out.push_back({-25 * deg, 25 * deg, 2 * deg, [](const Placement& p) { return p.tilt_rad; },
                   [](Placement& p, double x) { p.tilt_rad = x; }});
  }
  if (s.density)
    out.push_back({std::log10(0.02), std::log10(5.0), 0.1,
                   [](const Placement& p) { return std::log10(p.density_kg_m2.value_or(0.19)); },
                   [](Placement& p, double x) { p.density_kg_m2 = std::pow(10.0, x); }});
  return out;
}

}  // namespace

PhotoSceneProblem::PhotoSceneProblem(PhotoSceneSetup setup, render::Mask photo_mask,
                                     std::string source, std::optional<int> threads)
    : m_setup(std::move(setup)),
      m_mask(std::move(photo_mask)),
      m_source(std::move(source)),
      m_threads(threads) {}

PhotoSceneProblem::~PhotoSceneProblem() = default;

Scene PhotoSceneProblem::scene_at(const Placement& p, const std::string& texture_file) const {
  Scene scene = parse_scene(
      photo_scene_json(m_setup, p, "a placement of weft photo-scene", texture_file).dump(),
      m_source);
  apply_threads(scene, m_threads);
  return scene;
}

render::Renderer& PhotoSceneProblem::renderer(const Scene& scene) {
  if (!m_renderer) m_renderer = make_chosen_renderer(scene.render);
  return *m_renderer;
}

render::Mask PhotoSceneProblem::silhouette(const Scene& scene, const sim::Simulator& simulator) {
  return renderer(scene).render_mask(
      to_render_mesh(simulator.mesh(), simulator.state().x), scene.render,
      obstacle_render_objects(scene.sim.obstacles, scene.render), render::Renderer::MaskOf::cloth);
}

render::Image PhotoSceneProblem::render_look(const Scene& scene, const sim::Simulator& simulator) {
  return renderer(scene).render(to_render_mesh(simulator.mesh(), simulator.state().x), scene.render,
                                obstacle_render_objects(scene.sim.obstacles, scene.render));
}

PlacementEvaluation PhotoSceneProblem::evaluate(const Placement& p, Settled* settled_out) {
  const auto start = std::chrono::steady_clock::now();
  PlacementEvaluation e;
  e.placement = p;
  const Scene scene = scene_at(p);
  try {
    Settled s = settle_to_rest(scene, photo_scene_settle());
    e.settled = s.converged;
    e.iterations = s.iterations;
    const render::Mask mask = silhouette(scene, *s.simulator);
    e.iou = render::silhouette_iou(m_mask, mask);
    e.chamfer_px = render::moments(mask).area_px > 0
                       ? render::chamfer_distance(m_mask, mask).symmetric_px
                       : std::hypot(mask.width, mask.height);
    if (settled_out) *settled_out = std::move(s);
  } catch (const sim::DivergenceError& error) {
    e.failure = error.what();
    e.chamfer_px = kDivergedObjective;
  }
  e.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return e;
}

PlacementFit fit_placement(
    PhotoSceneProblem& problem, const Placement& start, const PlacementFitSettings& settings,
    const std::function<void(const PlacementEvaluation&, int)>& on_evaluation) {
  PlacementFit fit;
  const std::vector<FreedParameter> freed =
      freed_parameters(settings, depth_from_width(problem.setup()) * start.depth_scale);
  Placement from = start;  // where the local fit starts
  const auto placement_at = [&](const std::vector<double>& x) {
    Placement p = from;
    for (std::size_t i = 0; i < freed.size(); ++i) freed[i].set(p, x[i]);
    return p;
  };
  const auto record = [&](const PlacementEvaluation& e) {
    fit.evaluations.push_back(e);
    if (fit.evaluations.size() == 1 || e.chamfer_px < fit.best.chamfer_px) fit.best = e;
    if (on_evaluation) on_evaluation(e, static_cast<int>(fit.evaluations.size()));
    return e.chamfer_px;
  };
  if (freed.empty()) {
    record(problem.evaluate(start));
    fit.stop_reason = "nothing to fit";
    return fit;
  }
  // Depth and tilt trade along a curved valley of the outline (docs/photos.md, "Synthetic
  // photos"): a local fit from a level start finds a small tilt and a wrong depth. So the tilt
  // is first scanned coarsely, the local fit starting from the best of the scan.
  if (settings.tilt) {
    double best = record(problem.evaluate(start));
    for (const double t : kTiltScanDeg) {
      Placement p = start;
      p.tilt_rad = t * kTiltDegree;
      const double chamfer = record(problem.evaluate(p));
      if (chamfer < best) best = chamfer, from = p;
    }
  }
  nlopt::opt opt(nlopt::LN_BOBYQA, static_cast<unsigned>(freed.size()));
  std::vector<double> x, lo, hi, step;
  for (const FreedParameter& f : freed) {
    lo.push_back(f.lo);
    hi.push_back(f.hi);
    step.push_back(f.step);
    x.push_back(std::clamp(f.get(from), f.lo, f.hi));
  }
  opt.set_lower_bounds(lo);
  opt.set_upper_bounds(hi);
  opt.set_initial_step(step);
  opt.set_maxeval(settings.max_evaluations);
  opt.set_xtol_rel(1e-3);
  using Objective = std::function<double(const std::vector<double>&)>;
  Objective objective = [&](const std::vector<double>& v) {
    return record(problem.evaluate(placement_at(v)));
  };
  opt.set_min_objective([](const std::vector<double>& v, std::vector<double>&,
                           void* data) { return (*static_cast<Objective*>(data))(v); },
                        &objective);
  double best = 0.0;
  try {
    fit.stop_reason = nlopt_stop_reason(opt.optimize(x, best));
  } catch (const std::exception& e) {  // NLopt's roundoff-limited stop keeps the best so far
    fit.stop_reason = std::string("stopped: ") + e.what();
  }
  return fit;
}

render::PhotoTexture settled_photo_texture(const Scene& scene, const sim::Simulator& simulator,
                                           const render::Image& photo, const render::Mask& mask,
                                           int tw, int th) {
  const sim::ClothMesh& mesh = simulator.mesh();
  mesh.require_grid("a texture projected from a photo");
  render::ClothGridShape c;
  c.nu = static_cast<int>(mesh.nu);
  c.nv = static_cast<int>(mesh.nv);
  const sim::Vec2 size =
      mesh.material_coords[static_cast<std::size_t>(mesh.index(mesh.nu - 1, mesh.nv - 1))] -
      mesh.material_coords[0];
  c.width_m = size.x();
  c.height_m = size.y();
  const sim::Matrix3X& x = simulator.state().x;
  for (sim::Index v = 0; v < mesh.vertex_count(); ++v) c.positions.push_back(x.row(v).transpose());
  const render::Camera& camera = scene.render.camera;
  const int w = photo.width(), h = photo.height();
  return render::project_photo_texture(
      photo, mask, c, [&](const Eigen::Vector3d& p) { return camera.project(p, w, h); }, camera.eye,
      tw, th);
}

}  // namespace weft::app
