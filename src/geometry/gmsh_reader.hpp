#pragma once
// What the gmsh readers of plane domains (gmsh_domain.cpp) and of solids (gmsh_solid.cpp)
// share: the checks of a file before gmsh sees it, one quiet gmsh session in a child process
// under limits with its failures turned into errors naming the file, and the parts of
// entities from their physical groups. Private to the library.

#include <cstring>
#include <filesystem>
#include <functional>
#include <map>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "mfree/geometry/gmsh_domain.hpp"

namespace mfree::gmsh_reader {

[[nodiscard]] std::string lower_case(std::string s);

/// "'a'" or "'a', 'b' and 'c'".
[[nodiscard]] std::string quoted_list(const std::vector<std::string>& names);

/// Throws InputError naming the file when its extension is not one of gmsh_extensions, or it
/// is missing, not a regular file or unreadable (gmsh opens a missing file as an empty model).
void check_file(const std::filesystem::path& file);

/// The part index of every entity of dimension `dim` (-1: none) with the part names, from the
/// physical groups of that dimension. Parts are numbered by group tag; groups of the same name
/// are one part, a group without a name is named by its number. `kind` names the entities in
/// messages ("boundary curve"); an entity in groups of two names is an InputError. Runs in a
/// gmsh session.
[[nodiscard]] std::map<int, int> entity_parts(int dim, const std::vector<std::pair<int, int>>& entities,
                                              std::vector<std::string>& part_names, const std::string& source,
                                              std::string_view kind);

/// Runs read() in a child process (mfree/core/child_process.hpp) under the limits, inside a
/// quiet gmsh session (no configuration files, nothing on the terminal, messages kept by the
/// logger), and returns the bytes it returned. libgmsh crashes on some malformed files
/// (tests/fuzz/known_crashes), loops forever on others and may exhaust the memory; each ends
/// as an InputError naming the file, not the program, and gmsh's global state stays out of
/// this process. An error read() throws (gmsh's std::string, InputError, std::bad_alloc) is
/// an InputError naming the file; the reader killed from outside is an Error.
[[nodiscard]] std::string read_in_child(const std::string& file, const GmshReaderLimits& limits,
                                        const std::function<std::string()>& read);

/// Appends the bytes of a trivially copyable value (the readers' messages).
template <class T>
void put(std::string& out, const T& value) {
  out.append(reinterpret_cast<const char*>(&value), sizeof(T));
}

/// Appends a list of names: their count, then each one's length and bytes.
void put_names(std::string& out, const std::vector<std::string>& names);

/// Takes values back out of such a message, from offset 1 (after its kind letter).
class MessageReader {
 public:
  MessageReader(const std::string& bytes, const std::string& file) : bytes_(bytes), file_(file) {}
  /// n bytes into `to`; Error when the message is shorter.
  void take(void* to, std::size_t n);
  template <class T>
  T take() {
    T value;
    take(&value, sizeof value);
    return value;
  }
  /// A count, at most the message's size (Error otherwise).
  std::size_t count();
  /// A list of names (put_names).
  std::vector<std::string> names();
  /// Error unless every byte was taken.
  void finish() const;

 private:
  const std::string& bytes_;
  const std::string& file_;
  std::size_t at_ = 1;
};

}  // namespace mfree::gmsh_reader
