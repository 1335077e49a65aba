#pragma once
// The deal.II linear-elastic FEM reference (docs/fem-reference.md): the problem and the solve, seen
// through plain data only. This header includes no deal.II and no case-file reader, so tests and
// programs that build a FemProblem themselves compile against it cheaply; the result alone is
// fem_reference/fem_result.h. The core (src/solve_fem.cc, then the deal.II code in problem/, mg/,
// amg/) knows no case file: reading a case file into a FemProblem and writing a study's CSV files is
// fem_reference/fem_case.h, the MPI runtime (start-up settings, ranks, collective steps)
// fem_reference/mpi.h.
//
//   fem_reference::FemProblem problem;
//   problem.box = fem_reference::Box{{0, 0, 0}, {1, 0.1, 0}, {40, 4, 0}};
//   problem.supports.push_back({"x0", fem_reference::SupportKind::Clamped, {}});
//   problem.tractions.push_back({"x1", {0, -1e3, 0}, {}});
//   auto result = fem_reference::solve_fem(problem);          // result.sigma_y[e]: element e in gmsh order
//
// Small-strain linear elasticity: 2D plane stress (per unit thickness, forces reported times the
// thickness) or plane strain, and 3D; Q1/Q2 on quadrilateral/hexahedral meshes (serial or MPI on a
// p4est mesh), P1/P2 on triangle/tetrahedron meshes (serial only). Units: SI (m, N, Pa).
// Every bad input raises a workbench::Error with a one-line message naming the file and the cause.
#include <fem_reference/fem_result.h>

#include <array>
#include <filesystem>
#include <functional>
#include <iosfwd>
#include <limits>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

namespace fem_reference {

enum class Model { PlaneStress, PlaneStrain };   ///< 2D only; 3D meshes are solved as solids
enum class SolverKind { Auto, Direct, Amg, Mg };  ///< Mg: matrix-free geometric multigrid (quads/hexes)
enum class LoadKind { Traction, Point };

/// The [fem] table of a case file (docs/case-file.md lists each key with unit and default).
struct FemOptions {
  int degree = 1;                       ///< polynomial degree 1 or 2
  Model model = Model::PlaneStress;
  SolverKind solver = SolverKind::Auto;
  long direct_limit = 2000;             ///< Auto: direct solver up to this many DoFs times the body's
                                        ///< slenderness (2D and 3D), else CG + multigrid (geometric on
                                        ///< refined quads/hexes and Q2, else ML AMG); a multigrid coarse
                                        ///< level is factorised up to 10 x this in 2D, up to this in 3D
                                        ///< (src/elasticity.h)
  double tolerance = 1e-10;             ///< CG: stop at ||K u - f|| <= tolerance * ||f||
  int max_iterations = 2000;
  int refine = 0;                       ///< global refinements of the gmsh mesh
  LoadKind load = LoadKind::Traction;   ///< how [[load]] acts: traction on the group or point force
  bool write_vtu = true;                ///< VTU/PVTU + PVD next to the CSV files
  /// Also the solution on the mesh one refinement coarser (FemResult::coarser), taken from the
  /// geometric multigrid's hierarchy: with refine = 1, the multigrid solver and supports that hold
  /// zero displacement (else FemResult::coarser stays empty and the caller solves that level itself).
  bool coarser_level = false;
  /// With coarser_level: the CG on the fine mesh, started from the coarser solution, also stops
  /// once its residual is this share of the one the coarser solution leaves there (0: tolerance
  /// only), i.e. when its algebraic error is small beside the discretisation error the levels show.
  double coarser_share = 0;
};

/// f(x, value): x has 3 entries (z = 0 in 2D), value has dim entries.
using VectorFunction = std::function<void(const double* x, double* value)>;
/// g(x, grad): grad[i * dim + j] = d u_i / d x_j.
using GradientFunction = std::function<void(const double* x, double* grad)>;

enum class SupportKind {
  Clamped,       ///< all displacement components zero (the rigid base)
  Roller,        ///< the normal component zero; the group must lie in a plane x_a = const
  Displacement,  ///< all components prescribed by `displacement`
};

struct Support {
  std::string group;
  SupportKind kind = SupportKind::Clamped;
  VectorFunction displacement;  ///< Displacement only [m]
};

/// A load on the faces of a group: either a total force spread uniformly over the group's area
/// (traction = force / area, area = length * thickness in 2D) or a traction field [Pa].
struct Traction {
  std::string group;
  std::array<double, 3> force{};  ///< total force [N] (used when `traction` is empty)
  VectorFunction traction;        ///< [Pa], per unit thickness in 2D
};

/// A force [N] at the mesh vertex nearest to `point` (or, when `group` is set, nearest to the
/// centre of that group's faces).
struct PointForce {
  std::array<double, 3> point{};
  std::array<double, 3> force{};
  std::string group;
};

/// A structured box mesh instead of a gmsh file (tests): cells[2] == 0 means 2D. Its faces form the
/// groups "x0", "x1", "y0", "y1" (and "z0", "z1"): the sides at the low/high end of each axis.
struct Box {
  std::array<double, 3> lo{}, hi{1, 1, 1};
  std::array<int, 3> cells{1, 1, 0};
};

/// A complete problem: what the case file describes, or what a test builds directly.
struct FemProblem {
  std::string name = "fem";                    ///< names the input in messages (the case file)
  std::filesystem::path mesh_file;             ///< gmsh .geo or .msh
  std::map<std::string, double> mesh_parameters;
  double mesh_unit = 1.0;                      ///< metres per unit of mesh_file's coordinates ([mesh] unit)
  std::optional<Box> box;                      ///< used instead of mesh_file when set
  double young = 206e9;                        ///< [Pa]
  double poisson = 0.3;
  double thickness = 1.0;                      ///< [m], 2D
  std::vector<Support> supports;
  std::vector<Traction> tractions;
  std::vector<PointForce> point_forces;
  std::array<double, 3> body_force{};          ///< [N/m^3]
  VectorFunction body_force_function;          ///< [N/m^3], added to body_force
  VectorFunction exact_displacement;           ///< if set, result.l2_error/h1_error are computed
  GradientFunction exact_gradient;
  FemOptions options;
  /// Points [m] (z = 0 in 2D) where solve_fem evaluates the solution itself (FemResult::probes),
  /// e.g. agent centres on a mesh of another shape (docs/compare.md, the true-geometry reference).
  std::vector<std::array<double, 3>> probe_points;
};

/// Solves; with `output_dir` non-empty and options.write_vtu, writes fem.pvd and fem_000.vtu
/// (fem_000.pvtu + pieces under MPI) there. Runs on MPI_COMM_WORLD when MPI is initialised with
/// more than one rank (initialises MPI itself if needed). Progress goes to `log` (rank 0 only).
FemResult solve_fem(const FemProblem& problem, const std::filesystem::path& output_dir = {},
                    std::ostream* log = nullptr);

/// What solve_fem checks before it solves (the mesh read, its groups and elements against the
/// problem, the memory), without solving: `--check`. Every rank, as solve_fem.
void check_fem_problem(const FemProblem& problem);

/// Why solve_fem would refuse `problem` for its memory estimate on this machine (the mesh read and
/// checked as solve_fem does, nothing solved), or "" when it fits: a reference asks it before it
/// refines further. Every rank finds the same.
std::string fem_memory_refusal(const FemProblem& problem);

}  // namespace fem_reference
