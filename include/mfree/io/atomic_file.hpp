#pragma once
// Output files appear whole or not at all: the text is written to a hidden temporary file
// in the same folder (".NAME.tmpPID": no glob for *.vtu or *.csv picks it up), flushed to
// the disk (fsync), and renamed over the target (rename is atomic on POSIX).

#include <filesystem>
#include <string_view>

namespace mfree {

/// The hidden temporary name for `path` in its folder.
std::filesystem::path temporary_beside(const std::filesystem::path& path);

/// fsync of a written file. Error when it fails.
void sync_file(const std::filesystem::path& path);

/// Writes `content` to `path` atomically, creating parent folders. Throws Error on failure.
void write_file_atomically(const std::filesystem::path& path, std::string_view content);

}  // namespace mfree
