// End to end through the real `weft` command: a tiny scene writes its frames and stats, and
// each class of bad input gets its one-line message and exit code with nothing written.
#include <gtest/gtest.h>
#include <sys/wait.h>

#include <array>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "render/image.h"
#include "tests/app/cli_test_support.h"

namespace fs = std::filesystem;

namespace {

using Result = weft::app::test::CommandResult;
using weft::app::test::run_weft;
using weft::app::test::tiny_scene;

class Cli : public weft::app::test::CliDirectoryTest {
 protected:
  Cli() : CliDirectoryTest("cli") {}
};

TEST_F(Cli, VersionAndHelp) {
  const Result version = run_weft("--version");
  EXPECT_EQ(version.exit_code, 0);
  EXPECT_EQ(version.output.rfind("weft ", 0), 0u) << version.output;
  const Result bare = run_weft("");
  EXPECT_EQ(bare.exit_code, 1);
  EXPECT_NE(bare.output.find("run"), std::string::npos) << bare.output;  // lists the commands
  const Result help = run_weft("run --help");
  EXPECT_EQ(help.exit_code, 0);
  EXPECT_NE(help.output.find("--frames"), std::string::npos) << help.output;
  EXPECT_NE(help.output.find("--size"), std::string::npos) << help.output;
}

TEST_F(Cli, RunWritesFramesStatsAndTheScene) {
  const fs::path scene = write_scene("tiny.json", tiny_scene());
  const fs::path out = m_dir / "out";
  const Result r = run_weft("run " + scene.string() + " --out " + out.string());
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_NE(r.output.find("wrote 4 frames"), std::string::npos) << r.output;
  for (int k = 1; k <= 4; ++k) {
    char name[32];
    std::snprintf(name, sizeof name, "frame_%04d.png", k);
    const weft::render::Image image = weft::render::read_image(out / name);
    EXPECT_EQ(image.width(), 96);
    EXPECT_EQ(image.height(), 64);
    // Not a blank image: the cloth, the ground and the background give several colours.
    std::set<std::array<int, 3>> colours;
    for (int y = 0; y < image.height(); ++y)
      for (int x = 0; x < image.width(); ++x) {
        const auto c = image.at(x, y);
        colours.insert({c.r / 16, c.g / 16, c.b / 16});
      }
    EXPECT_GE(colours.size(), 4u) << name;
  }
  EXPECT_FALSE(fs::exists(out / "frame_0005.png"));
  std::ifstream stats(out / "stats.csv");
  std::string line;
  int rows = -1;  // the header
  while (std::getline(stats, line)) ++rows;
  EXPECT_EQ(rows, 4);
  std::ifstream copy(out / "scene.json");
  std::stringstream text;
  text << copy.rdbuf();
  EXPECT_EQ(text.str(), tiny_scene());
}

TEST_F(Cli, FramesAndSizeOptionsOverrideTheScene) {
  const fs::path scene = write_scene("tiny.json", tiny_scene());
  const fs::path out = m_dir / "out";
  const Result r =
      run_weft("run " + scene.string() + " --out " + out.string() + " --frames 2 --size 40x30");
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_EQ(weft::render::read_image(out / "frame_0002.png").width(), 40);
  EXPECT_FALSE(fs::exists(out / "frame_0003.png"));
}

struct BadInput {
  std::string name;
  std::string args_after_scene;
  std::string scene_text;  // empty: no scene file is written (a missing file)
  std::string expected;    // part of the one-line message
};

void PrintTo(const BadInput& bad, std::ostream* os) {
  *os << bad.name;
}

class CliBadInput : public Cli, public ::testing::WithParamInterface<BadInput> {};

TEST_P(CliBadInput, OneLineErrorExitCodeOneAndNothingWritten) {
  const BadInput& bad = GetParam();
  const fs::path scene =
      bad.scene_text.empty() ? m_dir / "missing.json" : write_scene("scene.json", bad.scene_text);
  const fs::path out = m_dir / "out";
  const Result r =
      run_weft("run " + scene.string() + " --out " + out.string() + " " + bad.args_after_scene);
  EXPECT_EQ(r.exit_code, 1) << r.output;
  EXPECT_EQ(r.output.rfind("weft: error: ", 0), 0u) << r.output;
  EXPECT_NE(r.output.find(bad.expected), std::string::npos) << r.output;
  EXPECT_EQ(std::count(r.output.begin(), r.output.end(), '\n'), 1) << r.output;
  EXPECT_FALSE(fs::exists(out)) << "a rejected run must write nothing";
}

INSTANTIATE_TEST_SUITE_P(
    Errors, CliBadInput,
    ::testing::Values(
        BadInput{"MissingFile", "", "", "missing.json: cannot read scene file"},
        BadInput{"MalformedJson", "", "{\"description\": \"x\",\n \"cloth\": {", "scene.json:2:"},
        BadInput{"UnknownKey", "", tiny_scene(",\n    \"colour\": 3"), "cloth.colour: unknown key"},
        BadInput{"NonFinite", "", tiny_scene(",\n    \"material\": {\"density\": 1e999}"),
                 "cloth.material.density"},
        BadInput{"NanString", "", tiny_scene(",\n    \"material\": {\"shear\": \"nan N/m\"}"),
                 "cloth.material.shear"},
        BadInput{"ZeroResolution", "",
                 tiny_scene().replace(tiny_scene().find("[9, 9]"), 6, "[0, 9]"),
                 "cloth.resolution[0]"},
        BadInput{"PinOutsideTheMesh", "",
                 tiny_scene().replace(tiny_scene().find("{\"corner\": \"u1v1\"}"), 18,
                                      "{\"vertex\": 81}"),
                 "cloth.pins[1]: vertex 81 is outside the mesh (0..80)"},
        BadInput{"WrongEnum", "", tiny_scene("", ",\n  \"simulation\": {\"integrator\": \"rk9\"}"),
                 "simulation.integrator"},
        BadInput{"BadSizeOption", "--size 10x", tiny_scene(), "--size: expected WIDTHxHEIGHT"},
        BadInput{"BadFramesOption", "--frames 0", tiny_scene(),
                 "output.frames: expected an integer in [1, 100000], got 0"},
        BadInput{"BadShadingOption", "--shading glossy", tiny_scene(),
                 "--shading: glossy not in {lit,normals,strain}"}),
    [](const ::testing::TestParamInfo<BadInput>& param) { return param.param.name; });

// --explain lists only what the scene needs — the tiny scene has no constraints and no
// obstacles but the ground; with them and self-collision, the projection and collision phases appear with their
// sizes (and stats.csv gets its self-contact column) — and
// ends with each phase's share of the time.
TEST_F(Cli, ExplainListsTheTermsAndPhasesTheSceneUses) {
  const fs::path plain = write_scene("plain.json", tiny_scene());
  const Result r = run_weft("run " + plain.string() + " --explain --out " + (m_dir / "a").string());
  EXPECT_EQ(r.exit_code, 0) << r.output;
  EXPECT_CONTAINS(r.output, "integrate: symplectic_euler, h = ");
  EXPECT_CONTAINS(r.output, "144 warp/weft springs, 128 shear springs");  // 9×9: 2·9·8, 2·8·8
  EXPECT_CONTAINS(r.output, "project: off (no constraints)");
  // No obstacles in the file, but the drawn ground is a collider (render.ground.collider).
  EXPECT_CONTAINS(r.output, "collide: 1 obstacles (0 meshes, 0 moving)");
  EXPECT_CONTAINS(r.output, "pins: 2 fixed, 0 moving vertices");
  EXPECT_CONTAINS(r.output, "weft: time per phase: forces ");

  const fs::path rich = write_scene(
      "rich.json",
      tiny_scene(
          "",
          ",\n  \"obstacles\": [{\"plane\": {\"point\": [0, 0, 0], \"normal\": [0, 0, 1]}}],\n"
          "  \"simulation\": {\"integrator\": \"implicit_euler\", \"constraints\": "
          "{\"method\": \"fast_projection\"}, \"self_collision\": {}}"));
  const Result q = run_weft("run " + rich.string() + " --explain --out " + (m_dir / "b").string());
  EXPECT_EQ(q.exit_code, 0) << q.output;
  EXPECT_CONTAINS(q.output, "integrate: implicit_euler, h = 8.33333 ms, sparse direct solve");
  EXPECT_EQ(q.output.find("warp/weft springs"), std::string::npos)
      << q.output;  // constraints instead
  // 144 warp/weft edges; the top edge runs between the two pins at its rest length, so its 7
  // inner vertices are held (sim/constraints/taut_chains.h) and its 8 edges leave the projection.
  EXPECT_CONTAINS(q.output, "project: fast_projection on 136 warp/weft edges");
  EXPECT_CONTAINS(q.output, "7 vertices held on 1 chain pulled straight between still pins");
  EXPECT_CONTAINS(q.output, "collide: 1 obstacles (0 meshes, 0 moving)");
  // 9×9 vertices: 2·8·8 triangles, 2·9·8 + 8·8 edges; marbles default to half the thickness.
  EXPECT_CONTAINS(q.output, "self-collision over 128 triangles and 208 edges, thickness 2 mm, "
                            "marbles of radius 1 mm");
  EXPECT_CONTAINS(q.output, "project ");
  std::ifstream stats(m_dir / "b" / "stats.csv");
  std::string header;
  std::getline(stats, header);
  EXPECT_CONTAINS(header, ",self_intersections,max_self_contacts");
}

// A time step beyond the critical one (1.6×) explodes after some frames (1 ms each here): the
// run stops with exit code 3, names the frame, step, time and quantity, and keeps the frames it
// wrote before.
TEST_F(Cli, DivergingRunStopsAndKeepsItsFrames) {
  std::string text = tiny_scene("", ",\n  \"simulation\": {\"time_step\": \"0.4 ms\"}");
  text.replace(text.find("\"frames\": 4"), 11, "\"frames\": 40");
  text.replace(text.find("\"fps\": 24"), 9, "\"fps\": 1000");
  const fs::path scene = write_scene("explode.json", text);
  const fs::path out = m_dir / "out";
  const Result r = run_weft("run " + scene.string() + " --out " + out.string());
  EXPECT_EQ(r.exit_code, 3) << r.output;
  EXPECT_NE(r.output.find("simulation diverged at step"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("(t = "), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("vertex"), std::string::npos) << r.output;
  EXPECT_TRUE(fs::exists(out / "stats.csv"));
  // The frames it says it kept are the ones on disk, and no more.
  const std::size_t kept = r.output.find("kept frames 1..");
  ASSERT_NE(kept, std::string::npos) << r.output;
  const int last = std::stoi(r.output.substr(kept + 15));
  ASSERT_GE(last, 1) << r.output;
  char name[32];
  std::snprintf(name, sizeof name, "frame_%04d.png", last);
  EXPECT_TRUE(fs::exists(out / name)) << name;
  std::snprintf(name, sizeof name, "frame_%04d.png", last + 1);
  EXPECT_FALSE(fs::exists(out / name)) << name;
}

// --renderer raytrace draws the same frames with the Embree ray tracer (its description in the
// header line); a bad --renderer or --samples is bad input with nothing written.
TEST_F(Cli, RunWithTheRayTracer) {
  const fs::path scene = write_scene("tiny.json", tiny_scene());
  const fs::path out = m_dir / "out";
  const Result r = run_weft("run " + scene.string() +
                            " --frames 1 --renderer raytrace --samples 2 --out " + out.string());
  if (r.exit_code == 2 && r.output.find("built without the ray tracer") != std::string::npos)
    GTEST_SKIP() << r.output;
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_CONTAINS(r.output, "Embree");
  const weft::render::Image image = weft::render::read_image(out / "frame_0001.png");
  EXPECT_EQ(image.width(), 96);
  EXPECT_EQ(image.height(), 64);

  const Result bad = run_weft("run " + scene.string() + " --renderer povray --out " +
                              (m_dir / "bad").string());
  EXPECT_EQ(bad.exit_code, 1) << bad.output;
  EXPECT_CONTAINS(bad.output, "--renderer: povray not in {raster,raytrace}");
  const Result bad_samples = run_weft("run " + scene.string() + " --samples 0 --out " +
                                      (m_dir / "bad").string());
  EXPECT_EQ(bad_samples.exit_code, 1) << bad_samples.output;
  EXPECT_CONTAINS(bad_samples.output, "--samples 0: " + scene.string() +
                                          ": render.raytrace.samples: expected an integer in "
                                          "[1, 65536], got 0");
  EXPECT_FALSE(fs::exists(m_dir / "bad"));
}

}  // namespace
