#include "app/scene/units.h"

#include <charconv>
#include <cmath>
#include <system_error>

#include "base/constants.h"

namespace weft::app {
namespace {
constexpr Dimension mass{1, 0, 0};
constexpr Dimension length{0, 1, 0};
constexpr Dimension time{0, 0, 1};
constexpr Dimension force{1, 1, -2};      // N = kg·m·s⁻²
constexpr Dimension pressure{1, -1, -2};  // Pa = N/m²: also a weight per area
constexpr Dimension none{0, 0, 0};
constexpr double gram_force_N = 1e-3 * standard_gravity_m_s2;

Unit multiply(const Unit& a, const Unit& b) {
  return {a.factor * b.factor,
          {a.dimension.mass + b.dimension.mass, a.dimension.length + b.dimension.length,
           a.dimension.time + b.dimension.time}};
}

Unit power(const Unit& u, int n) {
  Unit out{1.0, {u.dimension.mass * n, u.dimension.length * n, u.dimension.time * n}};
  for (int k = 0; k < std::abs(n); ++k) out.factor *= u.factor;
  if (n < 0) out.factor = 1.0 / out.factor;
  return out;
}

Unit divide(const Unit& a, const Unit& b) {
  return multiply(a, power(b, -1));
}

bool is_space(char c) {
  return c == ' ' || c == '\t';
}
bool is_letter(char c) {
  return (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z');
}
bool is_digit(char c) {
  return c >= '0' && c <= '9';
}

std::string_view trim(std::string_view s) {
  while (!s.empty() && is_space(s.front())) s.remove_prefix(1);
  while (!s.empty() && is_space(s.back())) s.remove_suffix(1);
  return s;
}

std::string known_unit_names() {
  std::string names;
  for (const auto& u : unit_table()) names += (names.empty() ? "" : " ") + std::string(u.name);
  return names;
}

// Recursive descent over a unit expression:
//   expression := ['/' factor | factor] { ('*' | '·' | '/' | spaces) factor }
//   factor     := atom [ '^' ['+'|'-'] digits | '²' | '³' ]
//   atom       := name | '1' | '(' expression ')'
class UnitParser {
 public:
  explicit UnitParser(std::string_view text) : m_text(text) {}

  Unit parse() {
    skip_spaces();
    if (at_end()) throw UnitError("empty unit expression");
    const Unit u = expression();
    if (!at_end()) fail("unexpected ')'");
    return u;
  }

 private:
  Unit expression() {
    skip_spaces();
    Unit result = peek() == '/' ? Unit{} : factor();
    for (;;) {
      const bool spaced = skip_spaces();
      if (at_end() || peek() == ')') return result;
      if (consume("*") || consume("\xC2\xB7")) {  // '·' U+00B7
        result = multiply(result, factor());
      } else if (consume("/")) {
        result = divide(result, factor());
      } else if (spaced) {
        result = multiply(result, factor());
      } else {
        fail("unexpected '" + std::string(m_text.substr(m_pos)) + "'");
      }
    }
  }

  Unit factor() {
    skip_spaces();
    const Unit base = atom();
    if (consume("\xC2\xB2")) return power(base, 2);  // '²'
    if (consume("\xC2\xB3")) return power(base, 3);  // '³'
    if (!consume("^")) return base;
    const bool negative = consume("-");
    if (!negative) consume("+");
    int n = 0;
    std::size_t digits = 0;
    while (!at_end() && is_digit(peek()) && digits < 3) {
      n = 10 * n + (peek() - '0');
      ++m_pos;
      ++digits;
    }
    if (digits == 0) fail("expected an integer exponent after '^'");
    if (!at_end() && is_digit(peek())) fail("exponent too large");
    return power(base, negative ? -n : n);
  }

  Unit atom() {
    if (consume("(")) {
      if (++m_depth > max_unit_parentheses)
        fail("parentheses nested deeper than " + std::to_string(max_unit_parentheses) +
             " levels (the limit)");
      const Unit inner = expression();
      if (!consume(")")) fail("missing ')'");
      --m_depth;
      return inner;
    }
    if (!at_end() && is_digit(peek())) {
      if (consume("1") && (at_end() || !is_digit(peek()))) return Unit{};
      fail("a number inside a unit expression (only '1' as in 1/s)");
    }
    std::string name;
    if (consume("\xC2\xB5") || consume("\xCE\xBC")) name = "u";  // micro sign or Greek mu
    while (!at_end() && is_letter(peek())) name += m_text[m_pos++];
    if (name.empty() || name == "u") {
      if (at_end()) fail("a unit is missing at the end");
      fail("expected a unit name at '" + std::string(m_text.substr(m_pos)) + "'");
    }
    for (const auto& u : unit_table())
      if (name == u.name) return u.unit;
    fail("unknown unit '" + name + "'; known units: " + known_unit_names());
  }

  bool at_end() const { return m_pos >= m_text.size(); }
  char peek() const { return at_end() ? '\0' : m_text[m_pos]; }
  bool consume(std::string_view token) {
    if (m_text.substr(m_pos, token.size()) != token) return false;
    m_pos += token.size();
    return true;
  }
  bool skip_spaces() {
    const std::size_t start = m_pos;
    while (!at_end() && is_space(peek())) ++m_pos;
    return m_pos > start;
  }
  [[noreturn]] void fail(const std::string& what) const { throw UnitError(what); }

  std::string_view m_text;
  std::size_t m_pos = 0;
  int m_depth = 0;  // parentheses open at m_pos
};

}  // namespace

const std::vector<NamedUnit>& unit_table() {
  static const std::vector<NamedUnit> table{
      {"m", {1.0, length}},
      {"km", {1e3, length}},
      {"cm", {1e-2, length}},
      {"mm", {1e-3, length}},
      {"um", {1e-6, length}},
      {"kg", {1.0, mass}},
      {"g", {1e-3, mass}},
      {"mg", {1e-6, mass}},
      {"s", {1.0, time}},
      {"ms", {1e-3, time}},
      {"us", {1e-6, time}},
      {"min", {60.0, time}},
      {"h", {3600.0, time}},
      {"Hz", {1.0, {0, 0, -1}}},
      {"N", {1.0, force}},
      {"kN", {1e3, force}},
      {"mN", {1e-3, force}},
      {"uN", {1e-6, force}},
      {"dyn", {1e-5, force}},
      {"gf", {gram_force_N, force}},
      {"kgf", {standard_gravity_m_s2, force}},
      {"Pa", {1.0, pressure}},
      {"kPa", {1e3, pressure}},
      {"MPa", {1e6, pressure}},
      {"GPa", {1e9, pressure}},
      {"rad", {1.0, none}},
      {"deg", {base::kPi / 180.0, none}},
  };
  return table;
}

Unit parse_unit(std::string_view expression) {
  return UnitParser(expression).parse();
}

Dimension dimension_of(Quantity kind) {
  switch (kind) {
    case Quantity::length:
      return length;
    case Quantity::time:
      return time;
    case Quantity::areal_density:
      return {1, -2, 0};
    case Quantity::force_per_length:
      return {1, 0, -2};
    case Quantity::bending_rigidity:
      return {1, 2, -2};
    case Quantity::speed:
      return {0, 1, -1};
    case Quantity::acceleration:
      return {0, 1, -2};
    case Quantity::inverse_time:
      return {0, 0, -1};
    case Quantity::angle:
      return none;
    case Quantity::stress:
      return pressure;
    case Quantity::moment_per_width:
      return {1, 1, -2};
    case Quantity::curvature:
      return {0, -1, 0};
    case Quantity::cubic_bending:
      return {1, 4, -2};
  }
  return none;
}

std::string quantity_name(Quantity kind) {
  switch (kind) {
    case Quantity::length:
      return "a length";
    case Quantity::time:
      return "a time";
    case Quantity::areal_density:
      return "an areal density";
    case Quantity::force_per_length:
      return "a force per length";
    case Quantity::bending_rigidity:
      return "a bending rigidity";
    case Quantity::speed:
      return "a speed";
    case Quantity::acceleration:
      return "an acceleration";
    case Quantity::inverse_time:
      return "an inverse time";
    case Quantity::angle:
      return "an angle";
    case Quantity::stress:
      return "a stress";
    case Quantity::moment_per_width:
      return "a moment per width";
    case Quantity::curvature:
      return "a curvature";
    case Quantity::cubic_bending:
      return "a cubic bending coefficient";
  }
  return "a quantity";
}

std::string quantity_description(Quantity kind) {
  switch (kind) {
    case Quantity::length:
      return "a length such as m, cm or mm";
    case Quantity::time:
      return "a time such as s or ms";
    case Quantity::areal_density:
      return "an areal density such as kg/m^2, g/m^2 or gf/cm^2";
    case Quantity::force_per_length:
      return "a force per length such as N/m or gf/cm";
    case Quantity::bending_rigidity:
      return "a bending rigidity such as N*m, uN*m or gf*cm (= gf*cm^2/cm)";
    case Quantity::speed:
      return "a speed such as m/s or km/h";
    case Quantity::acceleration:
      return "an acceleration such as m/s^2";
    case Quantity::inverse_time:
      return "an inverse time such as 1/s";
    case Quantity::angle:
      return "an angle such as deg or rad";
    case Quantity::stress:
      return "a stress (or modulus) such as Pa, MPa or GPa";
    case Quantity::moment_per_width:
      return "a moment per width such as N (= N*m/m) or gf*cm/cm";
    case Quantity::curvature:
      return "a curvature such as 1/m or 1/cm";
    case Quantity::cubic_bending:
      return "a cubic bending coefficient such as N*m^3";
  }
  return quantity_name(kind);
}

std::string si_unit_symbol(Quantity kind) {
  switch (kind) {
    case Quantity::length:
      return "m";
    case Quantity::time:
      return "s";
    case Quantity::areal_density:
      return "kg/m^2";
    case Quantity::force_per_length:
      return "N/m";
    case Quantity::bending_rigidity:
      return "N*m";
    case Quantity::speed:
      return "m/s";
    case Quantity::acceleration:
      return "m/s^2";
    case Quantity::inverse_time:
      return "1/s";
    case Quantity::angle:
      return "rad";
    case Quantity::stress:
      return "Pa";
    case Quantity::moment_per_width:
      return "N";
    case Quantity::curvature:
      return "1/m";
    case Quantity::cubic_bending:
      return "N*m^3";
  }
  return "";
}

std::string describe_dimension(const Dimension& d) {
  struct Named {
    Dimension dimension;
    const char* name;
  };
  static const Named named[] = {
      {none, "dimensionless"},
      {mass, "a mass"},
      {length, "a length"},
      {time, "a time"},
      {{0, 2, 0}, "an area"},
      {{0, 0, -1}, "an inverse time"},
      {{0, 1, -1}, "a speed"},
      {{0, 1, -2}, "an acceleration"},
      {force, "a force"},
      {{1, -1, 0}, "a mass per length"},
      {{1, -2, 0}, "an areal density"},
      {{1, 0, -2}, "a force per length"},
      {pressure, "a weight per area or a pressure"},
      {{1, 2, -2}, "a moment or bending rigidity"},
  };
  for (const auto& n : named)
    if (n.dimension == d) return n.name;
  std::string text;
  const auto append = [&](const char* symbol, int exponent) {
    if (exponent == 0) return;
    text += (text.empty() ? "" : "\xC2\xB7") + std::string(symbol);
    if (exponent != 1) text += "^" + std::to_string(exponent);
  };
  append("kg", d.mass);
  append("m", d.length);
  append("s", d.time);
  return "a quantity in " + text;
}

double parse_quantity(std::string_view text, Quantity kind) {
  const auto fail = [&](const std::string& reason) {
    const std::string shown =
        text.size() <= 80 ? std::string(text) : std::string(text.substr(0, 80)) + "…";
    throw UnitError("expected " + quantity_description(kind) + ", got '" + shown + "' (" +
                    reason + ")");
  };
  std::string_view s = trim(text);
  if (s.empty()) fail("an empty string");
  std::size_t start = 0;
  if (s.front() == '+' && s.size() > 1 && s[1] != '-' && s[1] != '+') start = 1;
  double value = 0.0;
  const auto [end, error] =
      std::from_chars(s.data() + start, s.data() + s.size(), value, std::chars_format::general);
  if (error == std::errc::invalid_argument) fail("it does not start with a number");
  if (error == std::errc::result_out_of_range) fail("the number is out of the range of a double");
  if (!std::isfinite(value)) fail("not a finite number");
  const std::string_view unit_text = trim(s.substr(static_cast<std::size_t>(end - s.data())));
  if (unit_text.empty())
    fail("the unit is missing; a JSON number is read in SI units, a string needs a unit");
  Unit unit;
  try {
    unit = parse_unit(unit_text);
  } catch (const UnitError& e) {
    fail(e.what());
  }
  double si = value * unit.factor;
  const Dimension want = dimension_of(kind);
  if (unit.dimension != want) {
    // Textile convention: a fabric's "weight" per area (gf/cm²) stands for its mass per area.
    if (kind == Quantity::areal_density && unit.dimension == pressure)
      si /= standard_gravity_m_s2;
    else
      fail("that is " + describe_dimension(unit.dimension));
  }
  if (!std::isfinite(si)) fail("not finite in SI units");
  return si;
}

}  // namespace weft::app
