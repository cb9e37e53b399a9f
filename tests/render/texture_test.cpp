// Textures by material coordinates (render/texture.h) and their use by both renderers:
// - sampling: a texel centre gives its colour exactly, halfway between two texels their mean,
//   and whole repeats give the same colour (bilinear, repeat);
// - the woven check: warp bands stacked along the weft, weft bands along the warp, mixed
//   where they cross, so the two directions can be told apart;
// - orientation: a flat sheet with material (u, v) along world (x, y), seen from above with +y
//   up, textured with an image whose four quadrants have distinct colours, shows each quadrant
//   in the matching corner of the image (bottom-left of the image at material (0, 0)), with
//   Loop subdivision on so that the UVs go through it too; both renderers, each skipped with
//   the reason when it cannot run. The back side keeps its own colour.
// On failure the rendered images are written to <build>/test_output/texture/.

#include "render/texture.h"

#include <gtest/gtest.h>

#include <memory>
#include <stdexcept>
#include <string>

#include "render/primitives.h"
#include "render/renderer.h"
#include "tests/render/render_test_support.h"

namespace weft::render {
namespace {

const Rgb8 top_left{230, 30, 30}, top_right{30, 200, 40}, bottom_left{40, 60, 220},
    bottom_right{240, 220, 40};

// 8×8 pixels, one colour per 4×4 quadrant.
std::shared_ptr<const Image> quadrant_image() {
  auto image = std::make_shared<Image>(8, 8);
  for (int y = 0; y < 8; ++y)
    for (int x = 0; x < 8; ++x)
      image->set(x, y,
                 y < 4 ? (x < 4 ? top_left : top_right) : (x < 4 ? bottom_left : bottom_right));
  return image;
}

void expect_near_rgb(const Rgb8& got, const Rgb8& want, const char* where) {
  EXPECT_NEAR(got.r, want.r, 3) << where;
  EXPECT_NEAR(got.g, want.g, 3) << where;
  EXPECT_NEAR(got.b, want.b, 3) << where;
}

Eigen::Vector3f color_of(const Rgb8& p) {
  return Eigen::Vector3f(p.r, p.g, p.b) / 255.0f;
}

TEST(Texture, SamplesTexelCentresBilinearlyAndRepeats) {
  const std::shared_ptr<const Image> image = quadrant_image();
  // Pixel (1, 1) (top-left quadrant) has its centre at s = 1.5/8, t = 1 − 1.5/8.
  EXPECT_LT((sample_texture(*image, 1.5f / 8, 1.0f - 1.5f / 8) - color_of(top_left)).norm(), 1e-6f);
  EXPECT_LT((sample_texture(*image, 6.5f / 8, 1.5f / 8) - color_of(bottom_right)).norm(), 1e-6f);
  // Halfway between the centres of pixels 3 and 4 of the top row: the mean of the two colours.
  EXPECT_LT((sample_texture(*image, 4.0f / 8, 1.0f - 0.5f / 8) -
             0.5f * (color_of(top_left) + color_of(top_right)))
                .norm(),
            1e-6f);
  for (const auto& [s, t] : {std::pair{0.3f, 0.8f}, std::pair{0.55f, 0.1f}}) {
    EXPECT_LT((sample_texture(*image, s + 2.0f, t - 3.0f) - sample_texture(*image, s, t)).norm(),
              1e-5f);
  }
  // At material (0, 0) a repeat ends and the next begins: the mean of the four corner colours.
  EXPECT_LT((sample_texture(*image, 0.0f, 0.0f) -
             0.25f * (color_of(top_left) + color_of(top_right) + color_of(bottom_left) +
                      color_of(bottom_right)))
                .norm(),
            1e-6f);
}

TEST(Texture, WovenCheckBandsFollowWarpAndWeft) {
  WovenCheck check;
  check.stripes = 2;
  const Image image = make_woven_check(check, 64);
  const auto at = [&](float s, float t) { return sample_texture(image, s, t); };
  const float tolerance = 0.25f;  // thread lines darken the bands by up to 20 %
  // Warp bands: t in [0, 1/4) and [1/2, 3/4); weft bands: s in the same ranges.
  EXPECT_LT((at(0.37f, 0.12f) - check.warp_color).norm(), tolerance);  // warp band only
  EXPECT_LT((at(0.12f, 0.37f) - check.weft_color).norm(), tolerance);  // weft band only
  EXPECT_LT((at(0.12f, 0.12f) - 0.5f * (check.warp_color + check.weft_color)).norm(), tolerance);
  EXPECT_LT((at(0.37f, 0.37f) - check.ground_color).norm(), 0.01f);  // neither (byte rounding)
  WovenCheck bad;
  bad.stripes = 0;
  EXPECT_THROW(make_woven_check(bad), std::invalid_argument);
}

// The view from above, lit so that a pixel shows its texel: colour × ambient^(1/2.2) with
// ambient 1 and no key light, one sample per pixel.
RenderSettings texel_view(RendererKind renderer) {
  RenderSettings s = test::view_from_above(96, 96);
  s.renderer = renderer;
  s.light_intensity = 0.0;
  s.ambient = 1.0;
  s.raytrace.samples_per_pixel = 1;
  s.cloth_surface.sheen = 0.0;
  s.msaa_samples = 1;
  return s;
}

class TextureOrientation : public ::testing::TestWithParam<RendererKind> {
 protected:
  void TearDown() override { m_evidence.save_if_failed(); }
  test::FailureEvidence m_evidence{"texture"};
};

TEST_P(TextureOrientation, ImageCornersLandOnTheSheetsCorners) {
  RenderSettings s = texel_view(GetParam());
  s.cloth_surface.subdivision_levels = 1;
  s.cloth_surface.texture = {quadrant_image(), Eigen::Vector2d(1.0, 1.0)};
  // Material (u, v) in [0, 1]² on world x, y in [−0.5, 0.5]², z = 0.5, front facing +z.
  const RenderMesh sheet = make_grid_mesh(
      3, 3, [](double u, double v) { return Eigen::Vector3d(u - 0.5, v - 0.5, 0.5); });

  std::string why;
  const std::unique_ptr<Renderer> renderer = test::try_renderer(s, why);
  if (!renderer) GTEST_SKIP() << renderer_name(GetParam()) << " renderer unavailable: " << why;
  const Image image = renderer->render(sheet, s, {});
  m_evidence.add(renderer_name(GetParam()), image);

  const auto expect_near = [&](double x, double y, const Rgb8& want, const char* where) {
    const test::Pixel p = test::project(s, Eigen::Vector3d(x, y, 0.5));
    const Rgb8 got = image.at(p.x, p.y);
    EXPECT_NEAR(got.r, want.r, 3) << where;
    EXPECT_NEAR(got.g, want.g, 3) << where;
    EXPECT_NEAR(got.b, want.b, 3) << where;
  };
  // Away from the quadrant borders and from the repeat seam at the sheet's edges.
  expect_near(-0.3, 0.3, top_left, "top left (low warp, high weft)");
  expect_near(0.3, 0.3, top_right, "top right");
  expect_near(-0.3, -0.3, bottom_left, "bottom left (material origin)");
  expect_near(0.3, -0.3, bottom_right, "bottom right");
  // The image's top-left pixel shows the top-left quadrant too: +y is up on screen.
  const test::Pixel corner = test::project(s, Eigen::Vector3d(-0.3, 0.3, 0.5));
  EXPECT_LT(corner.x, s.width / 2);
  EXPECT_LT(corner.y, s.height / 2);

  // Seen from below the texture covers the back too, mirrored (the camera's x runs along −x):
  // material (0.3, 0.3) now shows left of centre.
  s.camera.eye = {0, 0, -2};
  s.camera.target = {0, 0, 0.5};
  const Image back = renderer->render(sheet, s, {});
  m_evidence.add(std::string(renderer_name(GetParam())) + "_back", back);
  const test::Pixel mirrored = test::project(s, Eigen::Vector3d(0.3, 0.3, 0.5));
  EXPECT_LT(mirrored.x, s.width / 2);
  expect_near_rgb(back.at(mirrored.x, mirrored.y), top_right, "back, mirrored top right");
  // A back colour of its own replaces the texture there.
  s.back_color = Eigen::Vector3f(0.25f, 0.45f, 0.80f);
  const Image coloured_back = renderer->render(sheet, s, {});
  m_evidence.add(std::string(renderer_name(GetParam())) + "_back_colour", coloured_back);
  expect_near_rgb(coloured_back.at(mirrored.x, mirrored.y), test::to_rgb8(*s.back_color),
                  "back colour");
}

// Stretched over the piece, the image spans the material's bounding box once, wherever it
// starts and however long its sides: its quadrants land on the sheet's quadrants, and its
// edge texels on the sheet's edges (clamped, no wrap from the other side).
TEST_P(TextureOrientation, PieceMappingSpansTheWholeSheetOnce) {
  RenderSettings s = texel_view(GetParam());
  s.cloth_surface.texture = {quadrant_image(), Eigen::Vector2d(0.1, 0.1), TextureMapping::piece};
  RenderMesh sheet = make_grid_mesh(
      5, 5, [](double u, double v) { return Eigen::Vector3d(u - 0.5, v - 0.5, 0.5); });
  for (Eigen::Vector2f& uv : sheet.uvs) uv = {2.0f + 3.0f * uv.x(), -1.0f + 0.7f * uv.y()};

  std::string why;
  const std::unique_ptr<Renderer> renderer = test::try_renderer(s, why);
  if (!renderer) GTEST_SKIP() << renderer_name(GetParam()) << " renderer unavailable: " << why;
  const Image image = renderer->render(sheet, s, {});
  m_evidence.add(std::string(renderer_name(GetParam())) + "_piece", image);
  const auto expect_colour = [&](double x, double y, const Rgb8& want, const char* where) {
    const test::Pixel p = test::project(s, Eigen::Vector3d(x, y, 0.5));
    expect_near_rgb(image.at(p.x, p.y), want, where);
  };
  expect_colour(-0.3, 0.3, top_left, "top left");
  expect_colour(0.3, 0.3, top_right, "top right");
  expect_colour(-0.3, -0.3, bottom_left, "bottom left");
  expect_colour(0.3, -0.3, bottom_right, "bottom right");
  // At the sheet's very edges: the edge texels, not a blend with the opposite side.
  expect_colour(-0.49, -0.49, bottom_left, "bottom-left corner");
  expect_colour(0.49, 0.49, top_right, "top-right corner");
}

INSTANTIATE_TEST_SUITE_P(BothRenderers, TextureOrientation,
                         ::testing::Values(RendererKind::raster, RendererKind::raytrace),
                         [](const auto& param_info) {
                           return std::string(renderer_name(param_info.param));
                         });

}  // namespace
}  // namespace weft::render
