#pragma once
// Shared by the tests of weft's Slurm scripts: run by hand (slurm_scripts_cli_test.cpp) and
// through a one-node Slurm (slurm_cli_test.cpp).

#include <gtest/gtest.h>
#include <sys/wait.h>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "tests/app/cli_test_support.h"

namespace weft::app::test {

// Six points: three resolutions × two integrators of tiny_scene().
inline const std::string kSixPointSweep =
    " --set 'cloth.resolution=[5,5],[7,7],[9,9]'"
    " --set simulation.integrator=symplectic_euler,implicit_euler";
// Wall times from the step count (the test hook of app/cli/sweep_command.cpp), so that sweep.csv
// and sweep.png are the same bits however and wherever the points ran.
inline const std::string kModelWallTime = "WEFT_SWEEP_SECONDS_PER_VERTEX_STEP=1e-6";

// The output (stdout and stderr) of a shell command and its exit code.
inline CommandResult shell(const std::string& command) {
  CommandResult r;
  FILE* pipe = popen((command + " 2>&1").c_str(), "r");
  char buffer[512];
  while (pipe && fgets(buffer, sizeof buffer, pipe)) r.output += buffer;
  const int status = pipe ? pclose(pipe) : -1;
  r.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  return r;
}

inline std::vector<std::string> file_lines(const std::filesystem::path& path) {
  std::ifstream in(path);
  std::vector<std::string> out;
  for (std::string line; std::getline(in, line);) out.push_back(line);
  return out;
}

// A CSV line's fields; "quoted, fields" keep their commas.
inline std::vector<std::string> csv_line_fields(const std::string& line) {
  std::vector<std::string> out(1);
  bool quoted = false;
  for (char c : line) {
    if (c == '"') quoted = !quoted;
    else if (c == ',' && !quoted) out.emplace_back();
    else out.back() += c;
  }
  return out;
}

// The six-point sweep's CSV `got` against the local sweep's `want`: every row, every column but
// the wall clock's (wall_time_s and pareto, which follows from it), with row `failed_row` (0:
// none) marked failed and not compared.
inline void expect_same_sweep_rows(const std::filesystem::path& want_csv,
                                   const std::filesystem::path& got_csv, std::size_t failed_row) {
  const auto want = file_lines(want_csv), got = file_lines(got_csv);
  ASSERT_EQ(want.size(), 7u);
  ASSERT_EQ(got.size(), 7u);
  EXPECT_EQ(got[0], want[0]);
  const std::vector<std::string> header = csv_line_fields(got[0]);
  ASSERT_EQ(header.back(), "failed");
  for (std::size_t row = 1; row <= 6; ++row) {
    const std::vector<std::string> a = csv_line_fields(want[row]), b = csv_line_fields(got[row]);
    ASSERT_EQ(b.size(), header.size()) << got[row];
    EXPECT_EQ(b.back(), row == failed_row ? "1" : "0") << "failed, row " << row;
    if (row == failed_row) continue;
    for (std::size_t col = 0; col < header.size(); ++col)
      if (header[col] != "wall_time_s" && header[col] != "pareto") {
        EXPECT_EQ(b[col], a[col]) << header[col] << ", row " << row;
      }
  }
}

}  // namespace weft::app::test
