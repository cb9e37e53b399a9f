// No non-finite number reaches an output (app/io/finite_outputs.h): the CSV and JSON checks on
// their own, and through write_text, which refuses a .csv with one before writing anything.
#include "app/io/finite_outputs.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <limits>
#include <nlohmann/json.hpp>
#include <stdexcept>
#include <string>

#include "app/io/output_files.h"
#include "scene_test_support.h"
#include "tests/support/test_files.h"

namespace weft::app {
namespace {

std::string csv_error(const std::string& text) {
  try {
    require_finite_csv("stats.csv", text);
  } catch (const std::runtime_error& e) {
    return e.what();
  }
  return "";
}

TEST(FiniteOutputs, ACsvCellThatIsNotFiniteIsNamedByRowAndColumn) {
  const std::string header = "frame,time_s,gravity_energy_J\n";
  EXPECT_EQ(csv_error(header + "1,0.04,-1.5e+301\n2,0.08,-2e+301\n"), "");
  EXPECT_EQ(csv_error(header), "");
  for (const char* bad : {"inf", "-inf", "+INF", "nan", "-nan", "nan(ind)", "Infinity"}) {
    const std::string e = csv_error(header + "1,0.04,1\n2,0.08," + bad + "\n");
    EXPECT_CONTAINS(e, std::string("stats.csv: line 3 (frame 2), gravity_energy_J: '") + bad +
                           "' is not a finite number");
  }
  // Text that only starts like one is text (a scene name, a failure message).
  EXPECT_EQ(csv_error("scene,result\ninfo_panel,nanometre scale\n"), "");
}

TEST(FiniteOutputs, AJsonNumberThatIsNotFiniteIsNamedByItsPath) {
  nlohmann::json j = {{"best", {{"objective", 0.5}, {"values", {1.0, 2.0}}}}};
  EXPECT_NO_THROW(require_finite_json(j, "fit_result.json"));
  j["best"]["values"][1] = std::numeric_limits<double>::infinity();
  try {
    require_finite_json(j, "fit_result.json");
    ADD_FAILURE() << "an infinite value passed";
  } catch (const std::runtime_error& e) {
    EXPECT_CONTAINS(std::string(e.what()), "fit_result.json: /best/values/1 is not a finite number");
  }
}

// What weft compare, diff, folds and photo-scene print or write as JSON: the text only when
// every number is finite (nlohmann/json would print a NaN as null, which reads as "missing").
TEST(FiniteOutputs, JsonTextIsGivenOnlyWhenEveryNumberIsFinite) {
  nlohmann::json j = {{"iou", 0.97}, {"delta_e2000", {{"mean", 2.5}, {"p95", 6.0}}}};
  EXPECT_EQ(finite_json_text(j, "weft compare's result"), j.dump(2));
  j["delta_e2000"]["p95"] = std::numeric_limits<double>::quiet_NaN();
  try {
    (void)finite_json_text(j, "weft compare's result");
    ADD_FAILURE() << "a NaN passed";
  } catch (const std::runtime_error& e) {
    EXPECT_CONTAINS(std::string(e.what()),
                    "weft compare's result: /delta_e2000/p95 is not a finite number");
  }
}

TEST(FiniteOutputs, WriteTextRefusesACsvWithANonFiniteCellAndWritesNothing) {
  const std::filesystem::path dir =
      test_files::fresh_directory(::testing::TempDir(), "weft_finite_outputs_test");
  EXPECT_THROW(write_text(dir / "stats.csv", "frame,x\n1,nan\n"), std::runtime_error);
  EXPECT_FALSE(std::filesystem::exists(dir / "stats.csv"));
  write_text(dir / "notes.txt", "inf is a word here\n");  // not a CSV: not checked
  EXPECT_TRUE(std::filesystem::exists(dir / "notes.txt"));
}

}  // namespace
}  // namespace weft::app
