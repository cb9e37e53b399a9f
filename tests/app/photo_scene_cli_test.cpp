// End to end through the real `weft photo-scene`: φ-SfT R1 frame 0 (tests/data/photos/phi_sft_R1)
// placed from its photo, mask, camera (the dataset's R1_scene.json: (row, column) pairs) and
// the scarf's 0.55 m size alone — no template — and held against the template's
// corners and the mask; the scene it writes runs; bad input is refused naming the option or key.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <string>

#include "tests/app/cli_test_support.h"

namespace fs = std::filesystem;

namespace {

using weft::app::test::run_weft;

const fs::path kR1 = fs::path(WEFT_SOURCE_DIR) / "tests" / "data" / "photos" / "phi_sft_R1";

// The frame-0 template's held corners (0_R1_quad.obj vertices 0 and 992, x and y negated: the
// camera's frame; docs/photos.md), left and right in the image.
constexpr double kLeft[3] = {-0.713166, -0.153658, 1.274754};
constexpr double kRight[3] = {-0.139769, -0.155677, 1.221038};

class PhotoSceneCli : public ::testing::Test {
 protected:
  void SetUp() override {
    const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
    m_dir = fs::path(WEFT_BINARY_DIR) / "test_output" / "photo_scene_cli" / info->name();
    fs::remove_all(m_dir);
    fs::create_directories(m_dir);
  }
  std::string r1_args() const {
    return (kR1 / "rgb_000.png").string() + " --mask " + (kR1 / "mask_000.png").string() +
           " --camera " + (kR1 / "R1_scene.json").string() + " --cloth-size 0.55x0.55";
  }
  fs::path m_dir;
};

double distance_mm(const nlohmann::json& p, const double* q) {
  return 1e3 *
         std::sqrt(std::pow(p[0].get<double>() - q[0], 2) + std::pow(p[1].get<double>() - q[1], 2) +
                   std::pow(p[2].get<double>() - q[2], 2));
}

TEST_F(PhotoSceneCli, PlacesTheR1ScarfFromItsPhotoAlone) {
  const auto r =
      run_weft("photo-scene " + r1_args() + " --fit none --json --out " + (m_dir / "out").string());
  ASSERT_EQ(r.exit_code, 0) << r.output;
  const nlohmann::json j = nlohmann::json::parse(r.output.substr(r.output.find("{\n")));
  const nlohmann::json& corners = j["chosen"]["held_corners_m"];
  const double left = distance_mm(corners[0], kLeft), right = distance_mm(corners[1], kRight);
  std::printf(
      "R1 from the photo alone (no fit): corners %.1f and %.1f mm from the template's; "
      "IoU %.4f, Chamfer %.3f px\n",
      left, right, j["iou"].get<double>(), j["chamfer_px"].get<double>());
  // The depth from the 0.55 m width puts the corners 1.237 m away at one depth; the template's
  // are 1.275 m (left) and 1.221 m (right), its top edge 0.576 m long (stretched): 48 and 17 mm.
  EXPECT_LT(left, 80.0);
  EXPECT_LT(right, 80.0);
  EXPECT_GT(j["iou"].get<double>(), 0.9);
  EXPECT_LT(j["chamfer_px"].get<double>(), 3.0);
  for (const char* f : {"scene.json", "render.png", "mask.png", "overlay.png", "corners.png",
                        "placement.csv", "summary.json"})
    EXPECT_TRUE(fs::exists(m_dir / "out" / f)) << f;
  // The scene it wrote runs.
  const auto run = run_weft("run " + (m_dir / "out" / "scene.json").string() +
                            " --frames 2 --out " + (m_dir / "run").string());
  EXPECT_EQ(run.exit_code, 0) << run.output;
}

TEST_F(PhotoSceneCli, BadInputIsRefusedNamingTheOptionOrKey) {
  auto r =
      run_weft("photo-scene " + r1_args() + " --cloth-size 0.55 --out " + (m_dir / "a").string());
  EXPECT_EQ(r.exit_code, 1) << r.output;
  EXPECT_NE(r.output.find("--cloth-size"), std::string::npos) << r.output;
  r = run_weft("photo-scene " + r1_args() + " --fit depth,colour --out " + (m_dir / "b").string());
  EXPECT_EQ(r.exit_code, 1) << r.output;
  EXPECT_NE(r.output.find("colour"), std::string::npos) << r.output;
  std::ofstream(m_dir / "bad_camera.json")
      << R"({"intrinsics": {"fx": 500, "fy": 500, "cx": 240}})";
  r = run_weft("photo-scene " + (kR1 / "rgb_000.png").string() + " --mask " +
               (kR1 / "mask_000.png").string() + " --camera " +
               (m_dir / "bad_camera.json").string() + " --cloth-size 0.55x0.55 --out " +
               (m_dir / "c").string());
  EXPECT_EQ(r.exit_code, 1) << r.output;
  EXPECT_NE(r.output.find("intrinsics.cy"), std::string::npos) << r.output;
  r = run_weft("photo-scene " + (kR1 / "rgb_000.png").string() + " --mask " +
               (m_dir / "none.png").string() + " --camera " + (kR1 / "R1_scene.json").string() +
               " --cloth-size 0.55x0.55 --out " + (m_dir / "d").string());
  EXPECT_EQ(r.exit_code, 1) << r.output;
  EXPECT_NE(r.output.find("none.png: no such file"), std::string::npos) << r.output;
}

// A synthetic photo: weft's own render (and mask) of a 0.4 m square held by two corners at known
// places 1 m in front of a calibrated camera (unequal focal lengths, off-centre principal
// point; no clips drawn over the corners), placed again from the render alone.
TEST_F(PhotoSceneCli, RecoversTheCornersOfASyntheticHang) {
  // Truth: corners at (∓0.2, −0.15, 1) m, the cloth 0.4 m wide, so their distance is the width;
  // the cloth hangs in the plane z = 1, warp +x, weft up (−y), its front facing the camera.
  std::ofstream(m_dir / "truth.json") << R"({
    "description": "photo_scene_cli_test truth: two-corner hang at known corners",
    "cloth": {"size": ["0.4 m", "0.4 m"], "resolution": [24, 24],
              "origin": ["-0.2 m", "0.25 m", "1 m"], "warp_axis": [1, 0, 0], "weft_axis": [0, -1, 0],
              "pins": [{"corner": "u0v1"}, {"corner": "u1v1"}]},
    "simulation": {"model": "mass_spring", "integrator": "dynamic_relaxation",
                   "gravity": [0, 9.81, 0], "time_step": "auto"},
    "output": {"fps": 24, "frames": 48},
    "render": {"size": [240, 180],
               "camera": {"intrinsics": {"fx": 320, "fy": 300, "cx": 125.3, "cy": 85.6, "size": [240, 180]},
                          "position": [0, 0, 0], "rotation": [[1, 0, 0], [0, 1, 0], [0, 0, 1]]},
               "colors": {"background": [0, 0, 0]}, "ground": false, "supports": false}})";
  std::ofstream(m_dir / "camera.json")
      << R"({"intrinsics": {"fx": 320, "fy": 300, "cx": 125.3, "cy": 85.6, "size": [240, 180]}})";
  const auto truth = run_weft("run " + (m_dir / "truth.json").string() + " --mask --out " +
                              (m_dir / "truth").string());
  ASSERT_EQ(truth.exit_code, 0) << truth.output;
  const auto r = run_weft("photo-scene " + (m_dir / "truth" / "frame_0048.png").string() + " --mask " +
                          (m_dir / "truth" / "mask_0048.png").string() + " --camera " +
                          (m_dir / "camera.json").string() +
                          " --cloth-size 0.4x0.4 --fit none --json --out " + (m_dir / "out").string());
  ASSERT_EQ(r.exit_code, 0) << r.output;
  const nlohmann::json j = nlohmann::json::parse(r.output.substr(r.output.find("{\n")));
  const double left[3] = {-0.2, -0.15, 1.0}, right[3] = {0.2, -0.15, 1.0};
  const double el = distance_mm(j["chosen"]["held_corners_m"][0], left);
  const double er = distance_mm(j["chosen"]["held_corners_m"][1], right);
  std::printf("synthetic hang: corners %.1f and %.1f mm off, IoU %.4f, Chamfer %.3f px\n", el, er,
              j["iou"].get<double>(), j["chamfer_px"].get<double>());
  // A pixel is about 3.2 mm here; a mask's corner pixel lies within about a pixel of the corner.
  EXPECT_LT(el, 10.0);
  EXPECT_LT(er, 10.0);
  EXPECT_GT(j["iou"].get<double>(), 0.97);
}

