// One evaluation of `weft fit` (see fit_problem.h).

#include "app/fit/fit_problem.h"

#include <chrono>
#include <cmath>
#include <limits>
#include <stdexcept>

#include "analysis/measure/drape_measure.h"
#include "app/fit/chamfer_3d.h"
#include "app/run/frame_mesh.h"
#include "app/run/measure.h"
#include "app/run/obstacle_meshes.h"
#include "app/run/renderer_choice.h"
#include "app/run/rest_shape.h"
#include "app/scene/scene_patch.h"
#include "render/photo_compare/metrics.h"

namespace weft::app {
namespace {

// The objective of a diverged evaluation: worse than any real one, finite for the optimiser.
constexpr double kFailedObjective = 1e12;

// An objective or measure past what a double holds (a target far beyond the cloth) fails the
// evaluation: fit.csv and the report get no non-finite number, and the optimiser a finite one.
void refuse_non_finite(Evaluation& e) {
  std::string what = std::isfinite(e.objective) ? "" : "objective";
  for (const auto& [name, value] : e.measures)
    if (what.empty() && !std::isfinite(value)) what = name;
  if (what.empty()) return;
  if (e.failure.empty()) e.failure = "the " + what + " is not a finite number";
  e.objective = kFailedObjective;
  e.measures.clear();
}

sim::Vec3 mean_position(const sim::Matrix3X& x, const std::vector<sim::Index>& vertices) {
  sim::Vec3 sum = sim::Vec3::Zero();
  for (const sim::Index v : vertices) sum += x.row(v).transpose();
  return sum / static_cast<double>(vertices.size());
}

// The vertices of the four grid edges, u = 0, u = 1, v = 0, v = 1.
std::vector<std::vector<sim::Index>> grid_edges(const sim::ClothMesh& mesh) {
  mesh.require_grid("weft fit's cantilever (its clamped grid edge)");
  std::vector<std::vector<sim::Index>> edges(4);
  for (sim::Index j = 0; j < mesh.nv; ++j) {
    edges[0].push_back(mesh.index(0, j));
    edges[1].push_back(mesh.index(mesh.nu - 1, j));
  }
  for (sim::Index i = 0; i < mesh.nu; ++i) {
    edges[2].push_back(mesh.index(i, 0));
    edges[3].push_back(mesh.index(i, mesh.nv - 1));
  }
  return edges;
}

double relative_misfit(double simulated, double target) {
  const double r = (simulated - target) / target;
  return r * r;
}

}  // namespace

Settled settle_to_rest(Scene scene, const SettleSettings& settings) {
  Settled s;
  if (settings.method == SettleMethod::static_solve) {
    RestShape rest = solve_rest_shape(scene);
    s.simulator = std::move(rest.simulator);
    s.converged = rest.solve.converged;
    s.iterations = rest.solve.iterations;
    s.residual = rest.solve.residual;
    return s;
  }
  scene.sim.integrator = sim::Integrator::dynamic_relaxation;
  s.simulator = make_simulator(scene);
  sim::Simulator& simulator = *s.simulator;
  const double h = simulator.time_step();
  sim::Matrix3X previous = simulator.state().x;
  while (s.iterations < settings.max_iterations) {
    const long batch = std::min(settings.check_every, settings.max_iterations - s.iterations);
    for (long k = 0; k < batch; ++k) simulator.step(h);
    s.iterations += batch;
    s.residual = simulator.relaxation()->status().residual;
    const double moved = (simulator.state().x - previous).rowwise().norm().maxCoeff();
    previous = simulator.state().x;
    if (s.residual <= settings.tolerance || moved <= settings.still_m) {
      s.converged = true;
      break;
    }
  }
  return s;
}

CantileverShape measure_cantilever(const sim::Simulator& simulator) {
  const std::vector<sim::Index>& pinned = simulator.pinned();
  if (pinned.empty())
    throw std::invalid_argument("a cantilever measure (overhang, drop) needs pinned vertices (the clamp)");
  const sim::ClothMesh& mesh = simulator.mesh();
  const sim::Vec3 clamp_rest = mean_position(mesh.rest_positions, pinned);
  const auto edges = grid_edges(mesh);
  std::size_t far = 0;
  for (std::size_t k = 1; k < edges.size(); ++k)
    if ((mean_position(mesh.rest_positions, edges[k]) - clamp_rest).norm() >
        (mean_position(mesh.rest_positions, edges[far]) - clamp_rest).norm())
      far = k;
  const sim::Matrix3X& x = simulator.state().x;
  const sim::Vec3 d = mean_position(x, edges[far]) - mean_position(x, pinned);
  const sim::Vec3 down = simulator.system().gravity_m_s2.normalized();
  CantileverShape shape;
  shape.drop_m = d.dot(down);
  shape.overhang_m = (d - shape.drop_m * down).norm();
  return shape;
}

analysis::DrapeShape measure_settled_drape(const Scene& scene, const sim::Simulator& simulator) {
  const auto support = scene_support(scene, simulator.mesh(), true);
  return analysis::measure_drape(simulator.mesh(), simulator.mesh().triangles(), simulator.state().x,
                                 *support);
}

std::optional<double> column_midline_distance_px(const render::Mask& a, const render::Mask& b) {
  double sum = 0.0;
  long columns = 0;
  for (int x = 0; x < std::min(a.width, b.width); ++x) {
    double ra = 0.0, rb = 0.0;
    long na = 0, nb = 0;
    for (int y = 0; y < a.height; ++y)
      if (a.at(x, y)) ra += y, ++na;
    for (int y = 0; y < b.height; ++y)
      if (b.at(x, y)) rb += y, ++nb;
    if (na == 0 || nb == 0) continue;
    sum += std::abs(ra / static_cast<double>(na) - rb / static_cast<double>(nb));
    ++columns;
  }
  if (columns == 0) return std::nullopt;
  return sum / static_cast<double>(columns);
}

FitProblem::FitProblem(const FitSpec& spec) : m_spec(spec) {}

render::Renderer& FitProblem::renderer() {
  if (!m_renderer) m_renderer = make_chosen_renderer(m_spec.base.render);
  return *m_renderer;
}

FitProblem::~FitProblem() = default;

Scene FitProblem::scene_at(const std::vector<double>& values) const {
  std::vector<Setting> settings;
  for (std::size_t i = 0; i < m_spec.parameters.size(); ++i) {
    char text[40];
    std::snprintf(text, sizeof text, "%.17g", values[i]);
    for (const std::string& key : m_spec.parameters[i].keys)
      settings.push_back({key, text, m_spec.source + ": parameters[" + std::to_string(i) + "]"});
  }
  Scene scene = patched_scene(m_spec.base, settings);
  apply_threads(scene, m_spec.threads);  // not part of the scene's text
  return scene;
}

Evaluation FitProblem::evaluate(const std::vector<double>& values) {
  const auto start = std::chrono::steady_clock::now();
  Evaluation e;
  e.values = values;
  Scene scene = scene_at(values);
  try {
    // settle.seeds > 1: the mean objective and measures over that many imperfection seeds —
    // the expected drape over the buckled branches a fabric's specimens take.
    const int seeds = m_spec.settle.seeds;
    const unsigned first_seed = scene.sim.statics.seed;
    e.settled = true;
    for (int k = 0; k < seeds; ++k) {
      scene.sim.statics.seed = first_seed + static_cast<unsigned>(k);
      const Settled s = settle_to_rest(scene, m_spec.settle);
      double objective = 0.0;
      const auto measures = measure(scene, *s.simulator, objective);
      e.settled = e.settled && s.converged;
      e.iterations += s.iterations;
      e.residual = std::max(e.residual, s.residual);
      e.objective += objective / seeds;
      if (k == 0) e.measures.assign(measures.size(), {});
      for (std::size_t i = 0; i < measures.size(); ++i)
        e.measures[i] = {measures[i].first, e.measures[i].second + measures[i].second / seeds};
    }
  } catch (const sim::DivergenceError& error) {
    e.failure = error.what();
    e.objective = kFailedObjective;
  }
  refuse_non_finite(e);
  e.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return e;
}

std::vector<std::pair<std::string, double>> FitProblem::measure(const Scene& scene,
                                                                const sim::Simulator& s,
                                                                double& objective) {
  std::vector<std::pair<std::string, double>> m;
  objective = 0.0;
  if (const auto* t = std::get_if<MeasuredTarget>(&m_spec.target)) {
    if (t->overhang_m || t->drop_m) {
      const CantileverShape c = measure_cantilever(s);
      m.emplace_back("overhang_mm", 1e3 * c.overhang_m);
      m.emplace_back("drop_mm", 1e3 * c.drop_m);
      if (t->overhang_m) objective += relative_misfit(c.overhang_m, *t->overhang_m);
      if (t->drop_m) objective += relative_misfit(c.drop_m, *t->drop_m);
    }
    if (t->drape_coefficient || t->folds) {
      const analysis::DrapeShape d = measure_settled_drape(scene, s);
      m.emplace_back("drape_coefficient", d.drape_coefficient);
      m.emplace_back("folds", d.folds);
      if (t->drape_coefficient) objective += relative_misfit(d.drape_coefficient, *t->drape_coefficient);
      if (t->folds) objective += relative_misfit(d.folds, *t->folds);
    }
  } else if (const auto* drape = std::get_if<DrapePhotosTarget>(&m_spec.target)) {
    const analysis::DrapeShape d = measure_settled_drape(scene, s);
    const DrapePhotoMisfit f = drape_photo_misfit(*drape, d);
    m.emplace_back("drape_coefficient", d.drape_coefficient);
    m.emplace_back("folds", d.folds);
    m.emplace_back("outline_rms_mm", f.outline_rms_mm);
    m.emplace_back("outline_part", f.outline_part);
    m.emplace_back("dc_part", f.drape_coefficient_part);
    m.emplace_back("nodes_part", f.nodes_part);
    objective = f.objective;
  } else if (const auto* cloud = std::get_if<PointCloudTarget>(&m_spec.target)) {
    objective = 1e3 * chamfer_3d(cloth_points(s.mesh(), s.state().x), cloud->points).symmetric_m;
    m.emplace_back("chamfer_3d_mm", objective);
  } else {
    const auto& photo = std::get<PhotoTarget>(m_spec.target);
    const render::Mask mask = silhouette(scene, s);
    const double iou = render::silhouette_iou(photo.mask, mask);
    const double diagonal = std::hypot(mask.width, mask.height);
    const double chamfer = render::moments(mask).area_px > 0
                               ? render::chamfer_distance(photo.mask, mask).symmetric_px
                               : diagonal;  // nothing in view: as far off as the image is wide
    const double scale = photo.mm_per_px.value_or(0.0);
    m.emplace_back("iou", iou);
    m.emplace_back("chamfer_px", chamfer);
    if (const auto midline = column_midline_distance_px(photo.mask, mask)) {
      m.emplace_back("midline_px", *midline);
      if (scale > 0) m.emplace_back("midline_mm", *midline * scale);
    }
    if (scale > 0) m.emplace_back("chamfer_mm", chamfer * scale);
    objective = photo.metric == PhotoMetric::chamfer ? chamfer : 1.0 - iou;
  }
  return m;
}

render::Mask FitProblem::silhouette(const Scene& scene, const sim::Simulator& simulator) {
  return renderer().render_mask(to_render_mesh(simulator.mesh(), simulator.state().x), scene.render,
                                obstacle_render_objects(scene.sim.obstacles, scene.render),
                                render::Renderer::MaskOf::cloth);
}

render::Image FitProblem::render_look(const Scene& scene, const sim::Simulator& simulator) {
  return renderer().render(to_render_mesh(simulator.mesh(), simulator.state().x), scene.render,
                            obstacle_render_objects(scene.sim.obstacles, scene.render));
}

}  // namespace weft::app
