// The framing of the messages between the workbench and its mesher server (mesher_messages.h).
#include "mesher_messages.h"

#include <cerrno>
#include <cstdint>

#include <sys/socket.h>

namespace workbench::gmsh_detail {

namespace {

/// Receives exactly `size` bytes from `fd`; false at the end of input or on an error.
bool receive_all(int fd, char* data, std::size_t size) {
  for (std::size_t done = 0; done < size;) {
    const ssize_t n = ::recv(fd, data + done, size - done, 0);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) return false;
    done += std::size_t(n);
  }
  return true;
}

}  // namespace

bool send_all(int fd, const std::string& text) {
  for (std::size_t done = 0; done < text.size();) {
    const ssize_t n = ::send(fd, text.data() + done, text.size() - done, MSG_NOSIGNAL);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) return false;
    done += std::size_t(n);
  }
  return true;
}

bool send_message(int fd, const std::vector<std::string>& parts) {
  std::string text;
  const auto put = [&](std::uint64_t n) { text.append(reinterpret_cast<const char*>(&n), sizeof n); };
  put(parts.size());
  for (const auto& p : parts) {
    put(p.size());
    text += p;
  }
  return send_all(fd, text);
}

bool receive_message(int fd, std::vector<std::string>& parts) {
  std::uint64_t count = 0;
  if (!receive_all(fd, reinterpret_cast<char*>(&count), sizeof count) || count > 4096) return false;
  parts.assign(count, {});
  for (auto& p : parts) {
    std::uint64_t size = 0;
    if (!receive_all(fd, reinterpret_cast<char*>(&size), sizeof size) || size > (std::uint64_t(1) << 32)) return false;
    p.resize(size);
    if (!receive_all(fd, p.data(), size)) return false;
  }
  return true;
}

}  // namespace workbench::gmsh_detail
