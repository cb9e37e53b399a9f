// Through the real `weft` command: hostile input and extreme values get a clear error
// (or a warning) naming the file, key or option — never a crash, a hang, or exit 0 with a wrong
// result — and a run that stops before its first frame leaves an earlier run's files as they were.
#include <gtest/gtest.h>

#include <CLI/CLI.hpp>
#include <chrono>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
#include <string>

#include "app/cli/command.h"
#include "app/scene/json_reader.h"
#include "app/scene/scene.h"
#include "app/scene/units.h"
#include "render/image.h"
#include "tests/app/cli_test_support.h"

namespace fs = std::filesystem;

namespace {

using weft::app::test::CommandResult;
using weft::app::test::run_weft;
using weft::app::test::tiny_scene;

class HostileInput : public weft::app::test::CliDirectoryTest {
 protected:
  HostileInput() : CliDirectoryTest("hostile_input") {}
  // `weft run SCENE --out DIR` for a scene text written to NAME.json; DIR is m_dir/NAME.
  CommandResult run_scene(const std::string& name, const std::string& text,
                          const std::string& extra = "") const {
    const fs::path scene = write_scene(name + ".json", text);
    return run_weft("run " + scene.string() + " --out " + (m_dir / name).string() + " " + extra);
  }
};

std::string repeat(const std::string& s, int n) {
  std::string out;
  for (int k = 0; k < n; ++k) out += s;
  return out;
}

std::string file_bytes(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::stringstream bytes;
  bytes << in.rdbuf();
  return bytes.str();
}

// The "steps" column of stats.csv, one value per frame.
std::vector<long> steps_per_frame(const fs::path& stats) {
  std::ifstream in(stats);
  std::string line;
  std::getline(in, line);  // header: frame,time_s,sim_ms,render_ms,steps,...
  std::vector<long> steps;
  while (std::getline(in, line)) {
    std::stringstream fields(line);
    std::string field;
    for (int k = 0; k < 5; ++k) std::getline(fields, field, ',');
    steps.push_back(std::stol(field));
  }
  return steps;
}

// --- recursion: the JSON walk and the unit parser ----------------------------------------

TEST_F(HostileInput, JsonNestedBeyondTheLimitIsAnErrorNotACrash) {
  const int depth = 100000;
  const CommandResult r = run_scene(
      "deep", "{\"description\": " + repeat("[", depth) + repeat("]", depth) + "}\n");
  EXPECT_EQ(r.exit_code, 1) << r.output.substr(0, 400);
  EXPECT_CONTAINS(r.output, "deep.json:1:");
  EXPECT_CONTAINS(r.output, "nest deeper than " + std::to_string(weft::app::max_json_depth));
  // The same through --set: the value is taken as text, and the scene says what it expected.
  const CommandResult set = run_weft("run --frames 1 --out " + (m_dir / "set").string() +
                                     " --set 'cloth.resolution=" + repeat("[", 5000) +
                                     repeat("]", 5000) + "'");
  EXPECT_EQ(set.exit_code, 1) << set.output.substr(0, 400);
  EXPECT_CONTAINS(set.output, "cloth.resolution");
}

TEST_F(HostileInput, UnitNestedBeyondTheLimitIsAnErrorNotACrash) {
  const int depth = 100000;
  const std::string size = "\"1 " + repeat("(", depth) + "cm" + repeat(")", depth) + "\"";
  std::string text = tiny_scene();
  text.replace(text.find("[\"20 cm\", \"20 cm\"]"), 18, "[\"20 cm\", " + size + "]");
  const CommandResult r = run_scene("deep_unit", text);
  EXPECT_EQ(r.exit_code, 1) << r.output.substr(0, 400);
  EXPECT_CONTAINS(r.output, "cloth.size[1]");
  EXPECT_CONTAINS(r.output,
                  "nested deeper than " + std::to_string(weft::app::max_unit_parentheses));
  // Within the limit, parentheses still mean what they say.
  EXPECT_DOUBLE_EQ(weft::app::parse_quantity("2 ((((cm))))", weft::app::Quantity::length), 0.02);
}

// --- every numeric option of every command is bounded ------------------------------------

// The options that take numbers, as "COMMAND --OPTION", from the commands' own registration.
std::vector<std::string> numeric_options() {
  CLI::App app;
  const auto commands = weft::app::register_commands(app, "weft");
  std::vector<std::string> out;
  for (const weft::app::Command& command : commands)
    for (const CLI::Option* option : command.cli->get_options()) {
      const std::string type = option->get_type_name();
      const bool numeric = type.rfind("FLOAT", 0) == 0 || type.rfind("INT", 0) == 0 ||
                           type.rfind("UINT", 0) == 0 || type.rfind("NUMBER", 0) == 0;
      if (numeric && !option->get_lnames().empty())
        out.push_back(command.cli->get_name() + " --" + option->get_lnames().front());
    }
  return out;
}

TEST_F(HostileInput, EveryNumericOptionRejectsNanAndHugeValuesNamingItself) {
  const std::vector<std::string> options = numeric_options();
  ASSERT_GE(options.size(), 25u);  // run, folds, compare, measure, turntable, … have them
  // What a command needs before it reads a scene option (those are checked with the scene).
  const std::map<std::string, std::string> required = {
      {"sweep", " --set output.fps=24"},
      {"turntable", " " + write_scene("tiny.json", tiny_scene()).string()},
      {"render", " " + m_dir.string() + " --scene " + write_scene("tiny.json", tiny_scene()).string()}};
  for (const std::string& command_option : options) {
    const std::string command = command_option.substr(0, command_option.find(' '));
    const std::string option = command_option.substr(command.size() + 1);
    const std::string needs = required.count(command) ? required.at(command) : "";
    for (const char* value : {"nan", "inf", "1e308", "-1e308"}) {
      const CommandResult r = run_weft(command_option + " " + value + needs + " --out " +
                                       (m_dir / "numeric").string());
      EXPECT_GT(r.exit_code, 0) << command_option << " " << value << ":\n" << r.output;
      EXPECT_CONTAINS(r.output, option) << command_option << " " << value;
    }
  }
}

TEST_F(HostileInput, FoldSigmaZeroNegativeOrHugeIsAnError) {
  for (const char* sigma : {"0", "-2", "1e300"}) {
    const CommandResult r = run_weft("compare a.png b.png --fold-sigma " + std::string(sigma));
    EXPECT_EQ(r.exit_code, 1) << sigma << ": " << r.output;
    EXPECT_CONTAINS(r.output, "--fold-sigma: expected a number in (0, 1000], got '" +
                                  std::string(sigma) + "'");
  }
}

TEST_F(HostileInput, FoldsWithAnAbsurdHeightIsAnErrorNotNan) {
  const std::string rest = " --L-cm 50 --d-cm 5 --t-mm 0.3 --E-MPa 100 --w-N-mm2 15e-7";
  const CommandResult huge = run_weft("folds --h-cm 1e308" + rest);
  EXPECT_EQ(huge.exit_code, 1) << huge.output;
  EXPECT_CONTAINS(huge.output, "--h-cm: expected a number in (0, 10000]");
  EXPECT_EQ(huge.output.find("nan"), std::string::npos) << huge.output;
  // The largest accepted height gives numbers or an error, never nan.
  const CommandResult edge = run_weft("folds --h-cm 1e4" + rest);
  EXPECT_EQ(edge.output.find("nan"), std::string::npos) << edge.output;
}

// --- extremes that froze the cloth with exit 0 -------------------------------------------

TEST_F(HostileInput, ADensityOrTimeStepThatNeedsAbsurdlyManyStepsIsAnError) {
  const CommandResult light =
      run_scene("light", tiny_scene(",\n    \"material\": {\"density\": 1e-300}"));
  EXPECT_EQ(light.exit_code, 1) << light.output;
  EXPECT_CONTAINS(light.output, "cloth.material: the automatic time step");
  EXPECT_CONTAINS(light.output, "more than the limit of 1e+06");
  const CommandResult tiny_step =
      run_scene("tiny_step", tiny_scene("", ",\n  \"simulation\": {\"time_step\": 1e-300}"));
  EXPECT_EQ(tiny_step.exit_code, 1) << tiny_step.output;
  EXPECT_CONTAINS(tiny_step.output, "simulation.time_step: a time of 0.0416667 s needs 4.16667e+298 steps");
  EXPECT_FALSE(fs::exists(m_dir / "tiny_step" / "frame_0001.png"));
}

TEST_F(HostileInput, AHeavyClothStillMovesEveryFrame) {
  // 1e300 kg/m²: the critical step is astronomically long, so each frame is one step (it was
  // none: a frozen cloth with exit 0). Gravity moves a cloth whatever its density.
  // Its rigidity is nothing against its weight, so the edges by the pins stretch without bound
  // until the strain guard stops the run as diverged.
  const CommandResult heavy =
      run_scene("heavy", tiny_scene(",\n    \"material\": {\"density\": 1e300}"));
  ASSERT_TRUE(heavy.exit_code == 0 || heavy.exit_code == 3) << heavy.output;
  const std::vector<long> steps = steps_per_frame(m_dir / "heavy" / "stats.csv");
  ASSERT_GE(steps.size(), 2u) << heavy.output;
  for (long n : steps) EXPECT_GE(n, 1);
  EXPECT_NE(file_bytes(m_dir / "heavy" / "frame_0001.png"),
            file_bytes(m_dir / "heavy" / "frame_0002.png"));
}

// The case: the default scene on 11×11 vertices with symplectic Euler at 41.7 ms, 41×
// the critical step the banner prints, swung the cloth to 1388 % strain at finite speed (so the
// speed limit never fired) and exited 0. It stops as diverged in frame 2, exit 3, frame 1 kept —
// by the strain limit, and with that lifted, by the energy no passive cloth can gain.
TEST_F(HostileInput, FortyOneTimesTheCriticalStepStopsAsDiverged) {
  const std::string args = "run --frames 2 --size 32x32 --set 'cloth.resolution=[11, 11]' "
                           "--set simulation.time_step=41.7ms --out ";
  const CommandResult r = run_weft(args + (m_dir / "strain").string());
  const std::size_t at = r.output.find("(critical ");
  ASSERT_NE(at, std::string::npos) << r.output;
  const double critical_ms = std::stod(r.output.substr(at + 10));
  EXPECT_NEAR(41.7 / critical_ms, 41.0, 1.0) << r.output;
  EXPECT_EQ(r.exit_code, 3) << r.output;
  EXPECT_CONTAINS(r.output, "frame 2: simulation diverged at step 2");
  EXPECT_CONTAINS(r.output, "is strained");
  EXPECT_CONTAINS(r.output, "kept frames 1..1");
  EXPECT_EQ(steps_per_frame(m_dir / "strain" / "stats.csv").size(), 1u);
  EXPECT_TRUE(fs::exists(m_dir / "strain" / "frame_0001.png"));

  const CommandResult energy =
      run_weft(args + (m_dir / "energy").string() + " --set simulation.max_strain=1000");
  EXPECT_EQ(energy.exit_code, 3) << energy.output;
  EXPECT_CONTAINS(energy.output, "the total energy grew by");
  EXPECT_TRUE(fs::exists(m_dir / "energy" / "frame_0001.png"));
}

// --- sizes and counts ----------------------------------------------------------------------

TEST_F(HostileInput, AnEndlessSceneFileIsCapped) {
  const auto start = std::chrono::steady_clock::now();
  const CommandResult r = run_weft("run /dev/zero --out " + (m_dir / "zero").string());
  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  EXPECT_EQ(r.exit_code, 1) << r.output;
  EXPECT_CONTAINS(r.output, "/dev/zero: the scene file is larger than 16 MiB");
  EXPECT_LT(seconds, 10.0);
}

TEST_F(HostileInput, TooManyObstaclesIsAnErrorBeforeAnyWork) {
  const std::string plane = "{\"plane\": {\"point\": [0, 0, 0], \"normal\": [0, 0, 1]}}";
  std::string list;
  for (int k = 0; k < 100000; ++k) list += (k ? "," : "") + plane;
  const CommandResult r = run_scene("planes", tiny_scene("", ",\n  \"obstacles\": [" + list + "]"));
  EXPECT_EQ(r.exit_code, 1) << r.output.substr(0, 400);
  EXPECT_CONTAINS(r.output, "obstacles: expected at most " +
                                std::to_string(weft::app::max_obstacles) +
                                " obstacles (the limit");
  EXPECT_CONTAINS(r.output, "got 100000");
  // Before any work: nothing simulated or drawn (not a timing, which a loaded or sanitized
  // build stretches: 20.6 s under sanitizers on a busy machine).
  EXPECT_FALSE(fs::exists(m_dir / "planes" / "frame_0001.png"));
  EXPECT_FALSE(fs::exists(m_dir / "planes" / "stats.csv"));
}

// --- empty and clashing paths ------------------------------------------------------------

TEST_F(HostileInput, EmptyPathsAreErrorsNamingTheOption) {
  const CommandResult scene = run_weft("run ''");
  EXPECT_EQ(scene.exit_code, 1) << scene.output;
  EXPECT_CONTAINS(scene.output, "scene: expected a value, got an empty string ''");
  const fs::path path = write_scene("tiny.json", tiny_scene());
  const CommandResult out = run_weft("run " + path.string() + " --out ''");
  EXPECT_EQ(out.exit_code, 1) << out.output;
  EXPECT_CONTAINS(out.output, "--out: expected a value, got an empty string ''");
  EXPECT_FALSE(fs::exists("out/tiny"));
  const CommandResult diff = run_weft("diff '' b.png");
  EXPECT_EQ(diff.exit_code, 5) << diff.output;  // weft diff's exit code for bad arguments
  EXPECT_CONTAINS(diff.output, "a: expected a value");
}

TEST_F(HostileInput, AHeatmapOverAnInputIsRefused) {
  weft::render::Image a(16, 16, {10, 20, 30}), b(16, 16, {12, 20, 30});
  weft::render::write_png(a, m_dir / "a.png");
  weft::render::write_png(b, m_dir / "b.png");
  const std::string before = file_bytes(m_dir / "b.png");
  const CommandResult r = run_weft("diff " + (m_dir / "a.png").string() + " " +
                                   (m_dir / "b.png").string() + " --heatmap " +
                                   (m_dir / "." / "b.png").string());
  EXPECT_EQ(r.exit_code, 5) << r.output;
  EXPECT_CONTAINS(r.output, "--heatmap: ");
  EXPECT_CONTAINS(r.output, "is the input");
  EXPECT_EQ(file_bytes(m_dir / "b.png"), before);
}

TEST_F(HostileInput, AMeshFileWithANonFiniteVertexIsAnError) {
  // Its NaN corner used to be joined silently to the vertex (0, 1, 0): exit 0, a wrong obstacle.
  const fs::path mesh = m_dir / "nan.obj";
  std::ofstream(mesh) << "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 1 nan\nf 1 2 3\nf 1 2 4\n";
  const std::string expected = mesh.string() + ": vertex 3 of mesh 0 is at (";
  const CommandResult obstacle = run_scene(
      "mesh", tiny_scene("", ",\n  \"obstacles\": [{\"mesh\": {\"file\": \"" +
                                 mesh.string() + "\"}}]"),
      "--frames 1");
  EXPECT_EQ(obstacle.exit_code, 1) << obstacle.output;
  EXPECT_CONTAINS(obstacle.output, "obstacles[0].mesh.file: " + expected);
  const CommandResult turntable =
      run_weft("turntable " + mesh.string() + " --out " + (m_dir / "turntable").string());
  EXPECT_EQ(turntable.exit_code, 1) << turntable.output;
  EXPECT_CONTAINS(turntable.output, expected);
  EXPECT_CONTAINS(turntable.output, "not a finite position");
}

// --- accepted, with a warning ------------------------------------------------------------

TEST_F(HostileInput, DuplicatePinsAllPinnedAndAPointCapsuleAreWarnedOf) {
  const auto replaced = [](std::string text, const std::string& what, const std::string& by) {
    return text.replace(text.find(what), what.size(), by);
  };
  const std::string pins_given = "{\"corner\": \"u0v1\"}, {\"corner\": \"u1v1\"}";
  const std::string twice =
      replaced(tiny_scene(), pins_given, pins_given + ", {\"grid\": [0, 8]}");
  const CommandResult pins = run_scene("twice", twice, "--frames 1");
  EXPECT_EQ(pins.exit_code, 0) << pins.output;
  EXPECT_CONTAINS(pins.output, "weft: warning: ");
  EXPECT_CONTAINS(pins.output, "cloth.pins[2]: 1 of its vertices are pinned already by cloth.pins[0]");

  const std::string all =
      replaced(tiny_scene(), pins_given, "{\"region\": {\"u\": [0, 1], \"v\": [0, 1]}}");
  const CommandResult everything = run_scene("all", all, "--frames 1");
  EXPECT_EQ(everything.exit_code, 0) << everything.output;
  EXPECT_CONTAINS(everything.output, "cloth.pins: every vertex of the cloth is pinned");

  const CommandResult capsule = run_scene(
      "capsule",
      tiny_scene("", ",\n  \"obstacles\": [{\"capsule\": {\"a\": [0, 0, 0.2], \"b\": [0, 0, 0.2], "
                     "\"radius\": 0.05}}]"),
      "--frames 1");
  EXPECT_EQ(capsule.exit_code, 0) << capsule.output;
  EXPECT_CONTAINS(capsule.output, "obstacles[0].capsule: 'a' and 'b' are the same point");
}

// --- atomic outputs ------------------------------------------------------------------------

TEST_F(HostileInput, ARunThatFailsBeforeItsFirstFrameLeavesTheEarlierRunAsItWas) {
  const fs::path out = m_dir / "out";
  const fs::path scene = write_scene("tiny.json", tiny_scene());
  const CommandResult first = run_weft("run " + scene.string() + " --out " + out.string());
  ASSERT_EQ(first.exit_code, 0) << first.output;
  std::map<std::string, std::string> before;
  for (const auto& entry : fs::directory_iterator(out))
    before[entry.path().filename().string()] = file_bytes(entry.path());
  ASSERT_EQ(before.count("frame_0004.png"), 1u);
  ASSERT_EQ(before.count("stats.csv"), 1u);

  // Diverges in its first frame (0.5 s): a time step about 80× the critical one.
  std::string bad = tiny_scene("", ",\n  \"simulation\": {\"time_step\": \"0.1 s\"}");
  bad.replace(bad.find("\"fps\": 24"), 9, "\"fps\": 2");
  const CommandResult second = run_weft("run " + write_scene("bad.json", bad).string() +
                                        " --out " + out.string());
  EXPECT_EQ(second.exit_code, 3) << second.output;
  EXPECT_CONTAINS(second.output, "no frame was finished; " + out.string() + " is as it was");
  std::map<std::string, std::string> after;
  for (const auto& entry : fs::directory_iterator(out))
    after[entry.path().filename().string()] = file_bytes(entry.path());
  EXPECT_TRUE(after == before) << "the earlier run's files changed";
}

TEST_F(HostileInput, OutputsAreWrittenWholeWithNoPartialFilesLeft) {
  const fs::path out = m_dir / "out";
  const CommandResult r = run_weft("run " + write_scene("tiny.json", tiny_scene()).string() +
                                   " --out " + out.string() + " --report");
  ASSERT_EQ(r.exit_code, 0) << r.output;
  for (const auto& entry : fs::directory_iterator(out))
    EXPECT_NE(entry.path().extension(), ".partial") << entry.path();
  EXPECT_EQ(steps_per_frame(out / "stats.csv").size(), 4u);
  EXPECT_EQ(weft::render::read_image(out / "frame_0004.png").width(), 96);
}

}  // namespace
