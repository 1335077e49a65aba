// The deal.II part of the FEM reference: small-strain linear elasticity (step-8 / step-18 / step-40
// style), one problem class with make_grid / setup_system / assemble_system / solve / postprocess,
// dim-templated and instantiated for 2 and 3 in this one translation unit.
//
//   -div sigma(u) = b in the body,  sigma = lambda tr(eps) I + 2 mu eps,  eps = sym grad u,
//   u = 0 on clamped groups, u.n = 0 on rollers, u = g on displacement groups,
//   sigma n = t on traction groups, point forces at vertices.
// 2D plane stress uses lambda* = 2 lambda mu / (lambda + 2 mu) and is solved per unit thickness;
// forces (loads, reactions) are reported times the thickness.
//
// Meshes with quadrilaterals/hexahedra live on a parallel::distributed::Triangulation (p4est, also on
// one rank), triangles/tetrahedra on a serial Triangulation with FE_SimplexP. Linear algebra:
// Trilinos (Epetra) matrices; CG with ML smoothed-aggregation AMG given the rigid body modes as
// near-null space, or Amesos KLU as the direct solver. On quadrilaterals/hexahedra, fem.solver = "mg"
// (and "auto" on refined meshes beyond a cheap direct solve) is CG with matrix-free geometric
// multigrid (mg_solver.cc): no global matrix is assembled.
#include "mg_solver.h"
#include "plain_mesh.h"

#include <workbench/error.h>
#include <workbench/vtk_output.h>

#include <deal.II/base/conditional_ostream.h>
#include <deal.II/base/exceptions.h>
#include <deal.II/base/function.h>
#include <deal.II/base/index_set.h>
#include <deal.II/base/mpi.h>
#include <deal.II/base/multithread_info.h>
#include <deal.II/base/quadrature_lib.h>
#include <deal.II/base/timer.h>
#include <deal.II/base/utilities.h>
#include <deal.II/distributed/tria.h>
#include <deal.II/dofs/dof_handler.h>
#include <deal.II/dofs/dof_tools.h>
#include <deal.II/fe/fe_q.h>
#include <deal.II/fe/fe_simplex_p.h>
#include <deal.II/fe/fe_system.h>
#include <deal.II/fe/fe_values.h>
#include <deal.II/fe/mapping_fe.h>
#include <deal.II/fe/mapping_q.h>
#include <deal.II/grid/grid_tools.h>
#include <deal.II/grid/grid_tools_cache.h>
#include <deal.II/grid/tria.h>
#include <deal.II/lac/affine_constraints.h>
#include <deal.II/lac/dynamic_sparsity_pattern.h>
#include <deal.II/lac/full_matrix.h>
#include <deal.II/lac/solver_cg.h>
#include <deal.II/lac/solver_control.h>
#include <deal.II/lac/sparsity_tools.h>
#include <deal.II/lac/trilinos_precondition.h>
#include <deal.II/lac/trilinos_solver.h>
#include <deal.II/lac/trilinos_sparse_matrix.h>
#include <deal.II/lac/trilinos_vector.h>
#include <deal.II/lac/vector.h>
#include <deal.II/numerics/vector_tools.h>

#include <Eigen/Eigenvalues>
#include <p4est_base.h>
#include <sc.h>

#include <sys/resource.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <cmath>
#include <fstream>
#include <map>
#include <memory>
#include <ostream>
#include <set>
#include <sstream>

namespace fem_reference {

namespace fs = std::filesystem;
using namespace dealii;
using workbench::Error;

// ------------------------------------------------------------------------------------------------
// MPI
// ------------------------------------------------------------------------------------------------

namespace {

bool mpi_running() {
  int init = 0, fin = 0;
  MPI_Initialized(&init);
  MPI_Finalized(&fin);
  return init && !fin;
}

/// MPI (and p4est's sc library) initialised once per process unless the program did it, finalised
/// at exit. Not through a static Utilities::MPI::MPI_InitFinalize: its destructor would release
/// deal.II's vector pools after they were destroyed (they are statics created later).
void finalize_mpi() {
  int fin = 0;
  MPI_Finalized(&fin);
  if (!fin) MPI_Finalize();
}

void ensure_mpi() {
  deal_II_exceptions::disable_abort_on_exception();
  deal_II_exceptions::suppress_stacktrace_in_exceptions();
  int init = 0;
  MPI_Initialized(&init);
  if (init) return;
  int provided = 0;
  MPI_Init_thread(nullptr, nullptr, MPI_THREAD_SERIALIZED, &provided);
  sc_init(MPI_COMM_WORLD, 0, 0, nullptr, SC_LP_SILENT);
  p4est_init(nullptr, SC_LP_SILENT);
  MultithreadInfo::set_thread_limit(1);
  std::atexit(finalize_mpi);
}



/// One line out of a deal.II exception: its "Additional information", else its name.
std::string one_line(const ExceptionBase& e) {
  std::string text = e.what();
  const std::string marker = "Additional information:";
  auto pos = text.find(marker);
  text = pos == std::string::npos ? e.get_exc_name() : text.substr(pos + marker.size());
  std::string out;
  bool space = false;
  for (char c : text) {
    if (std::isspace(static_cast<unsigned char>(c))) {
      space = !out.empty();
    } else {
      if (space) out += ' ';
      out += c;
      space = false;
    }
  }
  return out;
}

/// A plain vector function as a deal.II Function (values and, if given, gradients).
template <int dim>
class PlainFunction : public Function<dim> {
 public:
  PlainFunction(VectorFunction f, GradientFunction g = {}) : Function<dim>(dim), f_(std::move(f)), g_(std::move(g)) {}
  double value(const Point<dim>& p, const unsigned int component) const override {
    double x[3] = {p[0], p[1], dim == 3 ? p[dim - 1] : 0.0}, v[3] = {0, 0, 0};
    f_(x, v);
    return v[component];
  }
  void vector_value(const Point<dim>& p, Vector<double>& values) const override {
    double x[3] = {p[0], p[1], dim == 3 ? p[dim - 1] : 0.0}, v[3] = {0, 0, 0};
    f_(x, v);
    for (int c = 0; c < dim; ++c) values[c] = v[c];
  }
  Tensor<1, dim> gradient(const Point<dim>& p, const unsigned int component) const override {
    double x[3] = {p[0], p[1], dim == 3 ? p[dim - 1] : 0.0}, g[9] = {};
    g_(x, g);
    Tensor<1, dim> out;
    for (int j = 0; j < dim; ++j) out[j] = g[component * dim + j];
    return out;
  }