// The issue's targets on R1 (a minute or two): the joint fit of the corners' pixels, depth,
// depth difference, tilt and density to the outline reaches IoU ≥ 0.96, and the photo projected
// onto the settled scarf and rendered lit gives SSIM ≥ 0.6 inside the mask.
TEST_F(PhotoSceneCli, SlowR1FitAndTextureMeetTheTargets) {
  const auto r = run_weft("photo-scene " + r1_args() +
                          " --fit corners,depth,depth-difference,tilt,density --max-evaluations 100"
                          " --texture --json --out " +
                          (m_dir / "out").string());
  ASSERT_EQ(r.exit_code, 0) << r.output;
  const nlohmann::json j = nlohmann::json::parse(r.output.substr(r.output.find("{\n")));
  const nlohmann::json& corners = j["chosen"]["held_corners_m"];
  std::printf(
      "R1 fitted and textured: corners %.1f and %.1f mm from the template's; IoU %.4f, "
      "Chamfer %.3f px, SSIM %.4f, dE2000 %.2f (p95 %.2f)\n",
      distance_mm(corners[0], kLeft), distance_mm(corners[1], kRight), j["iou"].get<double>(),
      j["chamfer_px"].get<double>(), j["ssim_mask"].get<double>(),
      j["delta_e2000"]["mean"].get<double>(), j["delta_e2000"]["p95"].get<double>());
  EXPECT_GE(j["iou"].get<double>(), 0.96);
  EXPECT_GE(j["ssim_mask"].get<double>(), 0.6);
  EXPECT_LT(distance_mm(corners[0], kLeft), 40.0);
  EXPECT_LT(distance_mm(corners[1], kRight), 40.0);
  EXPECT_TRUE(fs::exists(m_dir / "out" / "texture.png"));
}

}  // namespace
