// The mesher server (gmsh_session.h, start_geo_mesher_server): .geo files meshed in processes it
// forks, a crash or abort of gmsh one error while the server goes on, several .geo files in one
// process, the server ending with its parent, the mesher program when the server is gone, and a
// hung gmsh ended at the mesher's time limit.
#include <gmsh_session.h>

#include "../support/scratch_folder.h"

#include <gmsh.h>
#include <gtest/gtest.h>

#include <chrono>
#include <cstdlib>
#include <csignal>
#include <filesystem>
#include <fstream>
#include <stdexcept>
#include <string>
#include <thread>

#include <sys/wait.h>
#include <unistd.h>

namespace fs = std::filesystem;

namespace {

const fs::path source = WORKBENCH_SOURCE_DIR;

std::size_t loaded_nodes() {
  std::vector<std::size_t> tags;
  std::vector<double> coords, parametric;
  gmsh::model::mesh::getNodes(tags, coords, parametric);
  return tags.size();
}

/// The error gmsh_load gives for `geo`, "" when it loads.
std::string load_error(const fs::path& geo) {
  try {
    workbench::gmsh_load(geo, {});
  } catch (const std::runtime_error& e) {
    return e.what();
  }
  return "";
}

/// True while `pid` exists and is not a zombie.
bool running(int pid) {
  std::ifstream stat("/proc/" + std::to_string(pid) + "/stat");
  std::string text;
  if (!std::getline(stat, text)) return false;
  const auto end = text.rfind(')');
  return end != std::string::npos && text.size() > end + 2 && text[end + 2] != 'Z';
}

}  // namespace

TEST(GeoMesherServer, CrashesAreOneErrorAndTheServerGoesOnMeshing) {
  const int server = workbench::start_geo_mesher_server();
  ASSERT_GT(server, 0);
  const int served = workbench::geo_mesher_server_requests();
  const fs::path crashes = source / "tests/data/gmsh_crashes";
  // A SIGSEGV in gmsh's parser and a std::terminate (abort) in its meshing loop: each one error
  // naming the file and how the meshing process ended.
  const auto segv = crashes / "list_index_1e300.geo";
  EXPECT_EQ(load_error(segv), segv.string() + ": gmsh failed meshing it (killed by signal 11: Segmentation fault)");
  const auto abort = crashes / "transfinite_corner_not_a_point.geo";
  EXPECT_EQ(load_error(abort), abort.string() + ": gmsh failed meshing it (aborted)");
  EXPECT_EQ(workbench::geo_mesher_server_pid(), server);
  EXPECT_TRUE(running(server));
  EXPECT_EQ(workbench::geo_mesher_server_requests(), served + 2);

  // Two different .geo files, then the first again with other parameters: each meshed by the server.
  EXPECT_EQ(workbench::gmsh_load(source / "meshes/cook.geo", {{"n", 4}}), std::vector<std::string>{"n"});
  EXPECT_EQ(loaded_nodes(), 25u);
  workbench::gmsh_load(source / "meshes/plate2d.geo", {{"h", 0.02}, {"lw", 0.04}});
  EXPECT_EQ(loaded_nodes(), 121u);
  workbench::gmsh_load(source / "meshes/cook.geo", {{"n", 6}});
  EXPECT_EQ(loaded_nodes(), 49u);
  EXPECT_EQ(workbench::geo_mesher_server_requests(), served + 5);
  // An unknown parameter is refused by the meshing process, with the message of an in-process load.
  const auto cook = source / "meshes/cook.geo";
  try {
    workbench::gmsh_load(cook, {{"m", 1}});
    ADD_FAILURE() << "an unknown parameter was accepted";
  } catch (const std::runtime_error& e) {
    EXPECT_EQ(std::string(e.what()), cook.string() + ": unknown mesh parameter 'm' (the .geo declares none of that name)");
  }
  EXPECT_EQ(workbench::geo_mesher_server_pid(), server);
}

TEST(GeoMesherServer, WithoutTheServerTheMesherProgramMeshes) {
  const int server = workbench::start_geo_mesher_server();
  ASSERT_GT(server, 0);
  const int served = workbench::geo_mesher_server_requests();
  ::kill(server, SIGKILL);
  // The next load finds the server gone and runs the mesher program (beside the build's programs).
  workbench::gmsh_load(source / "meshes/cook.geo", {{"n", 4}});
  EXPECT_EQ(loaded_nodes(), 25u);
  EXPECT_EQ(workbench::geo_mesher_server_pid(), 0);
  EXPECT_EQ(workbench::geo_mesher_server_requests(), served);
  EXPECT_FALSE(running(server));
}

TEST(GeoMesherServer, EndsWithItsParent) {
  int ends[2];
  ASSERT_EQ(::pipe(ends), 0);
  const pid_t parent = ::fork();
  ASSERT_GE(parent, 0);
  if (parent == 0) {  // a process that starts a server and ends
    const int server = workbench::start_geo_mesher_server();
    (void)!::write(ends[1], &server, sizeof server);
    ::_exit(0);
  }
  ::close(ends[1]);
  int server = 0;
  ASSERT_EQ(::read(ends[0], &server, sizeof server), ssize_t(sizeof server));
  ::close(ends[0]);
  ASSERT_GT(server, 0);
  ::waitpid(parent, nullptr, 0);
  bool ended = false;
  for (int i = 0; i < 100 && !ended; ++i) {
    ended = !running(server);
    if (!ended) std::this_thread::sleep_for(std::chrono::milliseconds(20));
  }
  EXPECT_TRUE(ended) << "the server " << server << " outlived its parent";
}

TEST(GeoMesherServer, AHungGmshEndsAtTheTimeLimit) {
  const int server = workbench::start_geo_mesher_server();
  // The limit is this process's environment at the load (the server was started before it is set).
  ::setenv("WORKBENCH_MESH_TIME_LIMIT", "1", 1);
  ASSERT_GT(server, 0);
  // gmsh's parser counts to 2e9 (minutes): it is ended after 1 s, one error naming the .geo.
  const fs::path hang = test_support::scratch_folder() / "hang.geo";
  std::ofstream(hang) << "x = 0;\nFor i In {1:2e9}\n  x = x + i;\nEndFor\nPoint(1) = {0, 0, 0, 1};\n";
  const std::string expected =
      hang.string() + ": gmsh did not finish meshing it within 1 s (the time limit; WORKBENCH_MESH_TIME_LIMIT=<seconds> sets it)";
  EXPECT_EQ(load_error(hang), expected);
  // The server goes on; a .geo that meshes in time is not ended.
  EXPECT_EQ(workbench::geo_mesher_server_pid(), server);
  workbench::gmsh_load(source / "meshes/cook.geo", {{"n", 4}});
  EXPECT_EQ(loaded_nodes(), 25u);
  // The mesher program, once the server is gone, keeps the same limit.
  ::kill(server, SIGKILL);
  EXPECT_EQ(load_error(hang), expected);
  EXPECT_EQ(workbench::geo_mesher_server_pid(), 0);
  // A limit that is no whole number of seconds is one error.
  ::setenv("WORKBENCH_MESH_TIME_LIMIT", "1e3", 1);
  const auto cook = source / "meshes/cook.geo";
  EXPECT_EQ(load_error(cook), cook.string() + ": WORKBENCH_MESH_TIME_LIMIT: must be a whole number of seconds in [1, 604800] (got '1e3')");
  ::unsetenv("WORKBENCH_MESH_TIME_LIMIT");
}
