#pragma once
// The framing of the messages between the workbench and its mesher server, on a stream socket.
#include <string>
#include <vector>

namespace workbench::gmsh_detail {

/// Sends all of `text` on socket `fd` (never a SIGPIPE); false when the other end is gone.
bool send_all(int fd, const std::string& text);

/// A message: a count of strings, then each string with its length before it. False when the
/// other end is gone.
bool send_message(int fd, const std::vector<std::string>& parts);

/// Receives one message of send_message; false at the end of input, on an error or on a message
/// too large to be one.
bool receive_message(int fd, std::vector<std::string>& parts);

}  // namespace workbench::gmsh_detail
