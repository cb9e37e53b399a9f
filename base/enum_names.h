#pragma once
// Enum ↔ name, one mechanism for every enum that has names (scene files, command-line options,
// reports). Each enum keeps one table beside its declaration,
//
//   inline constexpr base::EnumNames<Integrator, 2> integrator_names{{
//       {Integrator::rk4, "rk4"}, {Integrator::implicit_euler, "implicit_euler"}}};
//
// and reads it through enum_name / enum_from_name / enum_choices / parse_enum. The table's order
// is the order in which an error lists the choices.

#include <array>
#include <cstddef>
#include <optional>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

#include "base/check.h"

namespace weft::base {

template <class E>
struct EnumName {
  E value;
  const char* name;
};

template <class E, std::size_t N>
using EnumNames = std::array<EnumName<E>, N>;

// The names, in table order.
template <class E, std::size_t N>
std::vector<std::string> enum_name_list(const EnumNames<E, N>& names) {
  std::vector<std::string> list;
  for (const EnumName<E>& n : names) list.emplace_back(n.name);
  return list;
}

// "one of 'a', 'b', 'c'": the choices as an error lists them.
std::string choices_text(const std::vector<std::string>& names);

template <class E, std::size_t N>
std::string enum_choices(const EnumNames<E, N>& names) {
  return choices_text(enum_name_list(names));
}

// The name of `value`. A value missing from its table is a bug (InternalError).
template <class E, std::size_t N>
const char* enum_name(const EnumNames<E, N>& names, E value) {
  for (const EnumName<E>& n : names)
    if (n.value == value) return n.name;
  WEFT_CHECK(false, "no name for enum value " + std::to_string(static_cast<long long>(value)));
  return "";  // not reached
}

// The value called `name`, if any.
template <class E, std::size_t N>
std::optional<E> enum_from_name(const EnumNames<E, N>& names, std::string_view name) {
  for (const EnumName<E>& n : names)
    if (name == n.name) return n.value;
  return std::nullopt;
}

// The value called `name`; otherwise std::invalid_argument (bad input):
// "<where>: expected one of 'a', 'b', got 'x'".
template <class E, std::size_t N>
E parse_enum(const EnumNames<E, N>& names, std::string_view name, const std::string& where) {
  if (const std::optional<E> value = enum_from_name(names, name)) return *value;
  throw std::invalid_argument(where + ": expected " + enum_choices(names) + ", got '" +
                              std::string(name) + "'");
}

}  // namespace weft::base
