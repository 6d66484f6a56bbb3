// The exchange of a distributed run: each step every process sends the positions and
// velocities of its own nodes that others hold as ghosts, and receives its ghosts', with
// non-blocking messages, one per neighbour and direction. Also the reductions of the
// ledger and the monitors (Distribution).
#pragma once
#include <vector>

#include "core/distribution.hpp"
#include "par/subdomain.hpp"

namespace dspdem::par {

class MpiHalo final : public Distribution {
 public:
  /// Collective: every process calls it with its own share. Learns which of its own nodes
  /// each neighbour needs (the neighbours ask by global node number).
  explicit MpiHalo(const Subdomain& sd);

  void exchange(Real* x, Real* v) override;
  void sum(Real* a, int n) const override;
  void max(Real* a, int n) const override;
  int rank() const override { return rank_; }
  int size() const override { return size_; }

  /// Per exchange: messages this process sends, and the values they carry.
  long messages_per_exchange() const { return static_cast<long>(send_.size()); }
  long values_sent_per_exchange() const;
  long ghosts() const;
  const std::vector<int>& neighbours() const { return neighbours_; }

 private:
  struct Link {
    int peer;
    std::vector<Index> nodes;  ///< local nodes, in the order both sides agreed (global order)
    std::vector<Real> buf;     ///< 6 values per node: x then v
  };
  int rank_ = 0, size_ = 1;
  std::vector<Link> send_, recv_;
  std::vector<int> neighbours_;
};

}  // namespace dspdem::par
