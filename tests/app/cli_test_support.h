#pragma once
// Shared by the tests that drive the real `weft` executable (WEFT_EXECUTABLE, set by CMake).

#include <sys/wait.h>

#include <gtest/gtest.h>

#include <array>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include "tests/support/test_files.h"

namespace weft::app::test {

struct CommandResult {
  int exit_code = -1;
  std::string output;  // stdout and stderr
};

// Runs `weft ARGS` through the shell and collects its output and exit code; `env` (e.g.
// "PATH=/dir") is put before the command.
inline CommandResult run_weft(const std::string& args, const std::string& env = "") {
  const std::string command =
      (env.empty() ? "" : env + " ") + std::string(WEFT_EXECUTABLE) + " " + args + " 2>&1";
  CommandResult r;
  FILE* pipe = popen(command.c_str(), "r");
  if (!pipe) return r;
  std::array<char, 4096> buffer{};
  std::size_t n;
  while ((n = fread(buffer.data(), 1, buffer.size(), pipe)) > 0) r.output.append(buffer.data(), n);
  const int status = pclose(pipe);
  r.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  return r;
}

// The file's bytes ("" when it cannot be read).
inline std::string file_bytes(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::stringstream bytes;
  bytes << in.rdbuf();
  return bytes.str();
}

// A fresh, empty folder for the running test: WEFT_BINARY_DIR/test_output/<suite>/<test name>.
// The names under `dir` that end in ".partial" (files, folders or links left half-written).
inline std::vector<std::string> partial_names(const std::filesystem::path& dir) {
  std::vector<std::string> names;
  for (const auto& entry : std::filesystem::recursive_directory_iterator(dir))
    if (entry.path().extension() == ".partial") names.push_back(entry.path().string());
  return names;
}

inline std::filesystem::path fresh_test_directory(const std::string& suite) {
  const std::filesystem::path root = std::filesystem::path(WEFT_BINARY_DIR) / "test_output";
  return test_files::fresh_directory(root, suite);
}

// A 9×9 cloth pinned at two corners, 4 frames of 96×64 pixels.
inline std::string tiny_scene(const std::string& cloth_extra = "", const std::string& top_extra = "") {
  return R"({
  "description": "tiny end-to-end test scene",
  "cloth": {
    "size": ["20 cm", "20 cm"], "resolution": [9, 9], "origin": [-0.1, 0, 0.5],
    "pins": [{"corner": "u0v1"}, {"corner": "u1v1"}])" +
         cloth_extra + R"(
  },
  "output": {"fps": 24, "frames": 4},
  "render": {"size": [96, 64], "camera": {"eye": [0.6, -0.5, 0.6], "target": [0, 0.1, 0.4]}})" +
         top_extra + "\n}\n";
}

// A fixture with that folder in m_dir and scene files written into it.
class CliDirectoryTest : public ::testing::Test {
 protected:
  explicit CliDirectoryTest(std::string suite) : m_suite(std::move(suite)) {}
  void SetUp() override { m_dir = fresh_test_directory(m_suite); }
  std::filesystem::path write_scene(const std::string& name, const std::string& text) const {
    const std::filesystem::path path = m_dir / name;
    std::ofstream(path) << text;
    return path;
  }
  std::filesystem::path m_dir;

 private:
  std::string m_suite;
};

}  // namespace weft::app::test

#ifndef EXPECT_CONTAINS
#define EXPECT_CONTAINS(text, part) \
  EXPECT_NE((text).find(part), std::string::npos) << "missing: " << (part) << "\nin: " << (text)
#endif
