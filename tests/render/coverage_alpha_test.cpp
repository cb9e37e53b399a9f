// render/coverage_alpha.h: the coverage is the share of a pixel's sub-samples the surfaces
// mask sets (a stand-in renderer whose mask is a half-plane at a known sub-pixel column), and
// unblending takes the background back out of an edge pixel exactly.
#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>

#include "render/coverage_alpha.h"

namespace weft::render {
namespace {

// A renderer whose surfaces mask is set left of x = edge × (the mask's width / 10), whatever
// its size: at 10 pixels wide, a vertical edge `edge` pixels from the left.
class HalfPlaneRenderer : public Renderer {
 public:
  explicit HalfPlaneRenderer(double edge) : m_edge(edge) {}
  Image render(const RenderMesh&, const RenderSettings& s, const std::vector<RenderObject>&) override {
    return Image(s.width, s.height, {0, 0, 0});
  }
  Mask render_mask(const RenderMesh&, const RenderSettings& s, const std::vector<RenderObject>&,
                   MaskOf which) override {
    EXPECT_EQ(which, MaskOf::surfaces);
    Mask mask(s.width, s.height);
    const double scale = s.width / 10.0;  // sub-samples per output pixel
    for (int y = 0; y < s.height; ++y)
      for (int x = 0; x < s.width; ++x) mask.set(x, y, (x + 0.5) / scale < m_edge);
    return mask;
  }
  std::string description() const override { return "half plane"; }

 private:
  double m_edge;
};

TEST(CoverageAlpha, IsTheShareOfSubSamplesCovered) {
  EXPECT_EQ(coverage_factor(640, 480), 4);
  EXPECT_EQ(coverage_factor(3000, 1000), 2);
  EXPECT_EQ(coverage_factor(9000, 10), 1);
  RenderSettings s;
  s.width = 10;
  s.height = 3;
  HalfPlaneRenderer renderer(4.5);  // pixel 4 half covered: 2 of its 4 sub-columns
  const std::vector<std::uint8_t> alpha = surface_coverage(renderer, RenderMesh{}, s, {});
  ASSERT_EQ(alpha.size(), 30u);
  for (int y = 0; y < 3; ++y) {
    for (int x = 0; x < 4; ++x) EXPECT_EQ(alpha[y * 10 + x], 255) << x;
    EXPECT_EQ(alpha[y * 10 + 4], 128);  // 8 of 16 samples: round(255 / 2)
    for (int x = 5; x < 10; ++x) EXPECT_EQ(alpha[y * 10 + x], 0) << x;
  }
  HalfPlaneRenderer quarter(4.25);  // 1 of 4 sub-columns
  EXPECT_EQ(surface_coverage(quarter, RenderMesh{}, s, {})[4], 64);
}

TEST(CoverageAlpha, UnblendingTakesTheBackgroundOutOfEdgePixels) {
  const Eigen::Vector3f background(0.8f, 0.4f, 0.2f);  // 204, 102, 51
  Image image(3, 1, {0, 0, 0});
  // Pixel 1: a quarter of colour (40, 200, 120) over the background.
  const float a = 64.0f / 255.0f;
  const Rgb8 blended{static_cast<std::uint8_t>(std::lround(a * 40 + (1 - a) * 204)),
                     static_cast<std::uint8_t>(std::lround(a * 200 + (1 - a) * 102)),
                     static_cast<std::uint8_t>(std::lround(a * 120 + (1 - a) * 51))};
  image.set(0, 0, {10, 20, 30});
  image.set(1, 0, blended);
  image.set(2, 0, {90, 80, 70});
  unblend_background(image, {255, 64, 0}, background);
  EXPECT_EQ(image.at(0, 0), (Rgb8{10, 20, 30}));  // opaque: as drawn
  EXPECT_EQ(image.at(2, 0), (Rgb8{90, 80, 70}));  // transparent: as drawn
  const Rgb8 c = image.at(1, 0);
  EXPECT_NEAR(c.r, 40, 2);  // the rounding of the blend, divided by a
  EXPECT_NEAR(c.g, 200, 2);
  EXPECT_NEAR(c.b, 120, 2);
  EXPECT_THROW(unblend_background(image, {255, 0}, background), std::invalid_argument);
}

}  // namespace
}  // namespace weft::render
