// Runs the Python scripts (and whatever they start) without a shell, killable as a group, in the
// foreground or beside the workbench's own work.
#include <workbench/child_process.h>
#include <workbench/error.h>
#include <workbench/interruption.h>
#include <workbench/staged_directory.h>

#include <cerrno>
#include <csignal>
#include <cstdlib>
#include <cstring>
#include <dlfcn.h>
#include <fstream>
#include <vector>

#include <fcntl.h>
#include <spawn.h>
#include <sys/socket.h>
#include <sys/wait.h>
#include <unistd.h>

extern char** environ;

namespace {
constexpr int kProgressFd = 3;  // the terminal, for a child's progress lines
}  // namespace

namespace workbench {

namespace fs = std::filesystem;

std::string python_interpreter() {
  const char* env = std::getenv("WORKBENCH_PYTHON");
  return env && *env ? env : "/usr/bin/python3";
}

fs::path find_beside_program(const std::string& relative) {
  // Beside the program, else beside the shared object that holds this code: the Python module
  // (build/python/workbench.*.so -> build/share/workbench/), whose program is python3.
  std::vector<fs::path> starts;
  std::error_code ec;
  if (auto exe = fs::read_symlink("/proc/self/exe", ec); !ec) starts.push_back(exe.parent_path());
  static const char anchor = 0;
  if (Dl_info info{}; ::dladdr(&anchor, &info) && info.dli_fname) starts.push_back(fs::absolute(info.dli_fname).parent_path());
  for (fs::path dir : starts)
    for (int up = 0; up < 3 && !dir.empty(); ++up, dir = dir.parent_path()) {
      const fs::path p = dir / relative;
      if (fs::is_regular_file(p)) return p;
    }
  return {};
}

fs::path find_script(const std::string& relative) {
  if (const char* env = std::getenv("WORKBENCH_SCRIPT_DIR"); env && *env) {
    const fs::path p = fs::path(env) / relative;
    if (!fs::is_regular_file(p)) throw Error(p.string() + ": script not found (WORKBENCH_SCRIPT_DIR is set)");
    return p;
  }
  if (fs::path p = find_beside_program("share/workbench/" + relative); !p.empty()) return p;
  throw Error(relative + ": script not found in share/workbench/ beside the program (set WORKBENCH_SCRIPT_DIR)");
}

ChildProcess::ChildProcess(const std::vector<std::string>& argv, const fs::path& log) {
  std::vector<char*> args;
  for (const auto& a : argv) args.push_back(const_cast<char*>(a.c_str()));
  args.push_back(nullptr);

  // Its standard input: a socket, so that a write after the child ended fails (MSG_NOSIGNAL)
  // instead of killing this process with SIGPIPE; this end is not inherited (SOCK_CLOEXEC), so
  // the child sees end of input once this end is closed.
  int ends[2];
  if (::socketpair(AF_UNIX, SOCK_STREAM | SOCK_CLOEXEC, 0, ends) != 0)
    throw Error(argv[0] + ": cannot run (" + std::strerror(errno) + ")");
  posix_spawn_file_actions_t files;
  posix_spawn_file_actions_init(&files);
  posix_spawn_file_actions_adddup2(&files, ends[1], 0);
  // On a terminal the child gets it as descriptor 3 for its progress lines (WORKBENCH_PROGRESS_FD);
  // everything else it prints goes to the log.
  const bool terminal = ::isatty(2);
  if (terminal) posix_spawn_file_actions_adddup2(&files, 2, kProgressFd);
  posix_spawn_file_actions_addopen(&files, 1, log.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
  posix_spawn_file_actions_adddup2(&files, 1, 2);
  posix_spawnattr_t attr;
  posix_spawnattr_init(&attr);
  // Its own process group (so an interruption can end it and its children), the default
  // disposition and an empty mask for the signals this process blocks (interruption.cc).
  sigset_t none, defaults;
  sigemptyset(&none);
  sigemptyset(&defaults);
  sigaddset(&defaults, SIGINT);
  sigaddset(&defaults, SIGTERM);
  sigaddset(&defaults, SIGPIPE);
  posix_spawnattr_setpgroup(&attr, 0);
  posix_spawnattr_setsigmask(&attr, &none);
  posix_spawnattr_setsigdefault(&attr, &defaults);
  posix_spawnattr_setflags(&attr, POSIX_SPAWN_SETPGROUP | POSIX_SPAWN_SETSIGMASK | POSIX_SPAWN_SETSIGDEF);

  std::vector<std::string> env_text;
  bool tunables = false;
  for (char** e = environ; *e; ++e) {
    if (std::strncmp(*e, "WORKBENCH_PROGRESS_FD=", 22) != 0) env_text.emplace_back(*e);
    tunables = tunables || std::strncmp(*e, "GLIBC_TUNABLES=", 15) == 0;
  }
  // The children draw images of many MB (matplotlib, PIL, ffmpeg): their malloc puts its heap on
  // transparent huge pages, a page fault per 2 MB instead of per 4 kB (figures.py's faults 61,000
  // -> 25,000; the seed study 0.97x the CPU, docs/performance.md). GLIBC_TUNABLES of the user's
  // own are left as they are.
  if (!tunables) env_text.emplace_back("GLIBC_TUNABLES=glibc.malloc.hugetlb=1");
  if (terminal) env_text.push_back("WORKBENCH_PROGRESS_FD=" + std::to_string(kProgressFd));
  std::vector<char*> env;
  for (auto& e : env_text) env.push_back(e.data());
  env.push_back(nullptr);

  pid_t pid = 0;
  int err;
  {
    auto lock = hold_interruptions();  // an interruption now sees the child's group
    err = posix_spawnp(&pid, args[0], &files, &attr, args.data(), env.data());
    if (err == 0) add_child_group(pid);
  }
  posix_spawn_file_actions_destroy(&files);
  posix_spawnattr_destroy(&attr);
  ::close(ends[1]);
  if (err != 0) {
    ::close(ends[0]);
    throw Error(argv[0] + ": cannot run (" + std::strerror(err) + ")");
  }
  pid_ = pid;
  input_ = ends[0];
}

bool ChildProcess::send(const std::string& line) {
  const std::string text = line + "\n";
  for (std::size_t done = 0; input_ >= 0 && done < text.size();) {
    const ssize_t n = ::send(input_, text.data() + done, text.size() - done, MSG_NOSIGNAL);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) return false;
    done += std::size_t(n);
  }
  return input_ >= 0;
}

std::optional<std::string> ChildProcess::receive() {
  for (;;) {
    if (const auto end = report_.find('\n', received_); end != std::string::npos) {
      std::string line = report_.substr(received_, end - received_);
      received_ = end + 1;
      return line;
    }
    if (input_ < 0) return std::nullopt;
    char text[4096];
    const ssize_t n = ::recv(input_, text, sizeof text, 0);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) return std::nullopt;
    report_.append(text, std::size_t(n));
  }
}

