#include "app/scene/units.h"

#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "base/constants.h"
#include "tests/app/scene_test_support.h"

namespace weft::app {
namespace {

constexpr double g0 = 9.80665;             // standard gravity, m/s²
using test::expect_close;
using test::gram_force;

std::string quantity_error_of(const std::string& text, Quantity kind) {
  try {
    const double value = parse_quantity(text, kind);
    return "no error, got " + std::to_string(value);
  } catch (const UnitError& e) {
    return e.what();
  }
}

TEST(Units, TextileUnitsOfKangAndYuWool) {
  // A weight per area where a mass per area is expected is divided by g0: 0.019 gf/cm² is
  // 0.019 g/cm², i.e. 0.19 kg/m².
  expect_close(parse_quantity("0.019 gf/cm^2", Quantity::areal_density), 0.19);
  expect_close(parse_quantity("0.019 gf/cm^2", Quantity::areal_density),
               0.019 * gram_force / (0.01 * 0.01) / g0);
  expect_close(parse_quantity("1118.2 gf/cm", Quantity::force_per_length),
               1118.2 * gram_force / 0.01);  // 1096.6 N/m
  EXPECT_NEAR(parse_quantity("1118.2 gf/cm", Quantity::force_per_length), 1096.6, 0.05);
  expect_close(parse_quantity("0.083 gf*cm", Quantity::bending_rigidity),
               0.083 * gram_force * 0.01);  // 8.14e-6 N·m
  EXPECT_NEAR(parse_quantity("0.083 gf*cm", Quantity::bending_rigidity), 8.14e-6, 0.005e-6);
}

TEST(Units, BendingRigidityAcceptsEquivalentSpellings) {
  const double b = 0.083 * gram_force * 0.01;
  expect_close(parse_quantity("0.083 gf*cm^2/cm", Quantity::bending_rigidity), b);
  expect_close(parse_quantity("0.083 gf\xC2\xB7"
                              "cm",
                              Quantity::bending_rigidity),
               b);  // gf·cm
  expect_close(parse_quantity("0.083 gf cm", Quantity::bending_rigidity), b);
  expect_close(parse_quantity("8.14 uN*m", Quantity::bending_rigidity), 8.14e-6);
  expect_close(parse_quantity("8.14 \xC2\xB5N*m", Quantity::bending_rigidity), 8.14e-6);  // µN
  expect_close(parse_quantity("2 N*m", Quantity::bending_rigidity), 2.0);
  expect_close(parse_quantity("2 N*m^2/m", Quantity::bending_rigidity), 2.0);
}

TEST(Units, EachKindInItsUnits) {
  expect_close(parse_quantity("190 g/m^2", Quantity::areal_density), 0.19);
  expect_close(parse_quantity("0.19 kg/m\xC2\xB2", Quantity::areal_density), 0.19);  // m²
  expect_close(parse_quantity("5 mm", Quantity::length), 5e-3);
  expect_close(parse_quantity("2.5 cm", Quantity::length), 0.025);
  expect_close(parse_quantity("2.5cm", Quantity::length), 0.025);
  expect_close(parse_quantity("1.2 km", Quantity::length), 1200.0);
  expect_close(parse_quantity("0.2 ms", Quantity::time), 2e-4);
  expect_close(parse_quantity("2 min", Quantity::time), 120.0);
  expect_close(parse_quantity("5 1/s", Quantity::inverse_time), 5.0);
  expect_close(parse_quantity("5 /s", Quantity::inverse_time), 5.0);
  expect_close(parse_quantity("5 Hz", Quantity::inverse_time), 5.0);
  expect_close(parse_quantity("9.81 m/s^2", Quantity::acceleration), 9.81);
  expect_close(parse_quantity("-9.81 m/s\xC2\xB2", Quantity::acceleration), -9.81);
  expect_close(parse_quantity("981 cm/s/s", Quantity::acceleration), 9.81);
  expect_close(parse_quantity("9.81 m*s^-2", Quantity::acceleration), 9.81);
  expect_close(parse_quantity("1.5 N/m", Quantity::force_per_length), 1.5);
  expect_close(parse_quantity("1.5 mN/mm", Quantity::force_per_length), 1.5);
  expect_close(parse_quantity("1.5 kg/s^2", Quantity::force_per_length), 1.5);
  expect_close(parse_quantity("36 km/h", Quantity::speed), 10.0);
  expect_close(parse_quantity("30 deg", Quantity::angle), 30.0 * base::kPi / 180.0);
  expect_close(parse_quantity("0.5 rad", Quantity::angle), 0.5);
  expect_close(parse_quantity("+1e-3 m", Quantity::length), 1e-3);
}

TEST(Units, ExpressionGrammar) {
  const Unit newton_metre = parse_unit("kg*m^2/s^2");
  EXPECT_EQ(newton_metre.dimension, (Dimension{1, 2, -2}));
  expect_close(newton_metre.factor, 1.0);
  const Unit left_associative = parse_unit("g/cm*s");  // (g/cm)·s
  EXPECT_EQ(left_associative.dimension, (Dimension{1, -1, 1}));
  const Unit grouped = parse_unit("g/(cm*s)");
  EXPECT_EQ(grouped.dimension, (Dimension{1, -1, -1}));
  expect_close(grouped.factor, 1e-3 / 1e-2);
  const Unit spaced = parse_unit("  N  *  m ");
  EXPECT_EQ(spaced.dimension, (Dimension{1, 2, -2}));
  const Unit gram_force_unit = parse_unit("gf");
  expect_close(gram_force_unit.factor, gram_force);
  expect_close(parse_unit("kgf").factor, g0);
  expect_close(parse_unit("deg").factor, base::kPi / 180.0);
  EXPECT_EQ(parse_unit("deg").dimension, (Dimension{}));
}

TEST(Units, WrongDimensionListsTheAcceptedUnits) {
  EXPECT_EQ(quantity_error_of("0.019 gf/cm", Quantity::areal_density),
            "expected an areal density such as kg/m^2, g/m^2 or gf/cm^2, got '0.019 gf/cm' "
            "(that is a force per length)");
  EXPECT_EQ(quantity_error_of("5 s", Quantity::length),
            "expected a length such as m, cm or mm, got '5 s' (that is a time)");
  EXPECT_EQ(quantity_error_of("1118.2 gf", Quantity::force_per_length),
            "expected a force per length such as N/m or gf/cm, got '1118.2 gf' (that is a force)");
  EXPECT_NE(quantity_error_of("0.083 gf/cm", Quantity::bending_rigidity)
                .find("expected a bending rigidity such as N*m, uN*m or gf*cm"),
            std::string::npos);
  EXPECT_NE(quantity_error_of("9.81 m/s", Quantity::acceleration).find("(that is a speed)"),
            std::string::npos);
  EXPECT_NE(quantity_error_of("5 kg^2", Quantity::length).find("(that is a quantity in kg^2)"),
            std::string::npos);
  // The g0 conversion is for areal density only: a pressure is not a force per length.
  EXPECT_NE(quantity_error_of("3 Pa", Quantity::force_per_length).find("weight per area"),
            std::string::npos);
}

TEST(Units, MalformedAndNonFiniteNumbers) {
  EXPECT_EQ(quantity_error_of("nan", Quantity::length),
            "expected a length such as m, cm or mm, got 'nan' (not a finite number)");
  EXPECT_NE(quantity_error_of("inf m", Quantity::length).find("(not a finite number)"), std::string::npos);
  EXPECT_NE(quantity_error_of("-Infinity m", Quantity::length).find("(not a finite number)"),
            std::string::npos);
  EXPECT_NE(quantity_error_of("1e999 m", Quantity::length).find("out of the range of a double"),
            std::string::npos);
  EXPECT_NE(quantity_error_of("1e300 km^3", Quantity::length).find("that is"), std::string::npos);
  EXPECT_NE(quantity_error_of("mm", Quantity::length).find("(it does not start with a number)"),
            std::string::npos);
  EXPECT_NE(quantity_error_of("", Quantity::length).find("(an empty string)"), std::string::npos);
  EXPECT_NE(quantity_error_of("5", Quantity::length).find("the unit is missing"), std::string::npos);
  EXPECT_NE(quantity_error_of("5 furlong", Quantity::length).find("unknown unit 'furlong'; known units: m"),
            std::string::npos);
  EXPECT_NE(quantity_error_of("5 Nm", Quantity::bending_rigidity).find("unknown unit 'Nm'"),
            std::string::npos);
  EXPECT_NE(quantity_error_of("2.5.3 m", Quantity::length).find("expected a unit name at '.3 m'"),
            std::string::npos);
  EXPECT_NE(quantity_error_of("5 m^", Quantity::length).find("integer exponent"), std::string::npos);
  EXPECT_NE(quantity_error_of("5 (m", Quantity::length).find("missing ')'"), std::string::npos);
  EXPECT_NE(quantity_error_of("5 m)", Quantity::length).find("unexpected ')'"), std::string::npos);
  EXPECT_NE(quantity_error_of("5 2/s", Quantity::inverse_time).find("only '1'"), std::string::npos);
  EXPECT_NE(quantity_error_of("5 m*", Quantity::length).find("a unit is missing at the end"),
            std::string::npos);
  EXPECT_NE(quantity_error_of("+-5 m", Quantity::length).find("does not start with a number"),
            std::string::npos);
  EXPECT_NE(quantity_error_of("1e308 km", Quantity::length).find("not finite in SI units"),
            std::string::npos);
}

}  // namespace
}  // namespace weft::app
