// Enum ↔ name tables: names round-trip, unknown names are bad input listing the choices in table
// order, and a value missing from its table is a bug.

#include "base/enum_names.h"

#include <gtest/gtest.h>

#include <stdexcept>
#include <string>

namespace weft::base {
namespace {

enum class Fruit { apple, pear, quince, durian };

constexpr EnumNames<Fruit, 3> fruit_names{
    {{Fruit::apple, "apple"}, {Fruit::pear, "pear"}, {Fruit::quince, "quince"}}};

TEST(EnumNames, NamesRoundTrip) {
  for (const EnumName<Fruit>& n : fruit_names) {
    EXPECT_STREQ(enum_name(fruit_names, n.value), n.name);
    EXPECT_EQ(enum_from_name(fruit_names, n.name), n.value);
    EXPECT_EQ(parse_enum(fruit_names, n.name, "fruit"), n.value);
  }
  EXPECT_EQ(enum_from_name(fruit_names, "banana"), std::nullopt);
  EXPECT_EQ(enum_from_name(fruit_names, "Apple"), std::nullopt);  // names are exact
}

TEST(EnumNames, ChoicesAreListedInTableOrder) {
  EXPECT_EQ(enum_choices(fruit_names), "one of 'apple', 'pear', 'quince'");
  EXPECT_EQ(enum_name_list(fruit_names), (std::vector<std::string>{"apple", "pear", "quince"}));
}

TEST(EnumNames, UnknownNameIsBadInputListingTheChoices) {
  try {
    (void)parse_enum(fruit_names, "banana", "lunch.fruit");
    FAIL() << "no exception";
  } catch (const std::invalid_argument& e) {
    EXPECT_EQ(std::string(e.what()),
              "lunch.fruit: expected one of 'apple', 'pear', 'quince', got 'banana'");
  }
}

TEST(EnumNames, ValueWithoutNameIsABug) {
  EXPECT_THROW((void)enum_name(fruit_names, Fruit::durian), InternalError);
}

}  // namespace
}  // namespace weft::base
