#pragma once
// One choice a user makes by name (a method, a wall kind, a body's shape): the table of its
// names and values, the single place both reading and printing look up. Scene readers check a
// name against names() (so an unlisted name is an input error naming the key) before value()
// is asked; name() prints a value the way a scene writes it.

#include <stdexcept>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

namespace mfree {

template <class T>
class NameTable {
 public:
  NameTable(std::initializer_list<std::pair<std::string, T>> entries) : entries_(entries) {}
  explicit NameTable(std::vector<std::pair<std::string, T>> entries) : entries_(std::move(entries)) {}

  /// Every name with its value, in the table's order.
  [[nodiscard]] const std::vector<std::pair<std::string, T>>& entries() const { return entries_; }

  /// Every name, in the table's order (the list a scene reader offers).
  [[nodiscard]] std::vector<std::string> names() const {
    std::vector<std::string> out;
    for (const auto& e : entries_) out.push_back(e.first);
    return out;
  }
  /// The value of a listed name; std::logic_error for any other (a reader that did not check).
  [[nodiscard]] const T& value(std::string_view name) const {
    for (const auto& e : entries_)
      if (e.first == name) return e.second;
    throw std::logic_error("NameTable: '" + std::string(name) + "' is not listed");
  }
  /// The name of a listed value; std::logic_error for any other.
  [[nodiscard]] const std::string& name(const T& value) const {
    for (const auto& e : entries_)
      if (e.second == value) return e.first;
    throw std::logic_error("NameTable: a value without a name");
  }

 private:
  std::vector<std::pair<std::string, T>> entries_;
};

}  // namespace mfree
