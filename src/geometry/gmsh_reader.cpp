#include "gmsh_reader.hpp"

#include <fmt/format.h>
#include <gmsh.h>

#include <algorithm>
#include <cctype>
#include <chrono>
#include <csignal>
#include <fstream>
#include <new>

#include "mfree/core/child_process.hpp"
#include "mfree/core/error.hpp"

namespace mfree::gmsh_reader {

namespace {
std::string accepted_extensions() {
  std::string list;
  for (const std::string_view e : gmsh_extensions) list += fmt::format("{}{}", list.empty() ? "" : ", ", e);
  return list;
}

/// One gmsh session: initialised quietly (no configuration files, nothing on the terminal, one thread),
/// its messages collected by the logger, finalised when it ends. gmsh keeps one model, one
/// option set and one logger for a whole process: a session runs in a process of its own
/// (read_in_child below).
class GmshSession {
 public:
  GmshSession() {
    gmsh::initialize(0, nullptr, /*readConfigFiles=*/false);
    gmsh::option::setNumber("General.Terminal", 0);
    // One thread: gmsh 4.8 meshes the faces of a solid in parallel with races (a double free
    // in its surface mesher was seen), and a serial mesh is the same in every run.
    gmsh::option::setNumber("General.NumThreads", 1);
    for (const char* option : {"Mesh.MaxNumThreads1D", "Mesh.MaxNumThreads2D", "Mesh.MaxNumThreads3D"})
      gmsh::option::setNumber(option, 1);
    gmsh::logger::start();
  }
  GmshSession(const GmshSession&) = delete;
  GmshSession& operator=(const GmshSession&) = delete;
  ~GmshSession() {
    // gmsh reports errors by throwing std::string; none may leave a destructor.
    try {
      gmsh::logger::stop();
      gmsh::finalize();
    } catch (...) {
    }
  }

