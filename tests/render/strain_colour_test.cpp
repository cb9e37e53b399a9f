// Shading::strain: the false-colour map, its legend, and a flat cloth whose
// left half is compressed and right half stretched, drawn by both renderers through the
// Renderer interface: each half takes its end of the map (blue, red), a strain-free strip the
// middle grey, and the legend sits in the top-right corner. The rasterizer's half is skipped,
// with the reason, when no GL context can be made; the ray tracer's when it was not built.

#include <gtest/gtest.h>

#include <cmath>
#include <memory>
#include <string>

#include "render/renderer.h"
#include "render/strain_colour.h"
#include "tests/render/render_test_support.h"

namespace weft::render {
namespace {

TEST(StrainColour, EndsMiddleAndClamping) {
  const Eigen::Vector3f blue = strain_colour(-0.05f, 0.05f), red = strain_colour(0.05f, 0.05f);
  const Eigen::Vector3f grey = strain_colour(0.0f, 0.05f);
  EXPECT_GT(blue.z(), blue.x() + 0.4f);  // compression: blue
  EXPECT_GT(red.x(), red.z() + 0.4f);    // stretch: red
  EXPECT_NEAR(grey.x(), grey.z(), 1e-6f);  // unstrained: grey
  EXPECT_TRUE(strain_colour(0.5f, 0.05f).isApprox(red));     // beyond the scale: the end
  EXPECT_TRUE(strain_colour(-0.5f, 0.05f).isApprox(blue));
  EXPECT_TRUE(strain_colour(std::nanf(""), 0.05f).isApprox(grey));
  // Red grows and blue falls monotonically from compression to stretch.
  float last_red_minus_blue = -2.0f;
  for (int k = -20; k <= 20; ++k) {
    const Eigen::Vector3f c = strain_colour(0.05f * static_cast<float>(k) / 20.0f, 0.05f);
    EXPECT_GT(c.x() - c.z(), last_red_minus_blue) << "at step " << k;
    last_red_minus_blue = c.x() - c.z();
  }
}

// A 2 × 1 m sheet at z = 0.5 seen from above, three separate cells: x < −0.1 compressed by 5 %,
// −0.1 < x < 0.1 unstrained, x > 0.1 stretched by 5 %.
RenderMesh strained_sheet() {
  RenderMesh mesh;
  const float cells[3][3] = {{-1.0f, -0.1f, -0.05f}, {-0.1f, 0.1f, 0.0f}, {0.1f, 1.0f, 0.05f}};
  for (const auto& cell : cells) {
    const auto a = static_cast<std::uint32_t>(mesh.positions.size());
    mesh.positions.insert(mesh.positions.end(), {{cell[0], -0.5f, 0.5f}, {cell[1], -0.5f, 0.5f},
                                                 {cell[1], 0.5f, 0.5f}, {cell[0], 0.5f, 0.5f}});
    mesh.strain.insert(mesh.strain.end(), 4, cell[2]);
    mesh.triangles.push_back({a, a + 1, a + 2});  // counter-clockwise seen from +z
    mesh.triangles.push_back({a, a + 2, a + 3});
  }
  compute_vertex_normals(mesh);
  return mesh;
}

class StrainShading : public ::testing::TestWithParam<RendererKind> {
 protected:
  void TearDown() override { m_evidence.save_if_failed(); }
  test::FailureEvidence m_evidence{"strain_shading"};
};

TEST_P(StrainShading, HalvesTakeTheEndsOfTheMapAndTheLegendIsDrawn) {
  RenderSettings s = test::view_from_above(320, 240);
  s.renderer = GetParam();
  s.shading = Shading::strain;
  s.strain_full_scale = 0.05;
  s.raytrace.samples_per_pixel = 4;
  std::string why;
  const std::unique_ptr<Renderer> renderer = test::try_renderer(s, why);
  if (!renderer) GTEST_SKIP() << renderer_name(GetParam()) << ": " << why;
  const Image image = renderer->render(strained_sheet(), s, {});
  m_evidence.add("strain", image);
  const test::Pixel left = test::project(s, {-0.9, 0.0, 0.5});
  const test::Pixel middle = test::project(s, {0.0, 0.0, 0.5});
  const test::Pixel right = test::project(s, {0.6, 0.0, 0.5});
  const Rgb8 l = image.at(left.x, left.y), m = image.at(middle.x, middle.y);
  const Rgb8 r = image.at(right.x, right.y);
  EXPECT_GT(l.b, l.r + 60) << "compressed half should be blue";
  EXPECT_GT(r.r, r.b + 60) << "stretched half should be red";
  EXPECT_NEAR(m.r, m.b, 3) << "unstrained strip should be grey";
  // The colours are the map's, lit: the hue of each half matches its end colour's.
  const Eigen::Vector3f blue = strain_colour(-1.0f, 1.0f), red = strain_colour(1.0f, 1.0f);
  EXPECT_NEAR(static_cast<double>(l.r) / l.b, blue.x() / blue.z(), 0.08);
  EXPECT_NEAR(static_cast<double>(r.b) / r.r, red.z() / red.x(), 0.08);
  // The legend: a white panel in the top-right corner holding both ends of the bar.
  int reds = 0, blues = 0, whites = 0;
  for (int y = 0; y < 120; ++y) {
    for (int x = 240; x < 320; ++x) {
      const Rgb8 c = image.at(x, y);
      whites += c.r == 255 && c.g == 255 && c.b == 255;
      reds += c.r > 150 && c.g < 40 && c.b < 60;
      blues += c.b > 170 && c.r < 80;
    }
  }
  EXPECT_GT(whites, 1000);
  EXPECT_GT(reds, 20);
  EXPECT_GT(blues, 20);
}

TEST_P(StrainShading, LitShadingIgnoresTheStrain) {
  RenderSettings s = test::view_from_above(160, 120);
  s.renderer = GetParam();
  s.raytrace.samples_per_pixel = 1;
  std::string why;
  const std::unique_ptr<Renderer> renderer = test::try_renderer(s, why);
  if (!renderer) GTEST_SKIP() << renderer_name(GetParam()) << ": " << why;
  RenderMesh without = strained_sheet();
  without.strain.clear();
  EXPECT_TRUE(test::same_bytes(renderer->render(strained_sheet(), s, {}),
                               renderer->render(without, s, {})));
}

INSTANTIATE_TEST_SUITE_P(BothRenderers, StrainShading,
                         ::testing::Values(RendererKind::raster, RendererKind::raytrace),
                         [](const auto& p) { return std::string(renderer_name(p.param)); });

}  // namespace
}  // namespace weft::render
