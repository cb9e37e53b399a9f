// The automatic camera (see auto_camera.h).

#include "app/run/auto_camera.h"

#include <algorithm>
#include <cmath>
#include <memory>
#include <stdexcept>

#include "app/run/frame_stream.h"
#include "base/constants.h"

namespace weft::app {

render::Camera framing_camera(const Eigen::AlignedBox3d& box_m, const render::Camera& base,
                              int width, int height) {
  if (box_m.isEmpty()) throw std::invalid_argument("framing_camera: empty bounding box");
  const double radius = std::max(0.5 * box_m.diagonal().norm(), 1e-3);
  const double half_v = 0.5 * base.fov_y_deg * base::kPi / 180.0;
  const double half_h = std::atan(std::tan(half_v) * width / std::max(height, 1));
  const double distance = 1.05 * radius / std::sin(std::min(half_v, half_h));
  render::Camera c = base;
  c.target = box_m.center();
  c.eye = c.target + distance * (base.eye - base.target).normalized();
  c.near_m = std::min(base.near_m, 0.5 * (distance - radius));
  c.far_m = std::max(base.far_m, 2.0 * (distance + radius));
  return c;
}

void extend_box(Eigen::AlignedBox3d& box, const sim::Matrix3X& x) {
  for (Eigen::Index v = 0; v < x.rows(); ++v) box.extend(x.row(v).transpose().eval());
}

Eigen::AlignedBox3d cloth_bounds_over_frames(const Scene& scene, int last_frame) {
  const std::unique_ptr<sim::Simulator> simulator = make_simulator(scene);
  Eigen::AlignedBox3d box;
  extend_box(box, simulator->state().x);
  if (last_frame < 1) return box;
  (void)stream_frames(scene, *simulator, [&](const Frame& frame) {
    extend_box(box, frame.simulator.state().x);
    return frame.index < last_frame ? StreamControl::go_on : StreamControl::stop;
  });
  return box;
}

bool frame_cloth_if_no_camera(Scene& scene, const Eigen::AlignedBox3d& cloth_box_m) {
  if (scene.camera_given) return false;
  scene.render.camera = framing_camera(cloth_box_m, scene.render.camera, scene.render.width,
                                       scene.render.height);
  return true;
}

}  // namespace weft::app
