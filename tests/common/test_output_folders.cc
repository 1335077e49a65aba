// Output folders and child processes: nothing of the user's is ever replaced, an output appears
// whole or not at all, stale staging folders of dead runs go, children run without a shell.
#include <workbench/child_process.h>
#include <workbench/csv_file.h>
#include <workbench/error.h>
#include <workbench/staged_directory.h>

#include <gtest/gtest.h>

#include "../support/error_of.h"

#include <cmath>
#include <fstream>
#include <functional>
#include <optional>
#include <sstream>

#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include "../support/scratch_folder.h"

namespace fs = std::filesystem;
using namespace workbench;

using test_support::error_of;

namespace {

using test_support::read_file;

// Everything in `dir` but the names listed (siblings a run may have left behind).
std::vector<std::string> entries(const fs::path& dir) {
  std::vector<std::string> names;
  for (const auto& e : fs::directory_iterator(dir)) names.push_back(e.path().filename().string());
  std::sort(names.begin(), names.end());
  return names;
}

// A process id that belonged to a process that has exited and been reaped.
pid_t dead_pid() {
  const pid_t pid = ::fork();
  if (pid == 0) ::_exit(0);
  ::waitpid(pid, nullptr, 0);
  return pid;
}

const fs::path kCase = "case.toml";

}  // namespace

TEST(StagedDirectory, AppearsWholeOrNotAtAllAndCarriesTheStamp) {
  const fs::path target = test_support::scratch_folder() / "out";
  {
    StagedDirectory staged(target, kCase);
    std::ofstream(staged.path() / "a.txt") << "half";
  }  // abandoned: nothing appears, nothing is left beside it
  EXPECT_FALSE(fs::exists(target));
  EXPECT_TRUE(entries(test_support::scratch_folder()).empty());
  {
    StagedDirectory staged(target, kCase);
    std::ofstream(staged.path() / "a.txt") << "whole";
    staged.commit();
  }
  EXPECT_EQ(read_file(target / "a.txt"), "whole");
  EXPECT_TRUE(carries_stamp(target));
  const std::string stamp = read_file(target / kStampFile);
  EXPECT_EQ(stamp.rfind("program = \"workbench\"\nversion = \"", 0), 0u) << stamp;
  EXPECT_NE(stamp.find("case = \"" + fs::absolute(kCase).string() + "\""), std::string::npos) << stamp;
}

TEST(StagedDirectory, ReplacesItsOwnOutputAndLeavesNothingBeside) {
  const fs::path target = test_support::scratch_folder() / "out";
  for (const char* text : {"first", "second"}) {
    StagedDirectory staged(target, kCase);
    std::ofstream(staged.path() / (std::string(text) + ".txt")) << text;
    staged.commit();
  }
  EXPECT_FALSE(fs::exists(target / "first.txt"));
  EXPECT_EQ(read_file(target / "second.txt"), "second");
  EXPECT_EQ(entries(test_support::scratch_folder()), std::vector<std::string>{"out"});
}

TEST(StagedDirectory, RefusesAFolderItDidNotWriteAndTouchesNothing) {
  const fs::path target = test_support::scratch_folder() / "mine";
  fs::create_directories(target);
  std::ofstream(target / "thesis.tex") << "years of work";
  const std::string e = error_of([&] { StagedDirectory staged(target, kCase); });
  EXPECT_EQ(e, target.string() + ": is a folder the workbench did not write (it has files and no " + kStampFile +
                   "); refusing to replace it, choose a new or empty folder");
  EXPECT_EQ(read_file(target / "thesis.tex"), "years of work");
  EXPECT_EQ(entries(test_support::scratch_folder()), std::vector<std::string>{"mine"});
  // A stamp that is not ours (a file of that name with other contents) does not count either.
  std::ofstream(target / kStampFile) << "something else\n";
  EXPECT_NE(error_of([&] { StagedDirectory staged(target, kCase); }).find("did not write"), std::string::npos);
}

TEST(StagedDirectory, RefusesAFolderThatChangedWhileTheStudyRan) {
  const fs::path target = test_support::scratch_folder() / "out";
  StagedDirectory staged(target, kCase);
  fs::create_directories(target);
  std::ofstream(target / "notes.txt") << "written meanwhile";
  EXPECT_NE(error_of([&] { staged.commit(); }).find("did not write"), std::string::npos);
  EXPECT_EQ(read_file(target / "notes.txt"), "written meanwhile");
}

