// The exchange of a distributed run: each step every process sends the positions and
// velocities of its own nodes that others hold as ghosts, and receives its ghosts', with
// non-blocking messages, one per neighbour and direction. Also the reductions of the
// ledger and the monitors (Distribution), and what contact needs (contact::ContactExchange).
#pragma once
#include <mpi.h>

#include <vector>

#include "contact/contact_exchange.hpp"
#include "core/distribution.hpp"
#include "par/subdomain.hpp"

namespace dspdem::par {

class MpiHalo final : public Distribution, public contact::ContactExchange {
 public:
  /// Collective: every process calls it with its own share. Learns which of its own nodes
  /// each neighbour needs (the neighbours ask by global node number).
  explicit MpiHalo(const Subdomain& sd);

  void exchange_begin(const Real* x, const Real* v) override;
  void exchange_end(Real* x, Real* v) override;
  /// Collective: every copy of an element (its owner's and the ghosts') takes the smallest
  /// of their values (labels in a distributed union-find, par/fragments.hpp).
  void min_over_copies(std::vector<Index>& elem_value);
  void sum(Real* a, int n) const override;
  void max(Real* a, int n) const override;
  int rank() const override { return rank_; }
  int size() const override { return size_; }

  // contact::ContactExchange
  bool any(bool flag) override;
  std::vector<std::vector<Real>> all_gather(const std::vector<Real>& mine) override;
  std::vector<std::vector<Real>> all_to_all(const std::vector<std::vector<Real>>& out) override;
  void trade(const std::vector<std::vector<Real>>& out, std::vector<std::vector<Real>>& in) override;
  void max_over_copies(std::vector<Index>& per_element) override;
  /// A union-find on the share, then labels made equal over every element's copies until
  /// none changes (par/fragments.hpp).
  std::vector<Index> fragment_ids(const Mesh& mesh, const joint::JointSet& js) override;

  /// Per exchange: messages this process sends; its ghost nodes (6 values each come in).
  long messages_per_exchange() const { return static_cast<long>(send_.size()); }
  long ghosts() const;

 private:
  struct Link {
    int peer;
    std::vector<Index> nodes;  ///< local nodes, in the order both sides agreed (global order)
    std::vector<Real> buf;     ///< 6 values per node: x then v
  };
  struct ElemLink {
    int peer;
    std::vector<Index> elems;  ///< local elements, in global order on both sides
    std::vector<long> buf;
  };
  int rank_ = 0, size_ = 1;
  std::vector<Link> send_, recv_;
  std::vector<ElemLink> elem_own_, elem_ghost_;  ///< own elements others hold; ghosts by owner
  std::vector<MPI_Request> pending_;             ///< the exchange under way (begin to end)
};

}  // namespace dspdem::par
