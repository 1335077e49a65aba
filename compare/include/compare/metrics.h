#pragma once
// Comparing two models on the same structured grid: sampling along lines, error norms and
// agent/FEM ratios with a mask where the reference is too small for a ratio to mean anything.
#include <agent/grid.h>

#include <Eigen/Core>

#include <string>
#include <vector>

namespace compare {

/// Value of component `comp` of a cell field (`comps` values per cell, grid order) at point `p`:
/// bilinear (trilinear in 3D) between cell centres, constant past the outer centres.
double sample_cells(const agent::Grid& grid, const std::vector<double>& values, int comps, int comp,
                    const Eigen::Vector3d& p);

/// Value of component `comp` of a node field (Grid::node_index order) at `p`: bilinear
/// (trilinear) in the cell that holds `p`, exact for a Q1 field.
double sample_nodes(const agent::Grid& grid, const std::vector<double>& values, int comps, int comp,
                    const Eigen::Vector3d& p);

/// A straight sample line through the body.
struct Line {
  std::string name;        ///< e.g. "vertical", "depth_0.25"
  std::string description; ///< for figure titles, e.g. "x = 100 mm, under the load"
  Eigen::Vector3d from, to;
  int samples = 0;
  Eigen::Vector3d point(int i) const { return from + (to - from) * (samples > 1 ? double(i) / (samples - 1) : 0.0); }
  double length() const { return (to - from).norm(); }
};

/// The vertical line under the load centre (top to bottom), and horizontal lines at the given
/// depths (fractions of the height below the top), through the load centre in 3D. One sample
/// per agent along each line, at agent centres.
std::vector<Line> standard_lines(const agent::Grid& grid, const Eigen::Vector3d& load_centre,
                                 const std::vector<double>& depths);

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
