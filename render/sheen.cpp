// The cloth's sheen lobe (see sheen.h).

#include "render/sheen.h"

#include <algorithm>
#include <cmath>

#include "base/constants.h"

namespace weft::render {

float charlie_distribution(float n_dot_h, float roughness) {
  const float inv_r = 1.0f / roughness;
  const float sin2 = std::max(0.0f, 1.0f - n_dot_h * n_dot_h);
  return (2.0f + inv_r) * std::pow(sin2, 0.5f * inv_r) / (2.0f * base::kPiF);
}

float sheen_visibility(float n_dot_l, float n_dot_v) {
  const float denominator = 4.0f * (n_dot_l + n_dot_v - n_dot_l * n_dot_v);
  return denominator > 0.0f ? 1.0f / denominator : 0.0f;
}

float sheen_response(const Eigen::Vector3f& n, const Eigen::Vector3f& l, const Eigen::Vector3f& v,
                     float roughness) {
  const float n_dot_l = n.dot(l), n_dot_v = n.dot(v);
  if (!(n_dot_l > 0.0f) || !(n_dot_v > 0.0f)) return 0.0f;
  const Eigen::Vector3f half = l + v;
  const float length = half.norm();
  if (!(length > 0.0f)) return 0.0f;
  const float n_dot_h = n.dot(half) / length;
  return base::kPiF * charlie_distribution(n_dot_h, roughness) * sheen_visibility(n_dot_l, n_dot_v) *
         n_dot_l;
}

}  // namespace weft::render
