#include "par/mpi_world.hpp"

#include <fmt/format.h>

#include <cstdlib>
#if DSPDEM_HAVE_MPI
#include <mpi.h>
#endif

namespace dspdem::par {

bool launched_by_mpi() {
  // Open MPI sets OMPI_COMM_WORLD_SIZE in the processes mpirun starts; PMIx and PMI
  // launchers (srun, MPICH's hydra) set PMIX_RANK or PMI_SIZE.
  for (const char* v : {"OMPI_COMM_WORLD_SIZE", "PMIX_RANK", "PMI_SIZE"})
    if (std::getenv(v)) return true;
  return false;
}

#if DSPDEM_HAVE_MPI
namespace {
bool g_started = false;
}

void init(int* argc, char*** argv) {
  if (g_started || !launched_by_mpi()) return;
  int provided = 0;
  MPI_Init_thread(argc, argv, MPI_THREAD_FUNNELED, &provided);
  g_started = true;
}

void finalize() {
  if (!g_started) return;
  MPI_Finalize();
  g_started = false;
}

int rank() {
  if (!g_started) return 0;
  int r = 0;
  MPI_Comm_rank(MPI_COMM_WORLD, &r);
  return r;
}

int size() {
  if (!g_started) return 1;
  int s = 1;
  MPI_Comm_size(MPI_COMM_WORLD, &s);
  return s;
}

void barrier() {
  if (g_started) MPI_Barrier(MPI_COMM_WORLD);
}

long broadcast(long value) {
  if (g_started) MPI_Bcast(&value, 1, MPI_LONG, 0, MPI_COMM_WORLD);
  return value;
}

void abort(int code) {
  if (g_started) MPI_Abort(MPI_COMM_WORLD, code);
  std::exit(code);
}

std::vector<long> all_gather(long value) {
  std::vector<long> out(static_cast<std::size_t>(size()), value);
  if (g_started) MPI_Allgather(&value, 1, MPI_LONG, out.data(), 1, MPI_LONG, MPI_COMM_WORLD);
  return out;
}

#else
// Built without MPI (DSPDEM_MPI=OFF): one process. Under mpirun every process would run the
// whole case into the same folder, so a launch with more than one is refused.
void init(int*, char***) {
  const char* n = std::getenv("OMPI_COMM_WORLD_SIZE");
  if (!n) n = std::getenv("PMI_SIZE");
  if (n && std::atoi(n) > 1) {
    fmt::print(stderr, "error: this dspdem was built without MPI (DSPDEM_MPI=OFF): run it without mpirun\n");
    std::exit(2);
  }
}
void finalize() {}
int rank() { return 0; }
int size() { return 1; }
void barrier() {}
long broadcast(long value) { return value; }
void abort(int code) { std::exit(code); }
std::vector<long> all_gather(long value) { return {value}; }
#endif

}  // namespace dspdem::par
