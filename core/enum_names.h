// One table per enum of its values' names, as scenario files and the command line spell them: to_string and
// from_string read the same table, so a value and its name cannot drift apart, and a new value is one entry.
#ifndef ARBOR_CORE_ENUM_NAMES_H_
#define ARBOR_CORE_ENUM_NAMES_H_

#include <array>
#include <cstddef>
#include <string_view>
#include <type_traits>
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

// An enum names its values by specialising this beside its declaration, so the names are read where the
// enum is:  template <> inline constexpr EnumNames<WorldKind, 3> kNamesOf<WorldKind>{...};
// The primary template, of another type, marks an enum without names.
template <class E>
inline constexpr std::nullptr_t kNamesOf = nullptr;

template <class E>
concept NamedEnum = std::is_enum_v<E> && !std::is_same_v<std::remove_cvref_t<decltype(kNamesOf<E>)>, std::nullptr_t>;

// The value's name as scenario files and the command line spell it ("?" for a value the table lacks).
template <NamedEnum E>
constexpr std::string_view to_string(E value) {
  return name_of(kNamesOf<E>, value);
}
// Sets *value to the value with this name; false (and *value untouched) for an unknown name.
template <NamedEnum E>
constexpr bool from_string(std::string_view name, E* value) {
  return value_named(kNamesOf<E>, name, value);
}

}  // namespace arbor

#endif  // ARBOR_CORE_ENUM_NAMES_H_
