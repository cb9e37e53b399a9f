// Keyframed obstacle poses (see obstacle_motion.h).

#include "sim/collision/obstacle_motion.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

#include "sim/keyframes.h"

namespace weft::sim {

ObstacleMotion::ObstacleMotion(std::vector<ObstacleKeyframe> keyframes)
    : m_keyframes(std::move(keyframes)) {
  check_keyframe_times(m_keyframes);
  for (std::size_t k = 0; k < m_keyframes.size(); ++k) {
    const ObstacleKeyframe& f = m_keyframes[k];
    const std::string name = "keyframe " + std::to_string(k) + ": ";
    if (!f.translate_m.allFinite())
      throw std::invalid_argument(name + "translate must be finite");
    if (!std::isfinite(f.rotate_z_rad))
      throw std::invalid_argument(name + "rotate_z must be finite");
  }
}

RigidPose ObstacleMotion::pose_at(double time_s) const {
  if (m_keyframes.empty()) return {};
  const KeyframeBlend k = keyframe_blend(m_keyframes, time_s);
  const ObstacleKeyframe& a = m_keyframes[k.before];
  const ObstacleKeyframe& b = m_keyframes[k.after];
  return {(1.0 - k.s) * a.translate_m + k.s * b.translate_m,
          (1.0 - k.s) * a.rotate_z_rad + k.s * b.rotate_z_rad};
}

RigidPose ObstacleMotion::motion_between(double t0_s, double t1_s) const {
  return compose(pose_at(t1_s), inverse(pose_at(t0_s)));
}

Obstacle posed(const Obstacle& obstacle, const RigidPose& pose) {
  if (const auto* s = std::get_if<SphereObstacle>(&obstacle))
    return SphereObstacle{pose.apply(s->center_m), s->radius_m};
  if (const auto* p = std::get_if<PlaneObstacle>(&obstacle))
    return PlaneObstacle{pose.apply(p->point_m), pose.rotate(p->normal)};
  if (const auto* b = std::get_if<BoxObstacle>(&obstacle))
    return BoxObstacle{pose.apply(b->center_m), b->half_size_m, b->yaw_rad + pose.yaw_rad};
  if (const auto* c = std::get_if<CylinderObstacle>(&obstacle))
    return CylinderObstacle{pose.apply(c->center_m), pose.rotate(c->axis), c->radius_m,
                            c->height_m};
  if (const auto* c = std::get_if<CapsuleObstacle>(&obstacle))
    return CapsuleObstacle{pose.apply(c->a_m), pose.apply(c->b_m), c->radius_m};
  const auto& mesh = std::get<MeshObstacle>(obstacle);
  return MeshObstacle{mesh.solid, compose(pose, mesh.pose)};
}

std::vector<Obstacle> posed_obstacles(const std::vector<Obstacle>& obstacles,
                                      const std::vector<ObstacleMotion>& motions, double time_s) {
  if (motions.empty()) return obstacles;
  if (motions.size() != obstacles.size()) {
    throw std::invalid_argument("posed_obstacles: " + std::to_string(motions.size()) +
                                " motions for " + std::to_string(obstacles.size()) + " obstacles");
  }
  std::vector<Obstacle> out;
  out.reserve(obstacles.size());
  for (std::size_t k = 0; k < obstacles.size(); ++k)
    out.push_back(motions[k].moves() ? posed(obstacles[k], motions[k].pose_at(time_s))
                                     : obstacles[k]);
  return out;
}

bool any_moves(const std::vector<ObstacleMotion>& motions) {
  return std::any_of(motions.begin(), motions.end(),
                     [](const ObstacleMotion& m) { return m.moves(); });
}

}  // namespace weft::sim
