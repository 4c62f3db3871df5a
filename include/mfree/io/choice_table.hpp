#pragma once
// One table per choice a scene makes (a method, a scheme, a model): the names a scene may
// write and the value each stands for, used both ways, so a name cannot be listed without
// its value or a value printed under another name. Reading a name that is not in the table
// is an error naming the key and the choices (SceneTable::choice); there is no fallback.

#include <initializer_list>
#include <string>
#include <utility>
#include <vector>

#include "mfree/io/scene_reader.hpp"

namespace mfree {

template <class T>
class ChoiceTable {
 public:
  ChoiceTable(std::initializer_list<std::pair<const char*, T>> entries) {
    for (const auto& [name, value] : entries) {
      names_.emplace_back(name);
      values_.push_back(value);
    }
  }
  [[nodiscard]] const std::vector<std::string>& names() const { return names_; }
  /// The value of `key` in t (required).
  [[nodiscard]] T read(const SceneTable& t, std::string_view key) const { return value_of(t.choice(key, names_)); }
  /// The value of `key`, or `fallback` when the key is absent.
  [[nodiscard]] T read_or(const SceneTable& t, std::string_view key, T fallback) const {
    return t.has(key) ? read(t, key) : (t.choice_or(key, name_of(fallback), names_), fallback);
  }
  /// The values of a list of names under `key`.
  [[nodiscard]] std::vector<T> read_list(const SceneTable& t, std::string_view key) const {
    std::vector<T> out;
    for (const std::string& n : t.choices(key, names_)) out.push_back(value_of(n));
    return out;
  }
  [[nodiscard]] const std::string& name_of(T value) const {
    for (std::size_t i = 0; i < values_.size(); ++i)
      if (values_[i] == value) return names_[i];
    throw std::logic_error("ChoiceTable: a value without a name");
  }

 private:
  [[nodiscard]] T value_of(const std::string& name) const {
    for (std::size_t i = 0; i < names_.size(); ++i)
      if (names_[i] == name) return values_[i];
    throw std::logic_error("ChoiceTable: a name without a value");  // choice() checked the name
  }
  std::vector<std::string> names_;
  std::vector<T> values_;
};

}  // namespace mfree