 private:
  VectorFunction f_;
  GradientFunction g_;
};

const char* kind_name(SupportKind k) {
  return k == SupportKind::Clamped ? "clamped" : k == SupportKind::Roller ? "roller" : "displacement";
}

}  // namespace

void configure_singleton_mpi() {
  for (const char* launcher : {"OMPI_COMM_WORLD_SIZE", "PMIX_RANK", "PMI_RANK", "SLURM_PROCID"})
    if (std::getenv(launcher)) return;  // started by mpirun or srun: their settings stand
  // Measured with MPI_Init_thread alone (docs/performance.md): 0.26 s as configured by Debian,
  // 0.08 s with ob1, 0.06 s without UCX's one-sided component too, 0.02 s without orted.
  ::setenv("OMPI_MCA_pml", "ob1", 0);
  ::setenv("OMPI_MCA_osc", "^ucx", 0);
  ::setenv("OMPI_MCA_ess_singleton_isolated", "1", 0);
}

int mpi_rank() {
  ensure_mpi();
  return mpi_running() ? int(Utilities::MPI::this_mpi_process(MPI_COMM_WORLD)) : 0;
}
int mpi_size() {
  ensure_mpi();
  return mpi_running() ? int(Utilities::MPI::n_mpi_processes(MPI_COMM_WORLD)) : 1;
}
void mpi_barrier() {
  ensure_mpi();
  if (mpi_running()) MPI_Barrier(MPI_COMM_WORLD);
}
std::string mpi_broadcast(const std::string& text) {
  if (mpi_size() == 1) return text;
  return Utilities::MPI::broadcast(MPI_COMM_WORLD, text, 0);
}
void mpi_collective(const std::function<void()>& step) {
  std::string message;
  bool failed = false;
  try {
    step();
  } catch (const std::exception& e) {
    message = e.what();
    failed = true;
  }
  if (mpi_size() > 1) {
    // The lowest failing rank (size if none) tells every rank its message.
    const unsigned size = unsigned(mpi_size());
    const unsigned first = Utilities::MPI::min(failed ? unsigned(mpi_rank()) : size, MPI_COMM_WORLD);
    if (first == size) return;
    message = Utilities::MPI::broadcast(MPI_COMM_WORLD, message, first);
    failed = true;
  }
  if (failed) throw Error(message);
}

// ------------------------------------------------------------------------------------------------
// The problem
// ------------------------------------------------------------------------------------------------

namespace {

/// The largest backward error a solution may have (see ElasticProblem::backward_error): a
/// backward-stable solve leaves about 1e-16, CG stopped on its recursive residual somewhat more.
constexpr double kBackwardErrorLimit = 1e-12;

std::string no_convergence(const FemProblem& problem, const char* preconditioner,
                           const SolverControl::NoConvergence& e) {
  std::ostringstream s;
  s << problem.name << ": CG with " << preconditioner << " did not reach the relative residual "
    << problem.options.tolerance << " in " << e.last_step << " iterations (residual " << e.last_residual
    << "); raise fem.max_iterations or use fem.solver = \"direct\"";
  return s.str();
}

template <int dim>
class ElasticProblem {
 public:
  ElasticProblem(const FemProblem& problem, const PlainMesh& mesh, std::ostream* log);
  FemResult run(const fs::path& output_dir);

 private:
  void make_grid();
  void setup_system();
  void check_rigid_motion() const;
  /// A point in the frame of the rigid body modes (x has 3 entries, 0 beyond dim).
  void to_mode_frame(const Point<dim>& p, double* x) const;
  void assemble_system();
  void solve();
  void element_residual(TrilinosWrappers::MPI::Vector& residual, TrilinosWrappers::MPI::Vector* bound);
  /// Componentwise backward error of the solution (see the definition).
  double backward_error();
  void compute_reactions();
  void postprocess();
  /// The stress (xx yy zz xy yz xz) of a displacement gradient.
  void stress_of(const Tensor<2, dim>& g, double* s) const;
  /// FemResult::probes: the solution at FemProblem::probe_points.
  void evaluate_probes();
  void compute_errors();
  void write_vtu(const fs::path& dir);

  /// Element matrix and load vector of one cell (body force and tractions).
  void cell_system(const typename DoFHandler<dim>::active_cell_iterator& cell, FEValues<dim>& fe_values,
                   FEFaceValues<dim>& fe_face_values, FullMatrix<double>& cell_matrix, Vector<double>& cell_rhs,
                   bool with_matrix = true);
  /// The solver may be matrix-free geometric multigrid (decided in make_grid: p4est needs to know).
  bool may_use_mg() const {
    return !mesh_.simplex && degree_ <= 2 &&
           (problem_.options.solver == SolverKind::Mg || problem_.options.solver == SolverKind::Auto);
  }
  std::vector<int> constrained_components(const Support& s) const;
  /// Whether faces with boundary id `id` belong to group `g` (index into groups_).
  bool carries(types::boundary_id id, int g) const {
    return id > 0 && id < groups_of_id_.size() &&
           std::count(groups_of_id_[id].begin(), groups_of_id_[id].end(), unsigned(g)) > 0;
  }
  bool has_body_force() const {
    return problem_.body_force_function || problem_.body_force != std::array<double, 3>{};
  }
  /// Throws (on every rank) unless `finite` holds on every rank: "<file>: <key>: <what> is not
  /// finite ...", the key being the one most likely responsible (material.young, or the load when
  /// it is itself beyond double precision's reach).
  void require_finite(bool finite, const std::string& what) const;
  void say(const std::string& line) { pcout_ << "fem: " << line << std::endl; }
  /// Wall seconds spent in a TimerOutput section of run().
  double seconds(const char* phase) const { return timer_.get_summary_data(TimerOutput::total_wall_time).at(phase); }

