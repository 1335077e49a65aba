// Checked writes, durable folders and the free-space check: the only place bytes reach the disk.
#include <workbench/error.h>
#include <workbench/output_file.h>
#include <workbench/staged_directory.h>

#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <limits>

#include <fcntl.h>
#include <sys/statvfs.h>
#include <unistd.h>

namespace workbench {

namespace fs = std::filesystem;

namespace {
constexpr std::size_t kBufferBytes = 1 << 16;

void sync_path(const fs::path& path, bool folder) {
  const int fd = ::open(path.c_str(), (folder ? O_RDONLY | O_DIRECTORY : O_RDONLY) | O_CLOEXEC);
  if (fd < 0) throw Error(write_failure(path, errno));
  int err = 0;
  while (::fsync(fd) != 0) {
    if (errno == EINTR) continue;
    // A file system that cannot sync a folder (EINVAL) has nothing to make durable there.
    if (!(folder && (errno == EINVAL || errno == EROFS))) err = errno;
    break;
  }
  ::close(fd);
  if (err) throw Error(write_failure(path, err));
}

std::string megabytes(std::uintmax_t bytes) {
  char text[32];
  std::snprintf(text, sizeof text, "%.3g MB", double(bytes) / 1e6);
  return text;
}
}  // namespace

std::string write_failure(const fs::path& file, int err) {
  return shown_path(file) + ": write failed (" + std::strerror(err) + ")";
}

OutputFile::OutputFile(fs::path file) : file_(std::move(file)) {
  fd_ = ::open(file_.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0644);
  if (fd_ < 0) throw Error(shown_path(file_) + ": cannot open for writing (" + std::strerror(errno) + ")");
  buffer_.reserve(kBufferBytes);
}

OutputFile::OutputFile(OutputFile&& other) noexcept
    : file_(std::move(other.file_)), fd_(other.fd_), buffer_(std::move(other.buffer_)) {
  other.fd_ = -1;
}

OutputFile::~OutputFile() {
  if (fd_ >= 0) ::close(fd_);
}

void OutputFile::write_all(const char* data, std::size_t left) {
  while (left > 0) {
    const ssize_t n = ::write(fd_, data, left);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) {
      const int err = n < 0 ? errno : ENOSPC;  // a write of nothing at all: the device took no more
      ::close(fd_);
      fd_ = -1;
      throw Error(write_failure(file_, err));
    }
    data += n;
    left -= std::size_t(n);
  }
}

void OutputFile::flush() {
  write_all(buffer_.data(), buffer_.size());
  buffer_.clear();
}

void OutputFile::write(std::string_view bytes) {
  if (fd_ < 0) throw Error(shown_path(file_) + ": write after close");
  if (buffer_.size() + bytes.size() > kBufferBytes) flush();
  if (bytes.size() >= kBufferBytes) write_all(bytes.data(), bytes.size());  // a VTU: straight through
  else buffer_.append(bytes.data(), bytes.size());
}

void OutputFile::close() {
  if (fd_ < 0) return;
  flush();
  // Start writing it to the disk now, beside the work that follows, so that the sync at the
  // commit (StagedDirectory::commit) mostly finds it written. A hint: its failure is not an error.
  ::sync_file_range(fd_, 0, 0, SYNC_FILE_RANGE_WRITE);
  const int fd = fd_;
  fd_ = -1;
  if (::close(fd) != 0 && errno != EINTR) throw Error(write_failure(file_, errno));
}

void write_file(const fs::path& file, std::string_view bytes) {
  OutputFile out(file);
  out.write(bytes);
  out.close();
}

void replace_file(const fs::path& file, std::string_view bytes) {
  replace_file(file, [bytes](const fs::path& temporary) { write_file(temporary, bytes); });
}

void replace_file(const fs::path& file, const std::function<void(const fs::path&)>& write) {
  const fs::path absolute = fs::absolute(file);
  const fs::path temporary =
      absolute.parent_path() / ("." + absolute.filename().string() + ".partial-" + std::to_string(::getpid()));
  try {
    write(temporary);
    sync_path(temporary, false);
  } catch (...) {
    std::error_code ec;
    fs::remove(temporary, ec);  // created just above by this process
    throw;
  }
  std::error_code ec;
  fs::rename(temporary, absolute, ec);
  if (ec) {
    std::error_code ignored;
    fs::remove(temporary, ignored);
    throw Error(file.string() + ": cannot replace it (" + ec.message() + ")");
  }
  sync_folder(absolute.parent_path());
}

void sync_tree(const fs::path& dir) {
  std::error_code ec;
  for (auto it = fs::recursive_directory_iterator(dir, ec); !ec && it != fs::recursive_directory_iterator();
       it.increment(ec)) {
    const auto status = it->symlink_status(ec);
    if (ec) break;
    if (fs::is_regular_file(status)) sync_path(it->path(), false);
    else if (fs::is_directory(status)) sync_path(it->path(), true);
  }
  if (ec) throw Error(shown_path(dir) + ": cannot list the output for syncing (" + ec.message() + ")");
  sync_path(dir, true);
}

void sync_folder(const fs::path& dir) { sync_path(dir, true); }

std::uintmax_t free_bytes(const fs::path& dir) {
  if (const char* forced = std::getenv("WORKBENCH_FREE_BYTES"); forced && *forced) {
    char* end = nullptr;
    const double v = std::strtod(forced, &end);
    if (end != forced && *end == '\0' && std::isfinite(v) && v >= 0) return std::uintmax_t(v);
  }
  struct statvfs s {};
  if (::statvfs(dir.c_str(), &s) != 0) return std::numeric_limits<std::uintmax_t>::max();
  return std::uintmax_t(s.f_bavail) * std::uintmax_t(s.f_frsize);
}

void require_room(const fs::path& dir, std::uintmax_t bytes, const std::string& what) {
  const std::uintmax_t free = free_bytes(dir);
  if (bytes <= free) return;
  throw Error(shown_path(dir) + ": " + what + " needs an estimated " + megabytes(bytes) +
              ", the file system has " + megabytes(free) + " free; refusing to start it");
}

}  // namespace workbench
