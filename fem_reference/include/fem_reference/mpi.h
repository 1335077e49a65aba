#pragma once
// The FEM reference's MPI runtime, for programs and tests (no MPI or deal.II in this header): the
// start-up settings of a one-process run, this process's rank, and the collective steps by which the
// ranks agree (the command line's staged output folder, an error on any rank ending every rank).
// The library starts MPI itself when first needed and finalises it at exit.
//
//   int main() {
//     fem_reference::configure_singleton_mpi();   // first: it sets the environment
//     ...
//     fem_reference::mpi_collective([&] { if (fem_reference::mpi_rank() == 0) make_folder(); });
//   }
#include <workbench/error.h>

#include <functional>
#include <string>
#include <vector>

namespace fem_reference {

/// For a run that mpirun or srun did not start (one process): sets OpenMPI's environment so that
/// MPI starts up in 0.02 s instead of 0.27 s: the ob1 point-to-point layer instead of probing UCX,
/// no UCX one-sided component (both serve networks one process does not use) and no orted helper
/// for the singleton. A variable already set is kept; under mpirun or srun nothing changes. Call it
/// first in main(), before any thread starts (setenv is not safe beside another thread's getenv).
/// It also gives the run's MPI session files a folder of its own, $TMPDIR/workbench-mpi-XXXXXX
/// (unless OMPI_MCA_orte_tmpdir_base is set), removed when the process exits or is interrupted:
/// in OpenMPI's shared /tmp/ompi.<host>.<uid> a run that finishes removes the folder another run
/// is creating its own in, and that run's MPI_Init aborts (two studies at once; open-mpi/ompi#3818).
void configure_singleton_mpi();

/// MPI rank of this process and the number of ranks (1 without mpirun); these initialise MPI
/// (finalised at exit) if the program has not.
int mpi_rank();
int mpi_size();
/// Waits for every rank.
void mpi_barrier();
/// Broadcasts a string from rank 0.
std::string mpi_broadcast(const std::string& text);
/// Sums `values` over the ranks, in place, on every rank (the same length on every rank).
void mpi_sum(std::vector<double>& values);

/// The error every rank throws from a collective step that failed on some rank: the program prints
/// it once (on rank 0), where an error of one rank alone is printed by that rank.
struct CollectiveError : workbench::Error {
  using workbench::Error::Error;
};

/// Runs `step` on every rank (collective: every rank calls it); if it throws on any rank, every rank
/// throws the same CollectiveError (the message of the lowest failing rank), so no rank is left
/// waiting in a later collective. For steps that may fail on one rank only (files, folders).
void mpi_collective(const std::function<void()>& step);
/// Runs `step` on rank 0 only, as a collective step: the other ranks wait, and a failure ends every
/// rank with its message. For the work done once under MPI (the fast models, the files written).
void mpi_on_root(const std::function<void()>& step);

/// True when mpirun or srun started this process (it may still be the only rank); tells without
/// starting MPI.
bool started_by_launcher();

}  // namespace fem_reference
