#pragma once
// Output files appear whole or not at all: the text is written to a temporary file in
// the same folder, flushed, and renamed over the target (rename is atomic on POSIX).

#include <filesystem>
#include <string_view>

namespace mfree {

/// Writes `content` to `path` atomically, creating parent folders. Throws Error on failure.
void write_file_atomically(const std::filesystem::path& path, std::string_view content);

}  // namespace mfree
