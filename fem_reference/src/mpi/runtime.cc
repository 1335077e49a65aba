// The FEM reference's MPI runtime (fem_reference/mpi.h): start-up (MPI, and the heap in huge
// pages), the singleton's settings and session folder, and the collectives by which the ranks
// agree. Plain MPI calls rather than deal.II's Utilities::MPI, so that this translation unit stays
// light (of deal.II only the exception and thread settings).
#include "runtime.h"

#include <workbench/error.h>
#include <workbench/interruption.h>

#include <deal.II/base/exceptions.h>
#include <deal.II/base/multithread_info.h>

#include <mpi.h>
#include <p4est_base.h>
#include <sc.h>

#include <algorithm>
#include <chrono>
#include <climits>
#include <cstdint>
#include <cstdlib>
#include <exception>
#include <filesystem>
#include <mutex>
#include <thread>

#include <unistd.h>
#if defined(__linux__) && defined(__GLIBC__)
#include <malloc.h>
#include <sys/mman.h>
#endif

namespace fem_reference {

using namespace dealii;
using workbench::Error;

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

}  // namespace

/// Transparent huge pages for what the FEM allocates (Linux with glibc; the kernel's THP mode is
/// usually "madvise", so malloc's memory gets 4 KiB pages): the heap is grown once by a 1 GiB pad
/// (address space, not memory: only touched pages are backed) and marked MADV_HUGEPAGE, and blocks
/// up to 32 MiB come from it instead of their own mmap. The mesh, the DoF tables, the multigrid's
/// vectors, element indices and transfer arrays are then touched in 2 MiB pages: on the 1e6-DoF
/// problems their page faults and TLB misses were a fifth to a third of the solve's CPU time
/// (GLIBC_TUNABLES=glibc.malloc.hugetlb=1 measured the same). The heap is no longer trimmed (freed
/// memory stays with the process, below 2 GiB of free top). Once per process; a no-op elsewhere.
void huge_page_heap() {
#if defined(__linux__) && defined(__GLIBC__)
  static std::once_flag once;  // the comparison starts the FEM beside the agent model's thread
  std::call_once(once, [] {
    constexpr std::size_t pad = std::size_t(1) << 30, huge = std::size_t(2) << 20;
    mallopt(M_MMAP_THRESHOLD, 32 << 20);  // the largest glibc allows
    mallopt(M_TRIM_THRESHOLD, INT_MAX);    // the pad is not given back (a trim would drop the advice)
    mallopt(M_TOP_PAD, int(pad));
    char* const start = static_cast<char*>(sbrk(0));
    if (start == reinterpret_cast<char*>(-1)) return;
    void* volatile block = std::malloc(16 << 20);  // below the mmap threshold: grows the heap by it plus
    std::free(block);                              // the pad (volatile: a malloc/free pair may be elided)
    char* const end = static_cast<char*>(sbrk(0));
    mallopt(M_TOP_PAD, 0);
    const auto first = (reinterpret_cast<std::uintptr_t>(start) + huge - 1) / huge * huge;
    const auto last = reinterpret_cast<std::uintptr_t>(end) / huge * huge;
    if (last > first) madvise(reinterpret_cast<void*>(first), last - first, MADV_HUGEPAGE);
  });
#endif
}

