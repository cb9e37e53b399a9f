// "The back of the cloth is lit": both renderers shade the cloth two-sided —
// the side seen takes its own colour and the normal turned towards it, so the key light
// lights the back when it shines on the back — through the real `weft run`. A flat sheet seen
// from above (its front) and from below (its back), the light above or below: the side the
// light falls on is lit, the other gets the ambient only, and the rasterizer's mean colour is
// the ray tracer's within its sheen.
#include <gtest/gtest.h>

#include <array>
#include <string>

#include "render/image.h"
#include "tests/app/cli_test_support.h"

namespace weft::app {
namespace {

class TwoSidedCli : public test::CliDirectoryTest {
 protected:
  TwoSidedCli() : CliDirectoryTest("two_sided_cli") {}
};

// The first frame of the tiny scene: the sheet still flat and level at z = 0.5 m.
const char* const flat_sheet = R"({
  "description": "a level sheet, seen from above or below",
  "cloth": {"size": ["20 cm", "20 cm"], "resolution": [9, 9], "origin": [-0.1, 0, 0.5],
            "pins": [{"corner": "u0v1"}, {"corner": "u1v1"}]},
  "output": {"fps": 24, "frames": 1},
  "render": {"size": [96, 64], "ground": false}
})";

// Mean colour of the frame's cloth pixels whose 3×3 neighbourhood is all cloth (--mask).
std::array<double, 3> mean_cloth_colour(const std::filesystem::path& dir, int& pixels) {
  const render::Image frame = render::read_image(dir / "frame_0001.png");
  const render::Image mask = render::read_image(dir / "mask_0001.png");
  std::array<double, 3> sum{};
  pixels = 0;
  for (int y = 1; y + 1 < frame.height(); ++y)
    for (int x = 1; x + 1 < frame.width(); ++x) {
      bool inside = true;
      for (int dy = -1; dy <= 1; ++dy)
        for (int dx = -1; dx <= 1; ++dx) inside = inside && mask.at(x + dx, y + dy).r == 255;
      if (!inside) continue;
      const render::Rgb8 p = frame.at(x, y);
      sum[0] += p.r, sum[1] += p.g, sum[2] += p.b;
      ++pixels;
    }
  for (double& s : sum) s /= pixels > 0 ? pixels : 1;
  return sum;
}

TEST_F(TwoSidedCli, TheSideTheLightFallsOnIsLitFrontOrBackInBothRenderers) {
  const auto scene = write_scene("flat.json", flat_sheet);
  for (const char* side : {"above", "below"}) {
    const std::string eye = side == std::string("above") ? "[0.05,-0.45,1.2]" : "[0.05,-0.45,-0.2]";
    std::array<double, 3> lit_colour{}, raster_lit{};
    for (const char* renderer : {"raster", "raytrace"}) {
      double brightness[2] = {};
      for (int lit = 0; lit < 2; ++lit) {
        // Light on the side seen (lit) or on the other side.
        const bool light_above = (side == std::string("above")) == (lit == 1);
        const std::string light = light_above ? "[0.3,-0.4,1.0]" : "[0.3,-0.4,-1.0]";
        const std::string name = std::string(side) + "_" + renderer + (lit ? "_lit" : "_unlit");
        const auto r = test::run_weft(
            "run " + scene.string() + " --renderer " + renderer + " --mask --set 'render.camera={" +
            "\"eye\":" + eye + ",\"target\":[0,0.1,0.5]}' --set render.light.direction=" + light +
            " --set 'render.colors.back=[0.25,0.45,0.8]' --out " + (m_dir / name).string());
        ASSERT_EQ(r.exit_code, 0) << r.output;
        int pixels = 0;
        const std::array<double, 3> c = mean_cloth_colour(m_dir / name, pixels);
        ASSERT_GT(pixels, 150) << name;
        brightness[lit] = c[0] + c[1] + c[2];
        if (lit) lit_colour = c;
      }
      // Lit: ambient 0.25 + 0.85·cos > 0.6 against the ambient alone, after gamma 1/2.2.
      EXPECT_GT(brightness[1], 1.5 * brightness[0]) << side << ", " << renderer;
      if (renderer == std::string("raster")) raster_lit = lit_colour;
    }
    // The side's own colour: the front red, the back blue (given: by default it is the front's).
    if (side == std::string("above")) EXPECT_GT(raster_lit[0], raster_lit[2] + 80) << "front";
    else EXPECT_GT(raster_lit[2], raster_lit[0] + 80) << "back";
    for (int c = 0; c < 3; ++c)  // the ray tracer's sheen also takes the sky (render/sheen.h)
      EXPECT_NEAR(raster_lit[c], lit_colour[c], 20.0) << side << " channel " << c;
  }
}

}  // namespace
}  // namespace weft::app
