// End to end through the real `weft diff`: pass, warn and fail against explicit thresholds,
// JSON output, a heatmap PNG, and the exit codes of bad input — 3 size mismatch, 4 unreadable
// file, 5 bad arguments.
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <string>

#include <nlohmann/json.hpp>

#include "render/image.h"
#include "tests/app/cli_test_support.h"

namespace fs = std::filesystem;

namespace {

using weft::app::test::run_weft;
using weft::render::Image;

class DiffCli : public ::testing::Test {
 protected:
  void SetUp() override {
    // One directory per test: ctest runs the tests of this fixture at once.
    const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
    m_dir = fs::path(WEFT_BINARY_DIR) / "test_output" / "diff_cli" / info->name();
    fs::remove_all(m_dir);
    fs::create_directories(m_dir);
    Image a(48, 32, {120, 80, 40}), b = a;
    for (int y = 8; y < 16; ++y)
      for (int x = 8; x < 16; ++x) b.set(x, y, {200, 80, 40});  // 64 of 1536 pixels
    weft::render::write_png(a, m_dir / "a.png");
    weft::render::write_png(b, m_dir / "b.png");
    weft::render::write_png(Image(40, 32), m_dir / "small.png");
  }
  std::string path(const char* name) const { return (m_dir / name).string(); }
  fs::path m_dir;
};

TEST_F(DiffCli, ThresholdsDecideTheExitCode) {
  const std::string ab = "diff " + path("a.png") + " " + path("b.png");
  EXPECT_EQ(run_weft("diff " + path("a.png") + " " + path("a.png") + " --fail 'psnr<99'").exit_code, 0);
  EXPECT_EQ(run_weft(ab + " --report-only").exit_code, 0) << "--report-only: pass";
  const auto warn = run_weft(ab + " --warn 'over>0.01' --fail 'over>0.5'");
  EXPECT_EQ(warn.exit_code, 1) << warn.output;
  EXPECT_NE(warn.output.find("over 0.0416667 > 0.01 (warn)"), std::string::npos) << warn.output;
  const auto fail = run_weft(ab + " --warn 'ssim<0.999' --fail 'max>50,psnr<99'");
  EXPECT_EQ(fail.exit_code, 2) << fail.output;
  EXPECT_NE(fail.output.find("max 80 > 50 (fail)"), std::string::npos) << fail.output;
}

TEST_F(DiffCli, JsonAndHeatmap) {
  const auto r = run_weft("diff " + path("a.png") + " " + path("b.png") + " --json --heatmap " +
                          path("heat.png") + " --report-only");
  ASSERT_EQ(r.exit_code, 0) << r.output;
  // stdout holds the JSON object; stderr's "wrote …" line is mixed into the output.
  const std::size_t open = r.output.find('{'), close = r.output.rfind('}');
  ASSERT_NE(open, std::string::npos) << r.output;
  const nlohmann::json j = nlohmann::json::parse(r.output.substr(open, close - open + 1));
  EXPECT_EQ(j["max"], 80);
  EXPECT_NEAR(j["over"].get<double>(), 64.0 / 1536.0, 1e-12);
  EXPECT_NEAR(j["channels"]["r"]["mean"].get<double>(), 80.0 * 64 / 1536, 1e-9);
  EXPECT_EQ(j["result"], "pass");
  const Image heat = weft::render::read_image(m_dir / "heat.png");
  EXPECT_EQ(heat.width(), 48);
}

TEST_F(DiffCli, BadInputHasItsOwnExitCode) {
  const auto size = run_weft("diff " + path("a.png") + " " + path("small.png"));
  EXPECT_EQ(size.exit_code, 3) << size.output;
  EXPECT_NE(size.output.find("sizes differ"), std::string::npos);
  const auto missing = run_weft("diff " + path("a.png") + " " + path("nope.png"));
  EXPECT_EQ(missing.exit_code, 4) << missing.output;
  EXPECT_NE(missing.output.find("nope.png"), std::string::npos);
  const auto bad = run_weft("diff " + path("a.png") + " " + path("b.png") + " --warn 'sharpness<3'");
  EXPECT_EQ(bad.exit_code, 5) << bad.output;
  EXPECT_NE(bad.output.find("unknown metric 'sharpness'"), std::string::npos);
  EXPECT_EQ(run_weft("diff " + path("a.png")).exit_code, 5);
}

}  // namespace

