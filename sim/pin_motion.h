#pragma once
// Moving pins: a pinned vertex that follows a prescribed path instead of staying put.
//
// A path is a list of keyframes (time, offset from the vertex's rest position), linear between
// keyframes and constant before the first and after the last. The simulator moves the vertex
// to rest + offset(t + h) at each step (its velocity is the path's mean velocity over the
// step); the cloth reacts through springs and constraints like at any pin, and a moving pin is
// as kinematic as a fixed one: nothing pushes it back.

#include <vector>

#include "sim/types.h"

namespace weft::sim {

struct PinKeyframe {
  double time_s = 0.0;
  Vec3 offset_m = Vec3::Zero();
};

class PinPath {
 public:
  PinPath() = default;  // empty: the pin does not move
  // Throws std::invalid_argument ("keyframe 2: time 0.5 s is not after keyframe 1's 0.5 s")
  // unless the times are finite and strictly increasing and the offsets finite.
  explicit PinPath(std::vector<PinKeyframe> keyframes);

  bool moves() const { return !m_keyframes.empty(); }
  Vec3 offset_at(double time_s) const;  // m
  const std::vector<PinKeyframe>& keyframes() const { return m_keyframes; }

 private:
  std::vector<PinKeyframe> m_keyframes;
};

}  // namespace weft::sim
