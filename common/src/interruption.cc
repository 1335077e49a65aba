// SIGINT/SIGTERM: end the children, remove the staging folders, one line, exit 128 + signal.
#include <workbench/interruption.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <csignal>
#include <cstdio>
#include <thread>
#include <vector>

#include <sys/types.h>
#include <sys/wait.h>
#include <unistd.h>

namespace workbench {

namespace {

std::mutex registry_mutex;
std::vector<std::filesystem::path> staging_folders;  // guarded by registry_mutex
std::vector<int> child_groups;                       // guarded by registry_mutex
std::atomic<bool> interrupted{false};

}  // namespace

void end_process_group(int pgid) {
  if (pgid <= 0) return;
  ::kill(-pgid, SIGTERM);
  // A child that ignores SIGTERM gets SIGKILL after a grace period; the group is gone once every
  // member has exited. The direct child (the group's leader) is reaped here: a zombie still counts
  // as a member, and a child running beside the work (workbench::ChildProcess) has no waiter now.
  for (int i = 0; i < 40; ++i) {
    ::waitpid(pgid, nullptr, WNOHANG);
    if (::kill(-pgid, 0) != 0) break;
    std::this_thread::sleep_for(std::chrono::milliseconds(50));
  }
  ::kill(-pgid, SIGKILL);
}

std::unique_lock<std::mutex> hold_interruptions() { return std::unique_lock<std::mutex>(registry_mutex); }

void remove_on_interruption(const std::filesystem::path& staging) { staging_folders.push_back(staging); }

void forget_on_interruption(const std::filesystem::path& staging) {
  staging_folders.erase(std::remove(staging_folders.begin(), staging_folders.end(), staging), staging_folders.end());
}

void add_child_group(int pgid) { child_groups.push_back(pgid); }

void forget_child_group(int pgid) {
  auto lock = hold_interruptions();
  child_groups.erase(std::remove(child_groups.begin(), child_groups.end(), pgid), child_groups.end());
}

bool interruption_under_way() { return interrupted; }

void handle_interruptions(const std::string& program) {
  sigset_t set;
  sigemptyset(&set);
  for (int sig : {SIGINT, SIGTERM}) {
    // A signal ignored on entry (`nohup`, a shell's background job) stays ignored, as is custom.
    struct sigaction now {};
    if (::sigaction(sig, nullptr, &now) == 0 && now.sa_handler == SIG_IGN) continue;
    sigaddset(&set, sig);
  }
  if (sigisemptyset(&set)) return;
  pthread_sigmask(SIG_BLOCK, &set, nullptr);  // inherited by every thread started from now on
  std::thread([set, program] {
    int sig = 0;
    while (sigwait(&set, &sig) != 0) {
    }
    interrupted = true;
    auto lock = hold_interruptions();  // waits for a commit or a spawn in progress to finish
    for (int pgid : child_groups) end_process_group(pgid);
    for (const auto& dir : staging_folders) {
      std::error_code ec;
      std::filesystem::remove_all(dir, ec);  // only folders this process created (StagedDirectory)
    }
    std::fprintf(stderr, "%s: interrupted by %s; unfinished output removed\n", program.c_str(),
                 sig == SIGINT ? "SIGINT" : "SIGTERM");
    std::fflush(stderr);
    ::_exit(128 + sig);
  }).detach();
}

}  // namespace workbench
