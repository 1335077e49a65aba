// The mesher server: a process forked from the workbench at its start, with gmsh's libraries
// loaded, which forks a process for each .geo (gmsh_session.h, start_geo_mesher_server).
#include "gmsh_internal.h"
#include "gmsh_session.h"
#include "mesher_messages.h"

#include <workbench/interruption.h>

#include <cerrno>
#include <csignal>
#include <cstdio>
#include <cstdlib>
#include <mutex>
#include <optional>
#include <string>
#include <vector>

#include <fcntl.h>
#include <sys/prctl.h>
#include <sys/socket.h>
#include <sys/wait.h>
#include <unistd.h>

namespace workbench {

namespace {

using gmsh_detail::receive_message;
using gmsh_detail::send_message;
using gmsh_detail::mesh_and_report;

/// The mesher server (start_geo_mesher_server): its channel to the workbench, its pid.
int server_channel = -1;
pid_t server_pid = 0;
int server_requests = 0;  // answered
std::mutex server_mutex;  // one request at a time

/// The exit status as ChildProcess::wait gives it: 128 + signal when a signal ended the process.
int exit_status(int status) {
  if (WIFEXITED(status)) return WEXITSTATUS(status);
  if (WIFSIGNALED(status)) return 128 + WTERMSIG(status);
  return 1;
}

/// A process forked for one .geo by the server: it ends with the server; its output goes to the
/// log, its report to `report_fd`. Never returns.
[[noreturn]] void mesher_worker(const std::vector<std::string>& request, int report_fd, pid_t server) {
  ::prctl(PR_SET_PDEATHSIG, SIGKILL);
  if (::getppid() != server) ::_exit(1);
  // request: the workbench's folder, the log, GEO, MSH, the time limit ("": none set), NAME VALUE...
  if (::chdir(request[0].c_str()) != 0) ::_exit(71);
  if (request[4].empty())
    ::unsetenv("WORKBENCH_MESH_TIME_LIMIT");
  else
    ::setenv("WORKBENCH_MESH_TIME_LIMIT", request[4].c_str(), 1);
  // Its scratch files (the size estimate's unrolled .geo) in the workbench's folder for this load,
  // which the workbench removes, also when an interruption ends this process half-way.
  ::setenv("TMPDIR", std::filesystem::path(request[1]).parent_path().c_str(), 1);
  const int log = ::open(request[1].c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0644);
  if (log >= 0) {
    ::dup2(log, 1);
    ::dup2(log, 2);
    ::close(log);
  }
  std::map<std::string, double> parameters;
  for (std::size_t i = 5; i + 1 < request.size(); i += 2) parameters[request[i]] = std::strtod(request[i + 1].c_str(), nullptr);
  const int code = mesh_and_report(report_fd, request[2], request[3], parameters);
  std::fflush(nullptr);
  ::_exit(code);  // no exit handlers: they belong to the workbench this process was forked from
}

/// The server's loop: a request in, a process forked to mesh it, its exit status and report out.
/// It ends when the workbench closes the channel (or ends: PR_SET_PDEATHSIG).
[[noreturn]] void serve(int channel) {
  for (std::vector<std::string> request; receive_message(channel, request);) {
    std::vector<std::string> reply{"71", ""};  // EX_OSERR: could not fork
    int ends[2];
    if (request.size() >= 5 && ::socketpair(AF_UNIX, SOCK_STREAM | SOCK_CLOEXEC, 0, ends) == 0) {
      const pid_t server = ::getpid();
      const pid_t pid = ::fork();
      if (pid == 0) {
        ::close(ends[0]);
        ::close(channel);
        mesher_worker(request, ends[1], server);
      }
      ::close(ends[1]);
      if (pid > 0) {
        char text[4096];
        for (ssize_t n; (n = ::recv(ends[0], text, sizeof text, 0)) != 0;) {
          if (n < 0 && errno == EINTR) continue;
          if (n < 0) break;
          reply[1].append(text, std::size_t(n));
        }
        int status = 0;
        while (::waitpid(pid, &status, 0) < 0 && errno == EINTR) {
        }
        reply[0] = std::to_string(exit_status(status));
      }
      ::close(ends[0]);
    }
    if (!send_message(channel, reply)) break;
  }
  ::_exit(0);
}

}  // namespace

namespace gmsh_detail {

bool geo_mesher_server_running() {
  const std::lock_guard<std::mutex> lock(server_mutex);
  return server_channel >= 0;
}

std::optional<int> mesh_in_server(const std::vector<std::string>& request, std::string& report) {
  const std::lock_guard<std::mutex> lock(server_mutex);
  if (server_channel < 0) return std::nullopt;
  std::vector<std::string> reply;
  const bool answered = send_message(server_channel, request) && receive_message(server_channel, reply) && reply.size() == 2;
  while (interruption_under_way()) ::pause();  // the watcher ended the server and ends this process
  if (!answered) {  // the server ended (killed from outside): reaped, not used again
    ::close(server_channel);
    server_channel = -1;
    ::waitpid(server_pid, nullptr, WNOHANG);
    forget_child_group(server_pid);
    server_pid = 0;
    return std::nullopt;
  }
  ++server_requests;
  report = reply[1];
  return std::stoi(reply[0]);
}

}  // namespace gmsh_detail

int start_geo_mesher_server() {
  if (server_pid > 0) return server_pid;
  int ends[2];
  if (::socketpair(AF_UNIX, SOCK_STREAM | SOCK_CLOEXEC, 0, ends) != 0) return 0;
  const pid_t parent = ::getpid();
  const pid_t pid = ::fork();
  if (pid == 0) {
    // Its own process group (the terminal's Ctrl-C goes to the workbench, whose interruption ends
    // this group); it ends with the workbench; nothing of the workbench's open but its channel.
    ::setpgid(0, 0);
    ::prctl(PR_SET_PDEATHSIG, SIGKILL);
    if (::getppid() != parent) ::_exit(0);
    ::prctl(PR_SET_NAME, "geo-mesher");
    if (const int null = ::open("/dev/null", O_RDWR); null >= 0)
      for (int fd = 0; fd < 3; ++fd) ::dup2(null, fd);
    ::dup2(ends[1], 3);
    ::close_range(4, ~0U, 0);
    serve(3);
  }
  ::close(ends[1]);
  if (pid < 0) {
    ::close(ends[0]);
    return 0;
  }
  ::setpgid(pid, pid);  // here too, so that the group exists when it is registered
  server_channel = ends[0];
  server_pid = pid;
  return pid;
}

void register_geo_mesher_server() {
  const auto lock = hold_interruptions();
  if (server_pid > 0) add_child_group(server_pid);
}

int geo_mesher_server_pid() {
  const std::lock_guard<std::mutex> lock(server_mutex);
  return server_pid;
}

int geo_mesher_server_requests() {
  const std::lock_guard<std::mutex> lock(server_mutex);
  return server_requests;
}

}  // namespace workbench
