// The ray tracer's random numbers, direction sampling and sheen lobe, against published values
// and analytic moments:
// - PCG32 reproduces the reference implementation's first outputs (pcg32-demo, seed 42, stream 54);
// - cosine-weighted directions stay in their hemisphere with E[cos θ] = 2/3;
// - uniform cone directions stay in the cone with E[cos θ] = (1 + cos θ_max)/2;
// - the Charlie sheen distribution is normalised: ∫ D(h) cos θ_h dω = 1 over the hemisphere;
// - the colour encoding inverts the reflectance conversion (byte = 255 · colour at L = ρ).

#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>

#include "base/constants.h"
#include "render/raytrace/sampling.h"
#include "render/raytrace/shading.h"

namespace weft::render::rt {
namespace {

TEST(RayTraceSampling, Pcg32MatchesTheReferenceOutputs) {
  Pcg32 rng(42u, 54u);
  const std::uint32_t expected[] = {0xa15c02b7u, 0x7b47f409u, 0xba1d3330u,
                                    0x83d2f293u, 0xbfa4784bu, 0xcbed606eu};
  for (std::uint32_t e : expected) EXPECT_EQ(rng.next_u32(), e);
}

TEST(RayTraceSampling, CosineHemisphereHasMeanCosineTwoThirds) {
  const Eigen::Vector3f n = Eigen::Vector3f(0.3f, -0.5f, 0.8f).normalized();
  Pcg32 rng(1u);
  const int count = 200000;
  double sum = 0.0;
  for (int k = 0; k < count; ++k) {
    const Eigen::Vector3f d = cosine_hemisphere(n, rng.next_float(), rng.next_float());
    ASSERT_NEAR(d.norm(), 1.0f, 1e-5f);
    ASSERT_GE(d.dot(n), -1e-6f);
    sum += d.dot(n);
  }
  // Standard error of the mean: sqrt(Var cos θ / count) = sqrt((1/2 − 4/9) / count) ≈ 5e-4.
  EXPECT_NEAR(sum / count, 2.0 / 3.0, 3e-3);
}

TEST(RayTraceSampling, UniformConeStaysInsideWithTheAnalyticMeanCosine) {
  const Eigen::Vector3f axis = Eigen::Vector3f(-0.2f, 0.1f, -1.0f).normalized();
  const float cos_max = std::cos(0.1f);
  Pcg32 rng(2u);
  const int count = 100000;
  double sum = 0.0;
  for (int k = 0; k < count; ++k) {
    const Eigen::Vector3f d = uniform_cone(axis, cos_max, rng.next_float(), rng.next_float());
    ASSERT_GE(d.dot(axis), cos_max - 1e-6f);
    sum += d.dot(axis);
  }
  EXPECT_NEAR(sum / count, 0.5 * (1.0 + cos_max), 1e-4);
}

TEST(RayTraceSampling, CharlieDistributionIsNormalised) {
  for (float roughness : {0.3f, 0.5f, 1.0f}) {
    // ∫ D cos θ dω = 2π ∫_0^{π/2} D(cos θ) cos θ sin θ dθ, midpoint rule.
    const int steps = 20000;
    const double h = 0.5 * base::kPi / steps;
    double integral = 0.0;
    for (int k = 0; k < steps; ++k) {
      const double theta = (k + 0.5) * h;
      integral += charlie_distribution(static_cast<float>(std::cos(theta)), roughness) *
                  std::cos(theta) * std::sin(theta) * h;
    }
    EXPECT_NEAR(2.0 * base::kPi * integral, 1.0, 1e-3) << "roughness " << roughness;
  }
}

TEST(RayTraceSampling, EncodingInvertsTheReflectanceConversion) {
  for (int byte = 0; byte <= 255; byte += 15) {
    const float colour = static_cast<float>(byte) / 255.0f;
    const Eigen::Vector3f rho = reflectance_from_color(Eigen::Vector3f::Constant(colour));
    EXPECT_EQ(int{encode_channel(rho.x())}, byte);
  }
  EXPECT_EQ(int{encode_channel(2.0f)}, 255);
  EXPECT_EQ(int{encode_channel(-1.0f)}, 0);
  EXPECT_EQ(int{encode_channel(std::nanf(""))}, 0);
}

}  // namespace
}  // namespace weft::render::rt
