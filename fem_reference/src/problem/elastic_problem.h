#pragma once
// The elastic problem (private header; deal.II types): small-strain linear elasticity in the style of
// deal.II's step-8 / step-18 / step-40, one class with make_grid / setup_system / assemble_system /
// solve / postprocess, dim-templated and instantiated for 2 and 3.
//
//   -div sigma(u) = b in the body,  sigma = lambda tr(eps) I + 2 mu eps,  eps = sym grad u,
//   u = 0 on clamped groups, u.n = 0 on rollers, u = g on displacement groups,
//   sigma n = t on traction groups, point forces at vertices.
// 2D plane stress uses lambda* = 2 lambda mu / (lambda + 2 mu) and is solved per unit thickness;
// forces (loads, reactions) are reported times the thickness.
//
// Meshes with quadrilaterals/hexahedra live on a parallel::distributed::Triangulation (p4est; a
// serial Triangulation on one rank), triangles/tetrahedra on a serial Triangulation with
// FE_SimplexP. Linear algebra: Trilinos (Epetra) matrices; CG with ML smoothed-aggregation AMG
// (amg/amg.h), or the direct solver (direct/direct_solver.h: CHOLMOD, KLU under MPI). On quadrilaterals/hexahedra, fem.solver = "mg"
// (and "auto" on refined meshes beyond a cheap direct solve) is CG with matrix-free geometric
// multigrid (mg/mg_solver.h): no global matrix is assembled.
//
// Two translation units: system.cc, from the mesh to the solution (grid, DoFs and constraints,
// assembly, the solvers), and elastic_problem.cc, run() and all that follows the solution
// (reactions, backward error, stresses, probes, errors, VTU) and solve_on_mesh.
#include "amg/amg.h"
#include "mg/mg_solver.h"
#include "plain_mesh.h"

#include <deal.II/base/conditional_ostream.h>
#include <deal.II/base/function.h>
#include <deal.II/base/index_set.h>
#include <deal.II/base/mpi.h>
#include <deal.II/base/quadrature.h>
#include <deal.II/base/timer.h>
#include <deal.II/base/utilities.h>
#include <deal.II/dofs/dof_handler.h>
#include <deal.II/fe/fe.h>
#include <deal.II/fe/fe_values.h>
#include <deal.II/fe/mapping.h>
#include <deal.II/grid/tria.h>
#include <deal.II/lac/affine_constraints.h>
#include <deal.II/lac/full_matrix.h>
#include <deal.II/lac/trilinos_sparse_matrix.h>
#include <deal.II/lac/trilinos_vector.h>
#include <deal.II/lac/vector.h>

#include <algorithm>
#include <array>
#include <cstdlib>
#include <filesystem>
#include <iostream>
#include <memory>
#include <ostream>
#include <string>
#include <utility>
#include <vector>

namespace fem_reference {

/// A point as the plain functions of fem.h take it: 3 coordinates, z = 0 in 2D.
template <int dim>
std::array<double, 3> plain_point(const dealii::Point<dim>& p) {
  return {p[0], p[1], dim == 3 ? p[dim - 1] : 0.0};
}

/// A plain vector function as a deal.II Function (values and, if given, gradients).
template <int dim>
class PlainFunction : public dealii::Function<dim> {
 public:
  PlainFunction(VectorFunction f, GradientFunction g = {})
      : dealii::Function<dim>(dim), f_(std::move(f)), g_(std::move(g)) {}
  double value(const dealii::Point<dim>& p, const unsigned int component) const override {
    double v[3] = {0, 0, 0};
    f_(plain_point(p).data(), v);
    return v[component];
  }
  void vector_value(const dealii::Point<dim>& p, dealii::Vector<double>& values) const override {
    double v[3] = {0, 0, 0};
    f_(plain_point(p).data(), v);
    for (int c = 0; c < dim; ++c) values[c] = v[c];
  }
  dealii::Tensor<1, dim> gradient(const dealii::Point<dim>& p, const unsigned int component) const override {
    double g[9] = {};
    g_(plain_point(p).data(), g);
    dealii::Tensor<1, dim> out;
    for (int j = 0; j < dim; ++j) out[j] = g[component * dim + j];
    return out;
  }

