// One name table per enum: the scene's name of each enumerator, written once and used for
// parsing (each choice is parsed once into its enum), printing, the "must be one of"
// messages and the schema test (tests/test_core_name_tables.cpp compares every table with
// configs/scene.schema.json). Header-only: a stage that names another stage's enum (the
// scene names the integrators' Method) needs its header, not its library.
//
// A table is a specialisation
//     template <> struct NameTable<E> {
//       static constexpr std::array<std::pair<E, std::string_view>, N> entries{{...}};
//     };
// next to the enum it names, listing every enumerator once, in the order the messages give.
#pragma once

#include <array>
#include <optional>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

namespace lub {

template <class E>
struct NameTable;  // specialised next to each enum

/// The scene name of `e` ("?" for a value outside the table).
template <class E>
constexpr std::string_view name_of(E e) {
  for (const auto& [value, name] : NameTable<E>::entries)
    if (value == e) return name;
  return "?";
}

/// The enumerator named `name` (exact, case-sensitive), or nullopt.
template <class E>
constexpr std::optional<E> parse_name(std::string_view name) {
  for (const auto& [value, n] : NameTable<E>::entries)
    if (n == name) return value;
  return std::nullopt;
}

/// All names in table order.
template <class E>
std::vector<std::string> names_of() {
  std::vector<std::string> out;
  for (const auto& entry : NameTable<E>::entries) out.emplace_back(entry.second);
  return out;
}

/// All names, comma separated (the "must be one of …" messages).
template <class E>
std::string names_list() {
  std::string out;
  for (const auto& entry : NameTable<E>::entries) {
    if (!out.empty()) out += ", ";
    out += entry.second;
  }
  return out;
}

}  // namespace lub
