#include "mfree/io/checkpoint.hpp"

#include <fmt/format.h>
#include <unistd.h>

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstring>
#include <fstream>
#include <limits>
#include <sstream>

#include "mfree/core/error.hpp"
#include "mfree/io/atomic_file.hpp"

namespace mfree {

namespace fs = std::filesystem;

namespace {

constexpr char magic[8] = {'M', 'F', 'R', 'E', 'E', 'C', 'K', '1'};
constexpr const char* prefix = "step_";

/// FNV-1a, 64 bits, continued from `hash`.
std::uint64_t fnv1a(std::string_view bytes, std::uint64_t hash = 14695981039346656037ULL) {
  for (const unsigned char c : bytes) hash = (hash ^ c) * 1099511628211ULL;
  return hash;
}

template <class T>
void append(std::string& out, const T& value) {
  out.append(reinterpret_cast<const char*>(&value), sizeof(T));
}

/// Reads from a byte string, InputError (naming the file) when it runs out.
class Reader {
 public:
  Reader(std::string_view bytes, const fs::path& file) : bytes_(bytes), file_(file) {}
  template <class T>
  T next() {
    T value;
    std::memcpy(&value, take(sizeof(T)).data(), sizeof(T));
    return value;
  }
  std::string_view take(std::size_t n) {
    if (n > bytes_.size() - at_) throw InputError(fmt::format("checkpoint {}: truncated", file_.string()));
    const std::string_view out = bytes_.substr(at_, n);
    at_ += n;
    return out;
  }

