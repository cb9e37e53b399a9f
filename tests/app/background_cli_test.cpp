// `--background transparent|R,G,B` on weft run and weft turntable: RGBA
// frames whose alpha is the surfaces' coverage of each pixel, a background colour, and a clear
// error.

#include <gtest/gtest.h>
#include <stb_image.h>

#include <cmath>
#include <cstdint>
#include <fstream>
#include <memory>
#include <string>

#include "render/image.h"
#include "tests/app/cli_test_support.h"

namespace weft::app {
namespace {

class BackgroundCli : public test::CliDirectoryTest {
 protected:
  BackgroundCli() : CliDirectoryTest("background_cli") {}
  std::string path(const std::string& name) const { return (m_dir / name).string(); }
};

// The PNG's IHDR colour type: 2 RGB, 6 RGBA.
int colour_type(const std::string& png_path) {
  std::ifstream png(png_path, std::ios::binary);
  char header[26] = {};
  png.read(header, sizeof header);
  return header[25];
}

struct Rgba {
  int width = 0, height = 0;
  std::unique_ptr<std::uint8_t, void (*)(void*)> pixels{nullptr, stbi_image_free};
  std::uint8_t alpha(int x, int y) const { return pixels.get()[4 * (y * width + x) + 3]; }
};

Rgba read_rgba(const std::string& png_path) {
  Rgba image;
  int channels = 0;
  image.pixels.reset(stbi_load(png_path.c_str(), &image.width, &image.height, &channels, 4));
  return image;
}

// Without a ground and supports (the pins' clips) the opaque pixels are the cloth's. Alpha is the share of the pixel the cloth
// covers (16 samples; the antialiased alpha of render/coverage_alpha.h): 255 inside the cloth's
// mask (--mask, pixel centres), 0 well outside it, in between along the silhouette, and the covered
// area is the mask's. The edge colours are freed of the background: composited over the background
// colour again they give the RGB frame that the same run writes without --background transparent.
TEST_F(BackgroundCli, TransparentRunHasAntialiasedCoverageAlpha) {
  const auto scene = write_scene("tiny.json", test::tiny_scene());
  const std::string common =
      " --frames 2 --mask --set render.ground=false --set render.supports=false --out ";
  const auto r = test::run_weft("run " + scene.string() + " --background transparent" + common +
                                path("run"));
  ASSERT_EQ(r.exit_code, 0) << r.output;
  const auto opaque_run = test::run_weft("run " + scene.string() + common + path("rgb"));
  ASSERT_EQ(opaque_run.exit_code, 0) << opaque_run.output;
  ASSERT_EQ(colour_type(path("run/frame_0002.png")), 6);
  const Rgba frame = read_rgba(path("run/frame_0002.png"));
  ASSERT_TRUE(frame.pixels) << stbi_failure_reason();
  const render::Image mask = render::read_image(m_dir / "run" / "mask_0002.png");
  const render::Image rgb = render::read_image(m_dir / "rgb" / "frame_0002.png");
  ASSERT_EQ(frame.width, mask.width());
  ASSERT_EQ(frame.width, rgb.width());
  const auto in_mask = [&](int x, int y) {
    return x >= 0 && y >= 0 && x < mask.width() && y < mask.height() && mask.at(x, y).r == 255;
  };
  // Background colour of the default scene, as bytes (render.colors.background).
  const int background[3] = {235, 237, 242};
  int fractional = 0, mask_pixels = 0, wrong_inside = 0, wrong_outside = 0;
  double covered = 0.0, edge_error = 0.0;
  for (int y = 0; y < frame.height; ++y) {
    for (int x = 0; x < frame.width; ++x) {
      const std::uint8_t a = frame.alpha(x, y);
      int neighbours = 0;
      for (int dy = -1; dy <= 1; ++dy)
        for (int dx = -1; dx <= 1; ++dx) neighbours += in_mask(x + dx, y + dy);
      mask_pixels += in_mask(x, y);
      covered += a / 255.0;
      wrong_inside += neighbours == 9 && a != 255;
      wrong_outside += neighbours == 0 && a != 0;
      if (a == 0 || a == 255) continue;
      ++fractional;
      const std::uint8_t* p = frame.pixels.get() + 4 * (y * frame.width + x);
      const render::Rgb8 want = rgb.at(x, y);
      const int wanted[3] = {want.r, want.g, want.b};
      for (int c = 0; c < 3; ++c)
        edge_error += std::abs(a / 255.0 * p[c] + (1.0 - a / 255.0) * background[c] - wanted[c]);
    }
  }
  EXPECT_EQ(wrong_inside, 0) << "inside the cloth: opaque";
  EXPECT_EQ(wrong_outside, 0) << "away from the cloth: transparent";
  EXPECT_GT(fractional, 20) << "the silhouette is antialiased";
  EXPECT_GT(mask_pixels, 100);
  EXPECT_NEAR(covered, mask_pixels, 0.05 * mask_pixels) << "the covered area is the mask's";
  EXPECT_LT(edge_error / (3.0 * fractional), 6.0) << "composited edges match the RGB frame";
  EXPECT_EQ(frame.alpha(0, 0), 0);
  // The scene copy says so: output.alpha is set.
  std::ifstream copy(path("run/scene.json"));
  const std::string text((std::istreambuf_iterator<char>(copy)), std::istreambuf_iterator<char>());
  EXPECT_NE(text.find("\"alpha\""), std::string::npos) << text;
}

TEST_F(BackgroundCli, TransparentTurntableAndColouredBackground) {
  const auto scene = write_scene("tiny.json", test::tiny_scene());
  const auto t = test::run_weft("turntable " + scene.string() + " --frames 2 --sim-frames 1 "
                                "--background transparent --out " + path("turn"));
  ASSERT_EQ(t.exit_code, 0) << t.output;
  ASSERT_EQ(colour_type(path("turn/turntable_0001.png")), 6);
  const Rgba turn = read_rgba(path("turn/turntable_0001.png"));
  ASSERT_TRUE(turn.pixels);
  EXPECT_EQ(turn.alpha(0, 0), 0) << "sky above the ground: transparent";
  EXPECT_EQ(turn.alpha(turn.width / 2, turn.height - 1), 255) << "the ground under the camera";

  const auto black = test::run_weft("run " + scene.string() + " --frames 1 --background 0,0,0 "
                                    "--set render.ground=false --out " + path("black"));
  ASSERT_EQ(black.exit_code, 0) << black.output;
  EXPECT_EQ(colour_type(path("black/frame_0001.png")), 2);
  const render::Image frame = render::read_image(m_dir / "black" / "frame_0001.png");
  EXPECT_EQ(frame.at(0, 0).r + frame.at(0, 0).g + frame.at(0, 0).b, 0);

  for (const std::string bad : {"blue", "2,0,0"}) {
    const auto r = test::run_weft("run " + scene.string() + " --frames 1 --background " + bad +
                                  " --out " + path("bad"));
    EXPECT_EQ(r.exit_code, 1) << r.output;
    EXPECT_NE(r.output.find("--background"), std::string::npos) << r.output;
  }
}

}  // namespace
}  // namespace weft::app