TEST(StagedDirectory, UsesAnEmptyFolder) {
  const fs::path target = test_support::scratch_folder() / "empty";
  fs::create_directories(target);
  StagedDirectory staged(target, kCase);
  std::ofstream(staged.path() / "a.txt") << "x";
  staged.commit();
  EXPECT_EQ(read_file(target / "a.txt"), "x");
}

TEST(StagedDirectory, RefusesAFileALinkTheRootAndTheCurrentFolder) {
  const fs::path dir = test_support::scratch_folder();
  std::ofstream(dir / "file") << "keep";
  EXPECT_EQ(error_of([&] { StagedDirectory s(dir / "file", kCase); }), (dir / "file").string() + ": exists and is not a folder");
  fs::create_directory_symlink(dir, dir / "link");
  EXPECT_NE(error_of([&] { StagedDirectory s(dir / "link", kCase); }).find("symbolic link"), std::string::npos);
  EXPECT_EQ(error_of([&] { StagedDirectory s("/", kCase); }), "/: refusing to write into the root folder");
  const fs::path before = fs::current_path();
  fs::create_directories(dir / "here");
  fs::current_path(dir / "here");
  const std::string e = error_of([&] { StagedDirectory s(".", kCase); });
  const std::string up = error_of([&] { StagedDirectory s("..", kCase); });
  fs::current_path(before);
  EXPECT_EQ(e, (dir / "here").string() + ": is the current folder or holds it; refusing to replace it");
  EXPECT_NE(up.find("is the current folder or holds it"), std::string::npos) << up;
  EXPECT_EQ(read_file(dir / "file"), "keep");
}

TEST(StagedDirectory, RemovesOnlyStaleStagingOfRunsThatAreGone) {
  const fs::path dir = test_support::scratch_folder();
  auto stamped = [&](const std::string& name) {
    fs::create_directories(dir / name);
    std::ofstream(dir / name / kStampFile) << "program = \"workbench\"\n";
    std::ofstream(dir / name / "frame.vtu") << "partial";
  };
  const std::string dead = std::to_string(dead_pid()), alive = std::to_string(::getppid());
  stamped(".out.partial-" + dead);  // killed run: removed
  stamped(".out.old-" + dead);      // killed in the middle of a commit: removed
  stamped(".out.partial-" + alive);  // a run still going: kept
  fs::create_directories(dir / (".out.partial-" + dead + "x"));  // not our pattern: kept
  fs::create_directories(dir / (".out.partial-" + dead + "-unstamped"));
  fs::create_directories(dir / (".other.partial-" + dead));  // another target's: kept
  std::ofstream(dir / (".other.partial-" + dead) / kStampFile) << "program = \"workbench\"\n";
  fs::create_directories(dir / (".out.partial-1" + dead));   // no stamp: kept even if its pid is gone
  StagedDirectory staged(dir / "out", kCase);
  EXPECT_FALSE(fs::exists(dir / (".out.partial-" + dead)));
  EXPECT_FALSE(fs::exists(dir / (".out.old-" + dead)));
  EXPECT_TRUE(fs::exists(dir / (".out.partial-" + alive)));
  EXPECT_TRUE(fs::exists(dir / (".out.partial-" + dead + "x")));
  EXPECT_TRUE(fs::exists(dir / (".out.partial-" + dead + "-unstamped")));
  EXPECT_TRUE(fs::exists(dir / (".other.partial-" + dead)));
  EXPECT_TRUE(fs::exists(dir / (".out.partial-1" + dead)));
}

TEST(ChildProcess, PassesArgumentsVerbatimAndReportsTheExitStatus) {
  const fs::path log = test_support::scratch_folder() / "child.log";
  const std::string tricky = "it's a $HOME `x` \"y\" ; rm -rf /nothing";
  EXPECT_EQ(run_child({"/bin/sh", "-c", "printf '%s|%s' \"$0\" \"$1\"; exit 3", tricky, "second arg"}, log), 3);
  EXPECT_EQ(read_file(log), tricky + "|second arg");
  EXPECT_EQ(run_child({"sh", "-c", "echo to-stderr >&2"}, log), 0);  // looked up on PATH; stderr to the log
  EXPECT_EQ(read_file(log), "to-stderr\n");
  EXPECT_EQ(run_child({"/bin/sh", "-c", "kill -TERM $$"}, log), 128 + 15);
  EXPECT_EQ(error_of([&] { run_child({"/nonexistent/program"}, log); }),
            "/nonexistent/program: cannot run (No such file or directory)");
}