// Without thresholds diff fails as the regression suite does (PSNR < 50 dB or
// more than 0.05 % of pixels over 16), and passes what that suite passes.
TEST_F(DiffCli, DefaultThresholdsAreTheRegressionSuites) {
  const auto real = run_weft("diff " + path("a.png") + " " + path("b.png"));
  EXPECT_EQ(real.exit_code, 2) << real.output;  // 64 of 1536 pixels differ by 80
  EXPECT_CONTAINS(real.output, "crossed: over 0.0416667 > 0.0005 (fail)");
  EXPECT_CONTAINS(real.output, "result: fail");
  // One pixel of 1536 differing by 17 (0.065 % > 0.05 %) fails; by 16 it passes (PSNR 61 dB).
  Image one = weft::render::read_image(m_dir / "a.png");
  one.set(0, 0, {137, 80, 40});
  weft::render::write_png(one, m_dir / "one17.png");
  one.set(0, 0, {136, 80, 40});
  weft::render::write_png(one, m_dir / "one16.png");
  EXPECT_EQ(run_weft("diff " + path("a.png") + " " + path("one17.png")).exit_code, 2);
  const auto near = run_weft("diff " + path("a.png") + " " + path("one16.png"));
  EXPECT_EQ(near.exit_code, 0) << near.output;
  // --fail replaces the defaults; --report-only cannot be combined with it.
  EXPECT_EQ(run_weft("diff " + path("a.png") + " " + path("b.png") + " --fail 'psnr<10'").exit_code, 0);
  EXPECT_EQ(run_weft("diff " + path("a.png") + " " + path("b.png") + " --fail 'psnr<10' --report-only")
                .exit_code, 5);
  EXPECT_CONTAINS(run_weft("diff --help").output, "PSNR below 50 dB");
}

// An RGBA image against the RGB image of the same colours differs where it is transparent.
TEST_F(DiffCli, AlphaIsCompared) {
  const Image a = weft::render::read_image(m_dir / "a.png");
  weft::render::Mask opaque(a.width(), a.height());
  std::fill(opaque.in.begin(), opaque.in.end(), std::uint8_t{1});
  weft::render::write_png(a, opaque, m_dir / "a_opaque.png");
  for (int i = 0; i < 48 * 4; ++i) opaque.in[static_cast<std::size_t>(i)] = 0;  // 4 rows
  weft::render::write_png(a, opaque, m_dir / "a_holes.png");
  EXPECT_EQ(run_weft("diff " + path("a.png") + " " + path("a_opaque.png")).exit_code, 0);
  const auto r = run_weft("diff " + path("a.png") + " " + path("a_holes.png") + " --json");
  EXPECT_EQ(r.exit_code, 2) << r.output;
  const nlohmann::json j = nlohmann::json::parse(r.output.substr(r.output.find('{')));
  EXPECT_EQ(j["channels"]["a"]["max"], 255);
  EXPECT_EQ(j["channels"]["r"]["max"], 0);
  EXPECT_NEAR(j["over"].get<double>(), 4.0 / 32.0, 1e-12);
}

// --heatmap writes what its name says: JPEG bytes under .jpg, and refuses other extensions.
TEST_F(DiffCli, HeatmapFormatFollowsTheName) {
  const std::string ab = "diff " + path("a.png") + " " + path("b.png") + " --report-only --heatmap ";
  ASSERT_EQ(run_weft(ab + path("heat.jpg")).exit_code, 0);
  std::ifstream jpg(m_dir / "heat.jpg", std::ios::binary);
  unsigned char magic[2] = {};
  jpg.read(reinterpret_cast<char*>(magic), 2);
  EXPECT_EQ(magic[0], 0xFF);
  EXPECT_EQ(magic[1], 0xD8);
  EXPECT_EQ(weft::render::read_image(m_dir / "heat.jpg").width(), 48);
  const auto tiff = run_weft(ab + path("heat.tiff"));
  EXPECT_EQ(tiff.exit_code, 5) << tiff.output;
  EXPECT_CONTAINS(tiff.output, "expected a .png, .jpg or .jpeg file name");
  EXPECT_FALSE(fs::exists(m_dir / "heat.tiff"));
}
