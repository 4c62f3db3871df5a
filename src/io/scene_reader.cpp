#include "mfree/io/scene_reader.hpp"

#include <fmt/format.h>
#include <fmt/ranges.h>
#include <toml++/toml.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <optional>
#include <sstream>

#include "mfree/core/error.hpp"

namespace mfree {

namespace {
std::string_view type_name(const toml::node& n) {
  switch (n.type()) {
    case toml::node_type::table: return "a table";
    case toml::node_type::array: return "an array";
    case toml::node_type::string: return "a string";
    case toml::node_type::integer: return "an integer";
    case toml::node_type::floating_point: return "a real number";
    case toml::node_type::boolean: return "a boolean";
    default: return "a date or time";
  }
}
}  // namespace

struct Scene::Impl {
  toml::table table;
  std::shared_ptr<const std::string> file;
  std::shared_ptr<const std::filesystem::path> folder;
};

Scene::Scene() : impl_(std::make_unique<Impl>()) {}
Scene::Scene(Scene&&) noexcept = default;
Scene::~Scene() = default;

Scene Scene::parse(std::string_view text, const std::string& name) {
  Scene scene;
  try {
    scene.impl_->table = toml::parse(text, name);
  } catch (const toml::parse_error& e) {
    const auto& at = e.source().begin;
    throw InputError(fmt::format("{}:{}:{}: {}", name, at.line, at.column, e.description()));
  }
  scene.impl_->file = std::make_shared<const std::string>(name);
  scene.impl_->folder = std::make_shared<const std::filesystem::path>(
      std::filesystem::path(name).parent_path());
  return scene;
}

namespace {

constexpr std::string_view bare_key_characters =
    "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789_-";

/// Replaces (or adds) the key of one override "a.b.c=value" in `root`.
void apply_override(toml::table& root, const std::string& setting) {
  const std::string origin = "--set " + setting;
  const std::size_t eq = setting.find('=');
  if (eq == std::string::npos || eq == 0)
    throw InputError(fmt::format("{}: expected section.key=value", origin));
  const std::string path = setting.substr(0, eq), value = setting.substr(eq + 1);
  toml::table parsed;
  try {
    parsed = toml::parse("value = " + value, origin);
  } catch (const toml::parse_error& as_value) {
    // A bare word (--set mpm.method=cpdi) is the string it spells; anything else (a quote, a
    // byte that is not UTF-8) is neither.
    try {
      parsed = toml::parse(fmt::format("value = \"{}\"", value), origin);
    } catch (const toml::parse_error&) {
      throw InputError(fmt::format("{}: '{}' is not a TOML value ({}) nor a bare word", origin, value,
                                   as_value.description()));
    }
  }
  // The path's parts: sections, then the key. A section that is a list of tables
  // ([[material]]) takes one of them: by its name (material.steel.model) or its place
  // (material[1].model, as errors name it).
  std::vector<std::string> parts;
  for (std::size_t begin = 0;;) {
    const std::size_t dot = path.find('.', begin);
    parts.push_back(path.substr(begin, dot == std::string::npos ? std::string::npos : dot - begin));
    if (dot == std::string::npos) break;
    begin = dot + 1;
  }
  const auto joined = [&](std::size_t upto) {
    std::string out = parts[0];
    for (std::size_t k = 1; k <= upto; ++k) out += "." + parts[k];
    return out;
  };
  toml::table* at = &root;
  for (std::size_t i = 0; i + 1 < parts.size(); ++i) {
    std::string section = parts[i];
    std::optional<std::size_t> place;
    if (const std::size_t open = section.find('['); open != std::string::npos && section.back() == ']') {
      const std::string digits = section.substr(open + 1, section.size() - open - 2);
      if (digits.empty() || digits.size() > 9 || digits.find_first_not_of("0123456789") != std::string::npos)
        throw InputError(
            fmt::format("{}: '{}' is not a place in a list of tables ([0], [1], ...)", origin, section));
      place = std::stoul(digits);
      section.resize(open);
    }
    if (section.empty() || section.find_first_not_of(bare_key_characters) != std::string::npos)
      throw InputError(
          fmt::format("{}: '{}' is not a section name (letters, digits, _ and -)", origin, parts[i]));
    if (!at->contains(section)) {
      if (place) throw InputError(fmt::format("{}: the scene has no [[{}]] tables", origin, section));
      // Parsed rather than made, so that the new section carries the override as its source.
      toml::table made = toml::parse(section + " = {}", origin);
      at->insert(section, std::move(*made.get(section)));
    }
    toml::node& node = at->find(section)->second;
    if (toml::array* list = node.as_array(); list && list->is_array_of_tables()) {
      // The tables' names, for the choice and for messages.
      std::vector<std::string> names;
      for (toml::node& t : *list)
        names.push_back(t.as_table()->get_as<std::string>("name")
                            ? **t.as_table()->get_as<std::string>("name")
                            : std::string());
      if (!place) {
        if (i + 2 >= parts.size())
          throw InputError(
              fmt::format("{}: '{}' is a list of tables ([[{}]]): name one, {}.<name>.{}, or give its "
                          "place, {}[k].{} (names: {})",
                          origin, joined(i), section, joined(i), parts.back(), joined(i), parts.back(),
                          fmt::join(names, ", ")));
        const auto it = std::find(names.begin(), names.end(), parts[i + 1]);
        if (it == names.end())
          throw InputError(fmt::format("{}: no [[{}]] table is named '{}' (names: {})", origin, section,
                                       parts[i + 1], fmt::join(names, ", ")));
        place = static_cast<std::size_t>(it - names.begin());
        ++i;
      }
      if (*place >= list->size())
        throw InputError(fmt::format("{}: the scene has {} [[{}]] table(s), numbered from 0: there is no {}",
                                     origin, list->size(), section, *place));
      at = (*list)[*place].as_table();
      continue;
    }
    if (place || !node.is_table())
      throw InputError(fmt::format("{}: '{}' is not a section of the scene", origin, joined(i)));
    at = node.as_table();
  }
  const std::string& key = parts.back();
  if (key.empty() || key.find_first_not_of(bare_key_characters) != std::string::npos)
    throw InputError(fmt::format("{}: '{}' is not a key name (letters, digits, _ and -)", origin, key));
  at->insert_or_assign(key, std::move(*parsed.get("value")));
}

}  // namespace

Scene Scene::load(const std::filesystem::path& path, const std::vector<std::string>& overrides) {
  std::error_code ec;
  const std::filesystem::file_status status = std::filesystem::status(path, ec);
  if (ec || !std::filesystem::exists(status))
    throw InputError(fmt::format("{}: cannot open the scene file (no such file)", path.string()));
  if (!std::filesystem::is_regular_file(status))
    throw InputError(fmt::format("{}: cannot open the scene file: not a regular file (a scene is a TOML file)",
                                 path.string()));
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError(fmt::format("{}: cannot open the scene file", path.string()));
  std::string text(max_scene_bytes + 1, '\0');
  in.read(text.data(), static_cast<std::streamsize>(text.size()));
  text.resize(static_cast<std::size_t>(in.gcount()));
  if (text.size() > max_scene_bytes)
    throw InputError(fmt::format("{}: the scene file is larger than {} bytes; a scene describes a problem, "
                                 "its data (meshes, WKT) lives in files it names",
                                 path.string(), max_scene_bytes));
  Scene scene = parse(text, path.string());
  for (const std::string& o : overrides) apply_override(scene.impl_->table, o);
  return scene;
}

SceneTable Scene::root() const {
  return SceneTable(&impl_->table, "", impl_->file, impl_->folder);
}

SceneTable::SceneTable(const toml::table* t, std::string prefix,
                       std::shared_ptr<const std::string> file,
                       std::shared_ptr<const std::filesystem::path> folder)
    : table_(t), prefix_(std::move(prefix)), file_(std::move(file)), folder_(std::move(folder)),
      used_(std::make_shared<std::set<std::string>>()) {}

const std::string& SceneTable::origin_of(const toml::source_region& region) const {
  return region.path && region.path->starts_with("--set ") ? *region.path : *file_;
}

void SceneTable::fail(const toml::node* at, std::string_view key, const std::string& what) const {
  const toml::source_region& region = at ? at->source() : table_->source();
  // A value from a command-line override carries the override as its path.
  throw InputError(fmt::format("{}:{}:{}: key '{}{}': {}", origin_of(region), region.begin.line, region.begin.column,
                               prefix_, key, what));
}

const toml::node* SceneTable::get(std::string_view key, bool required) const {
  used_->insert(std::string(key));
  const toml::node* n = table_->get(key);
  if (!n && required) fail(nullptr, key, "missing (required)");
  return n;
}

bool SceneTable::has(std::string_view key) const { return table_->contains(key); }

long long SceneTable::integer(std::string_view key, long long lo, long long hi) const {
  const toml::node* n = get(key, true);
  const auto v = n->value_exact<int64_t>();
  if (!v) fail(n, key, fmt::format("expected a whole number, got {}", type_name(*n)));
  if (*v < lo || *v > hi) fail(n, key, fmt::format("{} is out of range [{}, {}]", *v, lo, hi));
  return *v;
}

long long SceneTable::integer_or(std::string_view key, long long fallback, long long lo,
                                 long long hi) const {
  return has(key) ? integer(key, lo, hi) : (used_->insert(std::string(key)), fallback);
}

namespace {
std::optional<double> as_number(const toml::node& n) {
  if (const auto d = n.value_exact<double>()) return *d;
  if (const auto i = n.value_exact<int64_t>()) return static_cast<double>(*i);
  return std::nullopt;
}
}  // namespace

double SceneTable::number(std::string_view key, double lo, double hi) const {
  const toml::node* n = get(key, true);
  const auto v = as_number(*n);
  if (!v) fail(n, key, fmt::format("expected a number, got {}", type_name(*n)));
  if (!(*v >= lo && *v <= hi) || !std::isfinite(*v))
    fail(n, key, fmt::format("{} is out of range [{}, {}]", *v, lo, hi));
  return *v;
}

double SceneTable::number_or(std::string_view key, double fallback, double lo, double hi) const {
  return has(key) ? number(key, lo, hi) : (used_->insert(std::string(key)), fallback);
}

std::string SceneTable::string(std::string_view key) const {
  const toml::node* n = get(key, true);
  const auto v = n->value_exact<std::string>();
  if (!v) fail(n, key, fmt::format("expected a string, got {}", type_name(*n)));
  return *v;
}

std::string SceneTable::choice(std::string_view key, const std::vector<std::string>& choices) const {
  const std::string v = string(key);
  if (std::find(choices.begin(), choices.end(), v) == choices.end())
    fail(table_->get(key), key, fmt::format("'{}' is not one of: {}", v, fmt::join(choices, ", ")));
  return v;
}

std::string SceneTable::choice_or(std::string_view key, std::string fallback,
                                  const std::vector<std::string>& choices) const {
  return has(key) ? choice(key, choices) : (used_->insert(std::string(key)), fallback);
}

std::vector<std::string> SceneTable::choices(std::string_view key,
                                             const std::vector<std::string>& allowed) const {
  return string_list(key, &allowed);
}

std::vector<std::string> SceneTable::names(std::string_view key) const { return string_list(key, nullptr); }

bool SceneTable::is_array_of_tables(std::string_view key) const {
  const toml::node* n = table_->get(key);
  return n && n->is_array_of_tables();
}

std::vector<std::string> SceneTable::string_list(std::string_view key,
                                                 const std::vector<std::string>* allowed) const {
  const toml::node* n = get(key, true);
  const toml::array* a = n->as_array();
  if (!a || a->empty()) fail(n, key, "expected a non-empty array of strings");
  std::vector<std::string> out;
  for (const toml::node& item : *a) {
    const auto v = item.value_exact<std::string>();
    if (!v) fail(&item, key, fmt::format("expected strings, got {}", type_name(item)));
    if (allowed && std::find(allowed->begin(), allowed->end(), *v) == allowed->end())
      fail(&item, key, fmt::format("'{}' is not one of: {}", *v, fmt::join(*allowed, ", ")));
    if (v->empty()) fail(&item, key, "expected a name, got an empty string");
    if (std::find(out.begin(), out.end(), *v) != out.end())
      fail(&item, key, fmt::format("'{}' is listed twice", *v));
    out.push_back(*v);
  }
  return out;
}

std::vector<double> SceneTable::numbers(std::string_view key, std::size_t size, double lo,
                                        double hi) const {
  const toml::node* n = get(key, true);
  const toml::array* a = n->as_array();
  if (!a || a->empty() || (size && a->size() != size))
    fail(n, key, size ? fmt::format("expected an array of {} numbers", size)
                      : std::string("expected a non-empty array of numbers"));
  std::vector<double> out;
  for (const toml::node& item : *a) {
    const auto v = as_number(item);
    if (!v) fail(&item, key, fmt::format("expected numbers, got {}", type_name(item)));
    if (!(*v >= lo && *v <= hi) || !std::isfinite(*v))
      fail(&item, key, fmt::format("{} is out of range [{}, {}]", *v, lo, hi));
    out.push_back(*v);
  }
  return out;
}

SceneTable SceneTable::table(std::string_view key) const {
  const toml::node* n = get(key, true);
  const toml::table* t = n->as_table();
  if (!t) fail(n, key, fmt::format("expected a table, got {}", type_name(*n)));
  return SceneTable(t, prefix_ + std::string(key) + ".", file_, folder_);
}

SceneTable SceneTable::optional_table(std::string_view key) const {
  static const toml::table empty;
  if (!has(key)) return SceneTable(&empty, prefix_ + std::string(key) + ".", file_, folder_);
  return table(key);
}

void SceneTable::finish() const {
  for (const auto& [k, v] : *table_)
    if (!used_->count(std::string(k.str()))) {
      // Point at the key itself, not its value; a key an override added has no place of its
      // own, but its value names the override.
      const toml::source_region& region = k.source().begin.line > 0 ? k.source() : v.source();
      throw InputError(fmt::format("{}:{}:{}: key '{}{}': unknown key (misspelt, or not used by "
                                   "this kind of run)",
                                   origin_of(region), region.begin.line, region.begin.column, prefix_, k.str()));
    }
}

bool SceneTable::is_string(std::string_view key) const {
  const toml::node* n = table_->get(key);
  return n && n->is_string();
}

bool SceneTable::is_array_empty(std::string_view key) const {
  const toml::node* n = get(key, false);
  return n && n->is_array() && n->as_array()->empty();
}

bool SceneTable::boolean_or(std::string_view key, bool fallback) const {
  const toml::node* n = get(key, false);
  if (!n) return fallback;
  const auto v = n->value_exact<bool>();
  if (!v) fail(n, key, fmt::format("expected true or false, got {}", type_name(*n)));
  return *v;
}

template <std::size_t n>
std::vector<std::array<double, n>> SceneTable::points(std::string_view key, std::size_t size) const {
  const std::string point = n == 2 ? "[x, y]" : "[x, y, z]";
  const toml::node* node = get(key, true);
  const toml::array* a = node->as_array();
  if (!a || a->empty() || (size && a->size() != size))
    fail(node, key,
         size ? fmt::format("expected an array of {} points {}", size, point)
              : fmt::format("expected a non-empty array of points {}", point));
  std::vector<std::array<double, n>> out;
  for (const toml::node& item : *a) {
    const toml::array* p = item.as_array();
    if (!p || p->size() != n) fail(&item, key, fmt::format("expected a point {}", point));
    std::array<double, n> xyz{};
    for (std::size_t c = 0; c < n; ++c) {
      const auto v = as_number(*p->get(c));
      if (!v || !std::isfinite(*v)) fail(p->get(c), key, "expected finite numbers");
      xyz[c] = *v;
    }
    out.push_back(xyz);
  }
  return out;
}

std::vector<std::array<double, 2>> SceneTable::pairs(std::string_view key, std::size_t size) const {
  return points<2>(key, size);
}

std::vector<std::array<double, 3>> SceneTable::triples(std::string_view key, std::size_t size) const {
  return points<3>(key, size);
}

std::vector<SceneTable> SceneTable::tables(std::string_view key) const {
  const toml::node* n = get(key, false);
  std::vector<SceneTable> out;
  if (!n) return out;
  const toml::array* a = n->as_array();
  if (!a || !a->is_array_of_tables()) fail(n, key, "expected an array of tables ([[...]] sections)");
  for (std::size_t i = 0; i < a->size(); ++i)
    out.push_back(SceneTable(a->get(i)->as_table(), fmt::format("{}{}[{}].", prefix_, key, i), file_, folder_));
  return out;
}

namespace {
/// The text of a number or formula node; nullopt for anything else.
std::optional<std::string> expression_text(const toml::node& n) {
  if (const auto s = n.value_exact<std::string>()) return *s;
  if (const auto v = as_number(n)) return std::isfinite(*v) ? std::optional<std::string>(fmt::format("{}", *v)) : std::nullopt;
  return std::nullopt;
}
}  // namespace

std::string SceneTable::expression(std::string_view key) const {
  const toml::node* n = get(key, true);
  const auto v = expression_text(*n);
  if (!v) fail(n, key, fmt::format("expected a finite number or a formula (a string), got {}", type_name(*n)));
  return *v;
}

std::vector<std::string> SceneTable::expressions(std::string_view key, std::size_t size) const {
  const toml::node* n = get(key, true);
  const toml::array* a = n->as_array();
  if (!a || a->size() != size)
    fail(n, key, fmt::format("expected an array of {} numbers or formulas (strings)", size));
  std::vector<std::string> out;
  for (const toml::node& item : *a) {
    const auto v = expression_text(item);
    if (!v) fail(&item, key, fmt::format("expected finite numbers or formulas (strings), got {}", type_name(item)));
    out.push_back(*v);
  }
  return out;
}

std::vector<std::string> SceneTable::keys() const {
  std::vector<std::string> out;
  for (const auto& [k, v] : *table_) {
    out.emplace_back(k.str());
    used_->insert(out.back());
  }
  return out;
}

std::string SceneTable::where(std::string_view key, int index) const {
  const toml::node* n = table_->get(key);
  if (index >= 0 && n && n->is_array() && static_cast<std::size_t>(index) < n->as_array()->size())
    n = n->as_array()->get(static_cast<std::size_t>(index));
  const toml::source_region& region = n ? n->source() : table_->source();
  return fmt::format("{}:{}:{}: key '{}{}{}'", origin_of(region), region.begin.line, region.begin.column, prefix_, key,
                     index >= 0 ? fmt::format("[{}]", index) : "");
}

void SceneTable::error(std::string_view key, const std::string& what) const { fail(table_->get(key), key, what); }

}  // namespace mfree
