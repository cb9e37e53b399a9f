// The frame stream and scene patches end to end through the real `weft` command: the command-line
// overrides are scene patches (--set on run, the copied scene.json holds them, a bad one is the
// scene reader's error naming the key), --threads is checked on every command that has it, sweep
// honours simulation.dynamics: false, and the frames weft run writes are the golden tests'.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include <nlohmann/json.hpp>

#include "render/image.h"
#include "render/image_diff.h"
#include "tests/app/cli_test_support.h"

namespace fs = std::filesystem;

namespace {

using weft::app::test::CommandResult;
using weft::app::test::run_weft;

class FrameStreamCli : public weft::app::test::CliDirectoryTest {
 protected:
  FrameStreamCli() : CliDirectoryTest("frame_stream_cli") {}
};

using weft::app::test::tiny_scene;

nlohmann::json read_json(const fs::path& path) {
  std::ifstream in(path);
  return nlohmann::json::parse(in);
}

TEST_F(FrameStreamCli, SetOnRunPatchesTheScene) {
  const fs::path scene = write_scene("tiny.json", tiny_scene());
  const fs::path out = m_dir / "out";
  const CommandResult r = run_weft("run " + scene.string() + " --out " + out.string() +
                                   " --set 'render.size=[48,32]' --set output.frames=2");
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_EQ(weft::render::read_image(out / "frame_0002.png").width(), 48);
  EXPECT_FALSE(fs::exists(out / "frame_0003.png"));
}

// --frames, --size and --samples are scene patches: the copied scene.json holds them, and
// running that copy gives the same run.
TEST_F(FrameStreamCli, OverridesAreInTheCopiedSceneJson) {
  const fs::path scene = write_scene("tiny.json", tiny_scene());
  const fs::path out = m_dir / "out";
  const CommandResult r =
      run_weft("run " + scene.string() + " --out " + out.string() +
               " --frames 2 --size 40x30 --samples 3 --set simulation.integrator=velocity_verlet");
  ASSERT_EQ(r.exit_code, 0) << r.output;
  const nlohmann::json copy = read_json(out / "scene.json");
  EXPECT_EQ(copy["output"]["frames"], 2);
  EXPECT_EQ(copy["render"]["size"], nlohmann::json::array({40, 30}));
  EXPECT_EQ(copy["render"]["raytrace"]["samples"], 3);
  EXPECT_EQ(copy["simulation"]["integrator"], "velocity_verlet");
  EXPECT_EQ(copy["description"], "tiny end-to-end test scene");

  const fs::path again = m_dir / "again";
  const CommandResult rerun = run_weft("run " + (out / "scene.json").string() + " --out " +
                                       again.string());
  ASSERT_EQ(rerun.exit_code, 0) << rerun.output;
  EXPECT_TRUE(fs::exists(again / "frame_0002.png"));
  EXPECT_FALSE(fs::exists(again / "frame_0003.png"));
  const auto d = weft::render::compare_images(weft::render::read_image(out / "frame_0002.png"),
                                              weft::render::read_image(again / "frame_0002.png"));
  EXPECT_EQ(d.max_abs, 0);
}

// A bad override is the scene reader's one-line error, naming the option and the key; nothing
// is written.
TEST_F(FrameStreamCli, BadOverrideIsTheSceneReadersErrorNamingTheKey) {
  const fs::path scene = write_scene("tiny.json", tiny_scene());
  const fs::path out = m_dir / "out";
  const struct {
    std::string args, expected;
  } cases[] = {
      {"--set render.raytrace.samples=0", "--set render.raytrace.samples=0: "},
      {"--samples 0", "--samples 0: "},
      {"--frames 0", "--frames 0: "},
      {"--size 8x8", "--size 8x8: "},
      {"--set cloth.colour=red", "cloth.colour: unknown key"},
  };
  for (const auto& c : cases) {
    const CommandResult r = run_weft("run " + scene.string() + " --out " + out.string() + " " + c.args);
    EXPECT_EQ(r.exit_code, 1) << c.args << "\n" << r.output;
    EXPECT_EQ(r.output.rfind("weft: error: ", 0), 0u) << r.output;
    EXPECT_CONTAINS(r.output, c.expected);
    EXPECT_CONTAINS(r.output, scene.string() + ": ");  // the scene reader's message
    EXPECT_FALSE(fs::exists(out)) << c.args;
  }
  const CommandResult r = run_weft("run " + scene.string() + " --samples 0 --out " + out.string());
  EXPECT_CONTAINS(r.output, "render.raytrace.samples");
}

// --threads on every command that simulates or ray-traces: a bad N is a one-line error before
// anything runs; a good one changes no bit of the frames.
TEST_F(FrameStreamCli, ThreadsIsCheckedOnEveryCommandAndChangesNoBit) {
  const fs::path scene = write_scene("tiny.json", tiny_scene());
  const fs::path out = m_dir / "out";
  for (const std::string& command :
       {"run " + scene.string(), "measure " + scene.string(),
        "sweep " + scene.string() + " --set simulation.integrator=symplectic_euler",
        "turntable " + scene.string(), "gallery --scenes " + m_dir.string()}) {
    for (const std::string bad : {"-1", "4097", "two"}) {
      const CommandResult r = run_weft(command + " --out " + out.string() + " --threads=" + bad);
      EXPECT_EQ(r.exit_code, 1) << command << " --threads=" << bad << "\n" << r.output;
      EXPECT_CONTAINS(r.output, "--threads");
      EXPECT_FALSE(fs::exists(out)) << command;
    }
  }
  const std::string ray = " --renderer raytrace --samples 2 --frames 2";
  const CommandResult one = run_weft("run " + scene.string() + ray + " --threads 1 --out " +
                                     (m_dir / "one").string());
  if (one.exit_code != 0 && one.output.find("without the ray tracer") != std::string::npos)
    GTEST_SKIP() << one.output;
  ASSERT_EQ(one.exit_code, 0) << one.output;
  const CommandResult all = run_weft("run " + scene.string() + ray + " --threads 0 --out " +
                                     (m_dir / "all").string());
  ASSERT_EQ(all.exit_code, 0) << all.output;
  const auto d =
      weft::render::compare_images(weft::render::read_image(m_dir / "one" / "frame_0002.png"),
                                   weft::render::read_image(m_dir / "all" / "frame_0002.png"));
  EXPECT_EQ(d.max_abs, 0);
}

// simulation.dynamics: false shows the initial shape in every frame: every run of a sweep is
// then the same shape with no step taken, whatever its time step.
TEST_F(FrameStreamCli, SweepHonoursDynamicsFalse) {
  const fs::path scene =
      write_scene("still.json", tiny_scene("", R"(, "simulation": {"dynamics": false})"));
  const fs::path out = m_dir / "out";
  const CommandResult r = run_weft("sweep " + scene.string() +
                                   " --set 'simulation.time_step=1 ms,2 ms' --out " + out.string());
  ASSERT_EQ(r.exit_code, 0) << r.output;
  std::ifstream csv(out / "sweep.csv");
  std::string header, line;
  std::getline(csv, header);
  EXPECT_EQ(header.rfind("run,simulation.time_step,wall_time_s,steps,time_step_s,rms_error_m,", 0),
            0u)
      << header;
  int rows = 0;
  while (std::getline(csv, line)) {
    ++rows;
    std::stringstream fields(line);
    std::string run, step, wall, steps, h, rms;
    std::getline(fields, run, ',');
    std::getline(fields, step, ',');
    std::getline(fields, wall, ',');
    std::getline(fields, steps, ',');
    std::getline(fields, h, ',');
    std::getline(fields, rms, ',');
    EXPECT_EQ(steps, "0") << line;
    EXPECT_EQ(std::stod(rms), 0.0) << line;
  }
  EXPECT_EQ(rows, 2);
}

// weft run's frame 24 of the default scene on the golden tests' 17² grid is the golden image
// tests/data/golden/default_hang_raster.png: the golden tests draw the frame stream's frames.
TEST_F(FrameStreamCli, RunFramesAreTheGoldenTestsFrames) {
  const fs::path out = m_dir / "out";
  const fs::path scene = fs::path(WEFT_SOURCE_DIR) / "assets" / "scenes" / "default.json";
  const CommandResult r =
      run_weft("run " + scene.string() + " --set 'cloth.resolution=[17,17]' --frames 24 " +
               "--size 256x192 --renderer raster --out " + out.string());
  if (r.exit_code != 0 && r.output.find("OSMesa") != std::string::npos) GTEST_SKIP() << r.output;
  ASSERT_EQ(r.exit_code, 0) << r.output;
  const fs::path golden =
      fs::path(WEFT_SOURCE_DIR) / "tests" / "data" / "golden" / "default_hang_raster.png";
  const auto d = weft::render::compare_images(weft::render::read_image(out / "frame_0024.png"),
                                              weft::render::read_image(golden), 16);
  // The golden test's own margins (tests/regression/regression_test.cpp): a different CPU's
  // rounding in llvmpipe, not a different frame.
  EXPECT_GE(d.psnr_db, 50.0);
  EXPECT_LE(d.fraction_over, 0.0005);
}

}  // namespace
