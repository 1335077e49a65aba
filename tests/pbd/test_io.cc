// Mesh input (gmsh .geo/.msh, OBJ, VTU), the errors of degenerate meshes, the [pbd] case
// section and the study output.
#include <pbd_io/mesh_io.h>
#include <pbd_study.h>
#include <workbench/error.h>
#include <workbench/vtk_output.h>

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "../support/error_of.h"
#include "../support/scratch_folder.h"

namespace fs = std::filesystem;
using pbd::Vec3;

namespace {

const fs::path kSource = WORKBENCH_SOURCE_DIR;

struct TempDir {
  fs::path path;
  TempDir() {
    path = test_support::scratch_folder() / ::testing::UnitTest::GetInstance()->current_test_info()->name();
    fs::remove_all(path);
    fs::create_directories(path);
  }
  ~TempDir() { fs::remove_all(path); }
  fs::path write(const std::string& name, const std::string& text) const {
    std::ofstream(path / name) << text;
    return path / name;
  }
};

using test_support::error_of;

}  // namespace

TEST(PbdMeshIo, ReadsTheRodGeoWithItsGroups) {
  const auto m = pbd_io::read_mesh(kSource / "meshes/rod2d.geo", {{"N", 10}, {"L", 2.0}});
  EXPECT_EQ(m.mesh.points.size(), 12u);
  EXPECT_EQ(m.mesh.cell_count(), 11u);
  ASSERT_TRUE(m.mesh.groups.count("clamp"));
  EXPECT_EQ(m.mesh.groups.at("clamp").size(), 2u);
  const auto tip = pbd_io::group_nodes(m, "rod2d.geo", {"tip"});
  ASSERT_EQ(tip.size(), 1u);
  EXPECT_NEAR(m.mesh.points[tip[0]][0], 2.0, 1e-12);
}

TEST(PbdMeshIo, ReadsTheSheetGeoAsTriangles) {
  const auto m = pbd_io::read_mesh(kSource / "meshes/sheet3d.geo", {{"n", 4}});
  EXPECT_EQ(m.mesh.points.size(), 25u);
  EXPECT_EQ(m.mesh.cell_count(), 32u);
  for (int t : m.mesh.cell_types) EXPECT_EQ(t, pbd::kTriangle);
  EXPECT_EQ(m.mesh.groups.at("corners").size(), 2u);
}

TEST(PbdMeshIo, ReadsObjWithGroupsQuadsAndPolylines) {
  TempDir tmp;
  const auto f = tmp.write("m.obj",
                           "# two quads and a polyline\nv 0 0 0\nv 1 0 0\nv 2 0 0\nv 0 1 0\nv 1 1 0\nv 2 1 0\n"
                           "v 3 0 0\nv 4 0 0\nf 1 2 5 4\nf 2/1 3/2 6/3 5/4\ng tail\nl 3 7 8\n");
  const auto m = pbd_io::read_mesh(f);
  EXPECT_EQ(m.mesh.cell_count(), 4u);
  EXPECT_EQ(pbd_io::group_nodes(m, f, {"tail"}), (std::vector<int>{2, 6, 7}));
}

TEST(PbdMeshIo, ReadsVtuWithZeroOneArraysAsGroups) {
  TempDir tmp;
  workbench::OutputMesh out;
  out.points = {0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0};
  out.add_cell(5, {0, 1, 2});
  out.add_cell(5, {0, 2, 3});
  workbench::write_vtu(tmp.path / "m.vtu", out, {{"fixed", 1, {1, 0, 0, 1}, {}, {}}, {"other", 1, {0.5, 0, 0, 0}, {}, {}}}, {});
  const auto m = pbd_io::read_mesh(tmp.path / "m.vtu");
  EXPECT_EQ(m.mesh.cell_count(), 2u);
  EXPECT_EQ(pbd_io::group_nodes(m, "m.vtu", {"fixed"}), (std::vector<int>{0, 3}));
  EXPECT_FALSE(m.mesh.groups.count("other"));
}

