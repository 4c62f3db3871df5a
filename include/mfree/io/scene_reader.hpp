#pragma once
// Strict reading of TOML scene files into typed settings.
//
// A scene is parsed once. Each section is read through a SceneTable, which checks the
// type and range of every value it hands out, and whose finish() refuses keys nobody
// read (a misspelt key must not be silently ignored). Every error is an InputError of
// the form  "FILE:LINE:COLUMN: key 'section.key': what is wrong".

#include <array>
#include <filesystem>
#include <memory>
#include <optional>
#include <set>
#include <string>
#include <string_view>
#include <vector>

namespace toml {
inline namespace v3 {
class table;
class node;
struct source_region;
}  // namespace v3
}  // namespace toml

namespace mfree {

/// The largest scene file read [bytes].
inline constexpr std::size_t max_scene_bytes = 1 << 20;

class SceneTable {
 public:
  /// Whole-number value in [lo, hi].
  long long integer(std::string_view key, long long lo, long long hi) const;
  long long integer_or(std::string_view key, long long fallback, long long lo, long long hi) const;
  /// Real value (integers accepted) in [lo, hi].
  double number(std::string_view key, double lo, double hi) const;
  double number_or(std::string_view key, double fallback, double lo, double hi) const;
  /// One of `choices`.
  std::string choice(std::string_view key, const std::vector<std::string>& choices) const;
  std::string choice_or(std::string_view key, std::string fallback,
                        const std::vector<std::string>& choices) const;
  /// Non-empty list of distinct members of `choices`.
  std::vector<std::string> choices(std::string_view key, const std::vector<std::string>& choices) const;
  /// Non-empty list of distinct non-empty strings (names the scene chooses).
  std::vector<std::string> names(std::string_view key) const;
  /// True when the key holds an array of tables ([[name]] sections).
  bool is_array_of_tables(std::string_view key) const;
  std::string string(std::string_view key) const;
  /// Array of numbers, of length `size` (any length >= 1 when size is 0), each in [lo, hi].
  std::vector<double> numbers(std::string_view key, std::size_t size, double lo, double hi) const;
  bool has(std::string_view key) const;
  /// True when the key holds a string (for keys that take a word or numbers).
  bool is_string(std::string_view key) const;
  /// True when the key holds an empty array (marks it read).
  bool is_array_empty(std::string_view key) const;
  bool boolean_or(std::string_view key, bool fallback) const;
  /// Array of points [[x, y], ...] of length `size` (any length >= 1 when 0).
  std::vector<std::array<double, 2>> pairs(std::string_view key, std::size_t size) const;
  /// Array of points in space [[x, y, z], ...], likewise.
  std::vector<std::array<double, 3>> triples(std::string_view key, std::size_t size) const;
  /// A value that is a number or a formula (a string): its text, numbers written so that
  /// they read back to the same double.
  std::string expression(std::string_view key) const;
  /// An array of `size` such values.
  std::vector<std::string> expressions(std::string_view key, std::size_t size) const;
  /// Every key of this table (all marked read), for tables of user-chosen names.
  std::vector<std::string> keys() const;
  /// "FILE:LINE:COLUMN: key 'section.key'" of a key, for messages raised later (a formula
  /// that evaluates to NaN during a run names the key it came from).
  /// With index >= 0: the entry key[index] of an array.
  std::string where(std::string_view key, int index = -1) const;
  /// Array of tables ([[name]] sections); empty when the key is absent.
  std::vector<SceneTable> tables(std::string_view key) const;
  /// Throws an InputError at this key's position (for checks across several keys).
  [[noreturn]] void error(std::string_view key, const std::string& what) const;
  /// A required sub-table.
  SceneTable table(std::string_view key) const;
  /// A sub-table whose keys all have defaults: an empty one when the key is absent.
  SceneTable optional_table(std::string_view key) const;
  /// Throws for any key of this table that was never read.
  void finish() const;

  /// The folder of the scene file (relative paths in a scene are relative to it).
  const std::filesystem::path& folder() const { return *folder_; }

 private:
  friend class Scene;
  SceneTable(const toml::table* t, std::string prefix, std::shared_ptr<const std::string> file,
             std::shared_ptr<const std::filesystem::path> folder);
  const toml::node* get(std::string_view key, bool required) const;
  /// choices() with `allowed`, names() without.
  std::vector<std::string> string_list(std::string_view key, const std::vector<std::string>* allowed) const;
  [[noreturn]] void fail(const toml::node* at, std::string_view key, const std::string& what) const;
  /// pairs() (n = 2) and triples() (n = 3).
  template <std::size_t n>
  std::vector<std::array<double, n>> points(std::string_view key, std::size_t size) const;
  /// The scene file, or the --set override a value came from.
  [[nodiscard]] const std::string& origin_of(const toml::source_region& region) const;

  const toml::table* table_;
  std::string prefix_;
  std::shared_ptr<const std::string> file_;
  std::shared_ptr<const std::filesystem::path> folder_;
  std::shared_ptr<std::set<std::string>> used_;
};

/// A parsed scene file; root() reads its top-level table.
class Scene {
 public:
  /// Throws InputError for a missing file or a TOML syntax error (with line and column).
  /// `overrides` are command-line settings "section.key=value" (value in TOML syntax; a bare
  /// word is a string) replacing or adding keys before anything is read; errors about them
  /// name the override instead of the file.
  static Scene load(const std::filesystem::path& path, const std::vector<std::string>& overrides = {});
  static Scene parse(std::string_view text, const std::string& name);
  Scene(Scene&&) noexcept;
  ~Scene();
  SceneTable root() const;

 private:
  Scene();
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace mfree
