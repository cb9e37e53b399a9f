#pragma once
// The one helper through which every key of a scene file is read.
//
// An ObjectReader wraps one JSON object with the file name and the object's key path
// ("cloth.material"). Each accessor reads one key, checks its type and range and converts
// quantities to SI; finish() then rejects any key that was not read. Every error is a
// InputError reading "FILE: KEY.PATH: expected …, got …".

#include <Eigen/Core>
#include <cstdint>
#include <limits>
#include <nlohmann/json.hpp>
#include <optional>
#include <set>
#include <string>
#include <utility>
#include <vector>

#include "app/scene/units.h"
#include "base/enum_names.h"

namespace weft::app {

// Levenshtein distance between two names.
std::size_t edit_distance(const std::string& a, const std::string& b);
// The candidate closest to `key` within two edits (not `key` itself), or empty: the "did you
// mean" of an unknown key or command.
std::string closest(const std::string& key, const std::vector<std::string>& candidates);

// Keeps the file's key order, so that "the first unknown key" is the first in the file.
using Json = nlohmann::ordered_json;

// How deeply arrays and objects may nest in a JSON text weft reads (scene files need 6).
inline constexpr std::size_t max_json_depth = 64;

// Parses JSON text strictly. A syntax error reads "FILE:LINE:COLUMN: malformed JSON: …"; a
// duplicate key or a number too large for a double is an error naming its key path too, and
// nesting deeper than max_json_depth an error at its line and column.
Json parse_json(const std::string& text, const std::string& file);

// Throws InputError("FILE: PATH: what"), or "FILE: what" when the path is empty.
[[noreturn]] void throw_scene_error(const std::string& file, const std::string& path,
                                    const std::string& what);

// Pass as the fallback of an accessor to make its key required.
inline constexpr std::nullopt_t required = std::nullopt;

// An interval of accepted values, e.g. Range::gt(0).le(1) for (0, 1]. Default: everything.
struct Range {
  double min = -std::numeric_limits<double>::infinity();
  double max = std::numeric_limits<double>::infinity();
  bool min_open = false, max_open = false;

  static Range gt(double a) { return {a, std::numeric_limits<double>::infinity(), true, false}; }
  static Range ge(double a) { return {a, std::numeric_limits<double>::infinity(), false, false}; }
  static Range closed(double a, double b) { return {a, b, false, false}; }
  Range lt(double b) const { return {min, b, min_open, true}; }
  Range le(double b) const { return {min, b, min_open, false}; }

  bool contains(double x) const;
  bool unbounded() const;
  std::string text() const;  // "> 0", "≥ 0", "in (0, 1]"; empty when unbounded
};

class ObjectReader {
 public:
  // `object` must be a JSON object and outlive the reader and the readers made from it.
  // `path` is the object's key path, empty for the top level.
  ObjectReader(const Json& object, std::string file, std::string path);
  // The top level of a document; an error unless it is an object.
  static ObjectReader root(const Json& document, const std::string& file);

  const std::string& file() const { return m_file; }
  const std::string& path() const { return m_path; }
  std::string path_of(const std::string& key) const;  // "cloth.material" + "density"

  // Whether the key is present. Declares it known but does not read it.
  bool has(const std::string& key);
  // Whether the key is present and holds a boolean (for keys such as "ground": false | {…}).
  bool holds_boolean(const std::string& key);

  // Each accessor returns `fallback` when the key is absent; with `required` it is an error.
  std::string string(const std::string& key, std::optional<std::string> fallback);
  bool boolean(const std::string& key, std::optional<bool> fallback);
  double number(const std::string& key, std::optional<double> fallback, const Range& range = {});
  // An integer value (a float such as 3.0 counts); `range` bounds it.
  std::int64_t integer(const std::string& key, std::optional<std::int64_t> fallback,
                       const Range& range);
  // A number in SI units or a string with units (app/scene/units.h), converted to SI; `range` is in SI.
  double quantity(const std::string& key, Quantity kind, std::optional<double> fallback,
                  const Range& range = {});
  // A quantity or one of the strings `keywords` (e.g. "auto"); absent or a keyword give nullopt
  // (holds_keyword() tells which).
  std::optional<double> quantity_or_keyword(const std::string& key, Quantity kind,
                                            const std::vector<std::string>& keywords,
                                            const Range& range = {});
  // Whether the key is present and holds exactly the string `keyword`.
  bool holds_keyword(const std::string& key, const std::string& keyword);
  // An angle in degrees: a bare number is in degrees (the one exception to "numbers are SI"),
  // a string has units ("40 deg", "0.7 rad"). `range` is in degrees.
  double angle_deg(const std::string& key, std::optional<double> fallback_deg,
                   const Range& range_deg = {});