  /// gmsh's error messages so far, joined by "; ", or `thrown` (the message gmsh threw) if
  /// the log holds none.
  [[nodiscard]] static std::string errors(const std::string& thrown) {
    std::vector<std::string> log;
    gmsh::logger::get(log);
    std::string out;
    const std::string_view prefix = "Error: ";
    for (const std::string& line : log) {
      if (line.compare(0, prefix.size(), prefix) == 0) {
        out += fmt::format("{}{}", out.empty() ? "" : "; ", line.substr(prefix.size()));
      }
    }
    return out.empty() ? thrown : out;
  }
};

/// What the child process sends: read()'s bytes, or 'E' and an error message.
std::string message(const std::string& file, const std::function<std::string()>& read) {
  try {
    const GmshSession session;
    try {
      return read();
    } catch (const std::string& thrown) {
      return "E" + fmt::format("{}: gmsh cannot read it: {}", file, GmshSession::errors(thrown));
    }
  } catch (const std::bad_alloc&) {
    return "E" + fmt::format(
                     "{}: gmsh ran out of memory reading it: element sizes too small for the domain "
                     "(point sizes, Mesh.MeshSizeMax) are the usual cause; coarsen them",
                     file);
  } catch (const std::exception& e) {
    return std::string("E") + e.what();
  } catch (...) {
    return "E" + fmt::format("{}: gmsh cannot read it", file);
  }
}

/// Whether a signal is one a crash raises (rather than one sent from outside).
bool is_crash_signal(int signal) {
  for (const int crash : {SIGSEGV, SIGBUS, SIGABRT, SIGFPE, SIGILL, SIGSYS, SIGTRAP})
    if (signal == crash) return true;
  return false;
}

}  // namespace

std::string lower_case(std::string s) {
  std::transform(s.begin(), s.end(), s.begin(), [](unsigned char c) { return std::tolower(c); });
  return s;
}

/// "'a'" or "'a', 'b' and 'c'".
std::string quoted_list(const std::vector<std::string>& names) {
  std::string out;
  for (std::size_t i = 0; i < names.size(); ++i)
    out += fmt::format("{}'{}'", i == 0 ? "" : (i + 1 == names.size() ? " and " : ", "), names[i]);
  return out;
}

void check_file(const std::filesystem::path& file) {
  const std::string source = file.string();
  if (!is_gmsh_file(file)) {
    throw InputError(fmt::format("{}: unknown extension '{}' for a gmsh file; gmsh files end in {}", source,
                                 file.extension().string(), accepted_extensions()));
  }
  // gmsh opens a missing file without complaint (an empty model), so look first.
  std::error_code ec;
  if (!std::filesystem::is_regular_file(file, ec)) {
    throw InputError(fmt::format("mesh file '{}' does not exist or is not a regular file", source));
  }
  if (!std::ifstream(file)) throw InputError(fmt::format("cannot read mesh file '{}'", source));
}

std::map<int, int> entity_parts(int dim, const std::vector<std::pair<int, int>>& entities,
                                std::vector<std::string>& part_names, const std::string& source,
                                std::string_view kind) {
  std::map<int, int> group_of_entity;  // entity tag -> physical group tag, 0: none
  std::map<int, std::string> used;     // group tag -> name, groups on the boundary only
  for (const auto& [entity_dim, entity] : entities) {
    std::vector<int> groups;
    gmsh::model::getPhysicalGroupsForEntity(dim, entity, groups);
    std::vector<std::string> names;
    for (int g : groups) {
      std::string name;
      gmsh::model::getPhysicalName(dim, g, name);
      names.push_back(name.empty() ? std::to_string(g) : name);
    }
    std::sort(names.begin(), names.end());
    names.erase(std::unique(names.begin(), names.end()), names.end());
    if (names.size() > 1) {
      throw InputError(
          fmt::format("{}: {} {} belongs to the physical {} {}; a {} belongs to one "
                      "named part only",
                      source, kind, entity,
                      dim == 1   ? "curves"
                      : dim == 2 ? "surfaces"
                                 : "volumes",
                      quoted_list(names), kind));
    }
    group_of_entity[entity] = groups.empty() ? 0 : groups.front();
    if (!groups.empty()) used[groups.front()] = names.front();
  }
  std::map<int, int> part_of_group;
  for (const auto& [group, name] : used) {
    const auto known = std::find(part_names.begin(), part_names.end(), name);
    part_of_group[group] = static_cast<int>(known - part_names.begin());
    if (known == part_names.end()) part_names.push_back(name);
  }
  std::map<int, int> out;
  for (const auto& [entity, group] : group_of_entity) out[entity] = group == 0 ? -1 : part_of_group[group];
  return out;
}

std::string read_in_child(const std::string& file, const GmshReaderLimits& limits,
                          const std::function<std::string()>& read) {
  const ChildOutcome out =
      run_in_child([&] { return message(file, read); }, ChildLimits{limits.wall_time, limits.memory_bytes},
                   fmt::format("{}: the gmsh reader", file));
  switch (out.end) {
    case ChildOutcome::End::out_of_time:
      throw InputError(fmt::format(
          "{}: gmsh did not finish reading it within {:g} s (the limit of the gmsh reader; see README): an "
          "endless loop in a .geo script, an Include of a file that never ends (such as a device) or element "
          "sizes far too small for the domain",
          file, std::chrono::duration<double>(limits.wall_time).count()));
    case ChildOutcome::End::out_of_memory:
      throw InputError(fmt::format(
          "{}: gmsh used more than {:g} MiB of memory reading it (the limit of the gmsh reader; see README): "
          "element sizes too small for the domain (point sizes, Mesh.MeshSizeMax) are the usual cause; "
          "coarsen them",
          file, static_cast<double>(limits.memory_bytes) / (1024.0 * 1024.0)));
    case ChildOutcome::End::signalled:
      if (is_crash_signal(out.code))
        throw InputError(fmt::format("{}: gmsh crashed reading it ({}): the file is malformed", file,
                                     ::strsignal(out.code)));
      throw Error(
          fmt::format("{}: the gmsh reader process was ended from outside by signal {} ({}) while "
                      "reading it{}",
                      file, out.code, ::strsignal(out.code),
                      out.code == SIGKILL ? ", most likely by the system for lack of memory (element "
                                            "sizes too small for the domain?)"
                                          : ""));
    case ChildOutcome::End::exited:
      break;
  }
  if (out.code != 0 || out.output.empty())
    throw Error(fmt::format("{}: the gmsh reader process failed (exit status {})", file, out.code));
  if (out.output[0] == 'E') throw InputError(out.output.substr(1));
  return out.output;
}

void MessageReader::take(void* to, std::size_t n) {
  if (n > bytes_.size() - at_)
    throw Error(fmt::format("{}: the gmsh reader process sent a truncated message", file_));
  std::memcpy(to, bytes_.data() + at_, n);
  at_ += n;
}

std::size_t MessageReader::count() {
  const auto n = take<std::size_t>();
  if (n > bytes_.size())
    throw Error(fmt::format("{}: the gmsh reader process sent a malformed message", file_));
  return n;
}

void put_names(std::string& out, const std::vector<std::string>& names) {
  put(out, names.size());
  for (const std::string& name : names) {
    put(out, name.size());
    out += name;
  }
}

std::vector<std::string> MessageReader::names() {
  std::vector<std::string> out(count());
  for (std::string& name : out) {
    name.resize(count());
    take(name.data(), name.size());
  }
  return out;
}

void MessageReader::finish() const {
  if (at_ != bytes_.size())
    throw Error(fmt::format("{}: the gmsh reader process sent a malformed message", file_));
}

}  // namespace mfree::gmsh_reader
