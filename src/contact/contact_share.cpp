// Contact in a distributed run: the share's part of the whole model's contact data, the
// distributed broad phase (elements lent by their owners at each rebuild), the per-step
// exchange of the lent elements' nodes, and the ordered sums of the wall forces.
#include <algorithm>
#include <map>

#include "contact/contact_system.hpp"
#include "core/error.hpp"

namespace dspdem::contact {

namespace {
// What an owner lends: one element's contact data, its box and its nodes' global numbers.
constexpr int kHead = 15;  // gid type npe tag material radius kn node_mass fragment lo[3] hi[3]
}  // namespace

void ContactSystem::take_share(const ContactSystem& whole, const ShareMap& map) {
  DSPDEM_CHECK(whole.enabled_ && !whole.built_, "internal: take_share of contact that is off or has run");
  const Index ne = static_cast<Index>(map.elem_global.size());
  const Index nn = static_cast<Index>(map.node_global.size());
  *this = ContactSystem{};
  enabled_ = true;
  settings_ = whole.settings_;
  materials_ = whole.materials_;
  any_damping_ = whole.any_damping_;
  walls_ = whole.walls_;
  skin_ = whole.skin_;  // the whole model's: the same skin, so the same rebuilds
  setup_error_ = whole.setup_error_;
  // Global -> local node (the share's nodes are numbered own first, then ghosts).
  std::map<Index, Index> g2l;
  for (Index l = 0; l < nn; ++l) g2l.emplace(map.node_global[l], l);
  for (Index l = 0; l < ne; ++l) {
    const Index g = map.elem_global[l];
    Elem el = whole.elems_[g];
    for (int i = 0; i < el.npe; ++i) {
      const auto it = g2l.find(el.conn[i]);
      DSPDEM_CHECK(it != g2l.end(), "internal: element {} of the share lacks node {}", el.tag, el.conn[i]);
      el.conn[i] = it->second;
    }
    elems_.push_back(el);
    elem_material_.push_back(whole.elem_material_[g]);
    radius_.push_back(whole.radius_[g]);
    kn_.push_back(whole.kn_[g]);
    elem_node_mass_.push_back(whole.elem_node_mass_[g]);
    outer_faces_.push_back(whole.outer_faces_[g]);
    if (whole.skel_off_[g] < 0) {
      skel_off_.push_back(-1);
    } else {
      skel_off_.push_back(static_cast<Index>(skel_w_.size()));
      const auto b = whole.skel_w_.begin() + whole.skel_off_[g];
      skel_w_.insert(skel_w_.end(), b, b + el.npe * el.npe);
    }
    gid_.push_back(g);
    owner_.push_back(map.elem_owner[l]);
    bool active = map.elem_owner[l] == map.rank;
    for (int i = 0; i < el.npe && !active; ++i) active = el.conn[i] < map.own_nodes;
    active_.push_back(active);
  }
  skel_w_share_ = skel_w_.size();
  rank_ = map.rank;
  n_local_nodes_ = nn;
  own_nodes_ = map.own_nodes;
  share_elems_ = ne;
  global_elems_ = static_cast<Index>(whole.elems_.size());
  node_global_ = map.node_global;
  joint_owned_ = map.joint_owned;
  // Of the joined pairs only those with an element this process owns: a pair is looked up
  // only by the process that counts it, the owner of its first element (counts()).
  std::vector<char> owned(static_cast<std::size_t>(global_elems_), 0);
  for (Index l = 0; l < ne; ++l)
    if (map.elem_owner[l] == map.rank) owned[map.elem_global[l]] = 1;
  for (const PairKey& k : whole.joined_)
    if (owned[k.first] || owned[k.second]) joined_.push_back(k);  // still sorted, global numbers
  skel_slot_.assign(ne, -1);
  slots_from_map();
}

// Each process tells the others the box around its surface elements whose pairs it
// evaluates; each owner then lends every other process its own surface elements whose boxes
// meet that process's box. A pair (a, b) with a evaluated here and b elsewhere has b's box
// meeting a's, hence this process's box: b is lent here. So the pairs found here are the
// one-process run's that concern this process.
void ContactSystem::borrow(const Boxes& own_boxes) {
  const int np = ex_->size();
  const std::size_t ns = surface_list_.size();
  std::vector<Real> region{INFINITY, INFINITY, INFINITY, -INFINITY, -INFINITY, -INFINITY};
  for (std::size_t i = 0; i < ns; ++i)
    if (active_[surface_list_[i]])
      for (int d = 0; d < 3; ++d) {
        region[d] = std::min(region[d], own_boxes.lo[3 * i + d]);
        region[3 + d] = std::max(region[3 + d], own_boxes.hi[3 * i + d]);
      }
  const std::vector<std::vector<Real>> regions = ex_->all_gather(region);
  std::vector<std::vector<Real>> out(static_cast<std::size_t>(np));
  for (std::size_t i = 0; i < ns; ++i) {
    const Index e = surface_list_[i];
    if (owner_[e] != rank_) continue;
    const Elem& el = elems_[e];
    for (int p = 0; p < np; ++p) {
      if (p == rank_) continue;
      const std::vector<Real>& r = regions[p];
      bool meet = true;
      for (int d = 0; d < 3 && meet; ++d) meet = own_boxes.lo[3 * i + d] <= r[3 + d] && r[d] <= own_boxes.hi[3 * i + d];
      if (!meet) continue;
      std::vector<Real>& o = out[p];
      o.insert(o.end(), {static_cast<Real>(gid_[e]), static_cast<Real>(el.type == CellType::Tet4 ? 0 : 1),
                         static_cast<Real>(el.npe), static_cast<Real>(el.tag), static_cast<Real>(elem_material_[e]),
                         radius_[e], kn_[e], elem_node_mass_[e], static_cast<Real>(fragment_[e])});
      o.insert(o.end(), &own_boxes.lo[3 * i], &own_boxes.lo[3 * i] + 3);
      o.insert(o.end(), &own_boxes.hi[3 * i], &own_boxes.hi[3 * i] + 3);
      for (int k = 0; k < el.npe; ++k) o.push_back(static_cast<Real>(node_global_[el.conn[k]]));
      const Real* w = skeleton_row(e, 0);  // all npe rows
      o.insert(o.end(), w, w + el.npe * el.npe);
    }
  }
  const std::vector<std::vector<Real>> got = ex_->all_to_all(out);
  // The lent elements in global order (each comes from its owner only: no duplicates), with
  // their senders.
  std::vector<std::pair<Index, std::pair<int, const Real*>>> lent;
  for (int p = 0; p < np; ++p)
    for (std::size_t k = 0; k < got[p].size();) {
      const Real* r = &got[p][k];
      lent.push_back({static_cast<Index>(r[0]), {p, r}});
      const std::size_t npe = static_cast<std::size_t>(r[2]);
      k += kHead + npe + npe * npe;
    }
  std::sort(lent.begin(), lent.end(), [](const auto& a, const auto& b) { return a.first < b.first; });
  // Global -> local node: own nodes, then ghosts, each ascending.
  auto local_node = [&](Index g) -> Index {
    const auto b = node_global_.begin(), m = b + own_nodes_, e = node_global_.end();
    auto it = std::lower_bound(b, m, g);
    if (it != m && *it == g) return static_cast<Index>(it - b);
    it = std::lower_bound(m, e, g);
    return it != e && *it == g ? static_cast<Index>(it - b) : -1;
  };
  lent_nodes_.clear();
  take_.assign(static_cast<std::size_t>(np), {});
  std::map<Index, Index> lent_index;  // global node -> lent node
  lent_boxes_.lo.clear(), lent_boxes_.hi.clear();
  for (const auto& [g, src] : lent) {
    // Already here (the share holds it as a ghost): not lent again.
    if (std::binary_search(gid_.begin(), gid_.begin() + share_elems_, g)) continue;
    const auto [p, r] = src;
    const int npe = static_cast<int>(r[2]);
    Elem el{r[1] == 0 ? CellType::Tet4 : CellType::Hex8, npe, {}, static_cast<std::size_t>(r[3])};
    for (int k = 0; k < npe; ++k) {
      const Index gn = static_cast<Index>(r[kHead + k]);
      Index l = local_node(gn);
      if (l < 0) {
        auto [it, fresh] = lent_index.try_emplace(gn, static_cast<Index>(lent_nodes_.size()));
        if (fresh) lent_nodes_.push_back(gn), take_[p].push_back(it->second);
        l = n_local_nodes_ + it->second;
      }
      el.conn[k] = l;
    }
    elems_.push_back(el);
    elem_material_.push_back(static_cast<Index>(r[4]));
    radius_.push_back(r[5]);
    kn_.push_back(r[6]);
    elem_node_mass_.push_back(r[7]);
    outer_faces_.push_back(0);
    surface_.push_back(1);
    fragment_.push_back(static_cast<Index>(r[8]));
    skel_off_.push_back(static_cast<Index>(skel_w_.size()));
    skel_w_.insert(skel_w_.end(), r + kHead + npe, r + kHead + npe + npe * npe);
    gid_.push_back(g);
    owner_.push_back(p);
    lent_boxes_.lo.insert(lent_boxes_.lo.end(), r + kHead - 6, r + kHead - 3);
    lent_boxes_.hi.insert(lent_boxes_.hi.end(), r + kHead - 3, r + kHead);
  }
  most_lent_ = std::max<long>(most_lent_, static_cast<long>(elems_.size()) - share_elems_);
  // Each lent node comes from the owner of the first lent element using it, which holds it
  // (its own element's node) with this step's values: ask it, by global number.
  std::vector<std::vector<Real>> ask(static_cast<std::size_t>(np));
  for (int p = 0; p < np; ++p)
    for (Index k : take_[p]) ask[p].push_back(static_cast<Real>(lent_nodes_[k]));
  const std::vector<std::vector<Real>> asked = ex_->all_to_all(ask);
  lend_.assign(static_cast<std::size_t>(np), {});
  for (int p = 0; p < np; ++p)
    for (Real gn : asked[p]) {
      const Index l = local_node(static_cast<Index>(gn));
      DSPDEM_CHECK(l >= 0, "internal: process {} was asked for node {}, which it does not hold", rank_, gn);
      lend_[p].push_back(l);
    }
  lent_buffers();
}

void ContactSystem::lent_buffers() {
  xl_.assign(3 * lent_nodes_.size(), 0.0);
  vl_.assign(3 * lent_nodes_.size(), 0.0);
  out_.assign(lend_.size(), {});
  in_.assign(take_.size(), {});
  for (std::size_t p = 0; p < lend_.size(); ++p) out_[p].resize(6 * lend_[p].size());
  for (std::size_t p = 0; p < take_.size(); ++p) in_[p].resize(6 * take_[p].size());
}

void ContactSystem::fetch_lent_nodes(const Real* x, const Real* v) {
  const int np = ex_->size();
  for (int p = 0; p < np; ++p) {
    Real* b = out_[p].data();
    for (Index n : lend_[p]) {
      const std::size_t k = 3 * static_cast<std::size_t>(n);
      b[0] = x[k], b[1] = x[k + 1], b[2] = x[k + 2], b[3] = v[k], b[4] = v[k + 1], b[5] = v[k + 2];
      b += 6;
    }
  }
  ex_->trade(out_, in_);
  for (int p = 0; p < np; ++p) {
    const Real* b = in_[p].data();
    for (Index n : take_[p]) {
      const std::size_t k = 3 * static_cast<std::size_t>(n);
      xl_[k] = b[0], xl_[k + 1] = b[1], xl_[k + 2] = b[2], vl_[k] = b[3], vl_[k + 1] = b[4], vl_[k + 2] = b[5];
      b += 6;
    }
  }
}

ContactSystem::ShareLoad ContactSystem::share_load() const {
  ShareLoad l;
  l.evaluated = static_cast<long>(pairs_.size() + wall_pairs_.size());
  for (auto [ea, eb] : pairs_) l.counted += counts(ea);
  for (auto [w, e] : wall_pairs_) l.counted += counts(e);
  l.lent_elements = static_cast<long>(elems_.size()) - share_elems_;
  l.lent_nodes = static_cast<long>(lent_nodes_.size());
  l.most_lent = most_lent_;
  return l;
}

// One gather a step: each process's counted contacts, deepest overlap and wall records. The
// records are sorted by (wall, element), stably (a pair's touches come from one process, in
// order): the one-process order of the wall pairs, so every process adds the same numbers in
// the same order and the walls move alike.
void ContactSystem::reduce_step() {
  std::vector<Real> mine{static_cast<Real>(totals_.contacts), totals_.max_overlap, static_cast<Real>(totals_.deepest_a),
                         static_cast<Real>(totals_.deepest_b), static_cast<Real>(totals_.deepest_wall)};
  for (const BornOverlaps* b : {&born_own_.split, &born_own_.unseen, &born_own_.wall})
    mine.insert(mine.end(), {b->energy, b->max_ratio, static_cast<Real>(b->pairs)});
  const std::size_t n_totals = mine.size();  // the wall records follow
  mine.insert(mine.end(), wall_rec_.begin(), wall_rec_.end());
  const std::vector<std::vector<Real>> all = ex_->all_gather(mine);
  totals_.contacts = 0;
  totals_.max_overlap = 0;
  totals_.born = {};
  std::vector<const Real*> rec;
  for (const std::vector<Real>& a : all) {
    totals_.contacts += static_cast<Index>(a[0]);
    if (a[1] > totals_.max_overlap) {
      totals_.max_overlap = a[1];
      totals_.deepest_a = static_cast<std::size_t>(a[2]);
      totals_.deepest_b = static_cast<std::size_t>(a[3]);
      totals_.deepest_wall = static_cast<std::int64_t>(a[4]);
    }
    // Added in rank order: the same sum on every process (it differs from the one-process
    // run's in the last bits at most; the counts and maxima are the same).
    std::size_t k = 5;  // after the contacts and the deepest overlap
    for (BornOverlaps* b : {&totals_.born.split, &totals_.born.unseen, &totals_.born.wall}) {
      b->energy += a[k], b->max_ratio = std::max(b->max_ratio, a[k + 1]);
      b->pairs += static_cast<std::int64_t>(a[k + 2]);
      k += 3;
    }
    for (k = n_totals; k + 8 <= a.size(); k += 8) rec.push_back(&a[k]);
  }
  std::stable_sort(rec.begin(), rec.end(),
                   [](const Real* a, const Real* b) { return a[0] < b[0] || (a[0] == b[0] && a[1] < b[1]); });
  for (const Real* r : rec) {
    Wall& w = walls_[static_cast<std::size_t>(r[0])];
    w.force -= Vec3(r[2], r[3], r[4]);
    w.torque -= Vec3(r[5], r[6], r[7]);
  }
}

}  // namespace dspdem::contact
