// The MPI environment of a distributed run (`mpirun -n N dspdem run CASE`). dspdem starts
// MPI only when a launcher started it: a plain `dspdem` never touches MPI and behaves as a
// one-process run always has.
#pragma once
#include <string>
#include <vector>

namespace dspdem::par {

/// True when mpirun (Open MPI, or a PMI launcher) started this process.
bool launched_by_mpi();

/// Starts MPI (funnelled threads: only the main thread calls MPI) when launched by mpirun;
/// otherwise does nothing. Safe to call once.
void init(int* argc, char*** argv);
/// Ends MPI if init started it.
void finalize();
int rank();
int size();
void barrier();
/// Process 0's value on every process.
long broadcast(long value);
/// Ends every process of the run with `code` (after an error on one of them, so that the
/// others do not wait for it for ever).
[[noreturn]] void abort(int code);
/// Every process's value, in rank order, on every process.
std::vector<long> all_gather(long value);

}  // namespace dspdem::par
