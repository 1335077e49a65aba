#pragma once
// The PBD rod and the FEM strip it is compared with (`workbench compare` and `workbench front` for
// model = "pbd", docs/compare.md): the rod's centreline checked, the strip checked to be the rod's,
// and the FEM displacement sampled along it. Private to the compare library.
#include <fem_reference/fem_case.h>
#include <fem_reference/fem_result.h>
#include <pbd_study.h>
#include <workbench/case_file.h>

#include <array>
#include <string>
#include <vector>

namespace compare {

/// The FEM displacement (u_x, u_y) at points of the strip: linear in x along the row of mesh nodes
/// at the point's height, or between the two rows around it (a structured strip: rows of nodes at
/// constant y, e.g. tests/fem/meshes/strip.geo).
class RowSampler {
 public:
  RowSampler(const fem_reference::FemResult& fem, double tol);

  /// u_x, u_y at (x, y); throws workbench::Error outside the rows.
  std::array<double, 2> at(double x, double y) const;

 private:
  struct Node {
    double x, ux, uy;
  };
  struct Row {
    double y;
    std::vector<Node> nodes;
  };
  std::array<double, 2> along(const Row& row, double x) const;
  double tol_;
  std::vector<Row> rows_;
};

/// The PBD rod: a straight chain of line cells along +x, clamped at s = 0 (else bad input at
/// pbd.mesh).
struct Rod {
  pbd_study::Centreline line;
  double L = 0;              ///< its length beyond the clamp [m]
  pbd::Vec3 root_point;      ///< the node at s = 0 (after the ghost node inside the clamp)
};

Rod check_rod(const pbd_study::PbdStudy& study, const workbench::CaseTable& pbd_table);

/// The FEM strip's extent per axis (x, y: lo, hi) from the mesh it will be solved on, read before
/// either model runs (the box, or the mesh file loaded as the FEM loads it).
std::array<std::array<double, 2>, 2> strip_extent(const fem_reference::FemProblem& problem);

/// The FEM strip's height D from its extent, after checking that it is the rod's strip: x from the
/// clamp over L, the rod at mid-height. Before any solve: two bodies are an error, not a bad score.
double strip_height(const std::array<std::array<double, 2>, 2>& extent, const Rod& rod, const std::string& case_name);

/// The strip both models bend: Euler-Bernoulli's E I = E t D^3 / 12, q = body force * D * t,
/// P = end shear, and what the PBD case says about the same strip (its E I and transverse load).
struct Strip {
  double L = 0, D = 0, EI = 0, q = 0, P = 0, EI_pbd = 0, W_pbd = 0, W_fem = 0;
  /// Euler-Bernoulli's deflection at s.
  double eb(double s) const {
    return q * s * s * (6 * L * L - 4 * L * s + s * s) / (24 * EI) + P * s * s * (3 * L - s) / (6 * EI);
  }
};

/// The strip of `problem` (height D) and what the PBD case says about it.
Strip strip(const fem_reference::FemProblem& problem, const pbd_study::PbdStudy& study, const Rod& rod, double D);

}  // namespace compare
