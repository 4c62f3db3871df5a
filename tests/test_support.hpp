#pragma once
// Helpers shared by the test files.

#include <cstring>
#include <exception>
#include <filesystem>
#include <string>
#include <system_error>
#include <vector>

#include <unistd.h>

namespace mfree {
class Solid;
}

namespace mfree::testing {

/// The source tree's root (meshes/, verification/, tests/ below it), set by the build for
/// test_support.cpp alone, so that no other test file's compile line names a folder of this
/// machine and the compiler cache serves clones in other folders.
std::string source_dir();

/// The message of the exception of type E that f throws, or a marker when it throws none.
/// Exceptions of other types propagate (and fail the test case).
template <class E = std::exception, class F>
std::string message_of(F&& f) {
  try {
    f();
  } catch (const E& e) {
    return e.what();
  }
  return "<nothing thrown>";
}

/// A fresh folder path for one test case, removed when the case ends; created when `create`
/// (writers that make their own folder get the path only).
struct ScratchFolder {
  std::filesystem::path path;
  explicit ScratchFolder(const std::string& name, bool create = true)
      : path(std::filesystem::temp_directory_path() / ("mfree_test_" + name + "_" + std::to_string(::getpid()))) {
    std::filesystem::remove_all(path);
    if (create) std::filesystem::create_directories(path);
  }
  ~ScratchFolder() {
    std::error_code ec;
    std::filesystem::remove_all(path, ec);
  }
  /// Names of the files in the folder.
  [[nodiscard]] std::vector<std::string> entries() const {
    std::vector<std::string> names;
    for (const auto& e : std::filesystem::directory_iterator(path)) names.push_back(e.path().filename().string());
    return names;
  }
};

/// meshes/thick_sphere_octant.geo (a = 1 <= r <= b = 2, x, y, z >= 0) meshed by gmsh with
/// element size `size`, as a solid.
Solid thick_sphere_octant(double size);

/// True when two doubles are the same bit pattern (a value written and read back unchanged).
inline bool same_bits(double a, double b) { return std::memcmp(&a, &b, sizeof(double)) == 0; }

}  // namespace mfree::testing