 private:
  std::string_view bytes_;
  const fs::path& file_;
  std::size_t at_ = 0;
};

/// The index of the first value that is not finite (NaN, inf); none when all are.
std::optional<std::size_t> first_non_finite(const std::vector<double>& values) {
  for (std::size_t k = 0; k < values.size(); ++k)
    if (!std::isfinite(values[k])) return k;
  return std::nullopt;
}

fs::path step_folder(const fs::path& folder, long long step) { return folder / fmt::format("{}{:010d}", prefix, step); }

/// The complete checkpoints in `folder` (step_N folders with a state.bin), by step.
std::vector<std::pair<long long, fs::path>> checkpoints_in(const fs::path& folder) {
  std::vector<std::pair<long long, fs::path>> out;
  std::error_code ec;
  for (const fs::directory_entry& e : fs::directory_iterator(folder, ec)) {
    const std::string name = e.path().filename().string();
    if (name.rfind(prefix, 0) != 0) continue;
    const fs::path state = e.path() / "state.bin";
    std::error_code missing;
    if (!fs::exists(state, missing)) {
      if (missing && missing != std::errc::no_such_file_or_directory)  // a link loop, no permission
        throw InputError(fmt::format("checkpoint {}: {}", state.string(), missing.message()));
      continue;
    }
    const std::string digits = name.substr(std::strlen(prefix));
    if (digits.empty() || digits.find_first_not_of("0123456789") != std::string::npos) continue;
    long long step = 0;
    const auto [end, error] = std::from_chars(digits.data(), digits.data() + digits.size(), step);
    if (error != std::errc() || end != digits.data() + digits.size())
      throw InputError(fmt::format("checkpoint {}: the step number {} is out of range", e.path().string(), digits));
    out.emplace_back(step, e.path());
  }
  std::sort(out.begin(), out.end());
  return out;
}

std::string serialise(std::uint64_t fingerprint, long long step, const CheckpointState& state) {
  std::string out;
  append(out, static_cast<std::int64_t>(step));
  append(out, static_cast<std::uint64_t>(state.arrays().size()));
  for (const auto& [name, values] : state.arrays()) {
    append(out, static_cast<std::uint64_t>(name.size()));
    out += name;
    append(out, static_cast<std::uint64_t>(values.size()));
    if (!values.empty()) out.append(reinterpret_cast<const char*>(values.data()), values.size() * sizeof(double));
  }
  return checkpoint_file(fingerprint, out);
}

CheckpointState deserialise(const fs::path& file, std::uint64_t fingerprint, long long& step) {
  std::ifstream in(file, std::ios::binary);
  std::stringstream buffer;
  buffer << in.rdbuf();
  if (!in) throw InputError(fmt::format("checkpoint {}: cannot be read", file.string()));
  const std::string bytes = buffer.str();
  if (bytes.size() < sizeof magic + 8 || std::memcmp(bytes.data(), magic, sizeof magic) != 0)
    throw InputError(fmt::format("checkpoint {}: not an mfree checkpoint", file.string()));
  const std::string_view body(bytes.data(), bytes.size() - 8);
  std::uint64_t hash;
  std::memcpy(&hash, bytes.data() + body.size(), 8);
  if (hash != fnv1a(body)) throw InputError(fmt::format("checkpoint {}: damaged (its checksum does not match)", file.string()));
  Reader r(body, file);
  (void)r.take(sizeof magic);
  if (r.next<std::uint64_t>() != fingerprint)
    throw InputError(fmt::format("checkpoint {}: written by a run of another scene (or other --set overrides); "
                                 "restart with the scene and overrides of the run that wrote it",
                                 file.string()));
  step = r.next<std::int64_t>();
  CheckpointState state;
  state.source = file;
  const std::uint64_t arrays = r.next<std::uint64_t>();
  for (std::uint64_t a = 0; a < arrays; ++a) {
    const std::string name(r.take(r.next<std::uint64_t>()));
    const std::uint64_t n = r.next<std::uint64_t>();
    if (n > body.size() / sizeof(double)) throw InputError(fmt::format("checkpoint {}: truncated", file.string()));
    std::vector<double> values(n);
    const std::string_view raw = r.take(n * sizeof(double));
    if (n > 0) std::memcpy(values.data(), raw.data(), raw.size());  // an empty vector's data() may be null
    if (const auto k = first_non_finite(values))
      state.refuse(name, fmt::format("value {} is {}, not a finite number", *k, values[*k]));
    state.put(name, std::move(values));
  }
  return state;
}

/// Links (or copies) every file of `from` into `to`, recursively; Error on failure.
void link_tree(const fs::path& from, const fs::path& to) {
  std::error_code ec;
  fs::create_directories(to, ec);
  if (ec) throw Error(fmt::format("cannot create folder {}: {}", to.string(), ec.message()));
  for (const fs::directory_entry& e : fs::directory_iterator(from)) {
    const fs::path target = to / e.path().filename();
    if (e.is_directory()) {
      link_tree(e.path(), target);
      continue;
    }
    fs::create_hard_link(e.path(), target, ec);
    if (ec) {
      ec.clear();
      fs::copy_file(e.path(), target, fs::copy_options::overwrite_existing, ec);
    }
    if (ec) throw Error(fmt::format("cannot keep {} in {}: {}", e.path().string(), to.string(), ec.message()));
  }
}

}  // namespace

std::string checkpoint_file(std::uint64_t fingerprint, std::string_view body) {
  std::string out(magic, sizeof magic);
  append(out, fingerprint);
  out += body;
  append(out, fnv1a(out));
  return out;
}

void CheckpointState::put(const std::string& name, std::vector<double> values) { arrays_[name] = std::move(values); }

void CheckpointState::put_ints(const std::string& name, const std::vector<int>& values) {
  put(name, std::vector<double>(values.begin(), values.end()));
}

const std::vector<double>& CheckpointState::get(const std::string& name, std::optional<std::size_t> size) const {
  const auto it = arrays_.find(name);
  if (it == arrays_.end()) refuse(name, "it is missing");
  if (size && it->second.size() != *size)
    refuse(name, fmt::format("it holds {} values, and this run needs {}", it->second.size(), *size));
  return it->second;
}

const std::vector<double>& CheckpointState::within(const std::string& name, double lo, double hi,
                                                   const std::string& range,
                                                   std::optional<std::size_t> size) const {
  const std::vector<double>& v = get(name, size);
  for (std::size_t k = 0; k < v.size(); ++k)
    if (!(v[k] >= lo && v[k] <= hi)) refuse(name, fmt::format("value {} is {}, not {}", k, v[k], range));
  return v;
}

const std::vector<double>& CheckpointState::times(const std::string& name, double end,
                                                  std::size_t most) const {
  const std::vector<double>& t =
      within(name, 0.0, end, fmt::format("a time of the run so far (0 to {} s)", end));
  if (t.size() > most)
    refuse(name, fmt::format("it holds {} times, more than the {} the run can have so far", t.size(), most));
  for (std::size_t k = 1; k < t.size(); ++k)
    if (t[k] < t[k - 1])
      refuse(name, fmt::format("value {} is {}, before the one before it ({})", k, t[k], t[k - 1]));
  return t;
}

std::vector<long long> CheckpointState::integers(const std::string& name, long long lo, long long hi,
                                                 const std::string& range,
                                                 std::optional<std::size_t> size) const {
  const std::vector<double>& v = get(name, size);
  std::vector<long long> out(v.size());
  for (std::size_t k = 0; k < v.size(); ++k) {
    // Compared as doubles first: a cast of a value outside long long's range is undefined.
    if (!(v[k] >= static_cast<double>(lo) && v[k] <= static_cast<double>(hi) && v[k] == std::trunc(v[k])))
      refuse(name, fmt::format("value {} is {}, not {}", k, v[k], range));
    out[k] = static_cast<long long>(v[k]);
  }
  return out;
}

std::vector<int> CheckpointState::ints(const std::string& name, std::optional<std::size_t> size) const {
  const std::vector<long long> v =
      integers(name, std::numeric_limits<int>::min(), std::numeric_limits<int>::max(), "an int", size);
  return {v.begin(), v.end()};
}

void CheckpointState::refuse(const std::string& name, const std::string& what) const {
  throw InputError(
      fmt::format("checkpoint {}: array '{}': {}; the checkpoint does not fit this run (another version "
                  "of mfree?) or is damaged: restart from an earlier checkpoint or without --restart",
                  source.string(), name, what));
}

std::uint64_t scene_fingerprint(const fs::path& scene, const std::vector<std::string>& overrides) {
  std::ifstream in(scene, std::ios::binary);
  std::stringstream text;
  text << in.rdbuf();
  std::uint64_t hash = fnv1a(text.str());
  for (const std::string& o : overrides) hash = fnv1a(o + '\n', hash);
  return hash;
}

Checkpoints::Checkpoints(fs::path output_folder, int every, std::uint64_t fingerprint, const fs::path& restart)
    : folder_(output_folder.string() + ".checkpoints"), every_(every), fingerprint_(fingerprint) {
  if (every < 0) throw InputError(fmt::format("checkpoint_every must be 0 (none) or positive, got {}", every));
  if (restart.empty()) {
    // A fresh start: checkpoints of an earlier run of this folder would mix with this run's.
    if (every_ > 0)
      for (const auto& [step, path] : checkpoints_in(folder_)) fs::remove_all(path);
    return;
  }
  std::error_code ec;
  if (!fs::is_directory(restart, ec))
    throw InputError(fmt::format("--restart {}: {}", restart.string(),
                                 ec && ec != std::errc::no_such_file_or_directory ? ec.message()
                                                                                   : "no such folder of checkpoints"));
  const auto found = checkpoints_in(restart);
  if (found.empty())
    throw InputError(fmt::format("--restart {}: holds no checkpoint (step_N folders with a state.bin)", restart.string()));
  resume_folder_ = found.back().second;
  const fs::path state = resume_folder_ / "state.bin";
  resume_.emplace(deserialise(state, fingerprint_, resume_step_));
  if (resume_step_ != found.back().first)
    throw InputError(
        fmt::format("checkpoint {}: holds step {}, but its folder is named for step {}: the checkpoint "
                    "is damaged; restart from an earlier checkpoint or without --restart",
                    state.string(), resume_step_, found.back().first));
  if (!fs::is_directory(resume_folder_ / "output"))
    throw InputError(fmt::format("checkpoint {}: its output folder is missing", resume_folder_.string()));
}

void Checkpoints::restore_output(const fs::path& staging) const {
  if (resume_) link_tree(resume_folder_ / "output", staging);
}

void Checkpoints::write(long long step, const CheckpointState& state, const fs::path& staging) const {
  for (const auto& [name, values] : state.arrays())
    if (const auto k = first_non_finite(values))
      throw NumericalError(
          fmt::format("checkpoint of step {} in {}: array '{}': value {} is {}, not a finite number "
                      "(the run is unstable; use a smaller time step)",
                      step, folder_.string(), name, *k, values[*k]));
  std::error_code ec;
  fs::create_directories(folder_, ec);
  if (ec) throw Error(fmt::format("cannot create folder {}: {}", folder_.string(), ec.message()));
  const fs::path final = step_folder(folder_, step);
  const fs::path partial = folder_ / fmt::format(".{}.partial-{}", final.filename().string(), ::getpid());
  fs::remove_all(partial, ec);
  link_tree(staging, partial / "output");
  write_file_atomically(partial / "state.bin", serialise(fingerprint_, step, state));
  fs::remove_all(final, ec);
  fs::rename(partial, final, ec);
  if (ec) throw Error(fmt::format("cannot move checkpoint {} into place: {}", final.string(), ec.message()));
  const auto all = checkpoints_in(folder_);
  for (std::size_t k = 0; k + 2 < all.size(); ++k) fs::remove_all(all[k].second, ec);
}

void Checkpoints::remove() const {
  std::error_code ec;
  if (every_ > 0 || resume_) fs::remove_all(folder_, ec);
}

}  // namespace mfree
