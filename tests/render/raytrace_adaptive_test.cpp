// The ray tracer's adaptive sampling and stratified light samples
// (render/raytrace/adaptive_sampling.h, sampling.h):
// - a pixel's running sums give the standard error of its samples' mean (analytic values);
// - the display error follows the slope of the display curve and vanishes where it clamps;
// - the samples asked for grow as the square of the error over the target, within bounds;
// - the first hit's stratified light samples estimate a shadow edge's share with less than half
//   the mean squared error of independent random numbers;
// - under a uniform map a flat floor that the denoiser filters freely stops after the first
//   pass, with the furnace's value ρ L; with adaptive sampling off every pixel takes them all;
// - under a map with a bright patch (soft shadows) some pixels take more than the first pass,
//   and the bytes and the samples taken are the same for 1, 2 and 3 threads.
// On failure the rendered images are written to <build>/test_output/raytrace_adaptive/.

#include <gtest/gtest.h>

#include <cmath>
#include <memory>
#include <vector>

#include "render/environment.h"
#include "render/raytrace/adaptive_sampling.h"
#include "render/raytrace/ray_tracer.h"
#include "render/raytrace/sampling.h"
#include "render/raytrace/shading.h"
#include "tests/render/render_test_support.h"

namespace weft::render::rt {
namespace {

TEST(AdaptiveSampling, StandardErrorOfTheMeanOfKnownSamples) {
  PixelSamples pixel;
  EXPECT_EQ(pixel.luminance_standard_error(), 0.0f);
  // 0, 1, 0, 1, …: mean 1/2, unbiased variance n/(n−1) · 1/4.
  const int n = 20;
  for (int k = 0; k < n; ++k) {
    const float v = static_cast<float>(k % 2);
    pixel.add(Eigen::Vector3f(v, 2.0f * v, 0.0f), v);
  }
  EXPECT_EQ(pixel.count(), n);
  EXPECT_FLOAT_EQ(pixel.luminance_mean(), 0.5f);
  EXPECT_TRUE(pixel.mean().isApprox(Eigen::Vector3f(0.5f, 1.0f, 0.0f)));
  EXPECT_NEAR(pixel.luminance_standard_error(), std::sqrt(0.25 * n / (n - 1.0) / n), 1e-6);
  PixelSamples constant;
  for (int k = 0; k < 8; ++k) constant.add(Eigen::Vector3f::Constant(0.3f), 0.3);
  EXPECT_NEAR(constant.luminance_standard_error(), 0.0f, 1e-7f);
}

TEST(AdaptiveSampling, DisplayErrorFollowsTheDisplayCurve) {
  EXPECT_EQ(display_error(0.4f, 0.0f), 0.0f);
  // Small errors: the slope of 255 L^(1/2.2), (255 / 2.2) L^(1/2.2 − 1), times the error.
  for (const float mean : {0.02f, 0.2f, 0.7f}) {
    const float e = 1e-4f;
    const float slope = 255.0f / display_gamma * std::pow(mean, 1.0f / display_gamma - 1.0f);
    EXPECT_NEAR(display_error(mean, e), slope * e, 1e-3f * slope * e) << mean;
  }
  // Dark pixels are where the curve is steep: the same error counts for more levels.
  EXPECT_GT(display_error(0.02f, 0.01f), 4.0f * display_error(0.7f, 0.01f));
  // Clamped at white: no error shows.
  EXPECT_EQ(display_error(3.0f, 0.5f), 0.0f);
  // Bounded near black: mean ± error is clamped at 0, not extrapolated by the infinite slope.
  EXPECT_NEAR(display_error(0.0f, 0.01f), 0.5f * display_value(0.01f), 1e-4f);
}

TEST(AdaptiveSampling, SamplesNeededGrowAsTheSquareOfTheError) {
  EXPECT_EQ(samples_needed(16, 0.4f, 0.5f, 256), 16);   // already under the target
  EXPECT_EQ(samples_needed(16, 1.0f, 0.5f, 256), 64);   // twice the target: four times the samples
  EXPECT_EQ(samples_needed(16, 0.75f, 0.5f, 256), 36);  // (1.5)² · 16
  EXPECT_EQ(samples_needed(16, 10.0f, 0.5f, 256), 256); // at most samples_per_pixel
  EXPECT_EQ(samples_needed(16, 0.51f, 0.5f, 256), 17);  // rounded up
  EXPECT_EQ(samples_needed(300, 1.0f, 0.5f, 256), 256);
}

// Mean squared error, over 4000 per-pixel rotations, of the mean of an edge (a shadow's:
// 1 where u_i + 0.7 u_j < 0.8) over n points, whose true mean is 0.8² / 1.4.
double edge_mean_squared_error(int n, int i, int j, bool stratified) {
  Pcg32 rng(7u);
  double sum = 0.0;
  const int pixels = 4000;
  for (int r = 0; r < pixels; ++r) {
    Eigen::Vector4f rotation;
    for (int d = 0; d < 4; ++d) rotation[d] = rng.next_float();
    int inside = 0;
    for (int k = 0; k < n; ++k) {
      Eigen::Vector4f u;
      if (stratified) {
        u = stratified_dimensions(static_cast<std::uint32_t>(k), rotation);
      } else {
        for (int d = 0; d < 4; ++d) u[d] = rng.next_float();
      }
      EXPECT_TRUE((u.array() >= 0.0f).all() && (u.array() < 1.0f).all());
      inside += u[i] + 0.7f * u[j] < 0.8f;
    }
    const double error = static_cast<double>(inside) / n - 0.64 / 1.4;
    sum += error * error;
  }
  return sum / pixels;
}

TEST(RayTraceSampling, StratifiedLightSamplesHalveTheErrorOfAShadowEdge) {
  // The pairs the first hit uses: (0, 1) picks the map's direction, (2, 3) the cosine one.
  for (const auto& [i, j] : {std::pair{0, 1}, std::pair{2, 3}}) {
    for (const int n : {16, 64}) {
      const double random = edge_mean_squared_error(n, i, j, false);
      const double stratified = edge_mean_squared_error(n, i, j, true);
      std::printf("edge over %d points, dimensions %d, %d: mean squared error %.2e random, "
                  "%.2e stratified (x%.1f)\n", n, i, j, random, stratified, random / stratified);
      EXPECT_GT(random, 2.0 * stratified) << n << " points, dimensions " << i << ", " << j;
    }
  }
}

// A uniform map of radiance 0.8 over a grey Lambertian floor that fills the view from above.
RenderSettings furnace_settings(int samples, double adaptive_error) {
  RenderSettings s = test::view_from_above(48, 48);
  s.light_intensity = 0.0;
  s.cloth_surface.sheen = 0.0;
  s.raytrace.threads = 2;
  s.raytrace.samples_per_pixel = samples;
  s.raytrace.adaptive_error = adaptive_error;
  s.environment.map = std::make_shared<const EnvironmentMap>(
      32, 16, std::vector<Eigen::Vector3f>(32 * 16, Eigen::Vector3f::Constant(0.8f)));
  s.front_color = Eigen::Vector3f::Constant(std::pow(0.5f, 1.0f / display_gamma));
  return s;
}

class RayTraceAdaptive : public ::testing::Test {
 protected:
  void TearDown() override { m_rendered.save_if_failed(); }
  test::FailureEvidence m_rendered{"raytrace_adaptive"};
};

TEST_F(RayTraceAdaptive, AFlatFilteredSurfaceStopsAfterTheFirstPass) {
  // Every pixel sees the same open floor: the denoiser averages its neighbours freely, so the
  // error left after the first pass is far under half a level and no pixel takes more.
  const RenderMesh floor = test::rectangle(-5.0, 5.0, -5.0, 5.0, 0.0);
  RayTracer tracer;
  const Image image = tracer.render(floor, furnace_settings(256, 0.5), {});
  m_rendered.add("floor_adaptive", image);
  const std::uint64_t pixels = 48 * 48;
  EXPECT_EQ(tracer.last_ray_counts().camera, 16 * pixels);
  // The furnace's value, ρ L = 0.4, within a byte of noise.
  for (int y = 0; y < 48; ++y) {
    for (int x = 0; x < 48; ++x) {
      const double l = std::pow(image.at(x, y).g / 255.0, static_cast<double>(display_gamma));
      ASSERT_NEAR(l, 0.4, 0.01) << x << ", " << y;
    }
  }
  // Off: every pixel takes them all.
  tracer.render(floor, furnace_settings(64, 0.0), {});
  EXPECT_EQ(tracer.last_ray_counts().camera, 64 * pixels);
}

TEST_F(RayTraceAdaptive, SameBytesForAnyThreadCount) {
  // A grey map with one bright patch: soft shadows, noisy pixels that take more samples.
  std::vector<Eigen::Vector3f> texels(64 * 32, Eigen::Vector3f(0.1f, 0.1f, 0.12f));
  for (int y = 6; y < 10; ++y)
    for (int x = 20; x < 24; ++x) texels[static_cast<std::size_t>(y * 64 + x)] = Eigen::Vector3f::Constant(40.0f);
  RenderSettings s = furnace_settings(128, 0.5);
  s.environment.map = std::make_shared<const EnvironmentMap>(64, 32, std::move(texels));
  s.ground = true;
  const RenderMesh cloth = test::rectangle(-0.4, 0.4, -0.4, 0.4, 0.3);
  std::vector<Image> images;
  std::uint64_t camera = 0;
  for (const int threads : {1, 2, 3}) {
    s.raytrace.threads = threads;
    RayTracer tracer;
    images.push_back(tracer.render(cloth, s, {}));
    m_rendered.add("threads_" + std::to_string(threads), images.back());
    if (threads > 1) {
      EXPECT_EQ(tracer.last_ray_counts().camera, camera) << threads;
    }
    camera = tracer.last_ray_counts().camera;
  }
  EXPECT_GT(camera, 16u * 48 * 48);  // some pixels took more than the first pass
  EXPECT_TRUE(test::same_bytes(images[0], images[1]));
  EXPECT_TRUE(test::same_bytes(images[0], images[2]));
}

}  // namespace
}  // namespace weft::render::rt
