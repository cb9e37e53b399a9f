#pragma once
// Evaluating and fitting a scene from a photo (photo_scene.h): each placement's scene settled to
// rest by dynamic relaxation (fit_problem.h's settle_to_rest), its cloth silhouette rendered
// through the photo's camera and compared with the photo's mask (IoU, outline Chamfer); the
// joint fit of the held corners' depth, their depth difference, the camera's tilt and the
// cloth's density against the outline Chamfer distance (NLopt BOBYQA); and the texture of the
// settled cloth projected from the photo (render/photo_compare/photo_texture.h).

#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "app/fit/fit_problem.h"
#include "app/fit/photo_scene.h"
#include "app/scene/scene.h"
#include "render/photo_compare/photo_texture.h"
#include "render/renderer.h"

namespace weft::app {

struct PlacementEvaluation {
  Placement placement;
  double chamfer_px = 0.0, iou = 0.0;
  bool settled = false;
  long iterations = 0;
  double seconds = 0.0;
  std::string failure;  // the simulation diverged: the objective is then huge
};

// Which placement parameters a fit frees (the others stay at the start).
struct PlacementFitSettings {
  bool corners = true, depth = true, depth_difference = true, tilt = true, density = true;
  int max_evaluations = 100;
};

class PhotoSceneProblem {
 public:
  // `photo_mask`: the photo's silhouette, at the setup's size. `source` names the scenes.
  PhotoSceneProblem(PhotoSceneSetup setup, render::Mask photo_mask, std::string source,
                    std::optional<int> threads);
  ~PhotoSceneProblem();

  Scene scene_at(const Placement& p, const std::string& texture_file = "") const;
  // The placement's scene settled, its silhouette and metrics; `settled_out` (optional) keeps
  // the simulator.
  PlacementEvaluation evaluate(const Placement& p, Settled* settled_out = nullptr);

  render::Mask silhouette(const Scene& scene, const sim::Simulator& simulator);
  render::Image render_look(const Scene& scene, const sim::Simulator& simulator);

  const PhotoSceneSetup& setup() const { return m_setup; }
  const render::Mask& photo_mask() const { return m_mask; }

 private:
  render::Renderer& renderer(const Scene& scene);
  PhotoSceneSetup m_setup;
  render::Mask m_mask;
  std::string m_source;
  std::optional<int> m_threads;
  std::unique_ptr<render::Renderer> m_renderer;
};

struct PlacementFit {
  std::vector<PlacementEvaluation> evaluations;
  PlacementEvaluation best;
  std::string stop_reason;
};

// BOBYQA from `start` over the freed parameters (each corner's pixel within ±3 px, depth_scale in
// [0.75, 1.33] and density in [0.02, 5] kg/m² on log10, depth difference within ±25 % of the depth,
// tilt within ±25°); `on_evaluation` sees each evaluation and its 1-based number.
PlacementFit fit_placement(
    PhotoSceneProblem& problem, const Placement& start, const PlacementFitSettings& settings,
    const std::function<void(const PlacementEvaluation&, int)>& on_evaluation = {});

// The photo projected onto the settled cloth (a grid) through the scene's camera, tw × th.
render::PhotoTexture settled_photo_texture(const Scene& scene, const sim::Simulator& simulator,
                                           const render::Image& photo, const render::Mask& mask,
                                           int tw, int th);

}  // namespace weft::app
