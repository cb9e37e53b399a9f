#include "app/scene/json_reader.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "app/io/input_error.h"
#include "base/constants.h"

namespace weft::app {
namespace {

// Where a value sits: file and key path, for error messages.
struct Where {
  const std::string& file;
  std::string path;
};

[[noreturn]] void fail(const Where& where, const std::string& what) {
  throw_scene_error(where.file, where.path, what);
}

// Numbers as a person would write them: integers without a decimal point, else 10 digits.
std::string format_number(double x) {
  char buffer[32];
  std::snprintf(buffer, sizeof buffer, "%.10g", x);
  return buffer;
}

std::string shorten(std::string text, std::size_t limit = 60) {
  if (text.size() > limit) text = text.substr(0, limit) + "…";
  return text;
}

// A JSON value as it appears after "got": 1.5, true, null, the string '5 mm', the array [1,2].
std::string describe(const Json& v) {
  if (v.is_string()) return "the string '" + shorten(v.get<std::string>()) + "'";
  if (v.is_array()) {
    const std::string dump = v.dump();
    if (dump.size() <= 40) return "the array " + dump;
    return "an array of " + std::to_string(v.size()) + " elements";
  }
  if (v.is_object()) return v.empty() ? "an empty object" : "an object";
  return shorten(v.dump());
}

// "a number" + " > 0".
std::string bounded(const std::string& what, const Range& range, const std::string& unit = "") {
  if (range.unbounded()) return what;
  return what + " " + range.text() + (unit.empty() ? "" : " " + unit);
}

double read_number(const Json& v, const Where& where, const Range& range) {
  if (!v.is_number())
    fail(where, "expected " + bounded("a number", range) + ", got " + describe(v));
  const double x = v.get<double>();
  if (!std::isfinite(x)) fail(where, "expected a finite number, got " + describe(v));
  if (!range.contains(x))
    fail(where, "expected " + bounded("a number", range) + ", got " + v.dump());
  return x;
}

std::int64_t read_integer(const Json& v, const Where& where, const Range& range) {
  const auto wrong = [&]() {
    fail(where, "expected " + bounded("an integer", range) + ", got " + describe(v));
  };
  std::int64_t n = 0;
  if (v.is_number_unsigned()) {
    const auto u = v.get<std::uint64_t>();
    if (u > static_cast<std::uint64_t>(std::numeric_limits<std::int64_t>::max())) wrong();
    n = static_cast<std::int64_t>(u);
  } else if (v.is_number_integer()) {
    n = v.get<std::int64_t>();
  } else if (v.is_number_float()) {
    const double x = v.get<double>();
    if (!std::isfinite(x) || std::floor(x) != x || std::fabs(x) > 9.0e15) wrong();
    n = static_cast<std::int64_t>(x);
  } else {
    wrong();
  }
  if (!range.contains(static_cast<double>(n))) wrong();
  return n;
}

// A quantity: a number in SI units or a string with units. `alternative` (e.g. "'auto' or ")
// is prefixed to what is expected.
double read_quantity(const Json& v, const Where& where, Quantity kind, const Range& range,
                     const std::string& alternative = "") {
  double x = 0.0;
  if (v.is_number()) {
    x = v.get<double>();
    if (!std::isfinite(x)) fail(where, "expected a finite number, got " + describe(v));
  } else if (v.is_string()) {
    try {
      x = parse_quantity(v.get<std::string>(), kind);
    } catch (const UnitError& e) {
      fail(where, "expected " + alternative + (e.what() + std::string("expected ").size()));
    }
  } else {
    fail(where, "expected " + alternative + quantity_description(kind) +
                    " (a number in SI units or a string with a unit), got " + describe(v));
  }
  if (!range.contains(x)) {
    const std::string got = v.is_string() ? "'" + v.get<std::string>() + "' = " + format_number(x) +
                                                " " + si_unit_symbol(kind)
                                          : v.dump();
    fail(where,
         "expected " + bounded(quantity_name(kind), range, si_unit_symbol(kind)) + ", got " + got);
  }
  return x;
}

// A fixed-length array whose elements are read by `one(element, where)`.
template <class T, class ReadOne>
std::vector<T> read_array(const Json& v, const Where& where, std::size_t count,
                          const std::string& expected, ReadOne one) {
  if (!v.is_array() || v.size() != count)
    fail(where, "expected " + expected + ", got " + describe(v));
  std::vector<T> out;
  for (std::size_t i = 0; i < count; ++i)
    out.push_back(one(v[i], Where{where.file, where.path + "[" + std::to_string(i) + "]"}));
  return out;
}

std::string array_of(std::size_t count, const std::string& elements) {
  return "an array of " + std::to_string(count) + " " + elements;
}

}  // namespace

// Levenshtein distance, for "did you mean" hints.
std::size_t edit_distance(const std::string& a, const std::string& b) {
  std::vector<std::size_t> row(b.size() + 1);
  for (std::size_t j = 0; j <= b.size(); ++j) row[j] = j;
  for (std::size_t i = 1; i <= a.size(); ++i) {
    std::size_t diagonal = row[0];
    row[0] = i;
    for (std::size_t j = 1; j <= b.size(); ++j) {
      const std::size_t above = row[j];
      row[j] = std::min({row[j] + 1, row[j - 1] + 1, diagonal + (a[i - 1] == b[j - 1] ? 0 : 1)});
      diagonal = above;
    }
  }
  return row[b.size()];
}

// The candidate closest to `key` within two edits, or empty.
std::string closest(const std::string& key, const std::vector<std::string>& candidates) {
  std::string best;
  std::size_t best_distance = 3;
  for (const auto& c : candidates) {
    const std::size_t d = edit_distance(key, c);
    if (d < best_distance && c != key) {
      best = c;
      best_distance = d;
    }
  }
  return best;
}

namespace {

std::string join(const std::vector<std::string>& items, const std::string& quote = "") {
  std::string out;
  for (const auto& s : items) out += (out.empty() ? "" : ", ") + quote + s + quote;
  return out;
}

// First pass over the text with nlohmann's SAX interface: finds the position of a syntax
// error, duplicate keys and numbers that overflow a double, with the key path of each.
class StrictChecker : public nlohmann::json_sax<Json> {
 public:
  std::string error_path;       // key path of the offending value
  std::string error_message;    // what is wrong
  std::size_t error_index = 0;  // byte index into the text, for syntax errors and overflow
  bool positioned = false;      // whether error_index is meaningful

