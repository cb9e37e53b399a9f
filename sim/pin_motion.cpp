#include "sim/pin_motion.h"

#include <stdexcept>
#include <string>

#include "sim/keyframes.h"

namespace weft::sim {

PinPath::PinPath(std::vector<PinKeyframe> keyframes) : m_keyframes(std::move(keyframes)) {
  check_keyframe_times(m_keyframes);
  for (std::size_t k = 0; k < m_keyframes.size(); ++k) {
    if (!m_keyframes[k].offset_m.allFinite())
      throw std::invalid_argument("keyframe " + std::to_string(k) + ": offset is not finite");
  }
}

Vec3 PinPath::offset_at(double time_s) const {
  if (m_keyframes.empty()) return Vec3::Zero();
  const KeyframeBlend k = keyframe_blend(m_keyframes, time_s);
  return (1.0 - k.s) * m_keyframes[k.before].offset_m + k.s * m_keyframes[k.after].offset_m;
}

}  // namespace weft::sim