  // Fixed-length arrays; each element checked as above, its path "key[i]".
  std::vector<double> numbers(const std::string& key, std::size_t count,
                              std::optional<std::vector<double>> fallback, const Range& range = {});
  std::vector<std::int64_t> integers(const std::string& key, std::size_t count,
                                     std::optional<std::vector<std::int64_t>> fallback,
                                     const Range& range);
  std::vector<double> quantities(const std::string& key, Quantity kind, std::size_t count,
                                 std::optional<std::vector<double>> fallback,
                                 const Range& range = {});
  // The length of the array at `key` (required; not an array, or empty: an error).
  std::size_t array_length(const std::string& key);
  Eigen::Vector3d vec3(const std::string& key, std::optional<Eigen::Vector3d> fallback,
                       const Range& range = {});
  Eigen::Vector3d quantity_vec3(const std::string& key, Quantity kind,
                                std::optional<Eigen::Vector3d> fallback);
  // A unit direction: normalised when within unit_tolerance of unit length, an error otherwise.
  Eigen::Vector3d unit_vec3(const std::string& key, std::optional<Eigen::Vector3d> fallback);
  static constexpr double unit_tolerance = 1e-6;  // how far from unit length an axis may be

  // A required rows × cols matrix written as an array of rows, each an array of numbers
  // ([[a, b], [c, d]]); element paths "key[i][j]".
  Eigen::MatrixXd matrix(const std::string& key, int rows, int cols);

  // A string naming one of an enum's values, through its base::EnumNames table
  // (base/enum_names.h); the error lists the names in the table's order.
  template <class E, std::size_t N>
  E enumeration(const std::string& key, const base::EnumNames<E, N>& names,
                std::optional<E> fallback);
  // A string naming one of `choices`, values that are no enum (a material preset, a bool);
  // the error lists them.
  template <class T>
  T choice(const std::string& key, const std::vector<std::pair<std::string, T>>& choices,
           std::optional<T> fallback);

  // A nested object. When absent, a reader over an empty object: every key takes its default.
  ObjectReader object(const std::string& key);
  ObjectReader required_object(const std::string& key);
  // An array of objects, paths "key[0]", "key[1]", …; absent gives none.
  std::vector<ObjectReader> objects(const std::string& key);

  // Throws for the first key in the object that no accessor read, listing the known keys.
  void finish() const;
  // Throws InputError for `key` of this object: "FILE: PATH.key: what".
  [[noreturn]] void fail(const std::string& key, const std::string& what) const;

 private:
  // The value of `key`, marked read; nullptr when absent. Declares the key known either way.
  const Json* find(const std::string& key);
  // As find(), but a missing key is an error saying what was `expected`.
  const Json* find(const std::string& key, bool is_required, const std::string& expected);
  std::size_t enumeration_index(const std::string& key, const std::vector<std::string>& names,
                                bool is_required);

  const Json* m_object;
  std::string m_file;
  std::string m_path;
  std::vector<std::string> m_known;  // keys asked for, in order: listed by finish()
  std::set<std::string> m_read;
};

template <class T>
T ObjectReader::choice(const std::string& key, const std::vector<std::pair<std::string, T>>& choices,
                       std::optional<T> fallback) {
  std::vector<std::string> names;
  for (const auto& c : choices) names.push_back(c.first);
  const std::size_t k = enumeration_index(key, names, !fallback.has_value());
  return k < choices.size() ? choices[k].second : *fallback;
}

template <class E, std::size_t N>
E ObjectReader::enumeration(const std::string& key, const base::EnumNames<E, N>& names,
                            std::optional<E> fallback) {
  const std::size_t k = enumeration_index(key, base::enum_name_list(names), !fallback.has_value());
  return k < names.size() ? names[k].value : *fallback;
}

// An RGB colour in 0..1 at `key` (the fallback when absent), as the renderer keeps it.
Eigen::Vector3f read_color(ObjectReader& r, const std::string& key, const Eigen::Vector3f& fallback);

}  // namespace weft::app
