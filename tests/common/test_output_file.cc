// Checked writes (workbench/output_file.h): a failed write is one Error naming the file as the user
// knows it and the reason; the free-space check; a child's report of its failed write.
#include <workbench/child_process.h>
#include <workbench/error.h>
#include <workbench/output_file.h>
#include <workbench/staged_directory.h>
#include <workbench/vtk_output.h>

#include <gtest/gtest.h>

#include "../support/error_of.h"
#include "../support/scratch_folder.h"

#include <cstdlib>
#include <fstream>
#include <sstream>

namespace fs = std::filesystem;
using namespace workbench;
using test_support::error_of;

namespace {

using test_support::read_file;

// Sets an environment variable for one test's scope.
struct ScopedEnv {
  std::string name;
  ScopedEnv(std::string n, const char* value) : name(std::move(n)) { ::setenv(name.c_str(), value, 1); }
  ~ScopedEnv() { ::unsetenv(name.c_str()); }
};

}  // namespace

TEST(OutputFile, AFailedWriteNamesTheFileAndTheReason) {
  if (!fs::exists("/dev/full")) GTEST_SKIP() << "no /dev/full";
  EXPECT_EQ(error_of([] { write_file("/dev/full", std::string(100, 'x')); }),
            "/dev/full: write failed (No space left on device)");
  EXPECT_EQ(error_of([] { write_file("/dev/full", std::string(1 << 20, 'x')); }),  // past the buffer
            "/dev/full: write failed (No space left on device)");
  const fs::path missing = test_support::scratch_folder() / "no" / "file.txt";
  EXPECT_EQ(error_of([&] { write_file(missing, "x"); }),
            missing.string() + ": cannot open for writing (No such file or directory)");
}

TEST(OutputFile, WritesEveryByteInSmallAndLargePieces) {
  const fs::path file = test_support::scratch_folder() / "a.bin";
  std::string expected;
  OutputFile out(file);
  for (int i = 0; i < 3000; ++i) {  // small pieces through the buffer, a large one straight through
    const std::string piece = i == 1500 ? std::string(200000, 'L') : std::to_string(i) + ",";
    out.write(piece);
    expected += piece;
  }
  out.close();
  EXPECT_EQ(read_file(file), expected);
}

TEST(OutputFile, NamesAFileInTheStagingFolderAsInItsTarget) {
  const fs::path target = test_support::scratch_folder() / "out";
  StagedDirectory staged(target, "case.toml");
  EXPECT_EQ(shown_path(staged.path() / "figures" / "fig8.png"), (target / "figures" / "fig8.png").string());
  EXPECT_EQ(shown_path(staged.path()), target.string());
  EXPECT_EQ(shown_path("/elsewhere/a.csv"), "/elsewhere/a.csv");
  EXPECT_EQ(shown_text("x " + (staged.path() / "a.csv").string() + ": write failed (File too large)"),
            "x " + (target / "a.csv").string() + ": write failed (File too large)");
  // A child's report of its failed write, exit 74: the one line, the path shown below the target.
  const fs::path log = staged.path() / "child.log";
  const std::string line = (staged.path() / "figures" / "fig8.png").string() + ": write failed (No space left on device)";
  std::string report;
  const int status = run_child({"/bin/sh", "-c", "echo 'drawing' ; printf '%s\\n' \"$0\" >&0; exit 74", line}, log, &report);
  EXPECT_EQ(status, kWriteFailedStatus);
  EXPECT_EQ(report, line + "\n");
  EXPECT_EQ(error_of([&] { check_script_status(status, log, "figures.py", report); }),
            (target / "figures" / "fig8.png").string() + ": write failed (No space left on device)");
  // Without a report (a stand-in script): its log's last line.
  EXPECT_EQ(error_of([&] { check_script_status(status, log, "figures.py", ""); }), "drawing");
}

TEST(OutputFile, ReplaceFileLeavesNothingBeside) {
  const fs::path file = test_support::scratch_folder() / "junit.xml";
  write_file(file, "old");
  replace_file(file, "new");
  EXPECT_EQ(read_file(file), "new");
  std::string names;
  for (const auto& e : fs::directory_iterator(file.parent_path())) names += e.path().filename().string() + " ";
  EXPECT_EQ(names, "junit.xml ");
}

TEST(OutputFile, SyncsATreeAndRefusesWhatDoesNotFit) {
  const fs::path dir = test_support::scratch_folder() / "tree";
  fs::create_directories(dir / "sub");
  write_file(dir / "sub" / "a.csv", "1\n");
  EXPECT_EQ(error_of([&] { sync_tree(dir); }), "no error");
  ScopedEnv free_space("WORKBENCH_FREE_BYTES", "1000");
  EXPECT_EQ(free_bytes(dir), 1000u);
  EXPECT_EQ(error_of([&] { require_room(dir, 1000, "the study"); }), "no error");
  EXPECT_EQ(error_of([&] { require_room(dir, 2500000, "the study"); }),
            dir.string() + ": the study needs an estimated 2.5 MB, the file system has 0.001 MB free; refusing to start it");
}

TEST(OutputFile, AVtuSeriesThatDoesNotFitIsRefusedBeforeItsFirstFile) {
  OutputMesh mesh;
  mesh.points = {0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0};
  mesh.add_cell(9, {0, 1, 2, 3});
  const Field f{"u [m]", 1, {0.1, 0.2, 0.3, 0.4}, {}, {}};
  const fs::path file = test_support::scratch_folder() / "step_001.vtu";
  ScopedEnv free_space("WORKBENCH_FREE_BYTES", "100000");
  const std::string message = error_of([&] { write_vtu(file, mesh, {f}, {}, 1000); });
  EXPECT_EQ(message.rfind(test_support::scratch_folder().string() + ": the series of 1000 VTU files (", 0), 0u) << message;
  EXPECT_NE(message.find("the file system has 0.1 MB free"), std::string::npos) << message;
  EXPECT_FALSE(fs::exists(file));
  write_vtu(file, mesh, {f}, {}, 10);  // fits
  EXPECT_NE(read_file(file).find("<VTKFile type=\"UnstructuredGrid\""), std::string::npos);
}
