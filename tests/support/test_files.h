#pragma once
// Test support, part of no library: the files a test writes and reads back — a fresh folder of
// its own, a text file, a CSV table. Header-only, under tests/ so production code cannot use it.

#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <stdexcept>
#include <string>
#include <vector>

namespace weft::test_files {

// A fresh, empty folder for the running test: <root>/<suite>/<test name>, one per test, so tests
// that ctest runs at once never share (and clear) each other's output.
inline std::filesystem::path fresh_directory(const std::filesystem::path& root,
                                             const std::string& suite) {
  const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
  const std::filesystem::path dir = root / suite / info->name();
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  return dir;
}

// Writes `text` to `path` byte for byte.
inline void write_text(const std::filesystem::path& path, const std::string& text) {
  std::ofstream(path, std::ios::binary) << text;
}

// The fields of one CSV line; a field in double quotes may hold commas (the quotes are dropped).
inline std::vector<std::string> csv_fields(const std::string& line) {
  std::vector<std::string> fields(1);
  bool quoted = false;
  for (char c : line) {
    if (c == '"') {
      quoted = !quoted;
    } else if (c == ',' && !quoted) {
      fields.emplace_back();
    } else {
      fields.back() += c;
    }
  }
  return fields;
}

// Every line of a CSV file, split into fields; empty when the file cannot be read.
inline std::vector<std::vector<std::string>> read_csv(const std::filesystem::path& path) {
  std::ifstream in(path);
  std::vector<std::vector<std::string>> rows;
  for (std::string line; std::getline(in, line);) rows.push_back(csv_fields(line));
  return rows;
}

// The values of the column `name` of read_csv's rows, below the header; throws
// std::invalid_argument when there is no such column.
inline std::vector<double> csv_column(const std::vector<std::vector<std::string>>& rows,
                                      const std::string& name) {
  const auto& header = rows.at(0);
  const auto found = std::find(header.begin(), header.end(), name);
  if (found == header.end()) throw std::invalid_argument("no CSV column " + name);
  const auto column = static_cast<std::size_t>(found - header.begin());
  std::vector<double> values;
  for (std::size_t i = 1; i < rows.size(); ++i) values.push_back(std::stod(rows[i].at(column)));
  return values;
}

}  // namespace weft::test_files
