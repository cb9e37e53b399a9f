// Keyframed obstacle poses (see obstacle_motion.h).

#include "sim/collision/obstacle_motion.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

namespace weft::sim {

ObstacleMotion::ObstacleMotion(std::vector<ObstacleKeyframe> keyframes)
    : m_keyframes(std::move(keyframes)) {
  for (std::size_t k = 0; k < m_keyframes.size(); ++k) {
    const ObstacleKeyframe& f = m_keyframes[k];
    const std::string name = "keyframe " + std::to_string(k) + ": ";
    if (!std::isfinite(f.time_s)) throw std::invalid_argument(name + "time must be finite");
    if (!f.translate_m.allFinite())
      throw std::invalid_argument(name + "translate must be finite");
    if (!std::isfinite(f.rotate_z_rad))
      throw std::invalid_argument(name + "rotate_z must be finite");
    if (k > 0 && !(f.time_s > m_keyframes[k - 1].time_s)) {
      throw std::invalid_argument(name + "times must strictly increase, got " +
                                  std::to_string(f.time_s) + " s after " +
                                  std::to_string(m_keyframes[k - 1].time_s) + " s");
    }
  }
}

RigidPose ObstacleMotion::pose_at(double time_s) const {
  if (m_keyframes.empty()) return {};
  const auto pose_of = [](const ObstacleKeyframe& f) {
    return RigidPose{f.translate_m, f.rotate_z_rad};
  };
  if (!(time_s > m_keyframes.front().time_s)) return pose_of(m_keyframes.front());
  if (!(time_s < m_keyframes.back().time_s)) return pose_of(m_keyframes.back());
  // The first keyframe later than time_s, and the one before it.
  const auto next = std::upper_bound(
      m_keyframes.begin(), m_keyframes.end(), time_s,
      [](double t, const ObstacleKeyframe& f) { return t < f.time_s; });
  const ObstacleKeyframe& a = *(next - 1);
  const ObstacleKeyframe& b = *next;
  const double s = (time_s - a.time_s) / (b.time_s - a.time_s);
  return {(1.0 - s) * a.translate_m + s * b.translate_m,
          (1.0 - s) * a.rotate_z_rad + s * b.rotate_z_rad};
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
