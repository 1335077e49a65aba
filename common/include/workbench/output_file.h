#pragma once
// The one way the workbench puts bytes on disk: every write checked, a failure one Error naming
// the file (as the user will know it: the target folder, not the hidden staging folder) and the
// reason ("No space left on device", "File too large", "Input/output error"). CSV tables, VTU/PVTU/
// PVD, JSON, text, the stamp and calibrated case files all go through it; nothing it wrote is left
// half-finished once the staging folder is removed (workbench/staged_directory.h).
//
// VTK's XML writer is not trusted with the disk (it crashed after a failed write on a full disk):
// it writes to memory and write_file() puts the bytes down. The process ignores SIGXFSZ (main()),
// so a file-size limit (`ulimit -f`) is a failed write (EFBIG) here, not a kill.
#include <cstdint>
#include <filesystem>
#include <functional>
#include <string>
#include <string_view>

namespace workbench {

/// A file written through a buffer with checked write(2) calls (EINTR and short writes retried).
class OutputFile {
 public:
  /// Creates or truncates `file`; throws Error "<file>: cannot open for writing (<reason>)".
  explicit OutputFile(std::filesystem::path file);
  OutputFile(OutputFile&& other) noexcept;
  OutputFile& operator=(OutputFile&&) = delete;
  OutputFile(const OutputFile&) = delete;
  ~OutputFile();  // closes without checking: only reached on an error path (the folder is removed)

  /// Appends `bytes`; throws Error "<file>: write failed (<reason>)" when a write fails.
  void write(std::string_view bytes);
  /// Writes what is buffered and closes; throws as write() (close(2) can report a failed write too).
  void close();
  const std::filesystem::path& path() const { return file_; }

 private:
  void flush();
  void write_all(const char* data, std::size_t size);
  std::filesystem::path file_;
  int fd_ = -1;
  std::string buffer_;
};

/// Writes `bytes` to `file` (created or truncated) with OutputFile.
void write_file(const std::filesystem::path& file, std::string_view bytes);

/// Replaces `file` outside a staging folder (compare --junit): written to a hidden sibling, synced
/// and renamed over it, so that a failed write leaves the earlier file whole.
void replace_file(const std::filesystem::path& file, std::string_view bytes);
/// The same with a file that `write` writes (e.g. through a CsvFile) at the path it is given.
void replace_file(const std::filesystem::path& file, const std::function<void(const std::filesystem::path&)>& write);

/// The message of a failed write: "<file as the user knows it>: write failed (<strerror(err)>)".
std::string write_failure(const std::filesystem::path& file, int err);

/// fsync(2) of every regular file and folder below `dir` and of `dir` itself, so that a power
/// cut after a rename finds the whole content; throws like a failed write.
void sync_tree(const std::filesystem::path& dir);
/// fsync(2) of one folder (its entries: a rename done in it is durable afterwards).
void sync_folder(const std::filesystem::path& dir);

/// Free bytes for an unprivileged writer on the file system holding `dir` (statvfs f_bavail);
/// the maximum when it cannot be told.
std::uintmax_t free_bytes(const std::filesystem::path& dir);

/// Refuses (Error "<dir>: <what> needs an estimated N MB, the file system has M MB free") an
/// output whose estimated size does not fit in free_bytes(dir), before it is written.
/// WORKBENCH_FREE_BYTES (a number of bytes) stands in for statvfs's answer (tests).
void require_room(const std::filesystem::path& dir, std::uintmax_t bytes, const std::string& what);

}  // namespace workbench
