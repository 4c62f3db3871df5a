#include "mfree/io/staged_folder.hpp"

#include <fcntl.h>
#include <fmt/format.h>
#include <signal.h>
#include <unistd.h>

#include <cerrno>
#include <charconv>
#include <cstdio>
#include <cstring>
#include <map>
#include <mutex>
#include <string>

#include "mfree/core/error.hpp"
#include "mfree/io/atomic_file.hpp"

namespace mfree {

namespace fs = std::filesystem;

namespace {

constexpr const char* marker = ".mfree-output";

/// The staging folders of the StagedFolders alive (staging folder -> target), for a run
/// stopped by a signal. Its lock is held while a staging folder is made, committed or removed.
struct LiveFolders {
  std::mutex lock;
  std::map<fs::path, fs::path> staging;
};

LiveFolders& live_folders() {
  static LiveFolders folders;
  return folders;
}

/// The folder holding `p` (the working directory for a bare name).
fs::path parent_of(const fs::path& p) { return p.has_parent_path() ? p.parent_path() : fs::path("."); }

/// Removes staging folders of `target` left by runs that were killed (their process is gone).
void remove_abandoned(const fs::path& target) {
  std::error_code ec;
  const std::string prefix = fmt::format(".{}.partial-", target.filename().string());
  for (const fs::directory_entry& e : fs::directory_iterator(parent_of(target), ec)) {
    const std::string name = e.path().filename().string();
    if (name.rfind(prefix, 0) != 0) continue;
    const std::string pid = name.substr(prefix.size());
    // A name whose number is no process id was not made by a run: left alone.
    pid_t id = 0;
    const auto [end, error] = std::from_chars(pid.data(), pid.data() + pid.size(), id);
    if (pid.empty() || error != std::errc() || end != pid.data() + pid.size() || id <= 0) continue;
    if (::kill(id, 0) != 0 && errno == ESRCH) fs::remove_all(e.path(), ec);
  }
}

/// Flushes a folder's entries (the renames into it) to the disk.
void sync_folder(const fs::path& folder) {
  const int fd = ::open(folder.c_str(), O_RDONLY | O_DIRECTORY);
  if (fd < 0) return;
  (void)::fsync(fd);
  ::close(fd);
}

}  // namespace

StagedFolder::StagedFolder(fs::path target) : target_(std::move(target)) {
  std::error_code ec;
  const fs::file_status status = fs::symlink_status(target_, ec);
  if (fs::exists(status)) {
    if (!fs::is_directory(status))
      throw InputError(fmt::format("output folder {}: exists and is not a folder", target_.string()));
    // Written by mfree: the marker, or (folders of versions before the marker) the
    // summary.json of every run or the table of every study.
    const bool ours = fs::exists(target_ / marker) || fs::exists(target_ / "summary.json") ||
                      fs::exists(target_ / "convergence.csv") || fs::exists(target_ / "mpm_convergence.csv");
    if (!ours && !fs::is_empty(target_, ec))
      throw InputError(
          fmt::format("output folder {}: exists and was not written by mfree (no {} in it); a run "
                      "replaces its output folder as a whole, so name a new folder or remove this one",
                      target_.string(), marker));
  }
  fs::create_directories(parent_of(target_), ec);
  if (ec) throw Error(fmt::format("cannot create folder {}: {}", parent_of(target_).string(), ec.message()));
  remove_abandoned(target_);
  staging_ = parent_of(target_) / fmt::format(".{}.partial-{}", target_.filename().string(), ::getpid());
  {
    const std::scoped_lock hold(live_folders().lock);
    fs::remove_all(staging_, ec);
    fs::create_directory(staging_, ec);
    if (ec) throw Error(fmt::format("cannot create folder {}: {}", staging_.string(), ec.message()));
    live_folders().staging.emplace(staging_, target_);
  }
  try {
    write_file_atomically(staging_ / marker, "written by mfree: a run replaces this folder as a whole\n");
  } catch (...) {
    remove_staging();
    throw;
  }
}

StagedFolder::~StagedFolder() {
  if (!committed_) remove_staging();
}

void StagedFolder::remove_staging() {
  const std::scoped_lock hold(live_folders().lock);
  std::error_code ec;
  fs::remove_all(staging_, ec);
  live_folders().staging.erase(staging_);
}

std::vector<fs::path> abandon_staging_folders() {
  live_folders().lock.lock();  // never released: the process ends
  std::vector<fs::path> targets;
  for (const auto& [staging, target] : live_folders().staging) {
    std::error_code ec;
    fs::remove_all(staging, ec);
    targets.push_back(target);
  }
  return targets;
}

void StagedFolder::commit() {
  const std::scoped_lock hold(live_folders().lock);
  live_folders().staging.erase(staging_);
  std::error_code ec;
  const fs::path parent = parent_of(target_);
  if (fs::exists(target_, ec)) {
    // One atomic exchange: at every instant the folder holds the old results or the new.
    if (::renameat2(AT_FDCWD, staging_.c_str(), AT_FDCWD, target_.c_str(), RENAME_EXCHANGE) != 0)
      throw Error(fmt::format("cannot put the results in {}: {}", target_.string(), std::strerror(errno)));
    fs::remove_all(staging_, ec);  // now the old results
  } else {
    fs::rename(staging_, target_, ec);
    if (ec) throw Error(fmt::format("cannot put the results in {}: {}", target_.string(), ec.message()));
  }
  sync_folder(parent);
  committed_ = true;
}

}  // namespace mfree