void ensure_mpi() {
  deal_II_exceptions::disable_abort_on_exception();
  deal_II_exceptions::suppress_stacktrace_in_exceptions();
  huge_page_heap();
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

namespace {

/// Waits for `request` without spinning: a rank waiting while rank 0 alone works (the agent model,
/// the files: mpi_on_root) would otherwise poll at full speed and take a core from it and from
/// its child processes. Checks every millisecond at most, so a collective costs at most that more.
void wait_idle(MPI_Request& request) {
  int done = 0;
  for (int pause_us = 10;; pause_us = std::min(2 * pause_us, 1000)) {
    MPI_Test(&request, &done, MPI_STATUS_IGNORE);
    if (done) return;
    std::this_thread::sleep_for(std::chrono::microseconds(pause_us));
  }
}

/// `text` of rank `root` on every rank.
std::string broadcast(std::string text, int root) {
  unsigned long long size = text.size();
  MPI_Bcast(&size, 1, MPI_UNSIGNED_LONG_LONG, root, MPI_COMM_WORLD);
  text.resize(size);
  MPI_Bcast(text.data(), int(size), MPI_CHAR, root, MPI_COMM_WORLD);
  return text;
}

}  // namespace

bool started_by_launcher() {
  for (const char* launcher : {"OMPI_COMM_WORLD_SIZE", "PMIX_RANK", "PMI_RANK", "SLURM_PROCID"})
    if (std::getenv(launcher)) return true;
  return false;
}

namespace {

std::string session_folder;  // the folder this process made for its MPI session files, if any
pid_t session_folder_owner = 0;

void remove_session_folder() {
  if (session_folder.empty() || ::getpid() != session_folder_owner) return;  // not a forked child's
  std::error_code ec;
  std::filesystem::remove_all(session_folder, ec);  // after MPI_Finalize (registered before it)
}

}  // namespace

void configure_singleton_mpi() {
  if (started_by_launcher()) return;  // mpirun's or srun's settings stand
  // Measured with MPI_Init_thread alone (docs/performance.md): 0.26 s as configured by Debian,
  // 0.08 s with ob1, 0.06 s without UCX's one-sided component too, 0.02 s without orted.
  ::setenv("OMPI_MCA_pml", "ob1", 0);
  ::setenv("OMPI_MCA_osc", "^ucx", 0);
  ::setenv("OMPI_MCA_ess_singleton_isolated", "1", 0);
  if (std::getenv("OMPI_MCA_orte_tmpdir_base") || !session_folder.empty()) return;
  // Absolute: a later change of the working directory (a notebook's os.chdir) must not move the
  // folder removed at exit onto another one.
  std::error_code ec;
  const auto tmp = std::filesystem::absolute(std::filesystem::temp_directory_path(ec), ec);
  if (ec) return;  // OpenMPI's own default then, shared with other runs
  std::string folder = (tmp / "workbench-mpi-XXXXXX").string();
  if (!::mkdtemp(folder.data())) return;  // likewise
  session_folder = folder;
  session_folder_owner = ::getpid();
  ::setenv("OMPI_MCA_orte_tmpdir_base", folder.c_str(), 1);
  std::atexit(remove_session_folder);
  auto lock = workbench::hold_interruptions();
  workbench::remove_on_interruption(folder);
}

int mpi_rank() {
  ensure_mpi();
  int rank = 0;
  if (mpi_running()) MPI_Comm_rank(MPI_COMM_WORLD, &rank);
  return rank;
}
int mpi_size() {
  ensure_mpi();
  int size = 1;
  if (mpi_running()) MPI_Comm_size(MPI_COMM_WORLD, &size);
  return size;
}
void mpi_barrier() {
  ensure_mpi();
  if (mpi_running()) MPI_Barrier(MPI_COMM_WORLD);
}
std::string mpi_broadcast(const std::string& text) {
  if (mpi_size() == 1) return text;
  return broadcast(text, 0);
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
    const int size = mpi_size();
    const int mine = failed ? mpi_rank() : size;
    int first = size;
    MPI_Request request;
    MPI_Iallreduce(&mine, &first, 1, MPI_INT, MPI_MIN, MPI_COMM_WORLD, &request);
    wait_idle(request);
    if (first == size) return;
    message = broadcast(message, first);
    failed = true;
  }
  if (failed) throw CollectiveError(message);
}

void mpi_on_root(const std::function<void()>& step) {
  const bool root = mpi_rank() == 0;
  mpi_collective([&] {
    if (root) step();
  });
}

void mpi_sum(std::vector<double>& values) {
  if (mpi_size() == 1) return;
  MPI_Allreduce(MPI_IN_PLACE, values.data(), int(values.size()), MPI_DOUBLE, MPI_SUM, MPI_COMM_WORLD);
}

}  // namespace fem_reference