TEST(PbdMeshIo, DegenerateMeshesGiveOneLineErrors) {
  TempDir tmp;
  struct Case {
    std::string name, text, expect;
  } cases[] = {
      {"zero.obj", "v 0 0 0\nv 1 0 0\nv 1 0 0\nl 1 2 3\n", "zero-length edge between nodes 2 and 3 at (1, 0, 0)"},
      {"dup.obj", "v 0 0 0\nv 1 0 0\nv 1 0 0\nv 2 0 0\nl 1 2\nl 3 4\n", "duplicate nodes 2 and 3 at (1, 0, 0)"},
      {"iso.obj", "v 0 0 0\nv 1 0 0\nv 5 5 0\nl 1 2\n", "isolated node 3 at (5, 5, 0) (in no cell)"},
      {"pent.obj", "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nv -1 0 0\nf 1 2 3 4 5\n", "line 6: a face with 5 vertices"},
      {"empty.obj", "v 0 0 0\n", "has no line, triangle or quadrilateral cells"},
      {"bad.obj", "v 0 0 0\nl 1 9\n", "line 2: vertex 9 does not exist"},
      {"mesh.stl", "solid\n", "unknown mesh format '.stl'"},
  };
  for (const auto& c : cases) {
    const auto f = tmp.write(c.name, c.text);
    const std::string e = error_of([&] { pbd_io::read_mesh(f); });
    EXPECT_NE(e.find(f.string() + ": "), std::string::npos) << e;
    EXPECT_NE(e.find(c.expect), std::string::npos) << e;
    EXPECT_EQ(e.find('\n'), std::string::npos) << e;
  }
  EXPECT_NE(error_of([&] { pbd_io::read_mesh(tmp.path / "none.msh"); }).find("no such mesh file"), std::string::npos);
  const auto rod = pbd_io::read_mesh(kSource / "meshes/rod2d.geo", {{"N", 4}});
  const std::string e = error_of([&] { pbd_io::group_nodes(rod, "rod2d.geo", {"base"}); });
  EXPECT_EQ(e, "rod2d.geo: group 'base' does not exist (it has: clamp, rod, tip)");
  EXPECT_NE(error_of([&] { pbd_io::read_mesh(kSource / "meshes/rod2d.geo", {{"X", 1}}); }).find("unknown mesh parameter 'X'"),
            std::string::npos);
}

TEST(PbdMeshIo, GeoErrorsAreReportedAndTheSessionRecovers) {
  // An Error() in the .geo (N < 2) is reported with the file name.
  // (A syntax error would do too, but gmsh 4.8 leaks in its parser then, which LeakSanitizer flags.)
  const auto f = kSource / "meshes/rod2d.geo";
  const std::string e = error_of([&] { pbd_io::read_mesh(f, {{"N", 1}}); });
  EXPECT_EQ(e, f.string() + ": rod2d.geo: N must be at least 2");
  // The session recovers: a good file reads after the error.
  EXPECT_EQ(pbd_io::read_mesh(kSource / "meshes/rod2d.geo", {{"N", 3}}).mesh.points.size(), 5u);
}

TEST(PbdStudy, CaseKeysAreCheckedAndUnknownKeysRejected) {
  TempDir tmp;
  const std::string mesh = (kSource / "meshes/rod2d.geo").string();
  auto load = [&](const std::string& body) {
    const auto f = tmp.write("c.toml", "[pbd]\nmesh = \"" + mesh + "\"\nmesh_parameters = { N = 4 }\n" + body);
    workbench::CaseFile file(f);
    auto setup = pbd_study::read_pbd_case(file);
    file.reject_unknown_keys();
    return pbd_study::load_pbd_study(file, setup);
  };
  const auto s = load("pinned = [\"clamp\"]\nyoung = 2e11\nsecond_moment = 1e-12\n");
  EXPECT_TRUE(s.model.planar);
  EXPECT_DOUBLE_EQ(s.setup.model.bending_stiffness, 0.2);
  EXPECT_NE(error_of([&] { load("substep = 3\n"); }).find("pbd.substep"), std::string::npos);
  EXPECT_NE(error_of([&] { load("pinned = [\"wall\"]\n"); }).find("group 'wall' does not exist"), std::string::npos);
  EXPECT_NE(error_of([&] { load("young = 1e9\n"); }).find("second_moment"), std::string::npos);
  EXPECT_NE(error_of([&] { load("gravity = [0, 1]\n"); }).find("needs 3 numbers"), std::string::npos);
  EXPECT_NE(error_of([&] { load("bending_stiffness = 1\nbending_compliance = 1\n"); }).find("give one of"),
            std::string::npos);
  EXPECT_NE(error_of([&] { load("time_step = -1\n"); }).find("pbd.time_step"), std::string::npos);
  EXPECT_FALSE(load("gravity = [0, 0, -9.81]\n").model.planar);  // out-of-plane load: unsigned form
}

namespace {
/// Runs `frames` frames of an N = 8 rod case with `extra` [pbd] keys into tmp/out; returns the log.
std::string run_rod_case(TempDir& tmp, const std::string& extra, int frames = 20) {
  const auto f = tmp.write("c.toml", "[pbd]\nmesh = \"" + (kSource / "meshes/rod2d.geo").string() +
                                         "\"\nmesh_parameters = { N = 8, L = 1.0 }\npinned = [\"clamp\"]\n"
                                         "frames = " + std::to_string(frames) +
                                         "\nbending_stiffness = 1.0\nmasses = \"lumped\"\n" + extra);
  workbench::CaseFile file(f);
  auto setup = pbd_study::read_pbd_case(file);
  file.reject_unknown_keys();
  auto study = pbd_study::load_pbd_study(file, setup);
  std::ostringstream log;
  pbd_study::write_pbd_outputs(study, tmp.path / "out", false, log);
  return log.str();
}
std::string read_text(const fs::path& file) {
  std::ifstream in(file);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}
}  // namespace