  MPI_Comm comm_ = MPI_COMM_WORLD;
  const FemProblem& problem_;
  const PlainMesh& mesh_;
  // The rigid body modes are evaluated centred on the mesh and scaled by its size (well conditioned).
  std::array<double, 3> mode_centre_{};
  double mode_size_ = 1;
  std::ostream* log_;
  std::ostream null_stream_{nullptr};  // pcout_'s target without a log (writes nothing)
  ConditionalOStream pcout_{log_ ? *log_ : null_stream_, log_ && Utilities::MPI::this_mpi_process(comm_) == 0};
  TimerOutput timer_{pcout_, TimerOutput::never, TimerOutput::wall_times};  // phases of run()
  // WORKBENCH_FEM_PROFILE: the finer phases inside them, deal.II's table of cpu and wall times on
  // stderr (rank 0) when the problem ends, and the resident memory after each phase (TimerOutput
  // measures no memory).
  const bool profiling_ = std::getenv("WORKBENCH_FEM_PROFILE") != nullptr;
  ConditionalOStream profile_out_{std::cerr, profiling_ && Utilities::MPI::this_mpi_process(comm_) == 0};
  TimerOutput profile_{profile_out_, profiling_ ? TimerOutput::summary : TimerOutput::never, TimerOutput::cpu_and_wall_times};
  std::string phase_;  // profile_'s section in progress
  /// Ends the profiled phase in progress and starts `next` (nullptr: none).
  void phase(const char* next) {
    if (!phase_.empty()) {
      profile_.leave_subsection(phase_);
      Utilities::System::MemoryStats memory;
      if (profiling_) Utilities::System::get_memory_stats(memory);
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

  std::unique_ptr<Triangulation<dim>> tria_;
  std::unique_ptr<Mapping<dim>> mapping_;
  std::unique_ptr<FiniteElement<dim>> fe_;
  std::unique_ptr<Quadrature<dim>> quadrature_;
  std::unique_ptr<Quadrature<dim - 1>> face_quadrature_;
  DoFHandler<dim> dof_handler_;
  IndexSet owned_, relevant_;
  AffineConstraints<double> constraints_;
  TrilinosWrappers::SparseMatrix matrix_;
  TrilinosWrappers::MPI::Vector rhs_, solution_, ghosted_;

  // Groups: name -> index; every boundary id stands for one set of group indices.
  std::vector<std::string> groups_;
  std::vector<std::vector<unsigned>> groups_of_id_;   // by boundary id
  std::vector<int> support_group_, traction_group_;   // group index of each support / traction
  std::vector<Tensor<1, dim>> uniform_traction_;      // per traction (when not a function)
  std::vector<std::pair<types::global_dof_index, double>> point_loads_;  // owned dofs, per unit thickness
  std::array<double, 3> applied_{};

  FemResult result_;
  std::vector<Vector<float>> cell_fields_;  // per active cell, for VTU
};

template <int dim>
ElasticProblem<dim>::ElasticProblem(const FemProblem& problem, const PlainMesh& mesh, std::ostream* log)
    : problem_(problem), mesh_(mesh), log_(log), degree_(problem.options.degree) {
  const double E = problem.young, nu = problem.poisson;
  mu_ = E / (2 * (1 + nu));
  lambda_solid_ = E * nu / ((1 + nu) * (1 - 2 * nu));
  lambda_ = lambda_solid_;
  if (dim == 2) {
    thickness_ = problem.thickness;
    if (problem.options.model == Model::PlaneStress) lambda_ = 2 * lambda_solid_ * mu_ / (lambda_solid_ + 2 * mu_);
  }
  std::array<double, 3> lo{1e308, 1e308, 1e308}, hi{-1e308, -1e308, -1e308};
  for (std::size_t i = 0; i < mesh_.node_count(); ++i)
    for (int a = 0; a < 3; ++a) {
      lo[a] = std::min(lo[a], mesh_.nodes[3 * i + a]);
      hi[a] = std::max(hi[a], mesh_.nodes[3 * i + a]);
    }
  mode_size_ = 0;
  for (int a = 0; a < dim; ++a) {
    mode_centre_[a] = 0.5 * (lo[a] + hi[a]);
    mode_size_ = std::max(mode_size_, hi[a] - lo[a]);
  }
}

bool all_finite(const TrilinosWrappers::MPI::Vector& v) {
  for (const double x : v) if (!std::isfinite(x)) return false;
  return true;
}

template <class Container>
bool all_finite(const Container& v) {
  return std::all_of(v.begin(), v.end(), [](double x) { return std::isfinite(x); });
}

template <int dim>
void ElasticProblem<dim>::require_finite(bool finite, const std::string& what) const {
  if (Utilities::MPI::min(int(finite), comm_) == 1) return;
  double load = 0;
  for (const auto& t : problem_.tractions)
    for (double f : t.force) load = std::max(load, std::abs(f));
  for (const auto& p : problem_.point_forces)
    for (double f : p.force) load = std::max(load, std::abs(f));
  double body = 0;
  for (double b : problem_.body_force) body = std::max(body, std::abs(b));
  // Loads beyond 1e150 overflow on their own; else the stiffness (young) is out of range.
  const std::string key = !(body <= 1e150) ? "fem.body_force" : !(load <= 1e150) ? "load" : "material.young";
  std::ostringstream s;
  s << problem_.name << ": " << key << ": the " << what
    << " is not finite (it overflows double precision) with material.young = " << problem_.young
    << " Pa and loads up to " << std::max(load, body) << " (N, N/m^3); give values in SI units (Pa, N) within a sane range";
  throw Error(s.str());
}

template <int dim>
void ElasticProblem<dim>::to_mode_frame(const Point<dim>& p, double* x) const {
  x[0] = x[1] = x[2] = 0;
  for (int a = 0; a < dim; ++a) x[a] = (p[a] - mode_centre_[a]) / mode_size_;
}

template <int dim>
void ElasticProblem<dim>::make_grid() {
  std::vector<Point<dim>> vertices(mesh_.node_count());
  for (std::size_t i = 0; i < vertices.size(); ++i)
    for (int a = 0; a < dim; ++a) vertices[i][a] = mesh_.nodes[3 * i + a];
  std::vector<CellData<dim>> cells(mesh_.cell_count(), CellData<dim>(mesh_.corners));
  for (std::size_t c = 0; c < cells.size(); ++c)
    for (int k = 0; k < mesh_.corners; ++k) cells[c].vertices[k] = mesh_.cells[c * mesh_.corners + k];
  if (mesh_.simplex) {
    tria_ = std::make_unique<Triangulation<dim>>();
    mapping_ = std::make_unique<MappingFE<dim>>(FE_SimplexP<dim>(1));
    fe_ = std::make_unique<FESystem<dim>>(FE_SimplexP<dim>(degree_), dim);
    quadrature_ = std::make_unique<QGaussSimplex<dim>>(degree_ + 1);
    face_quadrature_ = std::make_unique<QGaussSimplex<dim - 1>>(degree_ + 1);
  } else {
    GridTools::invert_all_negative_measure_cells(vertices, cells);
    GridTools::consistently_order_cells(cells);
    if (Utilities::MPI::n_mpi_processes(comm_) > 1)
      tria_ = std::make_unique<parallel::distributed::Triangulation<dim>>(
          comm_, Triangulation<dim>::none,
          may_use_mg() ? parallel::distributed::Triangulation<dim>::construct_multigrid_hierarchy
                       : parallel::distributed::Triangulation<dim>::default_setting);
    else  // one rank: the serial triangulation refines faster and needs less memory than p4est's
      tria_ = std::make_unique<Triangulation<dim>>();
    mapping_ = std::make_unique<MappingQ<dim>>(1);
    fe_ = std::make_unique<FESystem<dim>>(FE_Q<dim>(degree_), dim);
    quadrature_ = std::make_unique<QGauss<dim>>(degree_ + 1);
    face_quadrature_ = std::make_unique<QGauss<dim - 1>>(degree_ + 1);
  }
  phase("create triangulation");
  // The coarse cells keep the order of `cells` (gmsh element order) and the vertices their indices.
  tria_->create_triangulation(vertices, cells, SubCellData());
  phase("boundary ids");

  // Boundary ids: one per distinct set of named groups a face belongs to (0: none).
  auto group_index = [&](const std::string& name) {
    auto it = std::find(groups_.begin(), groups_.end(), name);
    if (it != groups_.end()) return int(it - groups_.begin());
    groups_.push_back(name);
    return int(groups_.size() - 1);
  };
  for (const auto& s : problem_.supports) support_group_.push_back(group_index(s.group));
  for (const auto& t : problem_.tractions) traction_group_.push_back(group_index(t.group));
  std::map<std::vector<unsigned>, std::set<unsigned>> groups_of_face;
  for (unsigned g = 0; g < groups_.size(); ++g)
    for (auto face : mesh_.face_groups.at(groups_[g])) {
      std::sort(face.begin(), face.end());
      groups_of_face[face].insert(g);
    }
  std::map<std::set<unsigned>, types::boundary_id> id_of_set;
  groups_of_id_.assign(1, {});
  std::vector<std::size_t> matched(groups_.size(), 0);
  for (const auto& cell : tria_->cell_iterators_on_level(0))
    for (unsigned f = 0; f < cell->n_faces(); ++f) {
      if (!cell->face(f)->at_boundary()) continue;
      std::vector<unsigned> key;
      for (unsigned v = 0; v < cell->face(f)->n_vertices(); ++v) key.push_back(cell->face(f)->vertex_index(v));
      std::sort(key.begin(), key.end());
      auto it = groups_of_face.find(key);
      types::boundary_id id = 0;
      if (it != groups_of_face.end()) {
        auto [pos, inserted] = id_of_set.emplace(it->second, types::boundary_id(groups_of_id_.size()));
        if (inserted) groups_of_id_.emplace_back(it->second.begin(), it->second.end());
        id = pos->second;
        for (unsigned g : it->second) ++matched[g];
      }
      cell->face(f)->set_boundary_id(id);
    }
  for (unsigned g = 0; g < groups_.size(); ++g)
    if (matched[g] != mesh_.face_groups.at(groups_[g]).size())
      throw Error(problem_.name + ": group '" + groups_[g] + "' of " + mesh_.source + " has " +
                  std::to_string(mesh_.face_groups.at(groups_[g]).size() - matched[g]) +
                  " faces inside the body; supports and loads act on outer faces only");
  phase("refine");
  if (problem_.options.refine > 0) tria_->refine_global(problem_.options.refine);
  phase(nullptr);
}

template <int dim>
std::vector<int> ElasticProblem<dim>::constrained_components(const Support& s) const {
  if (s.kind == SupportKind::Roller) return {normal_axis(mesh_, s.group)};
  std::vector<int> all(dim);
  for (int c = 0; c < dim; ++c) all[c] = c;
  return all;
}

template <int dim>
void ElasticProblem<dim>::setup_system() {
  phase("distribute dofs");
  dof_handler_.reinit(*tria_);
  dof_handler_.distribute_dofs(*fe_);
  owned_ = dof_handler_.locally_owned_dofs();
  DoFTools::extract_locally_relevant_dofs(dof_handler_, relevant_);
  phase("constraints");

  constraints_.clear();
  constraints_.reinit(relevant_);
  DoFTools::make_hanging_node_constraints(dof_handler_, constraints_);
  for (std::size_t s = 0; s < problem_.supports.size(); ++s) {
    const Support& support = problem_.supports[s];
    ComponentMask mask(dim, false);
    for (int c : constrained_components(support)) mask.set(c, true);
    std::unique_ptr<Function<dim>> g;
    if (support.kind == SupportKind::Displacement)
      g = std::make_unique<PlainFunction<dim>>(support.displacement);
    else
      g = std::make_unique<Functions::ZeroFunction<dim>>(dim);
    for (types::boundary_id id = 1; id < groups_of_id_.size(); ++id)
      if (carries(id, support_group_[s]))
        VectorTools::interpolate_boundary_values(*mapping_, dof_handler_, id, *g, constraints_, mask);
  }
  constraints_.close();
  phase(nullptr);

  const auto& o = problem_.options;
  // auto: direct where the factorisation is cheap (direct_is_fast: 2D and 3D fill differently);
  // else multigrid on refined meshes (its coarse level by KLU or, when large, one ML cycle: in 3D
  // 4x faster than ML on the whole problem, the solver sweep), else ML (on an unrefined mesh
  // multigrid would have a single level).
  direct_ = o.solver == SolverKind::Direct ||
            (o.solver == SolverKind::Auto && direct_is_fast(double(dof_handler_.n_dofs()), dim, o.direct_limit));
  use_mg_ = may_use_mg() && (o.solver == SolverKind::Mg || (o.solver == SolverKind::Auto && !direct_ && o.refine > 0));
  rhs_.reinit(owned_, comm_);
  solution_.reinit(owned_, comm_);
  ghosted_.reinit(owned_, relevant_, comm_);
  if (use_mg_) return;  // matrix-free: no sparsity pattern, no matrix
  phase("sparsity pattern");
  DynamicSparsityPattern dsp(relevant_);
  DoFTools::make_sparsity_pattern(dof_handler_, dsp, constraints_, false);
  SparsityTools::distribute_sparsity_pattern(dsp, owned_, comm_, relevant_);
  phase("matrix reinit");
  matrix_.reinit(owned_, owned_, dsp, comm_);
  phase(nullptr);
}

/// The supports must hold every rigid body motion: translations and rotations, evaluated at the
/// vertices of the supported faces, must not vanish on all constrained components together.
template <int dim>
void ElasticProblem<dim>::check_rigid_motion() const {
  const int n_modes = dim == 2 ? 3 : 6;
  std::vector<double> gram(n_modes * n_modes, 0.0);
  for (const auto& cell : tria_->active_cell_iterators()) {
    if (!cell->is_locally_owned() || !cell->at_boundary()) continue;
    for (unsigned f = 0; f < cell->n_faces(); ++f) {
      if (!cell->face(f)->at_boundary()) continue;
      const auto id = cell->face(f)->boundary_id();
      for (std::size_t s = 0; s < problem_.supports.size(); ++s) {
        if (!carries(id, support_group_[s])) continue;
        for (unsigned v = 0; v < cell->face(f)->n_vertices(); ++v) {
          double x[3];
          to_mode_frame(cell->face(f)->vertex(v), x);
          for (int c : constrained_components(problem_.supports[s])) {
            std::vector<double> row(n_modes, 0.0);
            set_rigid_body_modes(dim, x, unsigned(c), 0, 1, row);
            for (int i = 0; i < n_modes; ++i)
              for (int j = 0; j < n_modes; ++j) gram[i * n_modes + j] += row[i] * row[j];
          }
        }
      }
    }
  }
  Utilities::MPI::sum(gram, comm_, gram);
  const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eigen(Eigen::Map<const Eigen::MatrixXd>(gram.data(), n_modes, n_modes));
  const Eigen::VectorXd& values = eigen.eigenvalues();
  const Eigen::MatrixXd& vectors = eigen.eigenvectors();
  const double top = std::max(values.maxCoeff(), 0.0);
  const char* names2[3] = {"translation along x", "translation along y", "rotation about z"};
  const char* names3[6] = {"translation along x", "translation along y", "translation along z",
                           "rotation about x",    "rotation about y",    "rotation about z"};
  for (int k = 0; k < n_modes; ++k)
    if (!(values[k] > 1e-10 * top) || top == 0) {
      int dominant = 0;
      for (int i = 0; i < n_modes; ++i)
        if (std::abs(vectors(i, k)) > std::abs(vectors(dominant, k))) dominant = i;
      throw Error(problem_.name + ": the supports leave the body free to move rigidly (" +
                  (dim == 2 ? names2[dominant] : names3[dominant]) +
                  "): no unique solution; add a rigid group or rollers that hold it");
    }
}

template <int dim>
void ElasticProblem<dim>::cell_system(const typename DoFHandler<dim>::active_cell_iterator& cell,
                                      FEValues<dim>& fe_values, FEFaceValues<dim>& fe_face_values,
                                      FullMatrix<double>& cell_matrix, Vector<double>& cell_rhs,
                                      bool with_matrix) {
  const unsigned n = fe_->n_dofs_per_cell(), nq = fe_values.n_quadrature_points;
  cell_matrix = 0;
  cell_rhs = 0;
  fe_values.reinit(cell);
  std::vector<Tensor<1, dim>> grads(n);
  std::vector<unsigned> comp(n);
  for (unsigned i = 0; i < n; ++i) comp[i] = fe_->system_to_component_index(i).first;
  const bool body = has_body_force();
  for (unsigned q = 0; q < nq; ++q) {
    const double JxW = fe_values.JxW(q);
    for (unsigned i = 0; i < n && with_matrix; ++i) grads[i] = fe_values.shape_grad(i, q);
    for (unsigned i = 0; i < n && with_matrix; ++i) {
      const unsigned ci = comp[i];
      const Tensor<1, dim>& gi = grads[i];
      for (unsigned j = 0; j <= i; ++j) {
        const unsigned cj = comp[j];
        const Tensor<1, dim>& gj = grads[j];
        cell_matrix(i, j) += elastic_entry<dim>(gi, gj, ci, cj, lambda_, mu_) * JxW;
      }
    }
    if (body) {
      double b[3] = {problem_.body_force[0], problem_.body_force[1], problem_.body_force[2]};
      if (problem_.body_force_function) {
        const Point<dim>& p = fe_values.quadrature_point(q);
        double x[3] = {p[0], p[1], dim == 3 ? p[dim - 1] : 0.0}, extra[3] = {0, 0, 0};
        problem_.body_force_function(x, extra);
        for (int a = 0; a < 3; ++a) b[a] += extra[a];
      }
      for (unsigned i = 0; i < n; ++i) cell_rhs(i) += fe_values.shape_value(i, q) * b[comp[i]] * JxW;
    }
  }
  for (unsigned i = 0; i < n; ++i)
    for (unsigned j = i + 1; j < n; ++j) cell_matrix(i, j) = cell_matrix(j, i);

  if (!cell->at_boundary() || traction_group_.empty()) return;
  for (unsigned f = 0; f < cell->n_faces(); ++f) {
    if (!cell->face(f)->at_boundary()) continue;
    const auto id = cell->face(f)->boundary_id();
    bool reinit = false;
    for (std::size_t t = 0; t < traction_group_.size(); ++t) {
      if (!carries(id, traction_group_[t])) continue;
      if (!reinit) fe_face_values.reinit(cell, f);
      reinit = true;
      const auto& traction = problem_.tractions[t];
      for (unsigned q = 0; q < fe_face_values.n_quadrature_points; ++q) {
        Tensor<1, dim> tq = uniform_traction_[t];
        if (traction.traction) {
          const Point<dim>& p = fe_face_values.quadrature_point(q);
          double x[3] = {p[0], p[1], dim == 3 ? p[dim - 1] : 0.0}, v[3] = {0, 0, 0};
          traction.traction(x, v);
          for (int a = 0; a < dim; ++a) tq[a] = v[a];
        }
        const double JxW = fe_face_values.JxW(q);
        for (unsigned i = 0; i < n; ++i) cell_rhs(i) += fe_face_values.shape_value(i, q) * tq[comp[i]] * JxW;
      }
    }
  }
}

template <int dim>
void ElasticProblem<dim>::assemble_system() {
  FEValues<dim> fe_values(*mapping_, *fe_, *quadrature_,
                          update_values | update_gradients | update_quadrature_points | update_JxW_values);
  FEFaceValues<dim> fe_face_values(*mapping_, *fe_, *face_quadrature_,
                                   update_values | update_quadrature_points | update_JxW_values);

  // Uniform tractions: total force over the group's area (times the thickness in 2D).
  std::vector<double> area(traction_group_.size(), 0.0);
  for (const auto& cell : dof_handler_.active_cell_iterators()) {
    if (!cell->is_locally_owned() || !cell->at_boundary()) continue;
    for (unsigned f = 0; f < cell->n_faces(); ++f) {
      if (!cell->face(f)->at_boundary()) continue;
      const auto id = cell->face(f)->boundary_id();
      bool reinit = false;
      for (std::size_t t = 0; t < traction_group_.size(); ++t)
        if (carries(id, traction_group_[t])) {
          if (!reinit) fe_face_values.reinit(cell, f);
          reinit = true;
          for (unsigned q = 0; q < fe_face_values.n_quadrature_points; ++q) area[t] += fe_face_values.JxW(q);
        }
    }
  }
  Utilities::MPI::sum(area, comm_, area);
  uniform_traction_.assign(traction_group_.size(), Tensor<1, dim>());
  for (std::size_t t = 0; t < traction_group_.size(); ++t)
    for (int a = 0; a < dim; ++a) uniform_traction_[t][a] = problem_.tractions[t].force[a] / (area[t] * thickness_);

  const unsigned n = fe_->n_dofs_per_cell();
  FullMatrix<double> cell_matrix(n, n);
  Vector<double> cell_rhs(n);
  std::vector<types::global_dof_index> dofs(n);
  std::array<double, 3> applied{};
  const bool body = has_body_force();
  for (const auto& cell : dof_handler_.active_cell_iterators()) {
    if (!cell->is_locally_owned()) continue;
    cell->get_dof_indices(dofs);
    if (!use_mg_) {
      cell_system(cell, fe_values, fe_face_values, cell_matrix, cell_rhs);
      constraints_.distribute_local_to_global(cell_matrix, cell_rhs, dofs, matrix_, rhs_);
    } else {
      // Right-hand side only; the element matrix where it moves inhomogeneous constraints over.
      bool inhomogeneous = false;
      for (auto d : dofs) inhomogeneous = inhomogeneous || constraints_.is_inhomogeneously_constrained(d);
      if (!inhomogeneous && !body && (!cell->at_boundary() || traction_group_.empty())) continue;
      cell_system(cell, fe_values, fe_face_values, cell_matrix, cell_rhs, inhomogeneous);
      constraints_.distribute_local_to_global(cell_rhs, dofs, rhs_, cell_matrix);
    }
    for (unsigned i = 0; i < n; ++i) applied[fe_->system_to_component_index(i).first] += cell_rhs(i);
  }

  // Point forces at the nearest vertex: every rank proposes its nearest vertex, all agree on the
  // closest (ties by coordinates), the owners of its DoFs add the force.
  point_loads_.clear();
  for (const auto& pf : problem_.point_forces) {
    Point<dim> target;
    for (int a = 0; a < dim; ++a) target[a] = pf.point[a];
    std::array<double, 4> best{1e308, 0, 0, 0};
    for (const auto& cell : dof_handler_.active_cell_iterators())
      if (cell->is_locally_owned())
        for (unsigned v = 0; v < cell->n_vertices(); ++v) {
          const double d = cell->vertex(v).distance(target);
          std::array<double, 4> cand{d, 0, 0, 0};
          for (int a = 0; a < dim; ++a) cand[1 + a] = cell->vertex(v)[a];
          if (cand < best) best = cand;
        }
    const auto all = Utilities::MPI::all_gather(comm_, best);
    best = *std::min_element(all.begin(), all.end());
    std::set<types::global_dof_index> done;
    for (const auto& cell : dof_handler_.active_cell_iterators())
      if (cell->is_locally_owned())
        for (unsigned v = 0; v < cell->n_vertices(); ++v) {
          bool same = true;
          for (int a = 0; a < dim; ++a) same = same && cell->vertex(v)[a] == best[1 + a];
          if (!same) continue;
          for (int c = 0; c < dim; ++c) {
            const auto dof = cell->vertex_dof_index(v, c);
            if (!owned_.is_element(dof) || !done.insert(dof).second) continue;
            const double value = pf.force[c] / thickness_;
            point_loads_.emplace_back(dof, value);
            applied[c] += value;
            if (!constraints_.is_constrained(dof)) rhs_(dof) += value;
          }
        }
  }
  if (!use_mg_) matrix_.compress(VectorOperation::add);
  rhs_.compress(VectorOperation::add);
  for (int a = 0; a < 3; ++a) applied_[a] = Utilities::MPI::sum(applied[a], comm_) * thickness_;
}

template <int dim>
void ElasticProblem<dim>::solve() {
  const auto& o = problem_.options;
  const double rhs_norm = rhs_.l2_norm();
  if (rhs_norm == 0) {
    solution_ = 0;
    result_.solver = "none (no load)";
  } else if (use_mg_) {
    MgSettings s;
    s.lambda = lambda_;
    s.mu = mu_;
    s.tolerance = o.tolerance;
    s.max_iterations = o.max_iterations;
    s.direct_limit = o.direct_limit;
    s.mode_centre = mode_centre_;
    s.mode_size = mode_size_;
    MgBoundaries boundaries;
    for (std::size_t k = 0; k < problem_.supports.size(); ++k) {
      ComponentMask mask(dim, false);
      for (int c : constrained_components(problem_.supports[k])) mask.set(c, true);
      std::set<types::boundary_id> ids;
      for (types::boundary_id id = 1; id < groups_of_id_.size(); ++id)
        if (carries(id, support_group_[k])) ids.insert(id);
      if (!ids.empty()) boundaries.emplace_back(ids, mask);
    }
    MgOutcome outcome;
    try {
      outcome = solve_mg(*mapping_, dof_handler_, constraints_, boundaries, rhs_, solution_, s,
                         [&](const char* what) { phase(what); });
    } catch (const SolverControl::NoConvergence& e) {
      require_finite(std::isfinite(e.last_residual), "CG residual");
      throw Error(no_convergence(problem_, "geometric multigrid", e));
    }
    result_.solver = outcome.solver;
    result_.iterations = outcome.iterations;
    profile_out_ << "fem-profile: element matrices stored per level:";
    for (std::size_t n : outcome.matrices_per_level) profile_out_ << ' ' << n;
    profile_out_ << std::endl;
    constraints_.distribute(solution_);
    result_.residual = outcome.residual;
    ghosted_ = solution_;
    return;
  } else if (direct_) {
    SolverControl control(1, 0);
    TrilinosWrappers::SolverDirect::AdditionalData data(false, "Amesos_Klu");
    TrilinosWrappers::SolverDirect solver(control, data);
    solver.solve(matrix_, solution_, rhs_);
    result_.solver = "direct (Amesos_Klu)";
    result_.iterations = 0;
  } else {
    // ML smoothed aggregation with the rigid body modes as near-null space.
    phase("rigid body modes");
    std::vector<double> modes = rigid_body_modes<dim>(
        *mapping_, *fe_, dof_handler_.active_cell_iterators(),
        [](const auto& cell, std::vector<types::global_dof_index>& dofs) {
          if (!cell->is_locally_owned()) return false;
          cell->get_dof_indices(dofs);
          return true;
        },
        owned_, mode_centre_, mode_size_);
    phase("AMG setup");
    TrilinosWrappers::PreconditionAMG amg;
    initialize_elasticity_ml(amg, matrix_, dim, degree_, modes);
    phase("CG");
    SolverControl control(o.max_iterations, o.tolerance * rhs_norm, false, false);
    SolverCG<TrilinosWrappers::MPI::Vector> cg(control);
    try {
      cg.solve(matrix_, solution_, rhs_, amg);
    } catch (const SolverControl::NoConvergence& e) {
      require_finite(std::isfinite(e.last_residual), "CG residual");
      throw Error(no_convergence(problem_, "AMG", e));
    }
    phase(nullptr);
    result_.solver = "cg+amg (ML)";
    result_.iterations = int(control.last_step());
  }
  constraints_.distribute(solution_);
  TrilinosWrappers::MPI::Vector residual(owned_, comm_);
  matrix_.vmult(residual, solution_);
  residual -= rhs_;
  result_.residual = rhs_norm == 0 ? 0.0 : residual.l2_norm() / rhs_norm;
  ghosted_ = solution_;
}

/// r = K u - f assembled element by element without constraints. With `bound`, over every cell,
/// and bound = sum over the elements of |K_e| |u_e| + |f_e|; without, only over the cells touching
/// a constrained DoF (enough for the reactions).
template <int dim>
void ElasticProblem<dim>::element_residual(TrilinosWrappers::MPI::Vector& residual,
                                           TrilinosWrappers::MPI::Vector* bound) {
  FEValues<dim> fe_values(*mapping_, *fe_, *quadrature_,
                          update_values | update_gradients | update_quadrature_points | update_JxW_values);
  FEFaceValues<dim> fe_face_values(*mapping_, *fe_, *face_quadrature_,
                                   update_values | update_quadrature_points | update_JxW_values);
  const unsigned n = fe_->n_dofs_per_cell();
  FullMatrix<double> cell_matrix(n, n);
  Vector<double> cell_rhs(n), u(n), r(n), scale(n);
  std::vector<types::global_dof_index> dofs(n);
  residual.reinit(owned_, comm_);
  if (bound) bound->reinit(owned_, comm_);
  for (const auto& cell : dof_handler_.active_cell_iterators()) {
    if (!cell->is_locally_owned()) continue;
    cell->get_dof_indices(dofs);
    if (!bound && std::none_of(dofs.begin(), dofs.end(), [&](auto d) { return constraints_.is_constrained(d); }))
      continue;
    cell_system(cell, fe_values, fe_face_values, cell_matrix, cell_rhs);
    for (unsigned i = 0; i < n; ++i) u(i) = ghosted_(dofs[i]);
    cell_matrix.vmult(r, u);
    r -= cell_rhs;
    residual.add(dofs, r);
    if (!bound) continue;
    for (unsigned i = 0; i < n; ++i) {
      scale(i) = std::abs(cell_rhs(i));
      for (unsigned j = 0; j < n; ++j) scale(i) += std::abs(cell_matrix(i, j) * u(j));
    }
    bound->add(dofs, scale);
  }
  for (const auto& [dof, value] : point_loads_) {
    residual(dof) -= value;
    if (bound) (*bound)(dof) += std::abs(value);
  }
  residual.compress(VectorOperation::add);
  if (bound) bound->compress(VectorOperation::add);
}

/// max_i |f - K u|_i / (|K| |u| + |f|)_i over the unconstrained DoFs, with |K| |u| summed element
/// by element (an upper bound of the assembled product). Near 1e-16, u solves K u = f to within
/// rounding of K's entries, as a direct solve does. Then a relative residual ||K u - f|| / ||f||
/// above the tolerance is the rounding floor of an ill-conditioned system (a thin bending strip:
/// K u cancels terms of E t |u| to leave loads many orders smaller), not an unconverged or failed
/// solve; the solution is then as accurate as the conditioning allows in double precision.
template <int dim>
double ElasticProblem<dim>::backward_error() {
  TrilinosWrappers::MPI::Vector residual, bound;
  element_residual(residual, &bound);
  double worst = 0;
  for (const auto i : owned_)
    if (!constraints_.is_constrained(i) && bound(i) > 0) worst = std::max(worst, std::abs(residual(i)) / bound(i));
  return Utilities::MPI::max(worst, comm_);
}

/// Reactions: r = K u - f assembled without constraints, summed over each support's DoFs (a DoF
/// shared by two supports counts for the first).
template <int dim>
void ElasticProblem<dim>::compute_reactions() {
  TrilinosWrappers::MPI::Vector residual;
  element_residual(residual, nullptr);

  std::set<types::global_dof_index> claimed;
  std::vector<double> forces(problem_.supports.size() * 3, 0.0);
  std::vector<types::global_dof_index> face_dofs;
  for (std::size_t s = 0; s < problem_.supports.size(); ++s) {
    const auto comps = constrained_components(problem_.supports[s]);
    for (const auto& cell : dof_handler_.active_cell_iterators()) {
      if (!cell->is_locally_owned() || !cell->at_boundary()) continue;
      for (unsigned f = 0; f < cell->n_faces(); ++f) {
        if (!cell->face(f)->at_boundary()) continue;
        const auto id = cell->face(f)->boundary_id();
        if (!carries(id, support_group_[s])) continue;
        face_dofs.resize(fe_->n_dofs_per_face(f));
        cell->face(f)->get_dof_indices(face_dofs);
        for (unsigned i = 0; i < face_dofs.size(); ++i) {
          const int c = fe_->face_system_to_component_index(i, f).first;
          if (std::find(comps.begin(), comps.end(), c) == comps.end()) continue;
          if (!owned_.is_element(face_dofs[i]) || !claimed.insert(face_dofs[i]).second) continue;
          forces[3 * s + c] += residual(face_dofs[i]);
        }
      }
    }
  }
  Utilities::MPI::sum(forces, comm_, forces);
  result_.reactions.clear();
  for (std::size_t s = 0; s < problem_.supports.size(); ++s) {
    GroupReaction g{problem_.supports[s].group, kind_name(problem_.supports[s].kind), {}};
    for (int a = 0; a < dim; ++a) g.force[a] = forces[3 * s + a] * thickness_;
    result_.reactions.push_back(g);
  }
}

/// Per-element (gmsh order) averages of the stress over the element's active descendants, nodal
/// displacements at the gmsh nodes, per-active-cell fields for the VTU.
template <int dim>
void ElasticProblem<dim>::postprocess() {
  const std::size_t n_el = mesh_.cell_count();
  constexpr int K = 10;  // volume, centre x y z, sx sy sz txy tyz txz
  std::vector<double> acc(n_el * K, 0.0);
  FEValues<dim> fe_values(*mapping_, *fe_, *quadrature_, update_gradients | update_quadrature_points | update_JxW_values);
  const FEValuesExtractors::Vector displacement(0);
  std::vector<Tensor<2, dim>> grads(quadrature_->size());
  cell_fields_.assign(7, Vector<float>(tria_->n_active_cells()));
  auto von_mises = [](const double* s) {
    const double a = s[0] - s[1], b = s[1] - s[2], c = s[2] - s[0];
    return std::sqrt(0.5 * (a * a + b * b + c * c) + 3 * (s[3] * s[3] + s[4] * s[4] + s[5] * s[5]));
  };
  for (const auto& cell : dof_handler_.active_cell_iterators()) {
    if (!cell->is_locally_owned()) continue;
    fe_values.reinit(cell);
    fe_values[displacement].get_function_gradients(ghosted_, grads);
    double local[K] = {};
    for (unsigned q = 0; q < grads.size(); ++q) {
      const double JxW = fe_values.JxW(q);
      double s[6];  // xx yy zz xy yz xz
      stress_of(grads[q], s);
      local[0] += JxW;
      for (int a = 0; a < dim; ++a) local[1 + a] += JxW * fe_values.quadrature_point(q)[a];
      for (int k = 0; k < 6; ++k) local[4 + k] += JxW * s[k];
    }
    double avg[6];
    for (int k = 0; k < 6; ++k) avg[k] = local[4 + k] / local[0];
    for (int k = 0; k < 6; ++k) cell_fields_[k][cell->active_cell_index()] = float(avg[k]);
    cell_fields_[6][cell->active_cell_index()] = float(von_mises(avg));
    typename Triangulation<dim>::cell_iterator coarse = cell;
    while (coarse->level() > 0) coarse = coarse->parent();
    const std::size_t e = coarse->index();
    for (int k = 0; k < K; ++k) acc[e * K + k] += local[k];
  }
  Utilities::MPI::sum(acc, comm_, acc);

  auto& r = result_;
  r.cell_centres.assign(3 * n_el, 0.0);
  for (auto* v : {&r.sigma_x, &r.sigma_y, &r.sigma_z, &r.tau_xy, &r.tau_yz, &r.tau_xz, &r.von_mises}) v->assign(n_el, 0.0);
  for (std::size_t e = 0; e < n_el; ++e) {
    const double* a = &acc[e * K];
    const double vol = a[0] > 0 ? a[0] : 1.0;
    for (int k = 0; k < dim; ++k) r.cell_centres[3 * e + k] = a[1 + k] / vol;
    double s[6];
    for (int k = 0; k < 6; ++k) s[k] = a[4 + k] / vol;
    r.sigma_x[e] = s[0];
    r.sigma_y[e] = s[1];
    r.sigma_z[e] = s[2];
    r.tau_xy[e] = s[3];
    r.tau_yz[e] = s[4];
    r.tau_xz[e] = s[5];
    r.von_mises[e] = von_mises(s);
  }

  const std::size_t n_nodes = mesh_.node_count();
  std::vector<double> u(n_nodes * (dim + 1), 0.0);
  std::vector<char> seen(n_nodes, 0);
  for (const auto& cell : dof_handler_.active_cell_iterators()) {
    if (!cell->is_locally_owned()) continue;
    for (unsigned v = 0; v < cell->n_vertices(); ++v) {
      const auto vi = cell->vertex_index(v);
      if (vi >= n_nodes || seen[vi]) continue;
      seen[vi] = 1;
      for (int c = 0; c < dim; ++c) u[vi * (dim + 1) + c] = ghosted_(cell->vertex_dof_index(v, c));
      u[vi * (dim + 1) + dim] = 1;
    }
  }
  Utilities::MPI::sum(u, comm_, u);
  r.node_points = mesh_.nodes;
  r.node_displacement.assign(n_nodes * dim, 0.0);
  for (std::size_t i = 0; i < n_nodes; ++i) {
    const double count = u[i * (dim + 1) + dim];
    for (int c = 0; c < dim; ++c) r.node_displacement[i * dim + c] = count > 0 ? u[i * (dim + 1) + c] / count : 0.0;
  }
}

template <int dim>
void ElasticProblem<dim>::stress_of(const Tensor<2, dim>& g, double* s) const {
  double tr = 0;
  for (int a = 0; a < dim; ++a) tr += g[a][a];
  s[0] = lambda_ * tr + 2 * mu_ * g[0][0];
  s[1] = lambda_ * tr + 2 * mu_ * g[1][1];
  s[3] = mu_ * (g[0][1] + g[1][0]);
  if (dim == 3) {
    s[2] = lambda_ * tr + 2 * mu_ * g[dim - 1][dim - 1];
    s[4] = mu_ * (g[1][dim - 1] + g[dim - 1][1]);
    s[5] = mu_ * (g[0][dim - 1] + g[dim - 1][0]);
  } else {
    s[2] = problem_.options.model == Model::PlaneStrain ? lambda_solid_ * tr : 0.0;
    s[4] = s[5] = 0;
  }
}

/// Each probe point located in the mesh (a bounding-box tree, GridTools::Cache), the solution's
/// value and gradient there from FEValues on a one-point quadrature at its unit-cell position.
template <int dim>
void ElasticProblem<dim>::evaluate_probes() {
  const auto& points = problem_.probe_points;
  if (points.empty()) return;
  constexpr int K = 1 + 3 + 6;  // found, u, sigma
  std::vector<double> acc(points.size() * K, 0.0);
  GridTools::Cache<dim> cache(*tria_, *mapping_);
  typename Triangulation<dim>::active_cell_iterator hint;
  const FEValuesExtractors::Vector displacement(0);
  std::vector<Tensor<1, dim>> value(1);
  std::vector<Tensor<2, dim>> grad(1);
  for (std::size_t i = 0; i < points.size(); ++i) {
    Point<dim> p;
    for (int a = 0; a < dim; ++a) p[a] = points[i][a];
    const auto [cell, unit] = GridTools::find_active_cell_around_point(cache, p, hint);
    if (cell == tria_->end() || !cell->is_locally_owned()) continue;
    hint = cell;
    const typename DoFHandler<dim>::active_cell_iterator dof_cell(&*tria_, cell->level(), cell->index(), &dof_handler_);
    const Quadrature<dim> at(mesh_.simplex ? unit : GeometryInfo<dim>::project_to_unit_cell(unit));
    FEValues<dim> fe_values(*mapping_, *fe_, at, update_values | update_gradients);
    fe_values.reinit(dof_cell);
    fe_values[displacement].get_function_values(ghosted_, value);
    fe_values[displacement].get_function_gradients(ghosted_, grad);
    double* out = &acc[i * K];
    out[0] = 1;
    for (int a = 0; a < dim; ++a) out[1 + a] = value[0][a];
    stress_of(grad[0], out + 4);
  }
  Utilities::MPI::sum(acc, comm_, acc);
  result_.probes.assign(points.size(), {});
  for (std::size_t i = 0; i < points.size(); ++i) {
    const double* in = &acc[i * K];
    if (in[0] == 0) continue;
    auto& probe = result_.probes[i];
    probe.found = true;
    for (int a = 0; a < 3; ++a) probe.u[a] = in[1 + a] / in[0];
    for (int k = 0; k < 6; ++k) probe.sigma[k] = in[4 + k] / in[0];
  }
}

template <int dim>
void ElasticProblem<dim>::compute_errors() {
  if (!problem_.exact_displacement) return;
  PlainFunction<dim> exact(problem_.exact_displacement, problem_.exact_gradient);
  std::unique_ptr<Quadrature<dim>> q;
  if (mesh_.simplex)
    q = std::make_unique<QGaussSimplex<dim>>(degree_ + 2);
  else
    q = std::make_unique<QGauss<dim>>(degree_ + 2);
  Vector<float> cell_errors(tria_->n_active_cells());
  VectorTools::integrate_difference(*mapping_, dof_handler_, ghosted_, exact, cell_errors, *q, VectorTools::L2_norm);
  result_.l2_error = VectorTools::compute_global_error(*tria_, cell_errors, VectorTools::L2_norm);
  if (problem_.exact_gradient) {
    VectorTools::integrate_difference(*mapping_, dof_handler_, ghosted_, exact, cell_errors, *q,
                                      VectorTools::H1_seminorm);
    result_.h1_error = VectorTools::compute_global_error(*tria_, cell_errors, VectorTools::H1_seminorm);
  }
}

template <int dim>
void ElasticProblem<dim>::write_vtu(const fs::path& dir) {
  // One VTK cell per active cell on shared vertices: the element-constant stresses as cell data,
  // the displacement at the vertices. Linear cells for every degree and cell shape alike (Q2 and
  // P2 show their vertex values; docs/fem-reference.md).
  const int ranks = int(Utilities::MPI::n_mpi_processes(comm_));
  workbench::OutputMesh out;
  std::vector<long long> point_of_vertex(tria_->n_vertices(), -1);
  workbench::Field u{"displacement [m]", 3, {}, {"x", "y", "z"}, {}};
  const char* stress_names[7] = {"sigma_x", "sigma_y", "sigma_z", "tau_xy", "tau_yz", "tau_xz", "von_mises"};
  std::vector<int> stresses;
  for (int k = 0; k < 7; ++k)
    if (dim == 3 || (k != 4 && k != 5)) stresses.push_back(k);
  std::vector<workbench::Field> cell_data;
  for (int k : stresses) cell_data.push_back({std::string(stress_names[k]) + " [Pa]", 1, {}, {}, {}});
  if (ranks > 1) cell_data.push_back({"rank [-]", 1, {}, {}, {}});
  // deal.II numbers quadrilateral/hexahedron vertices lexicographically, VTK counter-clockwise.
  const std::vector<unsigned> quad{0, 1, 3, 2}, hex{0, 1, 3, 2, 4, 5, 7, 6};
  std::vector<long long> ids;
  for (const auto& cell : dof_handler_.active_cell_iterators()) {
    if (!cell->is_locally_owned()) continue;
    ids.clear();
    for (unsigned v = 0; v < cell->n_vertices(); ++v) {
      const unsigned w = mesh_.simplex ? v : (dim == 2 ? quad[v] : hex[v]);
      auto& point = point_of_vertex[cell->vertex_index(w)];
      if (point < 0) {
        point = (long long)out.point_count();
        const auto x = cell->vertex(w);
        for (int c = 0; c < 3; ++c) out.points.push_back(c < dim ? x[c] : 0.0);
        for (int c = 0; c < 3; ++c) u.values.push_back(c < dim ? double(ghosted_(cell->vertex_dof_index(w, c))) : 0.0);
      }
      ids.push_back(point);
    }
    const int type = mesh_.simplex ? (dim == 2 ? 5 : 10) : (dim == 2 ? 9 : 12);  // triangle, tetra, quad, hexahedron
    out.add_cell(type, ids);
    for (std::size_t f = 0; f < stresses.size(); ++f)
      cell_data[f].values.push_back(cell_fields_[stresses[f]][cell->active_cell_index()]);
    if (ranks > 1) cell_data.back().values.push_back(double(tria_->locally_owned_subdomain()));
  }
  const unsigned rank = Utilities::MPI::this_mpi_process(comm_);
  std::string name = "fem_000.vtu";
  if (ranks == 1) {
    workbench::write_vtu(dir / name, out, {u}, cell_data);
  } else {
    workbench::write_vtu(dir / ("fem_000." + std::to_string(rank) + ".vtu"), out, {u}, cell_data);
    name = "fem_000.pvtu";
    std::vector<std::string> pieces;
    for (int r = 0; r < ranks; ++r) pieces.push_back("fem_000." + std::to_string(r) + ".vtu");
    if (rank == 0) workbench::write_pvtu(dir / name, pieces, {u}, cell_data);
  }
  if (rank == 0) workbench::write_pvd(dir / "fem.pvd", {{1.0, name}});
}

template <int dim>
FemResult ElasticProblem<dim>::run(const fs::path& output_dir) {
  timer_.enter_subsection("setup");
  make_grid();
  setup_system();
  result_.dim = dim;
  result_.degree = degree_;
  result_.model = dim == 3 ? "3d" : problem_.options.model == Model::PlaneStress ? "plane_stress" : "plane_strain";
  result_.cells = mesh_.simplex ? (dim == 2 ? "triangle" : "tetrahedron") : (dim == 2 ? "quadrilateral" : "hexahedron");
  result_.ranks = int(Utilities::MPI::n_mpi_processes(comm_));
  result_.n_dofs = dof_handler_.n_dofs();
  result_.n_active_cells = tria_->n_global_active_cells();
  check_rigid_motion();
  timer_.leave_subsection("setup");
  result_.setup_seconds = seconds("setup");
  std::ostringstream line;
  line << result_.n_dofs << " DoFs, " << result_.n_active_cells << " cells (" << (mesh_.simplex ? "P" : "Q") << degree_
       << ", " << result_.model << ", " << result_.ranks << " rank" << (result_.ranks > 1 ? "s" : "") << "), setup "
       << result_.setup_seconds << " s";
  say(line.str());

  require_finite(std::isfinite(lambda_) && std::isfinite(mu_) && std::isfinite(lambda_solid_), "stiffness (Lame coefficients)");
  timer_.enter_subsection("assemble");
  assemble_system();
  require_finite(all_finite(rhs_), "load vector");
  if (!use_mg_) require_finite(std::isfinite(matrix_.linfty_norm()), "stiffness matrix");
  timer_.leave_subsection("assemble");
  result_.assemble_seconds = seconds("assemble");
  say("assembled in " + std::to_string(result_.assemble_seconds) + " s");

  timer_.enter_subsection("solve");
  solve();
  require_finite(all_finite(solution_) && std::isfinite(result_.residual), "displacement");
  timer_.leave_subsection("solve");
  result_.solve_seconds = seconds("solve");
  {
    std::ostringstream s;
    s << "solved with " << result_.solver << ": " << result_.iterations << " iterations, relative residual "
      << result_.residual << " (" << result_.solve_seconds << " s)";
    say(s.str());
  }
  if (result_.residual > problem_.options.tolerance) {
    // Above the tolerance: the rounding floor of an ill-conditioned system, or a wrong solution.
    result_.backward_error = backward_error();
    std::ostringstream s;
    s << "relative residual " << result_.residual << " is above fem.tolerance " << problem_.options.tolerance
      << "; backward error " << *result_.backward_error;
    if (*result_.backward_error > kBackwardErrorLimit) {
      s << " (> " << kBackwardErrorLimit << "): the " << result_.solver
        << " solution is not accurate; use fem.solver = \"direct\" or check the supports";
      throw Error(problem_.name + ": " + s.str());
    }
    say(s.str() + ": the rounding floor of this ill-conditioned system (u solves K u = f to rounding)");
  }

  timer_.enter_subsection("output");
  compute_reactions();
  postprocess();
  evaluate_probes();
  compute_errors();
  result_.applied = applied_;
  {
    bool finite = all_finite(result_.node_displacement) && all_finite(result_.cell_centres);
    for (const auto* v : {&result_.sigma_x, &result_.sigma_y, &result_.sigma_z, &result_.tau_xy, &result_.tau_yz,
                          &result_.tau_xz, &result_.von_mises})
      finite = finite && all_finite(*v);
    for (const auto& g : result_.reactions)
      for (double f : g.force) finite = finite && std::isfinite(f);
    for (const auto& probe : result_.probes)
      finite = finite && all_finite(probe.u) && all_finite(probe.sigma);
    for (const auto& cell_field : cell_fields_)
      for (float x : cell_field) finite = finite && std::isfinite(x);
    require_finite(finite, "stress, displacement or reaction");
  }
  if (!output_dir.empty() && problem_.options.write_vtu)
    mpi_collective([&] {
      try {
        write_vtu(output_dir);
      } catch (const ExceptionBase& e) {  // one line, as solve_on_mesh makes of the others
        throw Error(problem_.name + ": " + output_dir.string() + ": deal.II: " + one_line(e));
      }
    });
  timer_.leave_subsection("output");
  result_.output_seconds = seconds("output");
  {
    std::ostringstream s;
    s.precision(6);
    auto vec = [&](const std::array<double, 3>& f) {
      s << "(" << f[0] << ", " << f[1];
      if (dim == 3) s << ", " << f[2];
      s << ") N";
    };
    s << "applied ";
    vec(applied_);
    for (const auto& g : result_.reactions) {
      s << "; reaction " << g.group << " ";
      vec(g.force);
    }
    say(s.str());
  }
  struct rusage usage {};
  getrusage(RUSAGE_SELF, &usage);
  result_.peak_memory_bytes = Utilities::MPI::max(double(usage.ru_maxrss) * 1024.0, comm_);
  return std::move(result_);
}

}  // namespace

FemResult solve_on_mesh(const FemProblem& problem, const PlainMesh& mesh, const fs::path& output_dir,
                        std::ostream* log, double mesh_seconds) {
  ensure_mpi();
  FemResult result;
  const char* solver = "solver";
  try {
    if (mesh.dim == 2) {
      ElasticProblem<2> p(problem, mesh, log);
      result = p.run(output_dir);
    } else {
      ElasticProblem<3> p(problem, mesh, log);
      result = p.run(output_dir);
    }
  } catch (const Error&) {
    throw;
  } catch (const ExceptionBase& e) {
    throw Error(problem.name + ": " + mesh.source + ": deal.II: " + one_line(e));
  } catch (const std::exception& e) {
    throw Error(problem.name + ": " + e.what());
  } catch (int code) {
    throw Error(problem.name + ": the Trilinos " + solver + " failed (error code " + std::to_string(code) + ")");
  }
  result.mesh_seconds = mesh_seconds;
  return result;
}

}  // namespace fem_reference