 private:
  VectorFunction f_;
  GradientFunction g_;
};

template <int dim>
class ElasticProblem {
 public:
  ElasticProblem(const FemProblem& problem, const PlainMesh& mesh, std::ostream* log);
  FemResult run(const std::filesystem::path& output_dir);

 private:
  // system.cc
  void make_grid();
  void choose_solver();  ///< direct_ and use_mg_ (the DoFs distributed)
  void sort_dofs_by_position();
  void setup_system();
  void check_rigid_motion() const;
  void assemble_system();
  void solve();
  /// Element matrix and load vector of one cell (body force and tractions).
  void cell_system(const typename dealii::DoFHandler<dim>::active_cell_iterator& cell, dealii::FEValues<dim>& fe_values,
                   dealii::FEFaceValues<dim>& fe_face_values, dealii::FullMatrix<double>& cell_matrix,
                   dealii::Vector<double>& cell_rhs, bool with_matrix = true);
  std::vector<int> constrained_components(const Support& s) const;

  // elastic_problem.cc
  void element_residual(dealii::TrilinosWrappers::MPI::Vector& residual, dealii::TrilinosWrappers::MPI::Vector* bound);
  /// Componentwise backward error of the solution (see the definition).
  double backward_error();
  void compute_reactions();
  void postprocess();
  /// The stress (xx yy zz xy yz xz) of a displacement gradient.
  void stress_of(const dealii::Tensor<2, dim>& g, double* s) const;
  /// FemResult::probes: the solution at FemProblem::probe_points.
  void evaluate_probes();
  void compute_errors();
  void write_vtu(const std::filesystem::path& dir);
  /// Throws (on every rank) unless `finite` holds on every rank: "<file>: <key>: <what> is not
  /// finite ...", the key being the one most likely responsible (material.young, or the load when
  /// it is itself beyond double precision's reach).
  void require_finite(bool finite, const std::string& what) const;

  /// The solver may be matrix-free geometric multigrid (decided in make_grid: p4est needs to know).
  bool may_use_mg() const {
    return !mesh_.simplex && degree_ <= 2 &&
           (problem_.options.solver == SolverKind::Mg || problem_.options.solver == SolverKind::Auto);
  }
  /// Whether faces with boundary id `id` belong to group `g` (index into groups_).
  bool carries(dealii::types::boundary_id id, int g) const {
    return id > 0 && id < groups_of_id_.size() &&
           std::count(groups_of_id_[id].begin(), groups_of_id_[id].end(), unsigned(g)) > 0;
  }
  /// Calls visit(cell, f, id) for each boundary face f, of boundary id `id`, of the locally owned
  /// active cells, in cell order (DoFs distributed).
  template <typename Visit>
  void for_each_boundary_face(const Visit& visit) const {
    for (const auto& cell : dof_handler_.active_cell_iterators()) {
      if (!cell->is_locally_owned() || !cell->at_boundary()) continue;
      for (unsigned f = 0; f < cell->n_faces(); ++f)
        if (cell->face(f)->at_boundary()) visit(cell, f, cell->face(f)->boundary_id());
    }
  }
  bool has_body_force() const {
    return problem_.body_force_function || problem_.body_force != std::array<double, 3>{};
  }
  void say(const std::string& line) { pcout_ << "fem: " << line << std::endl; }
  /// Wall seconds spent in a TimerOutput section of run().
  double seconds(const char* phase) const {
    return timer_.get_summary_data(dealii::TimerOutput::total_wall_time).at(phase);
  }

