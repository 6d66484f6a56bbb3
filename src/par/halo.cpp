#include "par/halo.hpp"

#include <mpi.h>

#include <algorithm>
#include <map>
#include <unordered_map>

#include "core/error.hpp"
#include "joint/fragments.hpp"

namespace dspdem::par {

namespace {
// Who holds which of whose items: `mine` lists, per other process, the global numbers of the
// items this process holds as ghosts of it (in global order); returned, per other process,
// the global numbers of this process's own items that it holds, in the order it asked.
std::vector<std::vector<long>> ask_owners(const std::map<int, std::vector<long>>& mine, int size) {
  std::vector<int> ask(static_cast<std::size_t>(size), 0), asked(static_cast<std::size_t>(size), 0);
  for (const auto& [p, items] : mine) ask[p] = static_cast<int>(items.size());
  MPI_Alltoall(ask.data(), 1, MPI_INT, asked.data(), 1, MPI_INT, MPI_COMM_WORLD);
  std::vector<int> sdisp(size + 1, 0), rdisp(size + 1, 0);
  for (int p = 0; p < size; ++p) sdisp[p + 1] = sdisp[p] + ask[p], rdisp[p + 1] = rdisp[p] + asked[p];
  std::vector<long> want(static_cast<std::size_t>(sdisp[size])), wanted(static_cast<std::size_t>(rdisp[size]));
  for (const auto& [p, items] : mine) std::copy(items.begin(), items.end(), want.begin() + sdisp[p]);
  MPI_Alltoallv(want.data(), ask.data(), sdisp.data(), MPI_LONG, wanted.data(), asked.data(), rdisp.data(), MPI_LONG,
                MPI_COMM_WORLD);
  std::vector<std::vector<long>> theirs(static_cast<std::size_t>(size));
  for (int p = 0; p < size; ++p) theirs[p].assign(wanted.begin() + rdisp[p], wanted.begin() + rdisp[p + 1]);
  return theirs;
}
}  // namespace

MpiHalo::MpiHalo(const Subdomain& sd) {
  MPI_Comm_rank(MPI_COMM_WORLD, &rank_);
  MPI_Comm_size(MPI_COMM_WORLD, &size_);
  {
    // Elements: the ghosts by owner, and the own ones that others hold.
    std::map<int, std::vector<long>> mine;
    std::map<int, std::vector<Index>> local;
    std::map<long, Index> own_local;
    for (std::size_t e = 0; e < sd.elem_owner.size(); ++e) {
      const int p = sd.elem_owner[e];
      if (p == rank_) {
        own_local[static_cast<long>(sd.elem_global[e])] = static_cast<Index>(e);
      } else {
        mine[p].push_back(static_cast<long>(sd.elem_global[e]));
        local[p].push_back(static_cast<Index>(e));
      }
    }
    const auto theirs = ask_owners(mine, size_);
    for (int p = 0; p < size_; ++p) {
      if (!theirs[p].empty()) {
        ElemLink l{p, {}, std::vector<long>(theirs[p].size())};
        for (long ge : theirs[p]) {
          const auto it = own_local.find(ge);
          DSPDEM_CHECK(it != own_local.end(), "internal: process {} was asked for element {}, not its own", rank_, ge);
          l.elems.push_back(it->second);
        }
        elem_own_.push_back(std::move(l));
      }
      if (local.count(p)) elem_ghost_.push_back({p, local[p], std::vector<long>(local[p].size())});
    }
  }
  const Index own = sd.local.owned_nodes;
  // Nodes: the ghosts by owner (numbered in global order), and the own ones others hold.
  std::map<int, std::vector<long>> mine;
  std::map<int, std::vector<Index>> from;
  for (std::size_t k = 0; k < sd.ghost_owner.size(); ++k) {
    const Index l = own + static_cast<Index>(k);
    mine[sd.ghost_owner[k]].push_back(static_cast<long>(sd.node_global[l]));
    from[sd.ghost_owner[k]].push_back(l);
  }
  const auto theirs = ask_owners(mine, size_);
  // Global -> local for the own nodes (numbered first, in global order: a binary search).
  auto local_of = [&](long gn) {
    const auto b = sd.node_global.begin(), e = b + own;
    const auto it = std::lower_bound(b, e, static_cast<Index>(gn));
    DSPDEM_CHECK(it != e && *it == gn, "internal: process {} was asked for node {}, which it does not own", rank_, gn);
    return static_cast<Index>(it - b);
  };
  for (int p = 0; p < size_; ++p) {
    if (!theirs[p].empty()) {
      Link l{p, {}, {}};
      for (long gn : theirs[p]) l.nodes.push_back(local_of(gn));
      l.buf.resize(6 * l.nodes.size());
      send_.push_back(std::move(l));
    }
    if (from.count(p)) {
      Link l{p, from[p], {}};
      l.buf.resize(6 * l.nodes.size());
      recv_.push_back(std::move(l));
    }
  }
}

void MpiHalo::exchange_begin(const Real* x, const Real* v) {
  DSPDEM_CHECK(pending_.empty(), "internal: an exchange begun twice");
  pending_.reserve(send_.size() + recv_.size());
  for (Link& l : recv_) {
    pending_.emplace_back();
    MPI_Irecv(l.buf.data(), static_cast<int>(l.buf.size()), MPI_DOUBLE, l.peer, 23, MPI_COMM_WORLD, &pending_.back());
  }
  for (Link& l : send_) {
    Real* b = l.buf.data();
    for (Index n : l.nodes) {
      const std::size_t k = 3 * static_cast<std::size_t>(n);
      b[0] = x[k], b[1] = x[k + 1], b[2] = x[k + 2], b[3] = v[k], b[4] = v[k + 1], b[5] = v[k + 2];
      b += 6;
    }
    pending_.emplace_back();
    MPI_Isend(l.buf.data(), static_cast<int>(l.buf.size()), MPI_DOUBLE, l.peer, 23, MPI_COMM_WORLD, &pending_.back());
  }
}

void MpiHalo::exchange_end(Real* x, Real* v) {
  MPI_Waitall(static_cast<int>(pending_.size()), pending_.data(), MPI_STATUSES_IGNORE);
  pending_.clear();
  for (const Link& l : recv_) {
    const Real* b = l.buf.data();
    for (Index n : l.nodes) {
      const std::size_t k = 3 * static_cast<std::size_t>(n);
      x[k] = b[0], x[k + 1] = b[1], x[k + 2] = b[2], v[k] = b[3], v[k + 1] = b[4], v[k + 2] = b[5];
      b += 6;
    }
  }
}

// Gathered and added in rank order, not MPI_Allreduce: its order is the library's choice,
// and a fixed order keeps a run repeatable on the same number of processes.
void MpiHalo::sum(Real* a, int n) const {
  std::vector<Real> all(static_cast<std::size_t>(n) * size_);
  MPI_Allgather(a, n, MPI_DOUBLE, all.data(), n, MPI_DOUBLE, MPI_COMM_WORLD);
  for (int i = 0; i < n; ++i) {
    Real s = all[i];
    for (int p = 1; p < size_; ++p) s += all[static_cast<std::size_t>(p) * n + i];
    a[i] = s;
  }
}

void MpiHalo::max(Real* a, int n) const {
  std::vector<Real> out(static_cast<std::size_t>(n));
  MPI_Allreduce(a, out.data(), n, MPI_DOUBLE, MPI_MAX, MPI_COMM_WORLD);
  std::copy(out.begin(), out.end(), a);
}

void MpiHalo::min_over_copies(std::vector<Index>& value) {
  // The holders tell the owners their values, the owners keep the smallest and send it back.
  std::vector<MPI_Request> req;
  auto post = [&](std::vector<ElemLink>& links, bool receive) {
    for (ElemLink& l : links) {
      req.emplace_back();
      if (receive)
        MPI_Irecv(l.buf.data(), static_cast<int>(l.buf.size()), MPI_LONG, l.peer, 24, MPI_COMM_WORLD, &req.back());
      else
        MPI_Isend(l.buf.data(), static_cast<int>(l.buf.size()), MPI_LONG, l.peer, 24, MPI_COMM_WORLD, &req.back());
    }
  };
  for (ElemLink& l : elem_ghost_)
    for (std::size_t k = 0; k < l.elems.size(); ++k) l.buf[k] = value[l.elems[k]];
  post(elem_own_, true);
  post(elem_ghost_, false);
  MPI_Waitall(static_cast<int>(req.size()), req.data(), MPI_STATUSES_IGNORE);
  req.clear();
  for (ElemLink& l : elem_own_)
    for (std::size_t k = 0; k < l.elems.size(); ++k)
      value[l.elems[k]] = std::min<Index>(value[l.elems[k]], static_cast<Index>(l.buf[k]));
  for (ElemLink& l : elem_own_)
    for (std::size_t k = 0; k < l.elems.size(); ++k) l.buf[k] = value[l.elems[k]];
  post(elem_ghost_, true);
  post(elem_own_, false);
  MPI_Waitall(static_cast<int>(req.size()), req.data(), MPI_STATUSES_IGNORE);
  for (ElemLink& l : elem_ghost_)
    for (std::size_t k = 0; k < l.elems.size(); ++k) value[l.elems[k]] = static_cast<Index>(l.buf[k]);
}

bool MpiHalo::any(bool flag) {
  int mine = flag ? 1 : 0, all = 0;
  MPI_Allreduce(&mine, &all, 1, MPI_INT, MPI_MAX, MPI_COMM_WORLD);
  return all != 0;
}

std::vector<std::vector<Real>> MpiHalo::all_gather(const std::vector<Real>& mine) {
  int n = static_cast<int>(mine.size());
  std::vector<int> counts(static_cast<std::size_t>(size_)), disp(static_cast<std::size_t>(size_) + 1, 0);
  MPI_Allgather(&n, 1, MPI_INT, counts.data(), 1, MPI_INT, MPI_COMM_WORLD);
  for (int p = 0; p < size_; ++p) disp[p + 1] = disp[p] + counts[p];
  std::vector<Real> flat(static_cast<std::size_t>(disp[size_]));
  MPI_Allgatherv(mine.data(), n, MPI_DOUBLE, flat.data(), counts.data(), disp.data(), MPI_DOUBLE, MPI_COMM_WORLD);
  std::vector<std::vector<Real>> out(static_cast<std::size_t>(size_));
  for (int p = 0; p < size_; ++p) out[p].assign(flat.begin() + disp[p], flat.begin() + disp[p + 1]);
  return out;
}

std::vector<std::vector<Real>> MpiHalo::all_to_all(const std::vector<std::vector<Real>>& out) {
  std::vector<int> send(static_cast<std::size_t>(size_)), recv(static_cast<std::size_t>(size_));
  for (int p = 0; p < size_; ++p) send[p] = static_cast<int>(out[p].size());
  MPI_Alltoall(send.data(), 1, MPI_INT, recv.data(), 1, MPI_INT, MPI_COMM_WORLD);
  std::vector<int> sdisp(size_ + 1, 0), rdisp(size_ + 1, 0);
  for (int p = 0; p < size_; ++p) sdisp[p + 1] = sdisp[p] + send[p], rdisp[p + 1] = rdisp[p] + recv[p];
  std::vector<Real> flat_out(static_cast<std::size_t>(sdisp[size_])), flat_in(static_cast<std::size_t>(rdisp[size_]));
  for (int p = 0; p < size_; ++p) std::copy(out[p].begin(), out[p].end(), flat_out.begin() + sdisp[p]);
  MPI_Alltoallv(flat_out.data(), send.data(), sdisp.data(), MPI_DOUBLE, flat_in.data(), recv.data(), rdisp.data(),
                MPI_DOUBLE, MPI_COMM_WORLD);
  std::vector<std::vector<Real>> in(static_cast<std::size_t>(size_));
  for (int p = 0; p < size_; ++p) in[p].assign(flat_in.begin() + rdisp[p], flat_in.begin() + rdisp[p + 1]);
  return in;
}

void MpiHalo::trade(const std::vector<std::vector<Real>>& out, std::vector<std::vector<Real>>& in) {
  std::vector<MPI_Request> req;
  for (int p = 0; p < size_; ++p)
    if (!in[p].empty()) {
      req.emplace_back();
      MPI_Irecv(in[p].data(), static_cast<int>(in[p].size()), MPI_DOUBLE, p, 25, MPI_COMM_WORLD, &req.back());
    }
  for (int p = 0; p < size_; ++p)
    if (!out[p].empty()) {
      req.emplace_back();
      MPI_Isend(out[p].data(), static_cast<int>(out[p].size()), MPI_DOUBLE, p, 25, MPI_COMM_WORLD, &req.back());
    }
  MPI_Waitall(static_cast<int>(req.size()), req.data(), MPI_STATUSES_IGNORE);
}

void MpiHalo::max_over_copies(std::vector<Index>& value) {
  for (Index& v : value) v = -v;
  min_over_copies(value);
  for (Index& v : value) v = -v;
}

std::vector<Index> MpiHalo::fragment_ids(const Mesh& mesh, const joint::JointSet& js) {
  const Index ne = mesh.n_elements();
  // Pieces of the share; each named by its smallest tag here, which also names it below.
  const joint::Fragments local = joint::find_fragments(mesh, js, std::vector<Real>(ne, 0.0));
  std::vector<Index> label = local.id;
  for (;;) {
    min_over_copies(label);
    std::unordered_map<Index, Index> least;  // local piece -> smallest label of its elements
    for (Index e = 0; e < ne; ++e) {
      auto [it, fresh] = least.emplace(local.id[e], label[e]);
      if (!fresh) it->second = std::min(it->second, label[e]);
    }
    bool changed = false;
    for (Index e = 0; e < ne; ++e) {
      const Index l = least[local.id[e]];
      if (l != label[e]) label[e] = l, changed = true;
    }
    if (!any(changed)) break;
  }
  return label;
}

long MpiHalo::ghosts() const {
  long s = 0;
  for (const Link& l : recv_) s += static_cast<long>(l.nodes.size());
  return s;
}

}  // namespace dspdem::par
