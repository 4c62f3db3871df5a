#pragma once
// Reading a choice (a method, a scheme, a model) from a scene through its one NameTable
// (core/name_table.hpp): a name that is not in the table is an error naming the key and the
// choices (SceneTable::choice); there is no fallback.

#include <string_view>
#include <vector>

#include "mfree/core/name_table.hpp"
#include "mfree/io/scene_reader.hpp"

namespace mfree {

/// The value of the name under `key` (required).
template <class T>
T read_choice(const SceneTable& t, std::string_view key, const NameTable<T>& table) {
  return table.value(t.choice(key, table.names()));
}

/// The value of the name under `key`, or `fallback` when the key is absent.
template <class T>
T read_choice_or(const SceneTable& t, std::string_view key, const NameTable<T>& table, const T& fallback) {
  return table.value(t.choice_or(key, table.name(fallback), table.names()));
}

/// The values of a non-empty list of distinct names under `key`.
template <class T>
std::vector<T> read_choices(const SceneTable& t, std::string_view key, const NameTable<T>& table) {
  std::vector<T> out;
  for (const std::string& n : t.choices(key, table.names())) out.push_back(table.value(n));
  return out;
}

}  // namespace mfree
