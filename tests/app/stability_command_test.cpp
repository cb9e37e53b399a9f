// `weft stability` (app/cli/stability_command.h) on a small cloth: every swept cell is stable exactly
// when its step is below the predicted critical step, implicit Euler everywhere, the bisection
// lands on the prediction, and bad options are reported naming the option.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
#include <string>
#include <vector>

#include "app/scene/scene.h"
#include "app/cli/stability_command.h"
#include "render/image.h"

namespace weft::app {
namespace {

namespace fs = std::filesystem;

// The rows of a CSV file as header name → text, one map per line.
std::vector<std::map<std::string, std::string>> read_csv(const fs::path& path) {
  std::ifstream in(path);
  std::string line;
  std::vector<std::string> header;
  std::vector<std::map<std::string, std::string>> rows;
  const auto split = [](const std::string& text) {
    std::vector<std::string> cells;
    std::stringstream s(text);
    std::string cell;
    while (std::getline(s, cell, ',')) cells.push_back(cell);
    if (!text.empty() && text.back() == ',') cells.emplace_back();
    return cells;
  };
  if (std::getline(in, line)) header = split(line);
  while (std::getline(in, line)) {
    const std::vector<std::string> cells = split(line);
    EXPECT_EQ(cells.size(), header.size()) << line;
    std::map<std::string, std::string> row;
    for (std::size_t k = 0; k < header.size() && k < cells.size(); ++k) row[header[k]] = cells[k];
    rows.push_back(row);
  }
  return rows;
}

TEST(StabilityCommand, StableExactlyBelowThePredictedStep) {
  StabilityOptions options;
  options.out = fs::path(WEFT_BINARY_DIR) / "test_output" / "stability_command";
  fs::remove_all(options.out);
  options.size = 5;
  options.integrators = {sim::Integrator::symplectic_euler, sim::Integrator::rk4,
                         sim::Integrator::implicit_euler};
  options.stiffness_scales = {10.0, 1.0};
  options.steps_per_row = 8;
  ASSERT_EQ(run_stability(options), 0);

  const auto sweep = read_csv(options.out / "stability.csv");
  ASSERT_EQ(sweep.size(), 3u * 2u * 8u);
  int explicit_cells = 0, explicit_stable = 0;
  for (const auto& row : sweep) {
    const bool stable = row.at("stable") == "1";
    if (row.at("integrator") == "implicit_euler") {
      EXPECT_TRUE(stable) << "implicit Euler at h = " << row.at("h_s");
      continue;
    }
    const double h = std::stod(row.at("h_s")), predicted = std::stod(row.at("predicted_h_s"));
    ++explicit_cells;
    explicit_stable += stable;
    if (std::abs(h / predicted - 1.0) > 0.05) {  // a cell this close may fall either way
      EXPECT_EQ(stable, h < predicted) << row.at("integrator") << " s = " << row.at("stiffness_scale")
                                       << ": h = " << h << " s, predicted " << predicted << " s";
    }
  }
  EXPECT_GT(explicit_stable, 0);  // the sweep straddles the limit
  EXPECT_LT(explicit_stable, explicit_cells);

  const auto critical = read_csv(options.out / "critical_steps.csv");
  ASSERT_EQ(critical.size(), 3u * 2u);
  for (const auto& row : critical) {
    if (row.at("integrator") == "implicit_euler") {
      EXPECT_EQ(row.at("observed_h_s"), "");
      continue;
    }
    EXPECT_NEAR(std::stod(row.at("observed_over_predicted")), 1.0, 0.05)
        << row.at("integrator") << " s = " << row.at("stiffness_scale");
    EXPECT_LE(std::stod(row.at("gershgorin_h_s")), std::stod(row.at("observed_h_s")));
  }
  // The stiffer cloth has the smaller critical step, by √10 (ω ∝ √s).
  EXPECT_NEAR(std::stod(critical[0].at("predicted_h_s")) / std::stod(critical[1].at("predicted_h_s")),
              std::sqrt(10.0), 1e-3);

  const render::Image png = render::read_image(options.out / "stability.png");
  EXPECT_GT(png.width(), 300);
  EXPECT_GT(png.height(), 200);
}

TEST(StabilityCommand, BadOptionsNameTheOption) {
  try {
    (void)parse_integrator_list({"rk4", "rk5"}, "--integrators");
    FAIL() << "rk5 accepted";
  } catch (const InputError& e) {
    const std::string message = e.what();
    EXPECT_NE(message.find("--integrators: unknown integrator 'rk5'"), std::string::npos) << message;
    EXPECT_NE(message.find("'central_difference'"), std::string::npos) << message;
  }
  EXPECT_THROW((void)parse_integrator_list({"rk4", "rk4"}, "--integrators"), InputError);

  StabilityOptions options;
  options.out = fs::path(WEFT_BINARY_DIR) / "test_output" / "stability_bad_options";
  fs::remove_all(options.out);
  options.size = 2;
  EXPECT_THROW(run_stability(options), InputError);
  options.size = 5;
  options.stiffness_scales = {1.0, 0.0};
  EXPECT_THROW(run_stability(options), InputError);
  options.stiffness_scales = {1.0, 1.0};
  EXPECT_THROW(run_stability(options), InputError);
  EXPECT_FALSE(fs::exists(options.out));  // nothing written for bad input
}

}  // namespace
}  // namespace weft::app
