// What contact needs from a run spread over several processes, without knowing how they
// talk (MPI lives in par/, which implements this): a few collective calls at each rebuild of
// the candidate list (agreement, the distributed broad phase's boxes and elements, fragment
// ids, surface flags) and, each step, the positions and velocities of the nodes of the
// surface elements other processes lent this one.
//
// Every call is collective: every process makes it, in the same order.
#pragma once
#include <vector>

#include "core/types.hpp"
#include "joint/joint_set.hpp"
#include "mesh/mesh.hpp"

namespace dspdem::contact {

class ContactExchange {
 public:
  virtual ~ContactExchange() = default;
  virtual int rank() const = 0;
  virtual int size() const = 0;
  /// True on every process when `flag` is true on one.
  virtual bool any(bool flag) = 0;
  /// Every process's `mine`, in rank order, on every process.
  virtual std::vector<std::vector<Real>> all_gather(const std::vector<Real>& mine) = 0;
  /// out[p] goes to process p (out has size() entries); returns, per process, what it sent here.
  virtual std::vector<std::vector<Real>> all_to_all(const std::vector<std::vector<Real>>& out) = 0;
  /// Like all_to_all with the sizes already known on both sides (in[p] is sized): the
  /// per-step exchange. Empty entries send or receive nothing.
  virtual void trade(const std::vector<std::vector<Real>>& out, std::vector<std::vector<Real>>& in) = 0;
  /// Per element of the share: each copy (the owner's and the ghosts') takes the largest of
  /// the copies' values.
  virtual void max_over_copies(std::vector<Index>& per_element) = 0;
  /// Fragment ids of the share's elements, as a one-process run names them.
  virtual std::vector<Index> fragment_ids(const Mesh& mesh, const joint::JointSet& js) = 0;
};

}  // namespace dspdem::contact