TEST(ChildProcess, MallocOnHugePagesUnlessTheUserTunesGlibc) {
  const fs::path log = test_support::scratch_folder() / "child.log";
  const char* saved = std::getenv("GLIBC_TUNABLES");
  const std::string keep = saved ? saved : "";
  ::unsetenv("GLIBC_TUNABLES");
  EXPECT_EQ(run_child({"/bin/sh", "-c", "printf %s \"$GLIBC_TUNABLES\""}, log), 0);
  EXPECT_EQ(read_file(log), "glibc.malloc.hugetlb=1");
  ::setenv("GLIBC_TUNABLES", "glibc.malloc.arena_max=1", 1);
  EXPECT_EQ(run_child({"/bin/sh", "-c", "printf %s \"$GLIBC_TUNABLES\""}, log), 0);
  EXPECT_EQ(read_file(log), "glibc.malloc.arena_max=1");
  if (saved) ::setenv("GLIBC_TUNABLES", keep.c_str(), 1);
  else ::unsetenv("GLIBC_TUNABLES");
}

TEST(ChildProcess, ReadsWhatIsSentAndSeesTheEndOfItsInput) {
  const fs::path log = test_support::scratch_folder() / "child.log";
  ChildProcess child({"/bin/sh", "-c", "read a; read b; echo \"$a|$b\"; if read c; then exit 1; fi; exit 4"}, log);
  EXPECT_TRUE(child.send("first line"));
  EXPECT_TRUE(child.send("second"));
  EXPECT_EQ(child.wait(), 4);  // wait() closed its input: the third read met the end
  EXPECT_EQ(read_file(log), "first line|second\n");
  EXPECT_EQ(child.pid(), 0);
}

TEST(ChildProcess, ReceivesTheLinesItWritesBackAndSeesItEnd) {
  const fs::path log = test_support::scratch_folder() / "child.log";
  // It writes two lines back on its standard input (the socket), then reads one and ends.
  ChildProcess child({"/bin/sh", "-c", "echo drawn >&0; echo 'two words' >&0; read a; echo \"got $a\"; exit 3"}, log);
  EXPECT_EQ(child.receive(), "drawn");
  EXPECT_EQ(child.receive(), "two words");
  EXPECT_TRUE(child.send("report"));
  EXPECT_EQ(child.receive(), std::nullopt);  // it ended: nothing more comes back
  EXPECT_EQ(child.wait(), 3);
  EXPECT_EQ(read_file(log), "got report\n");
  EXPECT_EQ(child.report(), "drawn\ntwo words\n");
}

TEST(ChildProcess, SendingToAnEndedChildFailsWithoutASignal) {
  const fs::path log = test_support::scratch_folder() / "child.log";
  ChildProcess child({"/bin/sh", "-c", "exit 5"}, log);
  siginfo_t info{};
  ASSERT_EQ(::waitid(P_PID, id_t(child.pid()), &info, WEXITED | WNOWAIT), 0);  // ended, not yet reaped
  EXPECT_FALSE(child.send("draw"));  // EPIPE, and no SIGPIPE ends this test
  EXPECT_EQ(child.wait(), 5);
}

TEST(ChildProcess, OneNotWaitedForIsEndedWithItsGroup) {
  const fs::path log = test_support::scratch_folder() / "child.log";
  const fs::path fifo = log.parent_path() / "ready";
  ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0);
  int pid = 0;
  {
    // A child that ignores SIGTERM (kept across exec): the destructor must end it with SIGKILL.
    // It says "ready" through the FIFO once the trap is set (opening the FIFO waits for it).
    ChildProcess child({"/bin/sh", "-c", "trap '' TERM; echo ready > \"$0\"; exec sleep 1000", fifo.string()}, log);
    pid = child.pid();
    ASSERT_GT(pid, 0);
    EXPECT_EQ(read_file(fifo), "ready\n");
  }
  EXPECT_EQ(::kill(-pid, 0), -1);  // no process of its group is left
  EXPECT_EQ(errno, ESRCH);
  EXPECT_EQ(::waitpid(pid, nullptr, WNOHANG), -1);  // and the child was reaped
  EXPECT_EQ(errno, ECHILD);
}

