// Output folders written whole into a staging folder and swapped in; user folders never touched.
#include <workbench/error.h>
#include <workbench/interruption.h>
#include <workbench/output_file.h>
#include <workbench/staged_directory.h>

#include <cerrno>
#include <csignal>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <mutex>
#include <system_error>
#include <utility>
#include <vector>
#include <unistd.h>

namespace workbench {

namespace fs = std::filesystem;

namespace {

// What may stand at `target` before we write it: nothing, an empty folder, or our own output.
void check_replaceable(const fs::path& target) {
  std::error_code ec;
  const auto status = fs::symlink_status(target, ec);
  if (ec || !fs::exists(status)) return;
  if (fs::is_symlink(status)) throw Error(target.string() + ": is a symbolic link; refusing to replace it");
  if (!fs::is_directory(status)) throw Error(target.string() + ": exists and is not a folder");
  if (fs::is_empty(target, ec) || carries_stamp(target)) return;
  throw Error(target.string() + ": is a folder the workbench did not write (it has files and no " + kStampFile +
              "); refusing to replace it, choose a new or empty folder");
}

// A sibling `.NAME.<kind>-PID` left by a run that is gone (killed): its process no longer exists
// and it carries our stamp, so it is ours to remove.
void remove_stale_siblings(const fs::path& target) {
  const std::string prefix = "." + target.filename().string() + ".";
  std::error_code ec;
  for (const auto& entry : fs::directory_iterator(target.parent_path(), ec)) {
    const std::string name = entry.path().filename().string();
    if (name.rfind(prefix, 0) != 0) continue;
    const std::string rest = name.substr(prefix.size());
    std::string pid_text;
    for (const char* kind : {"partial-", "old-"})
      if (rest.rfind(kind, 0) == 0) pid_text = rest.substr(std::string(kind).size());
    if (pid_text.empty() || pid_text.find_first_not_of("0123456789") != std::string::npos || pid_text.size() > 9)
      continue;
    const pid_t pid = static_cast<pid_t>(std::stol(pid_text));
    const bool gone = pid != ::getpid() && ::kill(pid, 0) != 0 && errno == ESRCH;
    std::error_code e2;
    if (gone && entry.is_directory(e2) && !entry.is_symlink(e2) && carries_stamp(entry.path()))
      fs::remove_all(entry.path(), e2);
  }
}

// Live staging folders and their targets, for messages (shown_path).
std::mutex shown_mutex;
std::vector<std::pair<fs::path, fs::path>> live_stagings;

void show_as(const fs::path& staging, const fs::path& target) {
  std::lock_guard<std::mutex> lock(shown_mutex);
  live_stagings.emplace_back(staging, target);
}

void forget_shown(const fs::path& staging) {
  std::lock_guard<std::mutex> lock(shown_mutex);
  for (auto it = live_stagings.begin(); it != live_stagings.end(); ++it)
    if (it->first == staging) {
      live_stagings.erase(it);
      break;
    }
}

}  // namespace

std::string shown_path(const fs::path& path) {
  std::lock_guard<std::mutex> lock(shown_mutex);
  for (const auto& [staging, target] : live_stagings) {
    const fs::path relative = path.lexically_relative(staging);
    if (relative == ".") return target.string();
    if (!relative.empty() && *relative.begin() != "..") return (target / relative).lexically_normal().string();
  }
  return path.string();
}

std::string shown_text(std::string text) {
  std::lock_guard<std::mutex> lock(shown_mutex);
  for (const auto& [staging, target] : live_stagings)
    for (std::size_t at; (at = text.find(staging.string())) != std::string::npos;)
      text.replace(at, staging.string().size(), target.string());
  return text;
}

bool carries_stamp(const fs::path& dir) {
  std::error_code ec;
  const fs::path stamp = dir / kStampFile;
  if (!fs::is_regular_file(fs::symlink_status(stamp, ec))) return false;
  std::ifstream in(stamp);
  std::string first;
  std::getline(in, first);
  return first == "program = \"workbench\"";
}

StagedDirectory::StagedDirectory(fs::path target, const fs::path& case_file)
    : target_(fs::absolute(std::move(target)).lexically_normal()) {
  if (target_.filename().empty()) target_ = target_.parent_path();
  if (target_ == target_.root_path()) throw Error(target_.string() + ": refusing to write into the root folder");
  // Replacing the current folder (or one holding it) would pull it from under the user's shell.
  const fs::path cwd = fs::current_path().lexically_normal();
  if (!cwd.lexically_relative(target_).empty() && *cwd.lexically_relative(target_).begin() != "..")
    throw Error(target_.string() + ": is the current folder or holds it; refusing to replace it");
  check_replaceable(target_);
  std::error_code ec;
  for (fs::path p = target_.parent_path(); !p.empty() && !fs::exists(p, ec) && p != p.parent_path(); p = p.parent_path())
    created_ = p;
  fs::create_directories(target_.parent_path(), ec);
  if (ec) throw Error(target_.string() + ": cannot create the output folder (" + ec.message() + ")");
  remove_stale_siblings(target_);

  staging_ = target_.parent_path() / ("." + target_.filename().string() + ".partial-" + std::to_string(::getpid()));
  auto lock = hold_interruptions();
  if (!fs::create_directory(staging_, ec) || ec)
    throw Error(target_.string() + ": cannot create the staging folder " + staging_.filename().string() + " (" +
                (ec ? ec.message() : "it exists") + ")");
  remove_on_interruption(staging_);
  show_as(staging_, target_);
  try {
    write_file(staging_ / kStampFile, std::string("program = \"workbench\"\nversion = \"") + WORKBENCH_VERSION +
                                          "\"\ncase = \"" + fs::absolute(case_file).lexically_normal().string() + "\"\n");
  } catch (...) {
    // No destructor runs for an object whose constructor throws: the folder created above goes here.
    fs::remove_all(staging_, ec);
    forget_on_interruption(staging_);
    forget_shown(staging_);
    throw;
  }
}

StagedDirectory::~StagedDirectory() {
  if (committed_) return;
  auto lock = hold_interruptions();
  std::error_code ec;
  fs::remove_all(staging_, ec);  // created by this object (create_directory above succeeded)
  forget_on_interruption(staging_);
  forget_shown(staging_);
  if (created_.empty()) return;
  for (fs::path p = target_.parent_path(); ; p = p.parent_path()) {  // fs::remove removes empty folders only
    if (!fs::remove(p, ec) || p == created_) break;
  }
}

void StagedDirectory::commit() {
  // Outside the lock: a slow disk's sync must not hold off an interruption (which removes the
  // folder); what the rename below moves is already on the disk. WORKBENCH_SYNC=off skips the
  // syncs (a scratch disk; the before/after measurement in docs/performance.md).
  const char* sync_setting = std::getenv("WORKBENCH_SYNC");
  const bool durable = !(sync_setting && std::string(sync_setting) == "off");
  if (durable) sync_tree(staging_);
  auto lock = hold_interruptions();
  check_replaceable(target_);  // again: the folder may have changed while the study ran
  std::error_code ec;
  const fs::path aside = target_.parent_path() / ("." + target_.filename().string() + ".old-" + std::to_string(::getpid()));
  const bool had_old = fs::exists(fs::symlink_status(target_, ec));
  if (had_old) {
    fs::rename(target_, aside, ec);
    if (ec) throw Error(target_.string() + ": cannot move the old output aside (" + ec.message() + ")");
  }
  fs::rename(staging_, target_, ec);
  if (ec) {
    std::error_code back;
    if (had_old) fs::rename(aside, target_, back);
    throw Error(target_.string() + ": cannot move the output into place (" + ec.message() + ")");
  }
  committed_ = true;
  forget_on_interruption(staging_);
  forget_shown(staging_);
  // The renames become durable once the parent folder is synced (before the old output is
  // deleted: a power cut in between leaves it as a stale sibling, removed by the next run). The new
  // output is in place and whole either way, so a failure here is a warning, not an error.
  try {
    if (durable) sync_folder(target_.parent_path());
  } catch (const Error& e) {
    std::fprintf(stderr, "workbench: warning: %s (the output is in place; a power cut now could undo the move)\n",
                 e.what());
  }
  if (had_old) fs::remove_all(aside, ec);  // empty or stamped: checked above
}

}  // namespace workbench
