#pragma once
// No non-finite number reaches an output (docs/reliability.md): every CSV file weft writes goes
// through write_text (app/io/output_files.h), which checks its cells here, and every JSON
// document is checked before it is written or printed. A value that overflowed (a density of
// 1.7e308 kg/m^2 used to write gravity_energy_J = inf in stats.csv) is an error naming the file,
// the row and the column, not a file that other tools read as a number.

#include <cmath>
#include <cstddef>
#include <string>

namespace weft::app {

// Throws std::runtime_error: "WHERE: … is not a finite number", and why none is written.
[[noreturn]] void throw_non_finite(const std::string& where);

// Throws std::runtime_error naming `file`, the line (with its first cell: the frame, run or
// point) and the header's column of the first cell that is "inf", "-inf", "nan" or another
// spelling of a non-finite number (any case, either sign).
void require_finite_csv(const std::string& file, const std::string& text);

// The JSON pointer of the first non-finite number in `document` (nlohmann/json would write it
// as null), or "" when every number is finite.
template <class Json>
std::string first_non_finite_number(const Json& document, const std::string& where = "") {
  if (document.is_number_float() && !std::isfinite(document.template get<double>()))
    return where.empty() ? "/" : where;
  if (document.is_object())
    for (const auto& [key, value] : document.items())
      if (std::string at = first_non_finite_number(value, where + "/" + key); !at.empty())
        return at;
  if (document.is_array())
    for (std::size_t k = 0; k < document.size(); ++k)
      if (std::string at = first_non_finite_number(document[k], where + "/" + std::to_string(k));
          !at.empty())
        return at;
  return "";
}

// Throws std::runtime_error naming `what` and the path to the first non-finite number of
// `document`.
template <class Json>
void require_finite_json(const Json& document, const std::string& what) {
  if (const std::string at = first_non_finite_number(document); !at.empty())
    throw_non_finite(what + ": " + at);
}

// `document` as text, indented by `indent`, after require_finite_json(document, what): what
// weft prints (--json) or writes as a .json file goes through here.
template <class Json>
std::string finite_json_text(const Json& document, const std::string& what, int indent = 2) {
  require_finite_json(document, what);
  return document.dump(indent);
}

}  // namespace weft::app
