// Runs the Python scripts (and whatever they start) without a shell, killable as a group.
#include <workbench/child_process.h>
#include <workbench/error.h>
#include <workbench/interruption.h>

#include <cerrno>
#include <csignal>
#include <cstdlib>
#include <cstring>
#include <fstream>

#include <fcntl.h>
#include <spawn.h>
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

fs::path find_script(const std::string& relative) {
  if (const char* env = std::getenv("WORKBENCH_SCRIPT_DIR"); env && *env) {
    const fs::path p = fs::path(env) / relative;
    if (!fs::is_regular_file(p)) throw Error(p.string() + ": script not found (WORKBENCH_SCRIPT_DIR is set)");
    return p;
  }
  std::error_code ec;
  fs::path dir = fs::read_symlink("/proc/self/exe", ec).parent_path();
  for (int up = 0; up < 3 && !ec && !dir.empty(); ++up, dir = dir.parent_path()) {
    const fs::path p = dir / "share" / "workbench" / relative;
    if (fs::is_regular_file(p)) return p;
  }
  throw Error(relative + ": script not found in share/workbench/ beside the program (set WORKBENCH_SCRIPT_DIR)");
}

int run_child(const std::vector<std::string>& argv, const fs::path& log) {
  std::vector<char*> args;
  for (const auto& a : argv) args.push_back(const_cast<char*>(a.c_str()));
  args.push_back(nullptr);

  posix_spawn_file_actions_t files;
  posix_spawn_file_actions_init(&files);
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
  posix_spawnattr_setpgroup(&attr, 0);
  posix_spawnattr_setsigmask(&attr, &none);
  posix_spawnattr_setsigdefault(&attr, &defaults);
  posix_spawnattr_setflags(&attr, POSIX_SPAWN_SETPGROUP | POSIX_SPAWN_SETSIGMASK | POSIX_SPAWN_SETSIGDEF);

  std::vector<std::string> env_text;
  for (char** e = environ; *e; ++e)
    if (std::strncmp(*e, "WORKBENCH_PROGRESS_FD=", 22) != 0) env_text.emplace_back(*e);
  if (terminal) env_text.push_back("WORKBENCH_PROGRESS_FD=" + std::to_string(kProgressFd));
  std::vector<char*> env;
  for (auto& e : env_text) env.push_back(e.data());
  env.push_back(nullptr);

  pid_t pid = 0;
  int err;
  {
    auto lock = hold_interruptions();  // an interruption now sees the child's group
    err = posix_spawnp(&pid, args[0], &files, &attr, args.data(), env.data());
    if (err == 0) set_child_group(pid);
  }
  posix_spawn_file_actions_destroy(&files);
  posix_spawnattr_destroy(&attr);
  if (err != 0) throw Error(argv[0] + ": cannot run (" + std::strerror(err) + ")");

  int status = 0;
  while (::waitpid(pid, &status, 0) < 0 && errno == EINTR) {
  }
  set_child_group(0);
  while (interruption_under_way()) ::pause();  // the watcher ends the process (its signals are blocked here)
  if (WIFEXITED(status)) return WEXITSTATUS(status);
  if (WIFSIGNALED(status)) return 128 + WTERMSIG(status);
  return 1;
}

void run_python_script(const std::string& script, const std::vector<std::string>& args, const fs::path& log,
                       const std::string& what) {
  std::vector<std::string> argv{python_interpreter(), find_script(script).string()};
  argv.insert(argv.end(), args.begin(), args.end());
  if (run_child(argv, log) != 0) {
    std::ifstream in(log);
    std::string line, last;
    while (std::getline(in, line))
      if (!line.empty()) last = line;
    throw Error(what + " failed: " + (last.empty() ? "see " + log.string() : last));
  }
}

}  // namespace workbench
