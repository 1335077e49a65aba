#pragma once
// Output that appears whole or not at all: files are written into a hidden sibling folder
// that replaces the target folder only when commit() is called. If the run fails first, the
// destructor removes the partial folder and the previous output stays untouched.
#include <filesystem>

namespace workbench {

class StagedDirectory {
 public:
  explicit StagedDirectory(std::filesystem::path target);
  ~StagedDirectory();
  StagedDirectory(const StagedDirectory&) = delete;
  StagedDirectory& operator=(const StagedDirectory&) = delete;

  /// Where to write now (the staging folder).
  const std::filesystem::path& path() const { return staging_; }
  /// The folder the files will end up in.
  const std::filesystem::path& target() const { return target_; }
  /// Replaces `target` by the staged folder.
  void commit();

 private:
  std::filesystem::path target_, staging_;
  bool committed_ = false;
};

}  // namespace workbench
