#include "app/io/finite_outputs.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <sstream>
#include <stdexcept>
#include <vector>

namespace weft::app {

namespace {

std::vector<std::string> csv_cells(const std::string& line) {
  std::vector<std::string> cells;
  std::stringstream in(line);
  std::string cell;
  while (std::getline(in, cell, ',')) cells.push_back(cell);
  return cells;
}

// "inf", "-inf", "+infinity", "nan", "-nan(ind)" …: what printf and streams write for a
// non-finite double.
bool non_finite_cell(std::string cell) {
  std::transform(cell.begin(), cell.end(), cell.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  if (!cell.empty() && (cell[0] == '-' || cell[0] == '+')) cell.erase(0, 1);
  return cell == "inf" || cell == "infinity" || cell == "nan" || cell.rfind("nan(", 0) == 0;
}

}  // namespace

void throw_non_finite(const std::string& where) {
  throw std::runtime_error(where + " is not a finite number: weft writes no non-finite number "
                           "(docs/reliability.md: an input beyond what the computation holds, "
                           "or a fault of weft's)");
}

void require_finite_csv(const std::string& file, const std::string& text) {
  // Numbers alone below the header (stats.csv, rewritten with each frame): no 'i' or 'n' to
  // look into.
  if (text.find_first_of("iInN", text.find('\n')) == std::string::npos) return;
  std::stringstream in(text);
  std::string line;
  std::vector<std::string> header;
  for (long number = 1; std::getline(in, line); ++number) {
    const std::vector<std::string> cells = csv_cells(line);
    if (number == 1) header = cells;
    for (std::size_t c = 0; c < cells.size(); ++c) {
      if (!non_finite_cell(cells[c])) continue;
      const bool named = number > 1 && c < header.size();
      const std::string column = named ? header[c] : "column " + std::to_string(c + 1);
      const std::string row = named && c > 0 ? " (" + header[0] + " " + cells[0] + ")" : "";
      throw_non_finite(file + ": line " + std::to_string(number) + row + ", " + column + ": '" +
                       cells[c] + "'");
    }
  }
}

}  // namespace weft::app
