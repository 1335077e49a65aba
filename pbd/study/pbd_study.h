#pragma once
// The PBD model as a workbench study: case file [pbd] section -> mesh -> frames -> VTU/PVD/CSV
// (and an animation). Key reference: docs/case-file.md, "PBD case files".
#include <pbd/model.h>
#include <pbd/solver.h>
#include <pbd/topology.h>
#include <pbd_io/mesh_io.h>
#include <workbench/case_file.h>
#include <workbench/vtk_output.h>

#include <filesystem>
#include <functional>
#include <iosfwd>
#include <map>
#include <string>
#include <vector>

namespace pbd_study {

struct PbdCase {
  std::filesystem::path case_file;  ///< for messages
  std::string title;
  std::filesystem::path mesh_file;
  std::map<std::string, double> mesh_parameters;
  std::vector<std::string> pinned_groups;
  std::string angle_form = "auto";  ///< auto | signed | unsigned
  pbd::ModelOptions model;
  pbd::StepSettings step;  ///< substeps 0 until load_pbd_study chooses them (pbd.substeps absent)
  bool substeps_chosen = false;  ///< substeps from pbd::substeps_for_accuracy, not from the case
  int frames = 100;
  int output_every = 1;
  std::string animation_format = "mp4";
  int fps = 25;
};

/// Reads [pbd] (and `title`). Does not reject unknown keys: the caller does.
PbdCase read_pbd_case(const workbench::CaseFile& file);

struct PbdStudy {
  PbdCase setup;
  pbd_io::LoadedMesh mesh;
  std::vector<int> pinned;
  pbd::Model model;
};

/// Reads the mesh, resolves the pinned groups, chooses the angle form and builds the model from
/// `setup` (read_pbd_case's): check the whole case file (reject_unknown_keys) before, so that no
/// mesh is built from a case that is refused anyway (studies::open_pbd_study does both).
PbdStudy load_pbd_study(const workbench::CaseFile& file, PbdCase setup);

/// Steps the model through the case's frames (seed steps 3-5 per frame, pbd::Solver::step) and
/// calls `frame(f)` at frame 0, every output_every-th frame and the last, after checking that
/// every position is finite (else a workbench::Error naming the case's keys); reports progress
/// on `log`. The one frame loop of `workbench pbd` and the Python module.
void step_frames(PbdStudy& study, pbd::Solver& solver, const std::function<void(int)>& frame, std::ostream& log);

/// Runs the frames and writes into `dir`: frames/frame_NNNNN.vtu and pbd.pvd, diagnostics.csv (per
/// written frame), nodes.csv (final state), summary.txt (substeps, final residuals against their
/// tolerances, and a warning when they exceed them, also on `log`), centreline.csv (for a single open chain of lines:
/// rest arc length, rest and final position, displacement; the input of a later comparison with
/// the FEM strip). With `animate`, also render/ (CSV frames, scripts/render_frames.py's input)
/// and animation.<mp4|gif>. Progress on `log`.
void write_pbd_outputs(PbdStudy& study, const std::filesystem::path& dir, bool animate, std::ostream& log);

/// The mesh at positions `x` as an output mesh.
workbench::OutputMesh output_mesh(const pbd::Mesh& mesh, const std::vector<pbd::Vec3>& x);

/// The nodes of a mesh made of line cells forming one open chain, in chain order starting at the
/// end given by `start_hint` (first pinned node) when it is an end, else at the lexicographically
/// smaller end; empty when the mesh is not such a chain.
std::vector<int> chain_order(const pbd::Mesh& mesh, const std::vector<int>& pinned);

/// The centreline of a rod mesh (one open chain of lines): its nodes in chain order from the
/// pinned end and their rest arc length s, with s = 0 at the clamp face (the last node of the
/// pinned run the chain starts with; negative inside the clamp, e.g. the ghost node), else at the
/// chain's first node. Empty when the mesh is not such a chain.
struct Centreline {
  std::vector<int> nodes;
  std::vector<double> s;
  bool empty() const { return nodes.empty(); }
};
Centreline centreline(const pbd::Mesh& mesh, const std::vector<int>& pinned);

/// Writes the generic animation frame format read by scripts/render_frames.py: `cells.csv`
/// ("type,nodes..." per cell, VTK type numbers) once, and `frame_NNNNN.csv` ("x,y,z,<field>").
void write_render_cells(const std::filesystem::path& dir, const workbench::OutputMesh& mesh);
void write_render_frame(const std::filesystem::path& file, const std::vector<double>& points, double time,
                        const std::string& field_name, const std::vector<double>& field);

/// Runs scripts/render_frames.py on `frames_dir` into `output` (ffmpeg); throws workbench::Error
/// when it fails. The script and python are found by workbench/child_process.h.
void render_animation(const std::filesystem::path& frames_dir, const std::filesystem::path& output, int fps,
                      const std::string& field, const std::string& title);

}  // namespace pbd_study