TEST(PbdStudy, WritesFramesSeriesAndCentreline) {
  TempDir tmp;
  const std::string log = run_rod_case(tmp, "output_every = 2\n", 6);
  for (const char* name : {"pbd.pvd", "diagnostics.csv", "nodes.csv", "centreline.csv", "frames/frame_00000.vtu",
                           "frames/frame_00006.vtu"})
    EXPECT_TRUE(fs::exists(tmp.path / "out" / name)) << name;
  EXPECT_FALSE(fs::exists(tmp.path / "out/frames/frame_00001.vtu"));
  std::ifstream in(tmp.path / "out/centreline.csv");
  std::string line;
  std::vector<std::string> rows;
  while (std::getline(in, line)) rows.push_back(line);
  ASSERT_EQ(rows.size(), 11u);  // header + ghost + 9 rod nodes
  EXPECT_EQ(rows[0], "s [m],x0 [m],y0 [m],z0 [m],x [m],y [m],z [m],u_x [m],u_y [m],u_z [m]");
  EXPECT_EQ(rows[1].rfind("-0.125,-0.125,0,0,-0.125,0,0,0,0,0", 0), 0u) << rows[1];  // ghost node in the clamp
  EXPECT_EQ(rows[2].rfind("0,0,0,0,0,0,0,0,0,0", 0), 0u) << rows[2];                   // s = 0 at the clamp face
  double tip_uy = std::stod(rows.back().substr(rows.back().rfind(',', rows.back().rfind(',') - 1) + 1));
  EXPECT_LT(tip_uy, 0.0);  // sags
  EXPECT_NE(log.find("pbd: frame 6/6"), std::string::npos);
}


TEST(PbdStudy, ChosenSubstepsConvergeAndAnUnderResolvedRunWarns) {
  {
    TempDir tmp;
    const std::string log = run_rod_case(tmp, "gravity = [0, -25, 0]\n");
    // N = 8, l = 0.125, lumped m = l: h = l^2 sqrt(0.01 / 12) = 4.5105e-4 s -> 0.01 / h = 22.17 -> 23.
    EXPECT_NE(log.find("23 substeps x 1 iterations per frame (substeps chosen"), std::string::npos) << log;
    EXPECT_EQ(log.find("warning"), std::string::npos) << log;
    EXPECT_EQ(read_text(tmp.path / "out/summary.txt").find("warning"), std::string::npos);
  }
  TempDir tmp;
  const std::string log = run_rod_case(tmp, "gravity = [0, -25, 0]\nsubsteps = 1\n");
  EXPECT_NE(log.find("pbd: warning: the final constraint residuals exceed their tolerances"), std::string::npos) << log;
  EXPECT_NE(read_text(tmp.path / "out/summary.txt").find("warning: the final constraint residuals"), std::string::npos);
}

TEST(PbdStudy, ADivergingRunNamesTheCaseKeys) {
  TempDir tmp;
  const std::string e = error_of([&] { run_rod_case(tmp, "node_force = [0, -1e90, 0]\ntime_step = 1e60\nsubsteps = 1\n"); });
  EXPECT_EQ(e.rfind((tmp.path / "c.toml").string() + ": pbd.gravity, pbd.node_force, pbd.time_step: the simulation diverged", 0),
            0u) << e;
}

TEST(PbdStudy, ChainOrderStartsAtThePinnedEnd) {
  auto line = pbd::Mesh::polyline(Vec3::Zero(), Vec3(1, 0, 0), 4);
  EXPECT_EQ(pbd_study::chain_order(line, {4}), (std::vector<int>{4, 3, 2, 1, 0}));
  EXPECT_EQ(pbd_study::chain_order(line, {}), (std::vector<int>{0, 1, 2, 3, 4}));
  EXPECT_TRUE(pbd_study::chain_order(pbd::Mesh::grid(2, 2, 1.0), {}).empty());
}

TEST(PbdStudy, RendersAnAnimationWithoutADisplay) {
  if (!fs::exists("/usr/bin/python3") || std::system("command -v ffmpeg > /dev/null 2>&1") != 0)
    GTEST_SKIP() << "no /usr/bin/python3 or ffmpeg";
  TempDir tmp;
  const auto mesh = pbd::Mesh::grid(3, 2, 0.5, true);
  std::vector<Vec3> x = mesh.points;
  const auto out = pbd_study::output_mesh(mesh, x);
  pbd_study::write_render_cells(tmp.path, out);
  for (int k = 0; k < 3; ++k) {
    for (auto& p : x) p[2] = 0.1 * k * p[0];
    const auto o = pbd_study::output_mesh(mesh, x);
    pbd_study::write_render_frame(tmp.path / ("frame_0000" + std::to_string(k) + ".csv"), o.points, 0.1 * k, "u",
                                  std::vector<double>(x.size(), double(k)));
  }
  pbd_study::render_animation(tmp.path, tmp.path / "a.gif", 5, "u", "test");
  ASSERT_TRUE(fs::exists(tmp.path / "a.gif"));
  EXPECT_GT(fs::file_size(tmp.path / "a.gif"), 1000u);
  const std::string e = error_of([&] { pbd_study::render_animation(tmp.path, tmp.path / "a.gif", 5, "nope", ""); });
  EXPECT_NE(e.find("no column 'nope'"), std::string::npos) << e;
}