int ChildProcess::wait() {
  if (input_ >= 0) ::shutdown(input_, SHUT_WR);  // the child sees the end of its input
  int status = 0;
  while (::waitpid(pid_, &status, 0) < 0 && errno == EINTR) {
  }
  // What it wrote back (a failed write's message); not waiting for a grandchild that holds the
  // socket open too.
  char text[4096];
  for (ssize_t n; input_ >= 0 && (n = ::recv(input_, text, sizeof text, MSG_DONTWAIT)) != 0;) {
    if (n < 0 && errno == EINTR) continue;
    if (n < 0) break;
    report_.append(text, std::size_t(n));
  }
  if (input_ >= 0) ::close(input_);
  input_ = -1;
  forget_child_group(pid_);
  pid_ = 0;
  while (interruption_under_way()) ::pause();  // the watcher ends the process (its signals are blocked here)
  if (WIFEXITED(status)) return WEXITSTATUS(status);
  if (WIFSIGNALED(status)) return 128 + WTERMSIG(status);
  return 1;
}

ChildProcess::~ChildProcess() {
  if (pid_ <= 0) return;
  // Not waited for: the caller stopped on an error. The child's group is ended (SIGKILL after a
  // grace period for one that ignores SIGTERM) and the child reaped, so nothing outlives the run.
  ::close(input_);
  end_process_group(pid_);
  while (::waitpid(pid_, nullptr, 0) < 0 && errno == EINTR) {  // if not reaped there (then: ECHILD)
  }
  forget_child_group(pid_);
}

int run_child(const std::vector<std::string>& argv, const fs::path& log, std::string* report) {
  ChildProcess child(argv, log);
  const int status = child.wait();
  if (report) *report = child.report();
  return status;
}

std::vector<std::string> python_script_command(const std::string& script, const std::vector<std::string>& args) {
  std::vector<std::string> argv{python_interpreter(), find_script(script).string()};
  argv.insert(argv.end(), args.begin(), args.end());
  return argv;
}

namespace {
std::string last_line(std::string text) {
  while (!text.empty() && (text.back() == '\n' || text.back() == '\r')) text.pop_back();
  return text.substr(text.find_last_of('\n') + 1);
}
}  // namespace

void check_script_status(int status, const fs::path& log, const std::string& what, const std::string& report) {
  if (status == 0) return;
  std::ifstream in(log);
  std::string line, last;
  while (std::getline(in, line))
    if (!line.empty()) last = line;
  if (status == kWriteFailedStatus) {
    const std::string message = last_line(report).empty() ? last : last_line(report);
    throw Error(shown_text(message.empty() ? what + ": a write failed (exit " + std::to_string(status) + ")" : message));
  }
  throw Error(shown_text(what + " failed: " + (last.empty() ? "see " + log.string() : last)));
}

void run_python_script(const std::string& script, const std::vector<std::string>& args, const fs::path& log,
                       const std::string& what) {
  std::string report;
  const int status = run_child(python_script_command(script, args), log, &report);
  check_script_status(status, log, what, report);
}

}  // namespace workbench
