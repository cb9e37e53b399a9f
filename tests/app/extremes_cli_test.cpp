// The edges users reach, one row each through the real `weft run` — stiffness
// and density from 1e-3× to 1e3× of wool, cloth from 1 mm to 100 m, 2×2 to 256² grids, g from 0
// to 100 g, every integrator and model, a fast obstacle. Each row either finishes with physical
// output (every frame stepped, finite numbers, the cloth moving under gravity) or stops with the
// documented divergence (exit 3, "simulation diverged", the frames before it kept); never NaN,
// never a frozen cloth with exit 0, never another exit code.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "tests/app/cli_test_support.h"

namespace fs = std::filesystem;

namespace {

using weft::app::test::CommandResult;
using weft::app::test::run_weft;

struct Row {
  const char* name;
  std::string settings;  // --set options
  bool moves = true;     // gravity (or an obstacle) must move the cloth when the run finishes
};

// Wool (Kang & Yu 1995, the default scene's material) with its rigidities and density scaled.
std::string wool(double stiffness, double density) {
  char text[400];
  std::snprintf(text, sizeof text,
                "--set 'cloth.material={\"density\": \"%g gf/cm^2\", \"stretch_warp\": \"%g gf/cm\", "
                "\"stretch_weft\": \"%g gf/cm\", \"shear\": \"%g gf/cm\", \"bend_warp\": "
                "\"%g gf*cm\", \"bend_weft\": \"%g gf*cm\"}'",
                0.019 * density, 1118.2 * stiffness, 759.5 * stiffness, 41.8 * stiffness,
                0.083 * stiffness, 0.063 * stiffness);
  return text;
}

std::vector<Row> rows() {
  std::vector<Row> out = {
      {"soft", wool(1e-3, 1.0)},
      {"stiff", wool(1e3, 1.0)},
      {"light", wool(1.0, 1e-3)},
      {"heavy", wool(1.0, 1e3)},
      {"one_millimetre", "--set 'cloth.size=[\"1 mm\", \"1 mm\"]'"},
      {"hundred_metres", "--set 'cloth.size=[\"100 m\", \"100 m\"]'"},
      {"grid_2x2", "--set 'cloth.resolution=[2, 2]'"},
      {"weightless", "--set 'simulation.gravity=[0, 0, 0]'", false},
      {"hundred_g", "--set 'simulation.gravity=[0, 0, \"-981 m/s^2\"]'"},
      {"fast_sphere",
       "--set 'obstacles=[{\"sphere\": {\"center\": [0, 0.1, 0.1], \"radius\": \"3 cm\"}, "
       "\"motion\": [{\"time\": 0, \"translate\": [0, 0, 0]}, {\"time\": \"0.1 s\", "
       "\"translate\": [0, 0, 2]}]}]'"},
  };
  for (const char* integrator : {"symplectic_euler", "implicit_euler", "explicit_euler", "rk4",
                                 "velocity_verlet", "central_difference", "dynamic_relaxation"})
    out.push_back({integrator, std::string("--set simulation.integrator=") + integrator});
  for (const char* model : {"baraff_witkin", "rft3", "rft6"})
    out.push_back({model, std::string("--set simulation.model=") + model});
  return out;
}

// stats.csv as numbers, one vector per frame.
std::vector<std::vector<double>> read_stats(const fs::path& path) {
  std::ifstream in(path);
  std::string line;
  std::getline(in, line);
  std::vector<std::vector<double>> table;
  while (std::getline(in, line)) {
    std::vector<double> row;
    std::stringstream fields(line);
    std::string field;
    while (std::getline(fields, field, ',')) row.push_back(std::strtod(field.c_str(), nullptr));
    table.push_back(row);
  }
  return table;
}

class Extremes : public weft::app::test::CliDirectoryTest,
                 public ::testing::WithParamInterface<Row> {
 protected:
  Extremes() : CliDirectoryTest("extremes") {}
};

TEST_P(Extremes, FinishesPhysicallyOrStopsAsDiverged) {
  const Row& row = GetParam();
  const fs::path scene = write_scene("tiny.json", weft::app::test::tiny_scene());
  const fs::path out = m_dir / "out";
  const CommandResult r = run_weft("run " + scene.string() + " --out " + out.string() +
                                   " --frames 3 --size 32x32 " + row.settings);
  ASSERT_TRUE(r.exit_code == 0 || r.exit_code == 3) << row.name << ":\n" << r.output;
  const auto stats = read_stats(out / "stats.csv");
  if (r.exit_code == 3) {
    EXPECT_CONTAINS(r.output, "simulation diverged at step");
    // The frames it kept are those of stats.csv.
    for (std::size_t k = 1; k <= stats.size(); ++k) {
      char name[32];
      std::snprintf(name, sizeof name, "frame_%04zu.png", k);
      EXPECT_TRUE(fs::exists(out / name)) << name;
    }
    return;
  }
  ASSERT_EQ(stats.size(), 3u) << r.output;
  double fastest = 0.0;
  for (const auto& frame : stats) {
    for (double x : frame) EXPECT_TRUE(std::isfinite(x)) << row.name << ": " << r.output;
    EXPECT_GE(frame[4], 1.0) << row.name << ": a frame without a step";  // steps
    fastest = std::max(fastest, frame[10]);                            // max_speed_m_s
  }
  if (row.moves) {
    EXPECT_GT(fastest, 0.0) << row.name << ": a frozen cloth";
  }
}

INSTANTIATE_TEST_SUITE_P(Rows, Extremes, ::testing::ValuesIn(rows()),
                         [](const ::testing::TestParamInfo<Row>& test) {
                           return std::string(test.param.name);
                         });

// The finest grid of the table (256², about 2 minutes per 1/24 s frame on one core, so one
// 1/240 s frame here): its own test, labelled slow.
TEST(ExtremesSlow, AGrid256SquaredFinishesOrStopsAsDiverged) {
  const fs::path dir = weft::app::test::fresh_test_directory("extremes_slow");
  const fs::path scene = dir / "tiny.json";
  std::ofstream(scene) << weft::app::test::tiny_scene();
  const CommandResult r = run_weft("run " + scene.string() + " --out " + (dir / "out").string() +
                                   " --frames 1 --size 32x32 --set 'cloth.resolution=[256, 256]'"
                                   " --set output.fps=240");  // one 1/240 s frame: about 10 s
  ASSERT_TRUE(r.exit_code == 0 || r.exit_code == 3) << r.output;
  const auto stats = read_stats(dir / "out" / "stats.csv");
  if (r.exit_code == 0) {
    ASSERT_EQ(stats.size(), 1u);
    EXPECT_GE(stats[0][4], 1.0);
    EXPECT_GT(stats[0][10], 0.0);
  }
}

}  // namespace
