// One table per enum of its values' names, as scenario files and the command line spell them: to_string and
// from_string read the same table, so a value and its name cannot drift apart, and a new value is one entry.
#ifndef ARBOR_CORE_ENUM_NAMES_H_
#define ARBOR_CORE_ENUM_NAMES_H_

#include <array>
#include <cstddef>
#include <string_view>
#include <utility>

namespace arbor {

template <class E, std::size_t N>
using EnumNames = std::array<std::pair<E, std::string_view>, N>;

// The name of value, "?" for a value the table lacks.
template <class E, std::size_t N>
constexpr std::string_view name_of(const EnumNames<E, N>& table, E value) {
  for (const auto& [v, name] : table)
    if (v == value) return name;
  return "?";
}

// Sets *value to the entry named name; false (and *value untouched) when no entry has that name.
template <class E, std::size_t N>
constexpr bool value_named(const EnumNames<E, N>& table, std::string_view name, E* value) {
  for (const auto& [v, n] : table)
    if (n == name) {
      *value = v;
      return true;
    }
  return false;
}

}  // namespace arbor

#endif  // ARBOR_CORE_ENUM_NAMES_H_