TEST(ChildProcess, PythonIsWorkbenchPythonElseTheSystemOne) {
  const char* saved = std::getenv("WORKBENCH_PYTHON");
  const std::string keep = saved ? saved : "";
  ::unsetenv("WORKBENCH_PYTHON");
  EXPECT_EQ(python_interpreter(), "/usr/bin/python3");
  ::setenv("WORKBENCH_PYTHON", "/opt/py/bin/python", 1);
  EXPECT_EQ(python_interpreter(), "/opt/py/bin/python");
  if (saved) ::setenv("WORKBENCH_PYTHON", keep.c_str(), 1);
  else ::unsetenv("WORKBENCH_PYTHON");
}

TEST(ChildProcess, ScriptsAreFoundBesideTheProgramOrInWorkbenchScriptDir) {
  // The build copies the scripts into <build>/share/workbench, two folders above this test.
  EXPECT_EQ(find_script("compare/figures.py").filename(), "figures.py");
  const fs::path dir = test_support::scratch_folder();
  ::setenv("WORKBENCH_SCRIPT_DIR", dir.c_str(), 1);
  EXPECT_EQ(error_of([&] { find_script("compare/figures.py"); }),
            (dir / "compare/figures.py").string() + ": script not found (WORKBENCH_SCRIPT_DIR is set)");
  fs::create_directories(dir / "compare");
  std::ofstream(dir / "compare/figures.py") << "";
  EXPECT_EQ(find_script("compare/figures.py"), dir / "compare/figures.py");
  ::unsetenv("WORKBENCH_SCRIPT_DIR");
}

TEST(CsvFile, WritesShortestRoundTripNumbersAndRefusesNonFiniteNamingTheColumn) {
  const fs::path file = test_support::scratch_folder() / "t.csv";
  auto out = open_csv(file);
  out << "# a comment, not the header\n" << "node,x,y\n";
  out << 7 << ',' << 0.1 << ',' << 1.0 / 3.0 << '\n';
  out << 8 << ',' << -2.5e-300 << ',' << 1e21 << '\n';
  EXPECT_EQ(error_of([&] { out << 9 << ',' << 1.0 << ',' << std::nan(""); }),
            "t.csv: column 'y' (row 9): nan is not a finite number");
  EXPECT_EQ(error_of([&] { out << ',' << -HUGE_VAL; }), "t.csv: column 'y' (row 9): -inf is not a finite number");
  out << '\n';
  out.close();
  EXPECT_EQ(read_file(file), "# a comment, not the header\nnode,x,y\n7,0.1,0.3333333333333333\n8,-2.5e-300,1e+21\n9,1,,\n");
  EXPECT_EQ(std::stod(shortest_decimal(1.0 / 3.0)), 1.0 / 3.0);
  EXPECT_EQ(shortest_decimal(0.1), "0.1");
}

TEST(CsvFile, AnUndefinedValueIsAnEmptyFieldOnlyWhenSaidSo) {
  const fs::path file = test_support::scratch_folder() / "ratios.csv";
  auto out = open_csv(file);
  out << "cell,ratio\n";
  out << 0 << ',' << std::optional<double>(0.25) << '\n';
  out << 1 << ',' << std::optional<double>() << '\n';  // masked: empty on purpose
  EXPECT_EQ(error_of([&] { out << 2 << ',' << std::optional<double>(std::nan("")); }),
            "ratios.csv: column 'ratio' (row 2): nan is not a finite number");
  out << '\n';
  out.close();
  EXPECT_EQ(read_file(file), "cell,ratio\n0,0.25\n1,\n2,\n");
}

TEST(CsvFile, AFailedWriteIsAnError) {
  if (!fs::exists("/dev/full")) GTEST_SKIP() << "no /dev/full";
  auto out = open_csv("/dev/full");
  EXPECT_EQ(error_of([&] {
              for (int i = 0; i < 100000; ++i) out << "a,b\n";
              out.close();
            }),
            "/dev/full: write failed (No space left on device)");
  EXPECT_EQ(error_of([&] { open_csv(test_support::scratch_folder() / "no" / "such" / "folder.csv"); }),
            (test_support::scratch_folder() / "no" / "such" / "folder.csv").string() +
                ": cannot open for writing (No such file or directory)");
}
