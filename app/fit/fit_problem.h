#pragma once
// One evaluation of `weft fit`: the scene with the parameters' values patched
// in, settled to rest by dynamic relaxation, and its distance to the target (fit_spec.h). Also
// the pictures of a photo target: the cloth's silhouette through the scene's camera and the
// fitted render.

#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "app/fit/fit_spec.h"
#include "render/renderer.h"
#include "sim/simulator.h"

namespace weft::app {

// A cloth settled to rest (SettleSettings): the simulator holds the positions.
struct Settled {
  std::unique_ptr<sim::Simulator> simulator;
  bool converged = false;   // residual ≤ tolerance or still; false: the iterations ran out
  long iterations = 0;      // Newton iterations, or dynamic relaxation's
  double residual = 0.0;    // ‖R‖/‖Mg‖ at the end
};

// The scene's cloth at rest by the settings' method: a static solve, or dynamic relaxation (the
// scene's integrator replaced) until it rests. Throws sim::DivergenceError, InputError as
// make_simulator and solve_rest_shape.
Settled settle_to_rest(Scene scene, const SettleSettings& settings);

// The cantilever measures of MeasuredTarget: clamp = mean of the pinned vertices, tip = mean of
// the grid edge (u = 0, u = 1, v = 0 or v = 1) whose rest mean lies farthest from the clamp's.
struct CantileverShape {
  double overhang_m = 0.0;  // horizontal distance clamp → tip
  double drop_m = 0.0;      // tip below the clamp, along gravity
};
// Throws std::invalid_argument when nothing is pinned.
CantileverShape measure_cantilever(const sim::Simulator& simulator);

// The drape of the simulator's positions over the scene's support, as `weft measure` measures
// it (analysis::measure_drape). Throws InputError when the scene has no support (scene_support).
analysis::DrapeShape measure_settled_drape(const Scene& scene, const sim::Simulator& simulator);

// Mean of |row_a − row_b| over the columns where both masks have pixels, the row of a column
// being the mean row of its pixels (the midline of a strip seen from the side), px; none when
// no column has both.
std::optional<double> column_midline_distance_px(const render::Mask& a, const render::Mask& b);

struct Evaluation {
  std::vector<double> values;   // one per parameter, SI
  double objective = 0.0;
  std::vector<std::pair<std::string, double>> measures;  // e.g. {"iou", 0.71}, {"overhang_mm", 201.3}
  bool settled = false;
  long iterations = 0;
  double residual = 0.0;
  double seconds = 0.0;
  std::string failure;          // non-empty: the simulation diverged (objective is then huge)
};

class FitProblem {
 public:
  explicit FitProblem(const FitSpec& spec);
  ~FitProblem();

  // The scene with these parameter values (SI, one per parameter). Throws InputError naming
  // the fit file's parameter when the scene rejects a value.
  Scene scene_at(const std::vector<double>& values) const;
  Evaluation evaluate(const std::vector<double>& values);

  // Photo targets: the cloth's silhouette at the simulator's positions through the scene's
  // camera — the renderer's cloth mask (render/renderer.h: from its geometry, pixel centres,
  // hidden where an obstacle is in front) — and the scene's own render of it.
  render::Mask silhouette(const Scene& scene, const sim::Simulator& simulator);
  render::Image render_look(const Scene& scene, const sim::Simulator& simulator);

  const FitSpec& spec() const { return m_spec; }

 private:
  std::vector<std::pair<std::string, double>> measure(const Scene& scene, const sim::Simulator& s,
                                                      double& objective);
  render::Renderer& renderer();  // made at the first render, for the base scene's settings
  const FitSpec& m_spec;
  std::unique_ptr<render::Renderer> m_renderer;
};

}  // namespace weft::app
