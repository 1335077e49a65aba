// The FEM core's front: solve_fem (fem.h) reads the mesh, checks the problem against it and its
// memory against the machine's limit (no deal.II needed for either), then solves (solve_on_mesh,
// problem/elastic_problem.cc). No case file: fem_case.cc turns one into a FemProblem.
#include "plain_mesh.h"

#include <fem_reference/fem.h>
#include <fem_reference/mpi.h>
#include <workbench/error.h>
#include <workbench/memory_limit.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdlib>
#include <ostream>
#include <sstream>
#include <thread>

#include <time.h>

namespace fem_reference {

namespace fs = std::filesystem;
using workbench::Error;

namespace {

std::string have_groups(const PlainMesh& mesh) {
  std::string have;
  for (const auto& [g, faces] : mesh.face_groups) have += (have.empty() ? "" : ", ") + g;
  return have.empty() ? "none" : have;
}

void check_problem(const FemProblem& p, const PlainMesh& mesh) {
  const std::string mesh_name = p.box ? std::string("the box mesh") : p.mesh_file.string();
  auto check = [&](const std::string& group, const std::string& role) {
    auto it = mesh.face_groups.find(group);
    if (it == mesh.face_groups.end())
      throw Error(p.name + ": " + role + ": group '" + group + "' is not a physical group of " + mesh_name +
                  " (it has: " + have_groups(mesh) + ")");
    if (it->second.empty()) throw Error(p.name + ": " + role + ": group '" + group + "' has no faces in " + mesh_name);
  };
  for (const auto& s : p.supports) {
    const std::string role = s.kind == SupportKind::Clamped   ? "boundary.rigid"
                             : s.kind == SupportKind::Roller ? "boundary.rollers"
                                                             : "displacement support";
    check(s.group, role);
    if (s.kind == SupportKind::Roller && normal_axis(mesh, s.group) < 0)
      throw Error(p.name + ": boundary.rollers: group '" + s.group +
                  "' does not lie in a plane perpendicular to the x, y or z axis (rollers need one normal axis)");
    if (s.kind == SupportKind::Displacement && !s.displacement)
      throw Error(p.name + ": displacement support on '" + s.group + "' has no displacement function");
  }
  for (std::size_t i = 0; i < p.tractions.size(); ++i) {
    check(p.tractions[i].group, "load[" + std::to_string(i) + "].group");
    if (!p.tractions[i].traction)
      for (int a = mesh.dim; a < 3; ++a)
        if (p.tractions[i].force[a] != 0)
          throw Error(p.name + ": load[" + std::to_string(i) + "].direction: " + char('x' + a) +
                      " is not an axis of a 2D mesh");
  }
  for (std::size_t i = 0; i < p.point_forces.size(); ++i) {
    if (!p.point_forces[i].group.empty()) check(p.point_forces[i].group, "load[" + std::to_string(i) + "].group");
    for (int a = mesh.dim; a < 3; ++a)
      if (p.point_forces[i].force[a] != 0)
        throw Error(p.name + ": load[" + std::to_string(i) + "].direction: " + char('x' + a) +
                    " is not an axis of a 2D mesh");
  }
  if (mesh.dim == 2 && p.body_force[2] != 0)
    throw Error(p.name + ": fem.body_force: a 2D mesh takes 2 components, got a z component");
  if (mesh.simplex && p.options.solver == SolverKind::Mg)
    throw Error(p.name + ": fem.solver: \"mg\" (geometric multigrid) needs a quadrilateral/hexahedral mesh; " +
                mesh.source + " has " + (mesh.dim == 2 ? "triangles" : "tetrahedra") +
                " (use \"amg\" or \"auto\", or Transfinite + Recombine in the .geo)");
  if (mesh.simplex && mpi_size() > 1)
    throw Error(p.name + ": " + mesh.source + ": has " + (mesh.dim == 2 ? "triangles" : "tetrahedra") +
                "; a distributed (MPI) run needs a quadrilateral/hexahedral mesh (Transfinite + Recombine in the .geo)");
}

/// The ranks of this run on this machine: the launcher's local count, else every rank.
int ranks_on_this_machine() {
  for (const char* local : {"OMPI_COMM_WORLD_LOCAL_SIZE", "MPI_LOCALNRANKS", "SLURM_NTASKS_PER_NODE"})
    if (const char* v = std::getenv(local)) {
      const int n = std::atoi(v);
      if (n > 0) return n;
    }
  return mpi_size();
}

/// Why a solve whose estimated memory on this machine exceeds its limit (workbench/memory_limit.h)
/// is refused, saying what it needs and on how many machines; empty when it fits.
/// Measured peaks (fem_summary.csv, one rank): about 190 MB of libraries and MPI per process; per
/// DoF 0.7-1.6 kB in 2D (matrix-free multigrid, KLU, AMG), 4 kB for 3D Q1 and 5-7 kB for 3D Q2
/// (the assembled matrix and its ML hierarchy); the mesh and the gathered results, on every rank,
/// about 1 kB per gmsh cell.
std::string memory_refusal(const FemProblem& p, const PlainMesh& mesh) {
  const int dim = mesh.dim, degree = p.options.degree;
  const double fine_cells = double(mesh.cell_count()) * std::pow(double(1 << dim), p.options.refine);
  const double dofs = dim * fine_cells * std::pow(double(degree), dim);
  const double per_dof = dim == 2 ? 1600.0 : degree == 1 ? 4000.0 : 7000.0;
  const double process = 200e6 + 1e3 * double(mesh.cell_count());
  const int ranks = mpi_size(), local = std::min(ranks_on_this_machine(), ranks);
  const double per_rank = process + dofs * per_dof / ranks;
  const double limit = workbench::memory_limit_bytes();
  if (local * per_rank <= limit) return {};
  // Machines of this one's memory, each with as many ranks as it has cores.
  const int cores = std::max(1u, std::thread::hardware_concurrency());
  const double room = limit - cores * process;
  const int machines = room > 0 ? int(std::ceil(dofs * per_dof / room)) : 0;
  std::ostringstream s;
  s.precision(3);
  s << p.name << ": the FEM problem (about " << dofs << " DoFs, Q" << degree << " in " << dim << "D) needs an estimated "
    << local * per_rank / workbench::kGiB << " GiB on this machine";
  if (local > 1) s << " (" << per_rank / workbench::kGiB << " GiB on each of its " << local << " ranks)";
  s << ", above its memory limit of " << limit / workbench::kGiB << " GiB";
  if (machines > 0)
    s << "; about " << (dofs * per_dof + machines * cores * process) / workbench::kGiB << " GiB in all: run it on "
      << machines << " machines of this memory, e.g. mpirun -np " << machines * cores << " (docs/scaling.md)";
  s << " (WORKBENCH_MEMORY_LIMIT=<GiB> sets the limit)";
  return s.str();
}

/// Refuses, before anything large is allocated, a solve whose memory_refusal is not empty.
void check_memory(const FemProblem& p, const PlainMesh& mesh) {
  if (auto refusal = memory_refusal(p, mesh); !refusal.empty())
    throw CollectiveError(refusal);  // every rank finds the same
}

/// CPU seconds of this process so far (all its threads; CLOCK_PROCESS_CPUTIME_ID: exact, unlike
/// getrusage's tick-based accounting).
double process_cpu_seconds() {
  timespec t{};
  clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &t);
  return double(t.tv_sec) + 1e-9 * double(t.tv_nsec);
}

/// Area-weighted centre of a group's faces.
std::array<double, 3> group_centre(const PlainMesh& mesh, const std::string& group) {
  std::array<double, 3> c{};
  double total = 0;
  for (const auto& face : mesh.face_groups.at(group)) {
    std::array<double, 3> lo{1e308, 1e308, 1e308}, hi{-1e308, -1e308, -1e308}, m{};
    for (unsigned v : face)
      for (int a = 0; a < 3; ++a) {
        lo[a] = std::min(lo[a], mesh.nodes[3 * v + a]);
        hi[a] = std::max(hi[a], mesh.nodes[3 * v + a]);
        m[a] += mesh.nodes[3 * v + a] / face.size();
      }
    double w = 0;
    for (int a = 0; a < 3; ++a) w = std::max(w, hi[a] - lo[a]);
    w = std::max(w, 1e-300);
    for (int a = 0; a < 3; ++a) c[a] += w * m[a];
    total += w;
  }
  for (auto& x : c) x /= total;
  return c;
}

/// The problem's mesh, read and checked against the problem (groups, elements), not yet its memory.
PlainMesh problem_mesh(const FemProblem& problem) {
  if (problem.supports.empty())
    throw Error(problem.name + ": no supports: the body could move freely, the FEM problem has no unique solution");
  PlainMesh mesh;
  try {
    mesh = problem.box ? box_mesh(*problem.box) : read_gmsh_mesh(problem.mesh_file, problem.mesh_parameters, problem.mesh_unit);
  } catch (const Error& e) {
    throw Error(problem.name + ": mesh: " + e.what());
  }
  check_problem(problem, mesh);
  return mesh;
}

/// The problem's mesh, read and checked against the problem (groups, elements, memory).
PlainMesh checked_mesh(const FemProblem& problem) {
  PlainMesh mesh = problem_mesh(problem);
  check_memory(problem, mesh);
  return mesh;
}

}  // namespace

void check_fem_problem(const FemProblem& problem) { checked_mesh(problem); }

std::string fem_memory_refusal(const FemProblem& problem) { return memory_refusal(problem, problem_mesh(problem)); }

FemResult solve_fem(const FemProblem& problem, const fs::path& output_dir, std::ostream* log) {
  const auto start = std::chrono::steady_clock::now();
  const PlainMesh mesh = checked_mesh(problem);
  FemProblem p = problem;
  for (auto& f : p.point_forces)
    if (!f.group.empty()) f.point = group_centre(mesh, f.group);
  const double mesh_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  if (log && mpi_rank() == 0)
    *log << "fem: mesh " << mesh.source << ": " << mesh.cell_count() << " cells, " << mesh.node_count() << " nodes ("
         << mesh_seconds << " s)\n";
  const double cpu_start = process_cpu_seconds();
  FemResult result = solve_on_mesh(p, mesh, output_dir, log, mesh_seconds);
  result.cpu_seconds = process_cpu_seconds() - cpu_start;
  return result;
}

}  // namespace fem_reference
