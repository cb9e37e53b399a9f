// Drawing one frame (see frame_painter.h).

#include "app/run/frame_painter.h"

#include <cstdio>
#include <utility>

#include "app/run/frame_mesh.h"
#include "app/io/frame_png.h"
#include "app/run/obstacle_meshes.h"
#include "app/run/support_meshes.h"
#include "render/image.h"

namespace weft::app {

FramePainter::FramePainter(const Scene& scene, render::Renderer& renderer,
                           const sim::ClothMesh& mesh)
    : m_scene(scene), m_renderer(renderer), m_mesh(mesh), m_obstacles(posed_obstacles(0.0)) {
  if (scene.render.supports) {
    m_pinned = sim::resolve_pins(scene.pins, mesh);
    m_edge_m = median_rest_edge_m(mesh);
  }
}

std::vector<render::RenderObject> FramePainter::posed_obstacles(double time_s) const {
  const std::vector<sim::Obstacle> posed =
      sim::posed_obstacles(m_scene.sim.obstacles, m_scene.sim.obstacle_motions, time_s);
  std::vector<render::RenderObject> objects = obstacle_render_objects(posed, m_scene.render);
  for (render::RenderObject& stand : stand_objects(posed, m_scene.render))
    objects.push_back(std::move(stand));
  return objects;
}

std::vector<render::RenderObject> FramePainter::objects(const sim::Matrix3X& x, double time_s) {
  // Moving obstacles are drawn where they are at the frame's time.
  if (sim::any_moves(m_scene.sim.obstacle_motions)) m_obstacles = posed_obstacles(time_s);
  std::vector<render::RenderObject> objects = m_obstacles;
  for (render::RenderObject& holder :
       pin_support_objects(m_pinned, x, m_edge_m, m_scene.sim.obstacles, m_scene.render))
    objects.push_back(std::move(holder));
  return objects;
}

render::RenderMesh FramePainter::paint(int frame, const sim::Matrix3X& x, double time_s,
                                       const std::filesystem::path& dir) {
  const std::vector<render::RenderObject> objects = this->objects(x, time_s);
  const render::RenderMesh cloth = to_render_mesh(m_mesh, x);
  render_frame_png(m_renderer, cloth, m_scene.render, objects, m_scene.write_alpha,
                   dir / numbered_file_name("frame", frame, "png"));
  if (m_scene.write_mask)
    render::write_png(m_renderer.render_mask(cloth, m_scene.render, objects,
                                             render::Renderer::MaskOf::cloth),
                      dir / numbered_file_name("mask", frame, "png"));
  return cloth;
}

}  // namespace weft::app
