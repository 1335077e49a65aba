#pragma once
// The one way the workbench runs another program (figures.py, render_frames.py, ffmpeg through
// them): an argument vector, no shell, its output to a log file, in its own process group so that
// an interruption (workbench/interruption.h) ends it and everything it started.
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

namespace workbench {

/// The exit status of a script whose write failed (sysexits' EX_IOERR; scripts/child_report.py
/// uses the same number). Its message ("<file>: write failed (<reason>)") comes back on the
/// child's standard input, a socket, since its log may sit on the very disk that is full.
inline constexpr int kWriteFailedStatus = 74;

/// The Python the scripts run under: $WORKBENCH_PYTHON, else /usr/bin/python3 (which has numpy
/// and matplotlib on Debian; the first python3 on PATH may not).
std::string python_interpreter();

/// `relative` (e.g. "libexec/workbench/workbench-geo-mesher") in the first folder, of the running
/// program's and of the shared object's that holds this code, and up to two folders above each,
/// that has it; empty when none has.
std::filesystem::path find_beside_program(const std::string& relative);

/// A script shipped with the program, `relative` to share/workbench/ (e.g. "compare/figures.py"):
/// $WORKBENCH_SCRIPT_DIR when set, else the first share/workbench/ found beside the running program
/// or up to two folders above it (the install tree: bin/../share; the build tree: the build
/// copies the scripts into <build>/share/workbench), then the same beside the shared object that
/// holds this code (the Python module in <build>/python). Throws Error when it is not there.
std::filesystem::path find_script(const std::string& relative);

/// A program running beside the workbench (figures.py drawing while the FEM reference solves):
/// started as run_child starts one, with its standard input a channel from this object.
///
///   workbench::ChildProcess figures({python, script, dir, "--wait"}, dir / "figures.log");
///   ...                        // the child works on what is ready; this process goes on
///   figures.send("draw");      // the rest of its input is ready
///   int status = figures.wait();
///
/// An interruption ends every running child's group. A ChildProcess that is destroyed without
/// wait() (an error in between) ends the child and its group and reaps it.
class ChildProcess {
 public:
  /// Starts `argv` (argv[0] a path or a name looked up on PATH) with stdout and stderr to `log`,
  /// this process's environment and, unless it has GLIBC_TUNABLES, glibc's malloc on transparent
  /// huge pages (GLIBC_TUNABLES=glibc.malloc.hugetlb=1); throws Error when it cannot be started.
  ChildProcess(const std::vector<std::string>& argv, const std::filesystem::path& log);
  ChildProcess(const ChildProcess&) = delete;
  ChildProcess& operator=(const ChildProcess&) = delete;
  ~ChildProcess();
  /// Writes `line` and a newline to the child's standard input; false when the child no longer
  /// reads it (it ended), never a SIGPIPE.
  bool send(const std::string& line);
  /// Waits for a line the child writes back on its standard input (figures.py's "drawn"): the
  /// line without its newline, or nothing when the child closed its input first (it ended). The
  /// lines are kept in report() too.
  std::optional<std::string> receive();
  /// Closes the child's standard input (it sees end of input) and waits for it to end; its exit
  /// status, 128 + signal when a signal ended it.
  int wait();
  /// The child's process id, also its process group's (0 once waited for).
  int pid() const { return pid_; }
  /// What the child wrote back on its standard input before it ended (read by receive() and wait()).
  const std::string& report() const { return report_; }

 private:
  int pid_ = 0;
  int input_ = -1;  // this end of the child's standard input
  std::string report_;
  std::size_t received_ = 0;  // the length of report_ that receive() has handed out
};

/// Runs `argv` (argv[0] a path or a name looked up on PATH) with stdout and stderr to `log` and
/// waits; when this program's stderr is a terminal, the child also gets it as descriptor
/// $WORKBENCH_PROGRESS_FD for its progress lines (quiet otherwise); its standard input is empty.
/// Returns its exit status (128 + signal when a signal ended it) and, when `report` is given, what
/// it wrote back on its standard input (ChildProcess::report). Throws Error when it cannot be started.
int run_child(const std::vector<std::string>& argv, const std::filesystem::path& log, std::string* report = nullptr);

/// The argument vector that runs a shipped script: python_interpreter(), find_script(script), `args`.
std::vector<std::string> python_script_command(const std::string& script, const std::vector<std::string>& args);

/// Throws Error "<what> failed: <last line of log>" when a script's exit `status` is not 0; for
/// kWriteFailedStatus, Error "<file>: write failed (<reason>)" from its `report` (else its log).
/// Paths in the staging folder are shown below the target (workbench::shown_text).
void check_script_status(int status, const std::filesystem::path& log, const std::string& what,
                         const std::string& report = "");

/// Runs python_interpreter() on find_script(script) with `args`; throws Error "<what> failed: <last
/// line of the log>" when it exits non-zero.
void run_python_script(const std::string& script, const std::vector<std::string>& args,
                       const std::filesystem::path& log, const std::string& what);

}  // namespace workbench
