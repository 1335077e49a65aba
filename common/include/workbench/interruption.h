#pragma once
// A run that is interrupted (SIGINT, SIGTERM) ends cleanly: its child processes are ended, its
// staging folders removed, one line is printed and the exit code is the conventional 128 + signal.
//
// handle_interruptions() must be called first in main(), before any thread starts: it blocks the
// two signals in every thread and leaves them to one watcher thread (sigwait), which does the
// clean-up outside a signal handler, so it may take locks and remove folders.
#include <filesystem>
#include <mutex>
#include <string>

namespace workbench {

/// Installs the watcher; `program` starts its one-line message ("workbench: interrupted ...").
void handle_interruptions(const std::string& program);

/// Held while the staged-folder bookkeeping changes (and while a folder is committed), so that an
/// interruption never sees half a commit.
std::unique_lock<std::mutex> hold_interruptions();

/// Staging folders to remove when interrupted; both must be called under hold_interruptions().
void remove_on_interruption(const std::filesystem::path& staging);
void forget_on_interruption(const std::filesystem::path& staging);

/// The process groups of running children, ended when interrupted (a figure script beside the FEM
/// reference, which may start gmsh's mesher meanwhile). Adding one must be done under
/// hold_interruptions(), together with starting the child; forgetting takes the lock itself.
void add_child_group(int pgid);
void forget_child_group(int pgid);

/// Ends process group `pgid`: SIGTERM, SIGKILL after a 2 s grace period, and reaps its leader when
/// it is this process's child (a zombie still counts as a member of its group).
void end_process_group(int pgid);

/// True once a signal arrived: a child that ended then was ended by the watcher, whose exit
/// follows; the caller must not report the child's failure as an error of its own.
bool interruption_under_way();

}  // namespace workbench