  bool null() override { return value(); }
  bool boolean(bool) override { return value(); }
  bool number_integer(number_integer_t) override { return value(); }
  bool number_unsigned(number_unsigned_t) override { return value(); }
  bool number_float(number_float_t, const string_t&) override { return value(); }
  bool string(string_t&) override { return value(); }
  bool binary(binary_t&) override { return value(); }
  bool start_object(std::size_t) override {
    value();
    m_stack.push_back({false, "", -1, {}});
    return true;
  }
  bool key(string_t& key) override {
    Frame& top = m_stack.back();
    top.key = key;
    if (top.keys.insert(key).second) return true;
    error_path = path(false);
    error_message = "duplicate key (each key may appear once in an object)";
    return false;
  }
  bool end_object() override { return pop(); }
  bool start_array(std::size_t) override {
    value();
    m_stack.push_back({true, "", -1, {}});
    return true;
  }
  bool end_array() override { return pop(); }
  bool parse_error(std::size_t position, const std::string& last_token,
                   const nlohmann::detail::exception& e) override {
    positioned = true;
    if (e.id == 406) {  // out_of_range.406: number overflow; point at the number's start
      error_index = position >= last_token.size() ? position - last_token.size() : 0;
      error_path = path(true);
      error_message = "expected a finite number, got " + last_token + " (too large for a double)";
      return false;
    }
    error_index = position > 0 ? position - 1 : 0;
    const std::string what = e.what();
    const std::size_t column = what.find("column ");
    const std::size_t colon = what.find(": ", column == std::string::npos ? 0 : column);
    error_message =
        "malformed JSON: " + (colon == std::string::npos ? what : what.substr(colon + 2));
    return false;
  }

