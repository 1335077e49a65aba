#pragma once
// The [compare] section of a case file, read and checked: what a comparison is asked to do. Part of
// the case schema (schema/every_section.h), so that checking a case needs no comparison code; the
// comparison (compare/reference.h) uses these types as compare::CompareOptions.
#include <workbench/case_file.h>

#include <Eigen/Core>

#include <array>
#include <filesystem>
#include <map>
#include <string>
#include <vector>

namespace schema {

/// [compare.reference]: FEM on the agents' geometry (or on `mesh`, the true geometry) with `refine`
/// global refinements of the gmsh mesh and polynomial `degree`. degree 1, refine 0 is FEM Q1 on the
/// agents' own mesh.
struct ReferenceOptions {
  static constexpr int kMaxRefine = 4;  ///< the most refinements a reference takes (the key's range)
  int degree = 2;
  /// -1 (the default): 1 in 2D; in 3D (a refinement costs 8 times more) Q2 starts at 0 and is
  /// refined until its own error is under `tolerance` (`converges`), Q1 stays at 0
  int refine = -1;
  /// The true (smooth) geometry the agents' staircase was voxelized from (.geo or .msh with the same
  /// physical groups); empty: the agents' own mesh.
  std::filesystem::path mesh;
  /// Where the estimate level comes from the reference's multigrid hierarchy (refine = 1): the
  /// reference's CG, started from the estimate level's solution, stops once its residual is this
  /// share of the one that solution leaves on the reference's mesh (or at fem.tolerance, if that
  /// is higher): an algebraic error this small beside the discretisation error the two levels
  /// show (docs/compare.md). 0: fem.tolerance alone.
  double algebraic_share = 1e-7;
  /// The converging default: the largest own error (body, relative L2, the reference's dominant
  /// stress component) it is refined down to, while the next level's memory estimate fits.
  double tolerance = 0.03;
  /// Resolved: refine from `refine` on until the own error is under `tolerance` (the 3D Q2 default).
  bool converges = false;
  /// These options with the default refinement resolved for a `dim`-dimensional mesh.
  ReferenceOptions resolved(int dim) const {
    ReferenceOptions r = *this;
    r.converges = refine < 0 && dim == 3 && degree == 2;
    r.refine = refine >= 0 ? refine : dim == 2 ? 1 : 0;
    return r;
  }
  /// These options at `level` refinements (nothing else changed).
  ReferenceOptions at(int level) const {
    ReferenceOptions r = *this;
    r.refine = level;
    return r;
  }
  /// The level beside the reference for its error estimate: one refinement coarser; on the
  /// unrefined mesh Q1 for Q2, and for Q1 itself one refinement finer.
  ReferenceOptions estimate() const {
    ReferenceOptions r = *this;
    r.converges = false;
    if (refine > 0) r.refine = refine - 1;
    else if (degree == 2) r.degree = 1;
    else r.refine = 1;
    return r;
  }
  std::string describe() const;  ///< e.g. "FEM Q2, the agents' mesh refined 1 time"
};

/// The [compare] table of a case file.
struct CompareOptions {
  std::string model = "agent";                  ///< the fast model: "agent" or "pbd"
  std::vector<double> depths{0.25, 0.5, 0.75};  ///< agent: lines across each load, fractions of the body along it
  double mask = 0.01;                           ///< agent: ratio masked where |FEM| < mask * max |FEM|
  ReferenceOptions reference;                   ///< agent: [compare.reference]
  /// agent: the far field leaves out cells closer than this to a loaded face [m]; 0: 5 agent sizes
  double far_distance = 0;
  /// agent: the warning when the agent model carries less than this share of the load to a rigid face
  double min_reaction_share = 0.9;
  std::vector<std::array<Eigen::Vector3d, 2>> lines;  ///< agent: [[compare.line]] from, to [m]
  std::map<std::string, double> gate;           ///< metric name -> largest value allowed
  /// agent: fields ("far.sigma_x") whose relative L2 error must be below the zero model's (1): the
  /// gate fails, naming the field, where the model does not beat predicting nothing
  std::vector<std::string> better_than_zero;
  bool figures = true;                          ///< Figures 8-11 and the animation (Python)
  /// The figures' files: "png" (quick to draw and view), "pdf" (vector, for print; about 1 s more
  /// CPU on the seed plate, docs/performance.md).
  std::vector<std::string> figure_formats{"png"};
};

/// Reads [compare]: model, then the keys that model uses (depths, mask, reference, far field and
/// lines for the agent model only), figures, gate.
CompareOptions read_compare_options(const workbench::CaseTable& root);

}  // namespace schema
