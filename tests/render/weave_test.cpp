// The weave's relief (render/weave.h): the built-in plain weave's normal map tilts both ways
// along warp and weft and averages to flat; depth 0 is flat; the tilt follows the tangents;
// and both renderers show the threads on a sheet under grazing light, at the same mean
// brightness as the flat sheet within their shading differences.

#include "render/weave.h"

#include <gtest/gtest.h>

#include <cmath>
#include <memory>
#include <string>

#include "render/primitives.h"
#include "render/renderer.h"
#include "tests/render/render_test_support.h"

namespace weft::render {
namespace {

TEST(Weave, PlainWeaveMapTiltsBothWaysAndAveragesFlat) {
  const Image map = make_weave_normal_map(64);
  Eigen::Vector3d mean = Eigen::Vector3d::Zero();
  double max_x = 0.0, min_x = 0.0, max_y = 0.0, min_y = 0.0;
  for (int y = 0; y < 64; ++y) {
    for (int x = 0; x < 64; ++x) {
      const float s = (static_cast<float>(x) + 0.5f) / 64.0f;
      const float t = 1.0f - (static_cast<float>(y) + 0.5f) / 64.0f;
      const Eigen::Vector3f m = weave_normal(map, s, t, 1.0f);
      EXPECT_NEAR(m.norm(), 1.0f, 1e-5f);
      EXPECT_GT(m.z(), 0.0f);
      mean += m.cast<double>();
      max_x = std::max(max_x, double(m.x())), min_x = std::min(min_x, double(m.x()));
      max_y = std::max(max_y, double(m.y())), min_y = std::min(min_y, double(m.y()));
    }
  }
  mean /= 64.0 * 64.0;
  EXPECT_NEAR(mean.x(), 0.0, 0.02);
  EXPECT_NEAR(mean.y(), 0.0, 0.02);
  EXPECT_GT(max_x, 0.3);
  EXPECT_LT(min_x, -0.3);
  EXPECT_GT(max_y, 0.3);
  EXPECT_LT(min_y, -0.3);
  // Depth 0: flat, wherever it is sampled.
  EXPECT_LT((weave_normal(map, 0.13f, 0.71f, 0.0f) - Eigen::Vector3f::UnitZ()).norm(), 1e-6f);
  EXPECT_THROW(make_weave_normal_map(4), std::invalid_argument);
}

TEST(Weave, TiltFollowsTheWarpAndWeftTangents) {
  const Eigen::Vector3f n = Eigen::Vector3f::UnitZ();
  // Warp along +y, weft along −x (the sheet turned by 90°), tangents not unit nor orthogonal to n.
  const Eigen::Vector3f warp(0.0f, 2.0f, 0.3f), weft(-0.5f, 0.0f, 0.1f);
  EXPECT_LT((tilt_normal(n, warp, weft, Eigen::Vector3f::UnitZ()) - n).norm(), 1e-6f);
  EXPECT_LT((tilt_normal(n, warp, weft, Eigen::Vector3f::UnitX()) - Eigen::Vector3f::UnitY()).norm(), 1e-6f);
  EXPECT_LT((tilt_normal(n, warp, weft, Eigen::Vector3f::UnitY()) + Eigen::Vector3f::UnitX()).norm(), 1e-6f);
  // Degenerate tangents leave n alone.
  EXPECT_EQ(tilt_normal(n, n, weft, Eigen::Vector3f::UnitX()), n);
}

class WeaveRender : public ::testing::TestWithParam<RendererKind> {
 protected:
  void TearDown() override { m_evidence.save_if_failed(); }
  test::FailureEvidence m_evidence{"weave"};
};

// Mean and standard deviation of the red channel over the square's middle (from above).
std::pair<double, double> red_statistics(const Image& image) {
  double sum = 0.0, sum2 = 0.0;
  int n = 0;
  for (int y = image.height() / 3; y < 2 * image.height() / 3; ++y)
    for (int x = image.width() / 3; x < 2 * image.width() / 3; ++x) {
      const double r = image.at(x, y).r;
      sum += r, sum2 += r * r, ++n;
    }
  const double mean = sum / n;
  return {mean, std::sqrt(std::max(0.0, sum2 / n - mean * mean))};
}

TEST_P(WeaveRender, ThreadsShowUnderGrazingLight) {
  RenderSettings s = test::view_from_above(128, 128);
  s.renderer = GetParam();
  s.light_direction = {1.0, 0.3, 0.4};
  s.cloth_surface.sheen = 0.0;
  s.raytrace.samples_per_pixel = 4;
  s.raytrace.denoise = false;
  s.ground = false;
  // Metre-sized UVs on the unit square: a 10 cm repeat is about 13 pixels.
  const RenderMesh sheet = make_grid_mesh(
      9, 9, [](double u, double v) { return Eigen::Vector3d(u - 0.5, v - 0.5, 0.5); });
  std::string why;
  const std::unique_ptr<Renderer> renderer = test::try_renderer(s, why);
  if (!renderer) GTEST_SKIP() << renderer_name(GetParam()) << " renderer unavailable: " << why;
  const Image flat = renderer->render(sheet, s, {});
  s.cloth_surface.weave.normal_map = std::make_shared<const Image>(make_weave_normal_map());
  s.cloth_surface.weave.repeat_m = {0.1, 0.1};
  s.cloth_surface.weave.depth = 1.0;
  const Image woven = renderer->render(sheet, s, {});
  m_evidence.add(std::string(renderer_name(GetParam())) + "_flat", flat);
  m_evidence.add(std::string(renderer_name(GetParam())) + "_woven", woven);
  const auto [flat_mean, flat_spread] = red_statistics(flat);
  const auto [woven_mean, woven_spread] = red_statistics(woven);
  EXPECT_LT(flat_spread, 1.5);
  EXPECT_GT(woven_spread, 8.0) << "the threads show";
  EXPECT_NEAR(woven_mean, flat_mean, 0.12 * flat_mean) << "the relief averages out";
}

INSTANTIATE_TEST_SUITE_P(BothRenderers, WeaveRender,
                         ::testing::Values(RendererKind::raster, RendererKind::raytrace),
                         [](const auto& param_info) {
                           return std::string(renderer_name(param_info.param));
                         });

}  // namespace
}  // namespace weft::render
