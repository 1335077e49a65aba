#pragma once
// Output that appears whole or not at all, and never at the cost of a user's files.
//
// Files are written into a hidden sibling folder `.NAME.partial-PID` that replaces the target
// folder only when commit() is called. The target may be replaced only if it is empty or carries
// the stamp file every output folder gets (kStampFile: program, version, case file); any other
// existing folder or file is refused up front, before anything is written. The replacement moves
// the old folder aside, renames the new one in, then deletes the old one, so a kill at any moment
// leaves either the old or the new output in place. If the run fails or is interrupted
// (workbench/interruption.h), the staging folder is removed; one left by a killed run
// (SIGKILL) is removed by the next run to the same target once its process is gone.
#include <filesystem>
#include <string>

namespace workbench {

/// The stamp file's name inside every output folder.
inline constexpr const char* kStampFile = ".workbench-output";

class StagedDirectory {
 public:
  /// Throws workbench::Error (one line naming `target`) when `target` may not be replaced.
  StagedDirectory(std::filesystem::path target, const std::filesystem::path& case_file);
  ~StagedDirectory();
  StagedDirectory(const StagedDirectory&) = delete;
  StagedDirectory& operator=(const StagedDirectory&) = delete;

  /// Where to write now (the staging folder).
  const std::filesystem::path& path() const { return staging_; }
  /// The folder the files will end up in.
  const std::filesystem::path& target() const { return target_; }
  /// Replaces `target` by the staged folder, durably: every file and folder in it is synced
  /// (fsync) before the rename and the parent folder after it, so that a power cut leaves the old
  /// output or the whole new one. A failed sync is a failed write (the old output stays).
  void commit();

 private:
  std::filesystem::path target_, staging_;
  /// The outermost parent folder this object created for the target (empty: none), removed again,
  /// when left empty, by a study that fails before it commits: a refused run leaves nothing behind.
  std::filesystem::path created_;
  bool committed_ = false;
};

/// True when `dir` is a folder the workbench wrote (it carries the stamp file).
bool carries_stamp(const std::filesystem::path& dir);

/// `path` as the user will know it: below a live staging folder, the same path below its target
/// (the hidden `.NAME.partial-PID` means nothing to a user); any other path unchanged.
std::string shown_path(const std::filesystem::path& path);
/// `text` with every live staging folder's path replaced by its target's (a child's message).
std::string shown_text(std::string text);

}  // namespace workbench
