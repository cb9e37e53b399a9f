#pragma once
// One frame of a scene drawn from the cloth's positions at the frame's time, written as
// frame_NNNN.png (and mask_NNNN.png with output.mask): the one way `weft run` and `weft render`
// draw a frame, so that frames rendered later from saved states (--save-states) are the same
// bytes as the ones weft run writes.

#include <filesystem>
#include <string>
#include <vector>

#include "app/scene/scene.h"
#include "render/renderer.h"
#include "sim/grid.h"

namespace weft::app {

class FramePainter {
 public:
  // `scene`, `renderer` and `mesh` must outlive the painter; the scene's camera is final.
  FramePainter(const Scene& scene, render::Renderer& renderer, const sim::ClothMesh& mesh);
  // Draws the cloth at positions x (#V×3, m), what holds it, and the obstacles where they are
  // at time_s, writes
  // dir/frame_NNNN.png (and the mask) and returns the cloth as drawn (for mesh exports).
  render::RenderMesh paint(int frame, const sim::Matrix3X& x, double time_s,
                           const std::filesystem::path& dir);
  // What paint draws beside the cloth at positions x and time_s: the obstacles, their stands
  // and the pins' clips and rods.
  std::vector<render::RenderObject> objects(const sim::Matrix3X& x, double time_s);

 private:
  // The obstacles where they are at time_s, with their stands (app/run/support_meshes.h).
  std::vector<render::RenderObject> posed_obstacles(double time_s) const;

  const Scene& m_scene;
  render::Renderer& m_renderer;
  const sim::ClothMesh& m_mesh;
  std::vector<render::RenderObject> m_obstacles;  // and stands
  std::vector<sim::Index> m_pinned;               // drawn with clips or rods
  double m_edge_m = 0.0;                          // the cloth's median rest edge
};

}  // namespace weft::app
