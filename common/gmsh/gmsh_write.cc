// gmsh::write with its writes checked (gmsh_write.h).
#include "gmsh_write.h"

#include <gmsh.h>

#include <workbench/output_file.h>

#include <cerrno>
#include <cstring>
#include <optional>
#include <stdexcept>
#include <string>
#include <thread>
#include <vector>

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

namespace workbench {

namespace {

/// Copies what arrives on `in` (a FIFO's read end) into `file` with checked writes until the last
/// writer closes it; returns the first failure's message ("" if none), reading on after a failure
/// so that the writer never blocks.
std::string copy_fifo(int in, const std::string& file) {
  std::string error;
  std::optional<OutputFile> out;
  try {
    out.emplace(file);
  } catch (const std::exception& e) {
    error = e.what();
  }
  std::vector<char> buffer(1 << 16);
  for (ssize_t n; (n = ::read(in, buffer.data(), buffer.size())) != 0;) {
    if (n < 0 && errno == EINTR) continue;
    if (n < 0) return file + ": read failed (" + std::strerror(errno) + ")";
    if (error.empty()) try {
        out->write({buffer.data(), std::size_t(n)});
      } catch (const std::exception& e) {
        error = e.what();
      }
  }
  if (error.empty()) try {
      out->close();
    } catch (const std::exception& e) {
      error = e.what();
    }
  return error;
}

std::string gmsh_error() {
  std::string error;
  gmsh::logger::getLastError(error);
  return error.empty() ? "gmsh failed" : error;
}

/// The FIFO's path, removed when done.
struct Fifo {
  std::string path;
  explicit Fifo(const std::filesystem::path& file)
      : path((file.parent_path() / ("." + file.filename().string() + ".fifo-" + std::to_string(::getpid()) +
                                    file.extension().string()))
                 .string()) {
    if (::mkfifo(path.c_str(), 0600) != 0) throw std::runtime_error(path + ": cannot create (" + std::strerror(errno) + ")");
  }
  Fifo(const Fifo&) = delete;
  Fifo& operator=(const Fifo&) = delete;
  ~Fifo() { ::unlink(path.c_str()); }
};

}  // namespace

void gmsh_write_checked(const std::filesystem::path& file) {
  const std::string name = file.string();
  const Fifo fifo(file);
  // This process holds a write end until gmsh is done, so the copier sees the end only then.
  const int in = ::open(fifo.path.c_str(), O_RDONLY | O_NONBLOCK | O_CLOEXEC);
  const int hold = in < 0 ? -1 : ::open(fifo.path.c_str(), O_WRONLY | O_CLOEXEC);
  if (in < 0 || hold < 0) {
    const std::string reason = std::strerror(errno);
    if (in >= 0) ::close(in);
    throw std::runtime_error(fifo.path + ": cannot open (" + reason + ")");
  }
  ::fcntl(in, F_SETFL, ::fcntl(in, F_GETFL) & ~O_NONBLOCK);
  std::string copy_error;
  std::thread copier([&] { copy_error = copy_fifo(in, name); });
  std::string write_error;
  try {
    gmsh::write(fifo.path);
  } catch (...) {
    write_error = name + ": " + gmsh_error();
  }
  ::close(hold);
  copier.join();
  ::close(in);
  if (!write_error.empty()) throw std::runtime_error(write_error);
  if (!copy_error.empty()) throw std::runtime_error(copy_error);
}

}  // namespace workbench