  MPI_Comm comm_ = MPI_COMM_WORLD;
  const FemProblem& problem_;
  const PlainMesh& mesh_;
  ModeFrame mode_frame_;  // where the rigid body modes are evaluated
  std::ostream* log_;
  std::ostream null_stream_{nullptr};  // pcout_'s target without a log (writes nothing)
  dealii::ConditionalOStream pcout_{log_ ? *log_ : null_stream_,
                                    log_ && dealii::Utilities::MPI::this_mpi_process(comm_) == 0};
  dealii::TimerOutput timer_{pcout_, dealii::TimerOutput::never, dealii::TimerOutput::wall_times};  // phases of run()
  // WORKBENCH_FEM_PROFILE: the finer phases inside them, deal.II's table of cpu and wall times on
  // stderr (rank 0) when the problem ends, and the resident memory after each phase (TimerOutput
  // measures no memory).
  const bool profiling_ = std::getenv("WORKBENCH_FEM_PROFILE") != nullptr;
  dealii::ConditionalOStream profile_out_{std::cerr, profiling_ && dealii::Utilities::MPI::this_mpi_process(comm_) == 0};
  dealii::TimerOutput profile_{profile_out_, profiling_ ? dealii::TimerOutput::summary : dealii::TimerOutput::never,
                               dealii::TimerOutput::cpu_and_wall_times};
  std::string phase_;  // profile_'s section in progress
  /// Ends the profiled phase in progress and starts `next` (nullptr: none).
  void phase(const char* next) {
    if (!phase_.empty()) {
      profile_.leave_subsection(phase_);
      dealii::Utilities::System::MemoryStats memory;
      if (profiling_) dealii::Utilities::System::get_memory_stats(memory);
      profile_out_ << "fem-profile: resident " << memory.VmRSS / 1024.0 << " MB after " << phase_ << std::endl;
    }
    phase_ = next ? next : "";
    if (!phase_.empty()) profile_.enter_subsection(phase_);
  }
  const int degree_;
  bool direct_ = false;  // the solver, decided in setup_system
  bool use_mg_ = false;  // matrix-free geometric multigrid: no global matrix
  double lambda_ = 0, mu_ = 0, lambda_solid_ = 0;  // lambda_ is lambda* in plane stress
  double thickness_ = 1;                          // 2D: force = thickness * per-unit-thickness force

  std::unique_ptr<dealii::Triangulation<dim>> tria_;
  std::unique_ptr<dealii::Mapping<dim>> mapping_;
  std::unique_ptr<dealii::FiniteElement<dim>> fe_;
  std::unique_ptr<dealii::Quadrature<dim>> quadrature_;
  std::unique_ptr<dealii::Quadrature<dim - 1>> face_quadrature_;
  dealii::DoFHandler<dim> dof_handler_;
  dealii::IndexSet owned_, relevant_;
  dealii::AffineConstraints<double> constraints_;
  dealii::TrilinosWrappers::SparseMatrix matrix_;
  dealii::TrilinosWrappers::MPI::Vector rhs_, solution_, ghosted_;
  // FemOptions::coarser_level: the coarse mesh's solution embedded in the fine space (empty when
  // not solved) and the multigrid's account of it.
  dealii::TrilinosWrappers::MPI::Vector coarser_;
  MgOutcome coarser_outcome_;
  /// FemResult::coarser: the post-processing of coarser_ (after the fine solution's own output).
  std::shared_ptr<FemResult> coarser_result();

  // Groups: name -> index; every boundary id stands for one set of group indices.
  std::vector<std::string> groups_;
  std::vector<std::vector<unsigned>> groups_of_id_;   // by boundary id
  std::vector<int> support_group_, traction_group_;   // group index of each support / traction
  std::vector<dealii::Tensor<1, dim>> uniform_traction_;  // per traction (when not a function)
  std::vector<std::pair<dealii::types::global_dof_index, double>> point_loads_;  // owned dofs, per unit thickness
  std::array<double, 3> applied_{};

  FemResult result_;
  std::vector<dealii::Vector<float>> cell_fields_;  // per active cell, for VTU
};

}  // namespace fem_reference
