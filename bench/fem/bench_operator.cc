// The multigrid's operator application against one core's memory bandwidth (the roofline of
// issue 25): a STREAM-style triad and the stored-element-matrix operator of the geometric multigrid
// (fem_reference/src/mg/cell_matrix_operator.h) on the 1e6-DoF problems of docs/performance.md
// (2D: 704 x 704 Q1 cells; 3D: 64^3 Q1 cells), in single precision (the levels) and double (the
// outer CG). Each operator run reports the bytes an application must move at least (the cell DoF
// indices and matrix numbers, the source read, the destination read and written; the few shared
// element matrices stay in cache) as bytes_per_second, to set against the triad's.
//   taskset -c 1 build/bench/fem/operator_bench    (results: docs/performance.md, "Roofline")
#include "mg/cell_matrix_operator.h"

#include <deal.II/base/mpi.h>
#include <deal.II/dofs/dof_handler.h>
#include <deal.II/fe/fe_q.h>
#include <deal.II/fe/fe_system.h>
#include <deal.II/fe/mapping_q.h>
#include <deal.II/grid/grid_generator.h>
#include <deal.II/grid/tria.h>

#include <benchmark/benchmark.h>

#include <vector>

namespace {

using namespace dealii;

/// a = b + s c over three arrays of 2^23 doubles (64 MiB each, far beyond the caches); STREAM
/// counts 24 bytes per element.
void BM_Triad(benchmark::State& state) {
  const std::size_t n = std::size_t(1) << 23;
  std::vector<double> a(n, 0.0), b(n, 1.0), c(n, 2.0);
  const double s = 3.0;
  for (auto _ : state) {
    double* __restrict pa = a.data();
    const double* __restrict pb = b.data();
    const double* __restrict pc = c.data();
    for (std::size_t i = 0; i < n; ++i) pa[i] = pb[i] + s * pc[i];
    benchmark::DoNotOptimize(a.data());
    benchmark::ClobberMemory();
  }
  state.SetBytesProcessed(int64_t(state.iterations()) * int64_t(24 * n));
}
BENCHMARK(BM_Triad)->Unit(benchmark::kMillisecond)->MinTime(1.0);

template <int dim, typename Number>
void run_operator(benchmark::State& state, unsigned cells) {
  Triangulation<dim> tria(Triangulation<dim>::limit_level_difference_at_vertices);
  GridGenerator::subdivided_hyper_cube(tria, cells, 0.0, 0.176, true);  // boundary ids by side
  const FESystem<dim> fe(FE_Q<dim>(1), dim);
  DoFHandler<dim> dof(tria);
  dof.distribute_dofs(fe);
  IndexSet clamped(dof.n_dofs());  // the side y = 0 (boundary id 2 of subdivided_hyper_cube)
  {
    std::vector<types::global_dof_index> face_dofs(fe.n_dofs_per_face());
    for (const auto& cell : dof.active_cell_iterators())
      for (const auto f : cell->face_indices())
        if (cell->face(f)->at_boundary() && cell->face(f)->boundary_id() == 2) {
          cell->face(f)->get_dof_indices(face_dofs);
          for (auto i : face_dofs) clamped.add_index(i);
        }
    clamped.compress();
  }
  const MappingQ<dim> mapping(1);
  fem_reference::CellMatrixOperator<dim, Number> op;
  op.build(mapping, dof, clamped, 1.2e11, 7.9e10);
  LinearAlgebra::distributed::Vector<Number> src, dst;
  op.initialize_dof_vector(src);
  op.initialize_dof_vector(dst);
  for (unsigned i = 0; i < src.locally_owned_size(); ++i) src.local_element(i) = Number(1e-9 * (i % 97));
  for (auto _ : state) {
    op.vmult(dst, src);
    benchmark::DoNotOptimize(dst.begin());
  }
  const double n_cells = double(tria.n_active_cells()), n_dofs = double(dof.n_dofs());
  const double per_cell = fe.n_dofs_per_cell() * sizeof(unsigned) + sizeof(unsigned);
  const double bytes = n_cells * per_cell + n_dofs * 3 * sizeof(Number);
  state.SetBytesProcessed(int64_t(double(state.iterations()) * bytes));
  state.counters["DoFs"] = n_dofs;
  state.counters["shapes"] = double(op.shapes());
  state.counters["dofs_per_second"] = benchmark::Counter(n_dofs, benchmark::Counter::kIsIterationInvariantRate);
  state.counters["bytes_per_dof"] = bytes / n_dofs;
}

void BM_Q1Plane2DFloat(benchmark::State& state) { run_operator<2, float>(state, 704); }
void BM_Q1Plane2DDouble(benchmark::State& state) { run_operator<2, double>(state, 704); }
void BM_Q1Solid3DFloat(benchmark::State& state) { run_operator<3, float>(state, 64); }
void BM_Q1Solid3DDouble(benchmark::State& state) { run_operator<3, double>(state, 64); }
BENCHMARK(BM_Q1Plane2DFloat)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_Q1Plane2DDouble)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_Q1Solid3DFloat)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_Q1Solid3DDouble)->Unit(benchmark::kMillisecond);

}  // namespace

int main(int argc, char** argv) {
  Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  benchmark::Initialize(&argc, argv);
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}
