#pragma once
// Random numbers and direction sampling for the ray tracer. Every pixel sample owns a PCG32
// generator seeded from (pixel index, sample index, settings seed) alone, never from a thread,
// so images are bit-identical whatever the thread count or tile order.

#include <Eigen/Core>
#include <algorithm>
#include <cmath>
#include <cstdint>

namespace weft::render::rt {

// SplitMix64's finaliser (Steele, Lea & Flood 2014): a bijective 64-bit mix.
inline std::uint64_t mix64(std::uint64_t z) {
  z += 0x9E3779B97F4A7C15ull;
  z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
  z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
  return z ^ (z >> 31);
}

// PCG32, XSH-RR output (O'Neill 2014, pcg-random.org): 64-bit state, 32-bit outputs.
class Pcg32 {
 public:
  explicit Pcg32(std::uint64_t seed, std::uint64_t stream = 0xDA3E39CB94B95BDBull)
      : m_increment((stream << 1u) | 1u) {
    next_u32();
    m_state += seed;
    next_u32();
  }
  std::uint32_t next_u32() {
    const std::uint64_t old = m_state;
    m_state = old * 6364136223846793005ull + m_increment;
    const auto xorshifted = static_cast<std::uint32_t>(((old >> 18u) ^ old) >> 27u);
    const auto rotation = static_cast<std::uint32_t>(old >> 59u);
    return (xorshifted >> rotation) | (xorshifted << ((32u - rotation) & 31u));
  }
  // Uniform in [0, 1): the top 24 bits, so the float is exact and never rounds up to 1.
  float next_float() { return static_cast<float>(next_u32() >> 8) * 0x1p-24f; }

 private:
  std::uint64_t m_state = 0;
  std::uint64_t m_increment;
};

// The generator of one camera sample: a function of where and which sample, nothing else.
inline Pcg32 sample_generator(std::uint64_t pixel_index, std::uint32_t sample_index,
                              std::uint32_t seed) {
  return Pcg32(mix64(pixel_index ^ (std::uint64_t{seed} << 40)),
               mix64((std::uint64_t{sample_index} << 32) ^ seed));
}

// Sub-pixel offset in [0, 1)² of sample k: the R2 low-discrepancy sequence (Roberts 2018)
// shifted by a per-pixel rotation (Cranley–Patterson), so neighbouring pixels do not share a
// pattern. `rotation` is in [0, 1)².
inline Eigen::Vector2f pixel_offset(std::uint32_t k, const Eigen::Vector2f& rotation) {
  constexpr double g = 1.32471795724474602596;  // plastic number
  const double x = 0.5 + static_cast<double>(k) / g + rotation.x();
  const double y = 0.5 + static_cast<double>(k) / (g * g) + rotation.y();
  return {static_cast<float>(x - std::floor(x)), static_cast<float>(y - std::floor(y))};
}

// The first hit's light and BSDF sample of camera sample k, (u1, u2, u3, u4) in [0, 1)⁴: the
// 4-D Kronecker sequence of Roberts (2018), generators 1/φ₄^i with φ₄ the real root of
// x⁵ = x + 1, shifted by a per-pixel rotation in [0, 1)⁴ (Cranley–Patterson). Any prefix of it
// covers the square of each pair evenly, so a pixel's light samples are spread over the light
// (soft shadows, bright spots of a map) rather than clumped, however many samples it takes.
// Its generators differ from pixel_offset's, so the sub-pixel point and the light sample of one
// camera sample are not correlated.
inline Eigen::Vector4f stratified_dimensions(std::uint32_t k, const Eigen::Vector4f& rotation) {
  constexpr double phi4 = 1.16730397826141868426;
  Eigen::Vector4f u;
  double alpha = 1.0;
  for (int i = 0; i < 4; ++i) {
    alpha /= phi4;
    const double x = 0.5 + static_cast<double>(k) * alpha + rotation[i];
    u[i] = static_cast<float>(x - std::floor(x));
    if (u[i] >= 1.0f) u[i] = 0.99999994f;  // a float rounding up to 1
  }
  return u;
}

// An orthonormal basis (t, b, n) around a unit n (Duff et al. 2017, "Building an Orthonormal
// Basis, Revisited", JCGT 6(1)).
inline void orthonormal_basis(const Eigen::Vector3f& n, Eigen::Vector3f& t, Eigen::Vector3f& b) {
  const float sign = std::copysign(1.0f, n.z());
  const float a = -1.0f / (sign + n.z());
  const float c = n.x() * n.y() * a;
  t = {1.0f + sign * n.x() * n.x() * a, sign * c, -sign * n.x()};
  b = {c, sign + n.y() * n.y() * a, -n.y()};
}

// Cosine-weighted direction about unit n from u1, u2 in [0, 1) (pdf cos θ / π).
inline Eigen::Vector3f cosine_hemisphere(const Eigen::Vector3f& n, float u1, float u2) {
  constexpr float two_pi = 6.28318530717958647692f;
  const float r = std::sqrt(u1), phi = two_pi * u2;
  Eigen::Vector3f t, b;
  orthonormal_basis(n, t, b);
  return r * std::cos(phi) * t + r * std::sin(phi) * b + std::sqrt(std::max(0.0f, 1.0f - u1)) * n;
}

// Uniform direction in the cone of half-angle acos(cos_max) about unit axis.
inline Eigen::Vector3f uniform_cone(const Eigen::Vector3f& axis, float cos_max, float u1,
                                    float u2) {
  constexpr float two_pi = 6.28318530717958647692f;
  const float cos_theta = 1.0f - u1 * (1.0f - cos_max);
  const float sin_theta = std::sqrt(std::max(0.0f, 1.0f - cos_theta * cos_theta));
  const float phi = two_pi * u2;
  Eigen::Vector3f t, b;
  orthonormal_basis(axis, t, b);
  return sin_theta * std::cos(phi) * t + sin_theta * std::sin(phi) * b + cos_theta * axis;
}

}  // namespace weft::render::rt
