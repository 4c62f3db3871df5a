#include "mfree/io/checkpoint.hpp"

#include <fmt/format.h>
#include <unistd.h>

#include <algorithm>
#include <charconv>
#include <cstring>
#include <fstream>
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
  std::string out(magic, sizeof magic);
  append(out, fingerprint);
  append(out, static_cast<std::int64_t>(step));
  append(out, static_cast<std::uint64_t>(state.arrays().size()));
  for (const auto& [name, values] : state.arrays()) {
    append(out, static_cast<std::uint64_t>(name.size()));
    out += name;
    append(out, static_cast<std::uint64_t>(values.size()));
    if (!values.empty()) out.append(reinterpret_cast<const char*>(values.data()), values.size() * sizeof(double));
  }
  append(out, fnv1a(out));
  return out;
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

void CheckpointState::put(const std::string& name, std::vector<double> values) { arrays_[name] = std::move(values); }

void CheckpointState::put_ints(const std::string& name, const std::vector<int>& values) {
  put(name, std::vector<double>(values.begin(), values.end()));
}

const std::vector<double>& CheckpointState::get(const std::string& name, std::optional<std::size_t> size) const {
  const auto it = arrays_.find(name);
  if (it == arrays_.end()) fail(name, "it is missing");
  if (size && it->second.size() != *size) fail(name, fmt::format("it holds {} values, not {}", it->second.size(), *size));
  return it->second;
}

std::vector<int> CheckpointState::ints(const std::string& name) const {
  const std::vector<double>& v = get(name);
  return {v.begin(), v.end()};
}

void CheckpointState::fail(const std::string& name, const std::string& what) const {
  throw InputError(fmt::format("checkpoint {}: array '{}': {} (written by another version of mfree?)", source.string(),
                               name, what));
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
  resume_.emplace(deserialise(resume_folder_ / "state.bin", fingerprint_, resume_step_));
  if (!fs::is_directory(resume_folder_ / "output"))
    throw InputError(fmt::format("checkpoint {}: its output folder is missing", resume_folder_.string()));
}

void Checkpoints::restore_output(const fs::path& staging) const {
  if (resume_) link_tree(resume_folder_ / "output", staging);
}

void Checkpoints::write(long long step, const CheckpointState& state, const fs::path& staging) const {
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
