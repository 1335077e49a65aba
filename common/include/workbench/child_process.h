#pragma once
// The one way the workbench runs another program (figures.py, render_frames.py, ffmpeg through
// them): an argument vector, no shell, its output to a log file, in its own process group so that
// an interruption (workbench/interruption.h) ends it and everything it started.
#include <filesystem>
#include <string>
#include <vector>

namespace workbench {

/// The Python the scripts run under: $WORKBENCH_PYTHON, else /usr/bin/python3 (which has numpy
/// and matplotlib on Debian; the first python3 on PATH may not).
std::string python_interpreter();

/// A script shipped with the program, `relative` to share/workbench/ (e.g. "compare/figures.py"):
/// $WORKBENCH_SCRIPT_DIR when set, else the first share/workbench/ found beside the running program
/// or up to two folders above it (the install tree: bin/../share; the build tree: the build
/// copies the scripts into <build>/share/workbench). Throws Error when it is not there.
std::filesystem::path find_script(const std::string& relative);

/// Runs `argv` (argv[0] a path or a name looked up on PATH) with stdout and stderr to `log` and
/// waits; when this program's stderr is a terminal, the child also gets it as descriptor
/// $WORKBENCH_PROGRESS_FD for its progress lines (quiet otherwise); returns its exit status (128 + signal when a signal ended it). Throws Error when it
/// cannot be started.
int run_child(const std::vector<std::string>& argv, const std::filesystem::path& log);

/// Runs python_interpreter() on find_script(script) with `args`; throws Error "<what> failed: <last
/// line of the log>" when it exits non-zero.
void run_python_script(const std::string& script, const std::vector<std::string>& args,
                       const std::filesystem::path& log, const std::string& what);

}  // namespace workbench
