// What the time loop needs from a run spread over several processes, without knowing how
// they talk (MPI lives in par/): each step the owners' positions and velocities copied to
// the processes that hold the same nodes as ghosts, and sums and maxima of the ledger and
// the monitors over all processes. A one-process run has none (a null pointer).
#pragma once
#include "core/types.hpp"

namespace dspdem {

class Distribution {
 public:
  virtual ~Distribution() = default;
  /// Overwrites the ghost nodes' x and v (3 per node) with their owners' values.
  void exchange(Real* x, Real* v) {
    exchange_begin(x, v);
    exchange_end(x, v);
  }
  /// The same in two halves, with work between them that neither reads the ghosts nor
  /// writes the own nodes: begin sends the own nodes' values, end waits for the ghosts'.
  virtual void exchange_begin(const Real* x, const Real* v) = 0;
  virtual void exchange_end(Real* x, Real* v) = 0;
  /// a[i] = the sum over processes of a[i], the same on every process, in rank order.
  virtual void sum(Real* a, int n) const = 0;
  /// a[i] = the maximum over processes of a[i], the same on every process.
  virtual void max(Real* a, int n) const = 0;
  virtual int rank() const = 0;
  virtual int size() const = 0;
};

}  // namespace dspdem
