#pragma once
// Keyframed rigid motion of obstacles. An obstacle as the scene gives it is at rest pose; a
// keyframe moves it by a rotation about the vertical (+z) axis through the ORIGIN followed by a
// translation (RigidPose, mesh_obstacle.h): x ↦ Rz(rotate_z)·x + translate. To turn an
// obstacle in place, give it centred on the z axis and move it out with translate.
// Between keyframes translate and angle are interpolated linearly in time; before the first
// keyframe the obstacle holds the first pose, after the last the last.

#include <vector>

#include "sim/collision/mesh_obstacle.h"
#include "sim/collision/obstacle.h"

namespace weft::sim {

struct ObstacleKeyframe {
  double time_s = 0.0;
  Vec3 translate_m{0.0, 0.0, 0.0};
  double rotate_z_rad = 0.0;  // counter-clockwise seen from above
};

class ObstacleMotion {
 public:
  ObstacleMotion() = default;  // no keyframes: the obstacle stays at rest pose
  // Throws std::invalid_argument ("keyframe 2: …") unless every time, translate and angle is
  // finite and the times strictly increase.
  explicit ObstacleMotion(std::vector<ObstacleKeyframe> keyframes);

  bool moves() const { return !m_keyframes.empty(); }
  const std::vector<ObstacleKeyframe>& keyframes() const { return m_keyframes; }
  // The pose at time_s (identity without keyframes).
  RigidPose pose_at(double time_s) const;
  // Carries a point fixed to the obstacle from where it is at t0_s to where it is at t1_s:
  // pose_at(t1) ∘ pose_at(t0)⁻¹.
  RigidPose motion_between(double t0_s, double t1_s) const;

 private:
  std::vector<ObstacleKeyframe> m_keyframes;
};

// The obstacle moved by `pose` (a sphere's centre, a plane's point and normal, a box's centre
// and yaw, a cylinder's centre and axis, a capsule's endpoints, a mesh's pose).
Obstacle posed(const Obstacle& obstacle, const RigidPose& pose);

// Every obstacle at time_s. motions: empty (nothing moves) or one per obstacle; throws
// std::invalid_argument for another count.
std::vector<Obstacle> posed_obstacles(const std::vector<Obstacle>& obstacles,
                                      const std::vector<ObstacleMotion>& motions, double time_s);

// Whether any of the motions has keyframes.
bool any_moves(const std::vector<ObstacleMotion>& motions);

}  // namespace weft::sim
