// Drawing one frame (see frame_painter.h).

#include "app/run/frame_painter.h"

#include <cstdio>

#include "app/run/frame_mesh.h"
#include "app/io/frame_png.h"
#include "app/run/obstacle_meshes.h"
#include "render/image.h"

namespace weft::app {

FramePainter::FramePainter(const Scene& scene, render::Renderer& renderer,
                           const sim::ClothMesh& mesh)
    : m_scene(scene), m_renderer(renderer), m_mesh(mesh),
      m_obstacles(obstacle_render_objects(scene.sim.obstacles, scene.render)) {}

render::RenderMesh FramePainter::paint(int frame, const sim::Matrix3X& x, double time_s,
                                       const std::filesystem::path& dir) {
  // Moving obstacles are drawn where they are at the frame's time.
  if (sim::any_moves(m_scene.sim.obstacle_motions))
    m_obstacles = obstacle_render_objects(m_scene.sim.obstacles, m_scene.sim.obstacle_motions,
                                          time_s, m_scene.render);
  const render::RenderMesh cloth = to_render_mesh(m_mesh, x);
  render_frame_png(m_renderer, cloth, m_scene.render, m_obstacles, m_scene.write_alpha,
                   dir / numbered_file_name("frame", frame, "png"));
  if (m_scene.write_mask)
    render::write_png(m_renderer.render_mask(cloth, m_scene.render, m_obstacles,
                                             render::Renderer::MaskOf::cloth),
                      dir / numbered_file_name("mask", frame, "png"));
  return cloth;
}

}  // namespace weft::app
