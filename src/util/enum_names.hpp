#pragma once
// The names of an enum's values, one table per enum, which its to_string and its parse both read:
// each name is written once, and the list a parse error offers cannot fall behind the enum.

#include <cstddef>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

namespace softdrop::detail {

template <class E>
struct EnumName {
  E value;
  const char* name;
};

/// The name of `value` in `table`; "?" for a value the table lacks (an out-of-range cast).
template <class E, std::size_t N>
constexpr const char* name_of(const EnumName<E> (&table)[N], E value) {
  for (const EnumName<E>& e : table)
    if (e.value == value) return e.name;
  return "?";
}

/// Stores the value named `name` in *value and returns true; false if no entry has that name.
template <class E, std::size_t N>
bool value_of(const EnumName<E> (&table)[N], std::string_view name, E* value) {
  for (const EnumName<E>& e : table)
    if (name == e.name) return *value = e.value, true;
  return false;
}

/// The table's names for a message: "a, b or c".
template <class E, std::size_t N>
std::string names_of(const EnumName<E> (&table)[N]) {
  std::string list;
  for (std::size_t i = 0; i < N; ++i) {
    if (i > 0) list += i + 1 == N ? " or " : ", ";
    list += table[i].name;
  }
  return list;
}

/// Every name of the table, in order (for a command line's list of choices).
template <class E, std::size_t N>
std::vector<std::string> name_list(const EnumName<E> (&table)[N]) {
  std::vector<std::string> names;
  for (const EnumName<E>& e : table) names.emplace_back(e.name);
  return names;
}

/// The value named `name`; throws std::invalid_argument "KEY = 'name': must be a, b or c" naming
/// the option `key` otherwise.
template <class E, std::size_t N>
E parse_name(const EnumName<E> (&table)[N], const std::string& name, const char* key) {
  E value{};
  if (!value_of(table, name, &value))
    throw std::invalid_argument(std::string(key) + " = '" + name + "': must be " + names_of(table));
  return value;
}

}  // namespace softdrop::detail
