#include "sim/pin_motion.h"

#include <algorithm>
#include <cmath>
#include <sstream>
#include <stdexcept>

namespace weft::sim {

PinPath::PinPath(std::vector<PinKeyframe> keyframes) : m_keyframes(std::move(keyframes)) {
  for (std::size_t k = 0; k < m_keyframes.size(); ++k) {
    const PinKeyframe& f = m_keyframes[k];
    std::ostringstream error;
    if (!std::isfinite(f.time_s)) {
      error << "keyframe " << k << ": time " << f.time_s << " s is not finite";
    } else if (!f.offset_m.allFinite()) {
      error << "keyframe " << k << ": offset is not finite";
    } else if (k > 0 && !(f.time_s > m_keyframes[k - 1].time_s)) {
      error << "keyframe " << k << ": time " << f.time_s << " s is not after keyframe " << k - 1
            << "'s " << m_keyframes[k - 1].time_s << " s";
    }
    if (!error.str().empty()) throw std::invalid_argument(error.str());
  }
}

Vec3 PinPath::offset_at(double time_s) const {
  if (m_keyframes.empty()) return Vec3::Zero();
  if (time_s <= m_keyframes.front().time_s) return m_keyframes.front().offset_m;
  if (time_s >= m_keyframes.back().time_s) return m_keyframes.back().offset_m;
  const auto after = std::upper_bound(
      m_keyframes.begin(), m_keyframes.end(), time_s,
      [](double t, const PinKeyframe& f) { return t < f.time_s; });
  const PinKeyframe& b = *after;
  const PinKeyframe& a = *(after - 1);
  const double s = (time_s - a.time_s) / (b.time_s - a.time_s);
  return (1.0 - s) * a.offset_m + s * b.offset_m;
}

}  // namespace weft::sim
