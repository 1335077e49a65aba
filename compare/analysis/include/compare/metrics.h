#pragma once
// Comparing two models on the same structured grid: sampling along lines, error norms and
// agent/FEM ratios with a mask where the reference is too small for a ratio to mean anything.
#include <agent/grid.h>
#include <agent/mesh_import.h>
#include <workbench/load_spec.h>

#include <Eigen/Core>

#include <string>
#include <vector>

namespace compare {

/// Whether `p` lies in an agent (not in air, not outside the grid's box); a point on a face between
/// two slots belongs to the upper one.
bool in_body(const agent::Grid& grid, const Eigen::Vector3d& p);

/// Value of component `comp` of a cell field (`comps` values per cell, grid order) at point `p`:
/// bilinear (trilinear in 3D) between the centres of the agents around `p`, air slots left out and
/// the agents' weights renormalised (so a value never mixes in air), constant past the outer
/// centres; NaN when no agent is around `p` (it is not in the body).
double sample_cells(const agent::Grid& grid, const std::vector<double>& values, int comps, int comp,
                    const Eigen::Vector3d& p);

/// Value of component `comp` of a node field (Grid::node_index order) at `p`: bilinear
/// (trilinear) in the cell that holds `p`, exact for a Q1 field.
double sample_nodes(const agent::Grid& grid, const std::vector<double>& values, int comps, int comp,
                    const Eigen::Vector3d& p);

/// The grid nodes (Grid::node_index order) that are a corner of an agent: air has none.
std::vector<char> body_nodes(const agent::Grid& grid);

/// The ids of those nodes in the box's order (i fastest, then j, then k): node id order on a dense
/// grid, sorted by box coordinates on a tiled one (whose ids are not in box order). Files and
/// probe points list the body's nodes in this order, whatever the layout.
std::vector<std::size_t> body_node_ids(const agent::Grid& grid);

/// The agents' slot ids in the box's order, likewise: sums over the body (norms) add in the
/// same order on a dense and a tiled grid, so they give the same number bit for bit.
std::vector<std::size_t> agent_ids(const agent::Grid& grid);

/// A straight sample line through the body.
struct Line {
  std::string name;        ///< line_name(from, to): the same in every file and in the gate
  std::string description; ///< for figure titles, e.g. "load 1 (group load, -y): along the load"
  std::string kind;        ///< "along" a load, "across" a load, or "user" ([[compare.line]])
  Eigen::Vector3d from, to;
  int samples = 0;
  std::vector<Eigen::Vector3d> points;  ///< the samples' positions [m], `samples` of them
  std::vector<int> body_samples;  ///< the samples (0 .. samples-1) in the body: a line stops at air
  const Eigen::Vector3d& point(int i) const { return points[i]; }
  double length() const { return (to - from).norm(); }
};

/// The one name of the line from `from` to `to`: "line_" then each end as x<mm>y<mm>(z<mm>),
/// millimetres with up to 6 significant digits, '.' written 'p' and '-' written 'm' so that the
/// name is one word in metric names and CSV files (e.g. line_x100y199_x100y1).
std::string line_name(const Eigen::Vector3d& from, const Eigen::Vector3d& to, int dim);

/// A line from `from` to `to` with one sample per agent along its main axis (at least 2), named by
/// line_name; body_samples lists those in_body. On a compressed grid the samples are evenly spaced
/// in slots, not metres: one per agent, and one per collapsed air slot however wide it is.
Line make_line(const agent::Grid& grid, const Eigen::Vector3d& from, const Eigen::Vector3d& to,
               const std::string& description, const std::string& kind);

/// A load in its own frame: where its patch is and which way it pushes.
struct LoadFrame {
  Eigen::Vector3d centre;  ///< force-weighted centre of the loaded faces [m]
  int axis = 1;            ///< direction of the load: axis and sign
  /// The sign of the march into the body: the load's for a push (or a load along the face), the
  /// opposite for a pull (docs/agent-model.md, "Tension"): a pull's lines lie where its push's do.
  int sign = -1;
  std::string label;       ///< e.g. "load 1 (group load, -y)"
};

/// Each [[load]] of a study in its frame (the agent mesh's faces of its group, weighted by area).
std::vector<LoadFrame> load_frames(const agent::ImportedMesh& mesh, const std::vector<workbench::LoadSpec>& loads);

/// For each load: the line along its direction through its patch centre, from the first agent
/// centre to the last one across the body, and lines across it at `depths` (fractions of the
/// body's extent along the load, measured from the loaded face), along the first other axis
/// through the patch centre (3D: in the slice through the centre). Lines shared by two loads
/// (same ends) appear once.
std::vector<Line> load_lines(const agent::Grid& grid, const std::vector<LoadFrame>& loads,
                             const std::vector<double>& depths);

/// Cells (grid order) and grid nodes (Grid::node_index order) closer than `distance` [m] to a
/// loaded face: an agent's centre, a node's position, to the nearest point of any face of the
/// given groups. The far field is everything else.
struct NearLoad {
  std::vector<char> cells, nodes;
};
NearLoad near_load(const agent::ImportedMesh& mesh, const std::vector<workbench::LoadSpec>& loads, double distance);

/// Component `c` of an interleaved field with `comps` values per entry.
std::vector<double> component(const std::vector<double>& v, int comps, int c);

/// ||model - reference|| / ||reference|| in the 2-norm and the max-norm (0 when both are 0).
struct Errors {
  double rel_l2 = 0;
  double rel_max = 0;
};
Errors relative_errors(const std::vector<double>& model, const std::vector<double>& reference);

/// model / reference per entry, masked where |reference| < mask * max|reference|.
struct Ratios {
  std::vector<double> ratio;       ///< 0 where masked
  std::vector<unsigned char> masked;
  std::size_t masked_count = 0;
  double median = 0;               ///< over the unmasked entries
};
Ratios ratios(const std::vector<double>& model, const std::vector<double>& reference, double mask);

}  // namespace compare
