#pragma once
// Physical quantities in scene files. A JSON number is already in SI units; a string is
// "<number> <unit expression>", e.g. "0.019 gf/cm^2", "0.083 gf*cm", "9.81 m/s^2", "30 deg".
//
// Unit expressions combine the units of unit_table() with `*`, `·` or a space (product), `/`
// (quotient, left-associative: a/b*c = (a/b)·c, write a/(b*c) otherwise), parentheses and
// integer powers `^n`, `^-n`, `²`, `³`; "1/s" and "/s" are both an inverse second. The value
// must be finite. docs/scene.md lists the units and the kinds of quantity.

#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

namespace weft::app {

// Standard gravity g0, m/s². Converts a weight (gram-force, kilogram-force) to a mass.
inline constexpr double standard_gravity_m_s2 = 9.80665;

// Exponents of mass (kg), length (m) and time (s). Angles are dimensionless (rad).
struct Dimension {
  int mass = 0, length = 0, time = 0;

  friend bool operator==(const Dimension& a, const Dimension& b) {
    return a.mass == b.mass && a.length == b.length && a.time == b.time;
  }
  friend bool operator!=(const Dimension& a, const Dimension& b) { return !(a == b); }
};

// One unit of an expression is `factor` times the SI unit of `dimension`
// (e.g. gf/cm: factor 0.980665, dimension kg·s⁻², i.e. N/m).
struct Unit {
  double factor = 1.0;
  Dimension dimension;
};

// A named unit of unit_table().
struct NamedUnit {
  const char* name;
  Unit unit;
};

// The kinds of quantity a scene file holds; the SI unit each is converted to is in brackets.
enum class Quantity {
  length,            // [m]
  time,              // [s]
  areal_density,     // [kg/m²]; a weight per area (gf/cm², N/m²) is divided by g0
  force_per_length,  // [N/m]  tensile and shear rigidity: force per width per unit strain
  bending_rigidity,  // [N·m]  moment per width per unit curvature, M/w = B κ ("gf·cm")
  speed,             // [m/s]
  acceleration,      // [m/s²]
  inverse_time,      // [1/s]  e.g. mass-proportional damping α
  angle,             // [rad]
  stress,            // [Pa]   e.g. Young's modulus
  moment_per_width,  // [N]    bending moment per width, N·m/m (a bending law's M)
  curvature,         // [1/m]
  cubic_bending,     // [N·m³] the cubic coefficient C of M/w = B κ + C κ³
};

// Bad quantity text. what() reads "expected <kind> such as …, got '<text>' (<reason>)".
class UnitError : public std::invalid_argument {
 public:
  using std::invalid_argument::invalid_argument;
};

// The units an expression may name (no general SI prefixes: "min" is minutes, "Pa" pascals).
const std::vector<NamedUnit>& unit_table();

// How deeply parentheses may nest in a unit expression (the parser is recursive).
inline constexpr int max_unit_parentheses = 16;

// Parses a unit expression such as "gf*cm^2/cm". Throws UnitError naming the problem.
Unit parse_unit(std::string_view expression);

// Parses "<number> <unit expression>" (the space is optional: "5mm") into SI units of `kind`.
// Throws UnitError when the text is malformed, the number not finite, a unit unknown, the
// unit missing or of the wrong dimension.
double parse_quantity(std::string_view text, Quantity kind);

Dimension dimension_of(Quantity kind);
// "a length", "an areal density", …: for messages such as "expected a length > 0".
std::string quantity_name(Quantity kind);
// "a length such as m, cm or mm": the name followed by accepted units.
std::string quantity_description(Quantity kind);
// The SI unit a quantity of `kind` is converted to: "m", "kg/m^2", "N*m", …
std::string si_unit_symbol(Quantity kind);
// "a force per length" for a dimension with a name, else "a quantity in kg·m^-1·s^-2".
std::string describe_dimension(const Dimension& dimension);

}  // namespace weft::app