 private:
  struct Frame {
    bool is_array;
    std::string key;  // objects: the current key
    long index;       // arrays: the current element
    std::set<std::string> keys;
  };

  bool value() {
    if (!m_stack.empty() && m_stack.back().is_array) ++m_stack.back().index;
    return true;
  }
  bool pop() {
    m_stack.pop_back();
    return true;
  }
  // The path of the current value; `pending` counts an array element not yet started.
  std::string path(bool pending) const {
    std::string out;
    for (std::size_t k = 0; k < m_stack.size(); ++k) {
      const Frame& f = m_stack[k];
      if (f.is_array) {
        const long i = f.index + (pending && k + 1 == m_stack.size() ? 1 : 0);
        out += "[" + std::to_string(i) + "]";
      } else {
        out += (out.empty() ? "" : ".") + f.key;
      }
    }
    return out;
  }

  std::vector<Frame> m_stack;
};

// 1-based line and column (in characters, not bytes) of a byte index.
std::pair<std::size_t, std::size_t> line_column(const std::string& text, std::size_t index) {
  index = std::min(index, text.size());
  std::size_t line = 1, column = 1;
  for (std::size_t i = 0; i < index; ++i) {
    if (text[i] == '\n') {
      ++line;
      column = 1;
    } else if ((static_cast<unsigned char>(text[i]) & 0xC0) != 0x80) {
      ++column;
    }
  }
  return {line, column};
}

// Throws when arrays and objects nest deeper than max_json_depth: nlohmann's dump() and the
// readers walk a value recursively, so a hostile file could otherwise overflow the stack.
void check_json_depth(const std::string& text, const std::string& file) {
  std::size_t depth = 0;
  bool in_string = false, escaped = false;
  for (std::size_t i = 0; i < text.size(); ++i) {
    const char c = text[i];
    if (in_string) {
      if (escaped) escaped = false;
      else if (c == '\\') escaped = true;
      else if (c == '"') in_string = false;
    } else if (c == '"') {
      in_string = true;
    } else if (c == '[' || c == '{') {
      if (++depth <= max_json_depth) continue;
      const auto [line, column] = line_column(text, i);
      throw_scene_error(file + ":" + std::to_string(line) + ":" + std::to_string(column), "",
                        "arrays and objects nest deeper than " + std::to_string(max_json_depth) +
                            " levels (the limit of weft's JSON reader)");
    } else if ((c == ']' || c == '}') && depth > 0) {
      --depth;
    }
  }
}

}  // namespace

void throw_scene_error(const std::string& file, const std::string& path, const std::string& what) {
  throw InputError(file + ": " + (path.empty() ? "" : path + ": ") + what);
}

Json parse_json(const std::string& text, const std::string& file) {
  check_json_depth(text, file);
  StrictChecker checker;
  if (!Json::sax_parse(text, &checker)) {
    if (!checker.positioned) throw_scene_error(file, checker.error_path, checker.error_message);
    const auto [line, column] = line_column(text, checker.error_index);
    throw_scene_error(file + ":" + std::to_string(line) + ":" + std::to_string(column),
                      checker.error_path, checker.error_message);
  }
  try {
    return Json::parse(text);
  } catch (const Json::exception& e) {  // not expected after the first pass
    throw_scene_error(file, "", std::string("malformed JSON: ") + e.what());
  }
}

bool Range::contains(double x) const {
  const bool above = min_open ? x > min : x >= min;
  const bool below = max_open ? x < max : x <= max;
  return above && below;
}

bool Range::unbounded() const {
  return std::isinf(min) && std::isinf(max);
}

std::string Range::text() const {
  const bool has_min = !std::isinf(min), has_max = !std::isinf(max);
  if (has_min && has_max)
    return std::string("in ") + (min_open ? "(" : "[") + format_number(min) + ", " +
           format_number(max) + (max_open ? ")" : "]");
  if (has_min) return (min_open ? "> " : "≥ ") + format_number(min);
  if (has_max) return (max_open ? "< " : "≤ ") + format_number(max);
  return "";
}

ObjectReader::ObjectReader(const Json& object, std::string file, std::string path)
    : m_object(&object), m_file(std::move(file)), m_path(std::move(path)) {}

ObjectReader ObjectReader::root(const Json& document, const std::string& file) {
  if (!document.is_object())
    throw_scene_error(file, "",
                      "expected a JSON object at the top level, got " + describe(document));
  return ObjectReader(document, file, "");
}

std::string ObjectReader::path_of(const std::string& key) const {
  return m_path.empty() ? key : m_path + "." + key;
}

void ObjectReader::fail(const std::string& key, const std::string& what) const {
  throw_scene_error(m_file, path_of(key), what);
}

const Json* ObjectReader::find(const std::string& key) {
  if (std::find(m_known.begin(), m_known.end(), key) == m_known.end()) m_known.push_back(key);
  const auto it = m_object->find(key);
  if (it == m_object->end()) return nullptr;
  m_read.insert(key);
  return &*it;
}

const Json* ObjectReader::find(const std::string& key, bool is_required,
                               const std::string& expected) {
  const Json* v = find(key);
  if (v || !is_required) return v;
  std::vector<std::string> unread;
  for (auto it = m_object->begin(); it != m_object->end(); ++it)
    if (!m_read.count(it.key())) unread.push_back(it.key());
  const std::string near = closest(key, unread);
  fail(key, "required key is missing (expected " + expected + ")" +
                (near.empty() ? "" : "; is '" + near + "' a misspelling?"));
}

bool ObjectReader::has(const std::string& key) {
  if (std::find(m_known.begin(), m_known.end(), key) == m_known.end()) m_known.push_back(key);
  return m_object->contains(key);
}

bool ObjectReader::holds_boolean(const std::string& key) {
  return has(key) && m_object->at(key).is_boolean();
}

std::string ObjectReader::string(const std::string& key, std::optional<std::string> fallback) {
  const Json* v = find(key, !fallback, "a string");
  if (!v) return *fallback;
  if (!v->is_string()) fail(key, "expected a string, got " + describe(*v));
  return v->get<std::string>();
}

bool ObjectReader::boolean(const std::string& key, std::optional<bool> fallback) {
  const Json* v = find(key, !fallback, "true or false");
  if (!v) return *fallback;
  if (!v->is_boolean()) fail(key, "expected true or false, got " + describe(*v));
  return v->get<bool>();
}

double ObjectReader::number(const std::string& key, std::optional<double> fallback,
                            const Range& range) {
  const Json* v = find(key, !fallback, bounded("a number", range));
  return v ? read_number(*v, Where{m_file, path_of(key)}, range) : *fallback;
}

std::int64_t ObjectReader::integer(const std::string& key, std::optional<std::int64_t> fallback,
                                   const Range& range) {
  const Json* v = find(key, !fallback, bounded("an integer", range));
  return v ? read_integer(*v, Where{m_file, path_of(key)}, range) : *fallback;
}

double ObjectReader::quantity(const std::string& key, Quantity kind, std::optional<double> fallback,
                              const Range& range) {
  const Json* v = find(key, !fallback, quantity_description(kind));
  return v ? read_quantity(*v, Where{m_file, path_of(key)}, kind, range) : *fallback;
}

std::optional<double> ObjectReader::quantity_or_keyword(const std::string& key, Quantity kind,
                                                        const std::vector<std::string>& keywords,
                                                        const Range& range) {
  const Json* v = find(key);
  if (!v) return std::nullopt;
  std::string alternatives;  // "'auto', 'adaptive' or "
  for (std::size_t k = 0; k < keywords.size(); ++k) {
    if (v->is_string() && v->get<std::string>() == keywords[k]) return std::nullopt;
    alternatives += "'" + keywords[k] + (k + 1 < keywords.size() ? "', " : "' or ");
  }
  return read_quantity(*v, Where{m_file, path_of(key)}, kind, range, alternatives);
}

bool ObjectReader::holds_keyword(const std::string& key, const std::string& keyword) {
  return has(key) && m_object->at(key).is_string() && m_object->at(key).get<std::string>() == keyword;
}

double ObjectReader::angle_deg(const std::string& key, std::optional<double> fallback_deg,
                               const Range& range_deg) {
  const std::string expected = "an angle: a number in degrees or a string such as '40 deg'";
  const Json* v = find(key, !fallback_deg, expected);
  if (!v) return *fallback_deg;
  const Where where{m_file, path_of(key)};
  double degrees = 0.0;
  if (v->is_number()) {
    degrees = read_number(*v, where, Range{});
  } else if (v->is_string()) {
    degrees = read_quantity(*v, where, Quantity::angle, Range{}) * 180.0 / base::kPi;
  } else {
    fail(key, "expected " + expected + ", got " + describe(*v));
  }
  if (!range_deg.contains(degrees))
    fail(key, "expected " + bounded("an angle", range_deg, "deg") + ", got " +
                  (v->is_string() ? "'" + v->get<std::string>() + "'" : v->dump()));
  return degrees;
}

std::vector<double> ObjectReader::numbers(const std::string& key, std::size_t count,
                                          std::optional<std::vector<double>> fallback,
                                          const Range& range) {
  const std::string expected = array_of(count, bounded("numbers", range));
  const Json* v = find(key, !fallback, expected);
  if (!v) return *fallback;
  return read_array<double>(
      *v, Where{m_file, path_of(key)}, count, expected,
      [&](const Json& e, const Where& w) { return read_number(e, w, range); });
}

std::vector<std::int64_t> ObjectReader::integers(const std::string& key, std::size_t count,
                                                 std::optional<std::vector<std::int64_t>> fallback,
                                                 const Range& range) {
  const std::string expected = array_of(count, bounded("integers", range));
  const Json* v = find(key, !fallback, expected);
  if (!v) return *fallback;
  return read_array<std::int64_t>(
      *v, Where{m_file, path_of(key)}, count, expected,
      [&](const Json& e, const Where& w) { return read_integer(e, w, range); });
}

std::vector<double> ObjectReader::quantities(const std::string& key, Quantity kind,
                                             std::size_t count,
                                             std::optional<std::vector<double>> fallback,
                                             const Range& range) {
  const std::string expected = array_of(count, "values, each " + quantity_description(kind));
  const Json* v = find(key, !fallback, expected);
  if (!v) return *fallback;
  return read_array<double>(
      *v, Where{m_file, path_of(key)}, count, expected,
      [&](const Json& e, const Where& w) { return read_quantity(e, w, kind, range); });
}

std::size_t ObjectReader::array_length(const std::string& key) {
  const Json* v = find(key, true, "a non-empty array");
  if (!v->is_array() || v->size() == 0) fail(key, "expected a non-empty array, got " + describe(*v));
  return v->size();
}

Eigen::MatrixXd ObjectReader::matrix(const std::string& key, int rows, int cols) {
  const std::string row = array_of(static_cast<std::size_t>(cols), "numbers");
  const std::string expected =
      array_of(static_cast<std::size_t>(rows), "rows") + ", each " + row;
  const Json* v = find(key, true, expected);
  const auto values = read_array<std::vector<double>>(
      *v, Where{m_file, path_of(key)}, static_cast<std::size_t>(rows), expected,
      [&](const Json& r, const Where& w) {
        return read_array<double>(r, w, static_cast<std::size_t>(cols), row,
                                  [](const Json& e, const Where& we) { return read_number(e, we, {}); });
      });
  Eigen::MatrixXd m(rows, cols);
  for (int i = 0; i < rows; ++i)
    for (int j = 0; j < cols; ++j) m(i, j) = values[static_cast<std::size_t>(i)][static_cast<std::size_t>(j)];
  return m;
}

Eigen::Vector3d ObjectReader::vec3(const std::string& key, std::optional<Eigen::Vector3d> fallback,
                                   const Range& range) {
  std::optional<std::vector<double>> f;
  if (fallback) f = std::vector<double>{fallback->x(), fallback->y(), fallback->z()};
  const auto v = numbers(key, 3, f, range);
  return {v[0], v[1], v[2]};
}

Eigen::Vector3d ObjectReader::unit_vec3(const std::string& key,
                                        std::optional<Eigen::Vector3d> fallback) {
  const Eigen::Vector3d axis = vec3(key, fallback);
  const double length = axis.norm();
  if (std::fabs(length - 1.0) > unit_tolerance) {
    char got[96];
    std::snprintf(got, sizeof got, "[%g, %g, %g] (length %.9g)", axis.x(), axis.y(), axis.z(),
                  length);
    fail(key, std::string("expected a unit vector, got ") + got);
  }
  return axis / length;
}

Eigen::Vector3d ObjectReader::quantity_vec3(const std::string& key, Quantity kind,
                                            std::optional<Eigen::Vector3d> fallback) {
  std::optional<std::vector<double>> f;
  if (fallback) f = std::vector<double>{fallback->x(), fallback->y(), fallback->z()};
  const auto v = quantities(key, kind, 3, f);
  return {v[0], v[1], v[2]};
}

std::size_t ObjectReader::enumeration_index(const std::string& key,
                                            const std::vector<std::string>& names,
                                            bool is_required) {
  const std::string expected = base::choices_text(names);
  const Json* v = find(key, is_required, expected);
  if (!v) return names.size();
  if (v->is_string()) {
    const auto it = std::find(names.begin(), names.end(), v->get<std::string>());
    if (it != names.end()) return static_cast<std::size_t>(it - names.begin());
  }
  fail(key, "expected " + expected + ", got " + describe(*v));
}

ObjectReader ObjectReader::object(const std::string& key) {
  static const Json empty = Json::object();
  const Json* v = find(key);
  if (!v) return ObjectReader(empty, m_file, path_of(key));
  if (!v->is_object()) fail(key, "expected an object, got " + describe(*v));
  return ObjectReader(*v, m_file, path_of(key));
}

ObjectReader ObjectReader::required_object(const std::string& key) {
  find(key, true, "an object");
  return object(key);
}

std::vector<ObjectReader> ObjectReader::objects(const std::string& key) {
  const Json* v = find(key);
  std::vector<ObjectReader> out;
  if (!v) return out;
  if (!v->is_array()) fail(key, "expected an array of objects, got " + describe(*v));
  for (std::size_t i = 0; i < v->size(); ++i) {
    const std::string path = path_of(key) + "[" + std::to_string(i) + "]";
    if (!(*v)[i].is_object())
      throw_scene_error(m_file, path, "expected an object, got " + describe((*v)[i]));
    out.emplace_back((*v)[i], m_file, path);
  }
  return out;
}

void ObjectReader::finish() const {
  for (auto it = m_object->begin(); it != m_object->end(); ++it) {
    const std::string& key = it.key();
    if (m_read.count(key)) continue;
    const bool known = std::find(m_known.begin(), m_known.end(), key) != m_known.end();
    if (known) fail(key, "this key is not used here");
    const std::string near = closest(key, m_known);
    fail(key, "unknown key" + (near.empty() ? "" : "; did you mean '" + near + "'?") +
                  (m_known.empty() ? " (no keys are accepted here)"
                                   : " (known keys here: " + join(m_known) + ")"));
  }
}

Eigen::Vector3f read_color(ObjectReader& r, const std::string& key,
                           const Eigen::Vector3f& fallback) {
  return r.vec3(key, fallback.cast<double>(), Range::closed(0.0, 1.0)).cast<float>();
}

}  // namespace weft::app
