// The ray tracer's denoiser (render/denoise.h) on synthetic images with known
// noise: it reduces the noise variance several-fold, keeps albedo/normal edges and shadow edges
// where they are (no bleeding across them), leaves noise-free pixels as they are, and gives
// the same bits for any number of threads.

#include "render/denoise.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>

#include "base/thread_pool.h"

namespace weft::render {
namespace {

constexpr int image_side = 64;

// A deterministic standard normal number for (pixel, salt) (Box–Muller on a hash).
double gaussian(std::uint32_t pixel, std::uint32_t salt) {
  const auto hash = [](std::uint64_t v) {
    v ^= v >> 33;
    v *= 0xff51afd7ed558ccdULL;
    v ^= v >> 33;
    v *= 0xc4ceb9fe1a85ec53ULL;
    v ^= v >> 33;
    return static_cast<double>(v >> 11) / 9007199254740992.0;  // [0, 1)
  };
  const double u1 = 1.0 - hash(2ull * pixel + 7919ull * salt), u2 = hash(2ull * pixel + 1 + 7919ull * salt);
  return std::sqrt(-2.0 * std::log(u1)) * std::cos(2.0 * M_PI * u2);
}

// A side × side image, every pixel covered at depth 2 m: illumination(x) × albedo(x) plus
// Gaussian noise of standard deviation sigma (in illumination units), with that noise's
// variance given as the pixel's variance. Left of x = 32 and right of it differ by `albedo`
// and `normal` (as two surfaces meeting) or only by `illumination` (a shadow edge).
struct Case {
  Eigen::Vector3f albedo_left, albedo_right, normal_left, normal_right;
  float light_left, light_right, sigma;
};

DenoiseInput make_input(const Case& c) {
  DenoiseInput in;
  in.width = in.height = image_side;
  for (int y = 0; y < image_side; ++y) {
    for (int x = 0; x < image_side; ++x) {
      const bool left = x < image_side / 2;
      const Eigen::Vector3f albedo = left ? c.albedo_left : c.albedo_right;
      const float light = left ? c.light_left : c.light_right;
      const auto pixel = static_cast<std::uint32_t>(y * image_side + x);
      const float noisy = light + c.sigma * static_cast<float>(gaussian(pixel, 1));
      in.radiance.push_back(noisy * albedo);
      in.variance.push_back(c.sigma * c.sigma);
      in.normal.push_back(left ? c.normal_left : c.normal_right);
      in.albedo.push_back(albedo);
      in.depth_m.push_back(2.0f);
      in.coverage.push_back(1.0f);
    }
  }
  return in;
}

// Mean and variance of the illumination (red channel / red albedo) over columns [x0, x1).
struct Stats {
  double mean = 0.0, variance = 0.0;
};
Stats column_stats(const std::vector<Eigen::Vector3f>& image, const DenoiseInput& in, int x0, int x1) {
  double sum = 0.0, squares = 0.0;
  int n = 0;
  for (int y = 0; y < image_side; ++y) {
    for (int x = x0; x < x1; ++x) {
      const std::size_t p = static_cast<std::size_t>(y * image_side + x);
      const double v = image[p].x() / in.albedo[p].x();
      sum += v;
      squares += v * v;
      ++n;
    }
  }
  const double mean = sum / n;
  return {mean, squares / n - mean * mean};
}

TEST(Denoise, ReducesNoiseAndKeepsASurfaceEdge) {
  const Case c{{0.8f, 0.2f, 0.2f}, {0.2f, 0.2f, 0.8f}, {0, 0, 1}, {1, 0, 0}, 1.0f, 1.0f, 0.2f};
  const DenoiseInput in = make_input(c);
  const std::vector<Eigen::Vector3f> out = denoise(in, DenoiseSettings{}, nullptr);
  const Stats before = column_stats(in.radiance, in, 0, 32), after = column_stats(out, in, 0, 32);
  std::printf("surface edge: illumination variance %.5f -> %.5f (x%.1f less)\n", before.variance,
              after.variance, before.variance / after.variance);
  EXPECT_LT(after.variance, before.variance / 8.0);
  // The edge: the columns on either side keep their own surface's colour — red stays red, blue
  // stays blue (a blur across the edge would mix them half and half).
  for (int y = 0; y < image_side; ++y) {
    const Eigen::Vector3f l = out[static_cast<std::size_t>(y * image_side + 31)];
    const Eigen::Vector3f r = out[static_cast<std::size_t>(y * image_side + 32)];
    EXPECT_GT(l.x(), 3.0f * l.z()) << "row " << y;
    EXPECT_GT(r.z(), 3.0f * r.x()) << "row " << y;
  }
}

TEST(Denoise, KeepsAShadowEdgeThatOnlyTheColourShows) {
  // Same surface on both sides; the right half is in shadow (light 0.25 instead of 1).
  const Eigen::Vector3f grey(0.6f, 0.6f, 0.6f), up(0, 0, 1);
  const Case c{grey, grey, up, up, 1.0f, 0.25f, 0.04f};
  const DenoiseInput in = make_input(c);
  const std::vector<Eigen::Vector3f> out = denoise(in, DenoiseSettings{}, nullptr);
  const Stats lit_before = column_stats(in.radiance, in, 0, 28);
  const Stats lit_after = column_stats(out, in, 0, 28);
  std::printf("shadow edge: lit illumination variance %.6f -> %.6f (x%.1f less)\n",
              lit_before.variance, lit_after.variance, lit_before.variance / lit_after.variance);
  EXPECT_LT(lit_after.variance, lit_before.variance / 4.0);
  // The last lit column and the first shadowed one keep their light within 3 noise sigmas of
  // one pixel (a blur over the edge would give 0.625 on both).
  const Stats last_lit = column_stats(out, in, 31, 32), first_dark = column_stats(out, in, 32, 33);
  std::printf("shadow edge: column 31 %.3f (true 1), column 32 %.3f (true 0.25)\n", last_lit.mean,
              first_dark.mean);
  EXPECT_NEAR(last_lit.mean, 1.0, 0.03);
  EXPECT_NEAR(first_dark.mean, 0.25, 0.03);
}

TEST(Denoise, NoiseFreePixelsAndUncoveredPixelsAreKept) {
  const Eigen::Vector3f grey(0.6f, 0.6f, 0.6f), up(0, 0, 1);
  DenoiseInput in = make_input({grey, grey, up, up, 1.0f, 0.25f, 0.04f});
  for (float& v : in.variance) v = 0.0f;  // a pixel whose samples all agree
  in.coverage[5] = 0.5f;                  // an antialiased silhouette pixel
  const std::vector<Eigen::Vector3f> out = denoise(in, DenoiseSettings{}, nullptr);
  for (std::size_t p = 0; p < out.size(); ++p) ASSERT_EQ(out[p], in.radiance[p]) << p;
}

TEST(Denoise, MixedEdgePixelsAreKeptAndAreNoNeighbours) {
  // The two columns at the surface edge are mixed (their samples hit both sides): their mean
  // albedo and normal describe neither side.
  const Case c{{0.8f, 0.2f, 0.2f}, {0.2f, 0.2f, 0.8f}, {0, 0, 1}, {1, 0, 0}, 1.0f, 1.0f, 0.2f};
  DenoiseInput in = make_input(c);
  in.mixed.assign(in.radiance.size(), 0);
  for (int y = 0; y < image_side; ++y) {
    for (const int x : {31, 32}) {
      const std::size_t p = static_cast<std::size_t>(y * image_side + x);
      in.mixed[p] = 1;
      in.albedo[p] = Eigen::Vector3f(0.5f, 0.2f, 0.5f);
    }
  }
  const std::vector<Eigen::Vector3f> out = denoise(in, DenoiseSettings{}, nullptr);
  // Ten times brighter edge pixels change nothing else: they are nobody's neighbour.
  DenoiseInput brighter = in;
  for (std::size_t p = 0; p < in.radiance.size(); ++p)
    if (in.mixed[p]) brighter.radiance[p] *= 10.0f;
  const std::vector<Eigen::Vector3f> out_brighter = denoise(brighter, DenoiseSettings{}, nullptr);
  int filtered = 0;
  for (std::size_t p = 0; p < out.size(); ++p) {
    if (in.mixed[p]) {
      ASSERT_EQ(out[p], in.radiance[p]) << p;
      ASSERT_EQ(out_brighter[p], brighter.radiance[p]) << p;
    } else {
      ASSERT_EQ(out[p], out_brighter[p]) << p;
      filtered += out[p] != in.radiance[p];
    }
  }
  EXPECT_GT(filtered, image_side * (image_side - 2) * 9 / 10);  // the rest is filtered
}

TEST(Denoise, SameBitsForAnyThreadCount) {
  const DenoiseInput in =
      make_input({{0.8f, 0.2f, 0.2f}, {0.2f, 0.2f, 0.8f}, {0, 0, 1}, {1, 0, 0}, 1.0f, 0.5f, 0.2f});
  const std::vector<Eigen::Vector3f> one = denoise(in, DenoiseSettings{}, nullptr);
  for (const int threads : {1, 2, 3}) {
    base::ThreadPool pool(threads);
    EXPECT_EQ(denoise(in, DenoiseSettings{}, &pool), one) << threads << " threads";
  }
}

}  // namespace
}  // namespace weft::render
