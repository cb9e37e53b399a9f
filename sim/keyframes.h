#pragma once
// Piecewise-linear keyframe tracks, shared by pin paths (pin_motion.h) and obstacle motion
// (collision/obstacle_motion.h): the time checks and where a time falls between two keyframes.
// Keyframe is any type with a `double time_s` member.

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <sstream>
#include <stdexcept>
#include <vector>

namespace weft::sim {

// Throws std::invalid_argument "keyframe k: time … s is not finite" or "keyframe k: time … s is
// not after keyframe k−1's … s" unless every time is finite and the times strictly increase.
template <class Keyframe>
void check_keyframe_times(const std::vector<Keyframe>& keyframes) {
  for (std::size_t k = 0; k < keyframes.size(); ++k) {
    std::ostringstream error;
    const double t = keyframes[k].time_s;
    if (!std::isfinite(t)) {
      error << "keyframe " << k << ": time " << t << " s is not finite";
    } else if (k > 0 && !(t > keyframes[k - 1].time_s)) {
      error << "keyframe " << k << ": time " << t << " s is not after keyframe " << k - 1
            << "'s " << keyframes[k - 1].time_s << " s";
    }
    if (!error.str().empty()) throw std::invalid_argument(error.str());
  }
}

// Where time_s falls on a non-empty track: keyframes[before] and keyframes[after] and the
// fraction s ∈ [0, 1] from one to the other; the track holds its first keyframe before it
// starts and its last after it ends (before = after, s = 0).
struct KeyframeBlend {
  std::size_t before = 0, after = 0;
  double s = 0.0;
};

template <class Keyframe>
KeyframeBlend keyframe_blend(const std::vector<Keyframe>& keyframes, double time_s) {
  const std::size_t last = keyframes.size() - 1;
  if (!(time_s > keyframes.front().time_s)) return {0, 0, 0.0};
  if (!(time_s < keyframes.back().time_s)) return {last, last, 0.0};
  const auto next = std::upper_bound(keyframes.begin(), keyframes.end(), time_s,
                                     [](double t, const Keyframe& f) { return t < f.time_s; });
  const auto after = static_cast<std::size_t>(next - keyframes.begin());
  const Keyframe& a = keyframes[after - 1];
  const Keyframe& b = keyframes[after];
  return {after - 1, after, (time_s - a.time_s) / (b.time_s - a.time_s)};
}

}  // namespace weft::sim
