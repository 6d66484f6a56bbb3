// Broad phase: hashed uniform grid (linear time), CGAL's box_intersection_d and brute force.
#include "contact/broad_phase.hpp"

#include <CGAL/box_intersection_d.h>

#include <algorithm>
#include <cassert>
#include <cmath>
#include <cstddef>
#include <limits>

namespace dspdem::contact {
namespace {

// Three cell coordinates pack into the low 60 bits of a 64-bit key, so a cell is identified
// by one compare; bits 60-62 of an entry's key flag the axes on which its box starts in
// that cell (see collect).
constexpr int kKeyBits = 20;
constexpr Index kMaxCell = (Index{1} << kKeyBits) - 1;
constexpr int kFlagShift = 3 * kKeyBits;
constexpr std::uint64_t kCellMask = (std::uint64_t{1} << kFlagShift) - 1;
// Upper bound on cell entries per box on average (see choose_cell).
constexpr double kEntriesPerBox = 32;
constexpr int kMinTableBits = 4;

std::uint64_t pack(Index i, Index j, Index k) {
  return static_cast<std::uint64_t>(i) | static_cast<std::uint64_t>(j) << kKeyBits |
         static_cast<std::uint64_t>(k) << (2 * kKeyBits);
}

// Fibonacci hashing: neighbouring cells differ in the low bits of the key, the multiply
// spreads them over the top bits, which are the ones kept.
Index bucket_of(std::uint64_t key, int shift) { return static_cast<Index>((key * 0x9E3779B97F4A7C15ull) >> shift); }

// floor is monotone, so the cell of max(x, y) is the max of their cells: the reporting
// cell of a pair can be computed from the boxes' own cell ranges without rounding doubts.
// The clamp only matters for values rounded up to the scene's far end.
Index cell_of(Real x, Real origin, Real inv_h) {
  const Real c = std::floor((x - origin) * inv_h);
  return static_cast<Index>(std::min(c, static_cast<Real>(kMaxCell)));
}

bool overlap(const Boxes& b, Index i, Index j) {
  for (int k = 0; k < 3; ++k)
    if (b.lo[3 * i + k] > b.hi[3 * j + k] || b.lo[3 * j + k] > b.hi[3 * i + k]) return false;
  return true;
}

bool same_group(const std::vector<Index>* group, Index i, Index j) {
  return group != nullptr && (*group)[i] == (*group)[j];
}

/// Visits the cells of one box (range i0 j0 k0 i1 j1 k1) in a fixed order, giving each
/// cell's key and the flags of the axes on which the box starts there.
template <class F>
void for_each_cell(const Index* c, F&& f) {
  for (Index k = c[2]; k <= c[5]; ++k)
    for (Index j = c[1]; j <= c[4]; ++j)
      for (Index i = c[0]; i <= c[3]; ++i) {
        const unsigned starts = unsigned{i == c[0]} | unsigned{j == c[1]} << 1 | unsigned{k == c[2]} << 2;
        f(pack(i, j, k), starts);
      }
}

/// Stable counting sort of pairs on one member (values in [0, n)).
template <class Key>
void counting_sort(const PairList& in, PairList& out, std::vector<Index>& offset, Index n, Key key) {
  offset.assign(static_cast<std::size_t>(n) + 1, 0);
  for (const auto& p : in) ++offset[key(p) + 1];
  for (Index i = 0; i < n; ++i) offset[i + 1] += offset[i];
  out.resize(in.size());
  for (const auto& p : in) out[offset[key(p)]++] = p;
}

/// Sorts by (i, j) in linear time: LSD radix, j first then i.
void sort_pairs(PairList& pairs, PairList& tmp, std::vector<Index>& offset, Index n) {
  counting_sort(pairs, tmp, offset, n, [](const auto& p) { return p.second; });
  counting_sort(tmp, pairs, offset, n, [](const auto& p) { return p.first; });
}

}  // namespace

// Fills box_cells_ for cell size h; returns how many (box, cell) entries that makes. Counted
// in floating point: a huge box at a small h must not overflow the count.
Real GridBroadPhase::measure(const Boxes& b, Real h) {
  const Index n = b.size();
  const Real inv_h = 1 / h;
  box_cells_.resize(6 * static_cast<std::size_t>(n));
  Real entries = 0;
  for (Index i = 0; i < n; ++i) {
    Index* c = &box_cells_[6 * static_cast<std::size_t>(i)];
    Real cells = 1;
    for (int k = 0; k < 3; ++k) {
      c[k] = cell_of(b.lo[3 * i + k], origin_[k], inv_h);
      c[k + 3] = cell_of(b.hi[3 * i + k], origin_[k], inv_h);
      cells *= static_cast<Real>(c[k + 3] - c[k] + 1);
    }
    entries += cells;
  }
  return entries;
}

// Cell size. The mean box extent puts a typical box in ~8 cells and a handful of boxes in a
// cell. Guards:
// - all boxes points: the mean extent is 0; take the scene span / cbrt(n) (about one point
//   per cell if spread out), or 1 if the scene is a single point (one cell holds all);
// - at most 2^20 cells per axis over the scene, so keys pack into 60 bits (a tiny mean
//   extent in a huge scene);
// - at most kEntriesPerBox * n entries in all. A few boxes much larger than the rest (walls,
//   a container) would each enter (L/h)^3 cells. The grid is coarsened until the total
//   fits, rather than sized by the largest box (e.g. h >= largest / 8): a floor or wall under
//   a pile of n boxes spans only ~n^(2/3) cells and should not coarsen the grid for
//   everybody; only boxes whose cells rival the whole pile do. Memory stays O(n) whatever
//   the sizes; time is linear while the size ratios (hence the coarsening) stay bounded.
Real GridBroadPhase::choose_cell(const Boxes& b, Index& entries) {
  const Index n = b.size();
  Real span = 0, mean = 0;
  for (Index i = 0; i < n; ++i) {
    Real extent = 0;
    for (int k = 0; k < 3; ++k) {
      extent = std::max(extent, b.hi[3 * i + k] - b.lo[3 * i + k]);
      span = std::max(span, b.hi[3 * i + k] - origin_[k]);
    }
    mean += extent / static_cast<Real>(n);
  }
  Real h = mean;
  if (!(h > 0)) h = span / std::cbrt(static_cast<Real>(n));
  if (!(h > 0)) h = 1;
  h = std::max(h, span / static_cast<Real>(kMaxCell - 1));
  // Entries are addressed by Index; the budget is at least n (one cell per box suffices).
  const Real budget =
      std::min(kEntriesPerBox * static_cast<Real>(n) + 1024, static_cast<Real>(std::numeric_limits<Index>::max() / 2));
  Real count = measure(b, h);
  // Terminates: once h exceeds the span a box covers at most 2 cells per axis, count <= 8 n.
  while (count > budget) {
    h *= std::max(Real(1.25), std::cbrt(count / budget));
    count = measure(b, h);
  }
  entries = static_cast<Index>(count);
  return h;
}

// Counting sort of the entries by hashed cell: pass one counts per bucket, pass two
// scatters. Boxes are visited in order, so within a bucket box ids ascend.
void GridBroadPhase::bin(Index n, Index entries) {
  int bits = kMinTableBits;
  while ((Index{1} << bits) < entries) ++bits;
  const Index table = Index{1} << bits;
  hash_shift_ = 64 - bits;

  // start_[bucket + 2] counts, so that after the prefix sum start_[bucket + 1] is the
  // bucket's first slot and the scatter's increments leave start_[bucket] there.
  start_.assign(static_cast<std::size_t>(table) + 2, 0);
  cell_of_entry_.resize(static_cast<std::size_t>(entries));
  std::size_t e = 0;
  for (Index i = 0; i < n; ++i)
    for_each_cell(&box_cells_[6 * static_cast<std::size_t>(i)], [&](std::uint64_t key, unsigned) {
      const Index bucket = bucket_of(key, hash_shift_);
      cell_of_entry_[e++] = bucket;
      ++start_[bucket + 2];
    });
  for (Index t = 2; t < table + 2; ++t) start_[t] += start_[t - 1];

  entries_.resize(static_cast<std::size_t>(entries));
  e = 0;
  for (Index i = 0; i < n; ++i)
    for_each_cell(&box_cells_[6 * static_cast<std::size_t>(i)], [&](std::uint64_t key, unsigned starts) {
      const Index slot = start_[cell_of_entry_[e++] + 1]++;
      entries_[slot] = {key | std::uint64_t{starts} << kFlagShift, i};
    });
}

// A pair meets in every cell both boxes cover; it is reported only from the cell holding the
// lower corner of the intersection (componentwise max of the two lower corners, which
// overlapping boxes both contain), so exactly once. As both boxes reach the cell, that is
// the cell where, on each axis, at least one of them starts: the OR of the entries' flags
// is 7. This test needs only the entries, which are contiguous; the boxes' coordinates are
// read for its survivors alone. Both filters compact their survivors without branching:
// their outcomes are random, and mispredicted branches cost more than the tests.
void GridBroadPhase::collect(const Boxes& b, PairList& out, const std::vector<Index>* group) {
  const Real* lo = b.lo.data();
  const Real* hi = b.hi.data();
  const Index buckets = static_cast<Index>(start_.size()) - 2;
  Index largest = 0;
  for (Index t = 0; t < buckets; ++t) largest = std::max(largest, start_[t + 1] - start_[t]);
  candidates_.resize(static_cast<std::size_t>(largest));
  Index* cand = candidates_.data();
  for (Index t = 0; t < buckets; ++t) {
    const Entry* first = entries_.data() + start_[t];
    const Entry* last = entries_.data() + start_[t + 1];
    for (const Entry* p = first; p + 1 < last; ++p) {
      Index m = 0;
      for (const Entry* q = p + 1; q < last; ++q) {
        cand[m] = q->box;
        const bool same_cell = ((p->key ^ q->key) & kCellMask) == 0;
        const bool reports_here = ((p->key | q->key) >> kFlagShift) == 7;
        m += same_cell & reports_here;
      }
      const Index i = p->box;
      const Real *ilo = lo + 3 * i, *ihi = hi + 3 * i;
      Index hits = 0;
      for (Index c = 0; c < m; ++c) {
        const Index j = cand[c];
        const Real *jlo = lo + 3 * j, *jhi = hi + 3 * j;
        const bool meet = (ilo[0] <= jhi[0]) & (jlo[0] <= ihi[0]) & (ilo[1] <= jhi[1]) & (jlo[1] <= ihi[1]) &
                          (ilo[2] <= jhi[2]) & (jlo[2] <= ihi[2]);
        cand[hits] = j;
        hits += meet;
      }
      for (Index c = 0; c < hits; ++c) {
        assert(i < cand[c]);
        if (!same_group(group, i, cand[c])) out.emplace_back(i, cand[c]);
      }
    }
  }
}

void GridBroadPhase::find(const Boxes& b, PairList& out, const std::vector<Index>* group) {
  out.clear();
  const Index n = b.size();
  assert(b.hi.size() == b.lo.size());
  assert(group == nullptr || static_cast<Index>(group->size()) == n);
  if (n < 2) return;
  for (int k = 0; k < 3; ++k) {
    origin_[k] = b.lo[k];
    for (Index i = 1; i < n; ++i) origin_[k] = std::min(origin_[k], b.lo[3 * i + k]);
  }
  Index entries = 0;
  cell_ = choose_cell(b, entries);
  bin(n, entries);
  collect(b, out, group);
  sort_pairs(out, scratch_, order_, n);
}

namespace {
namespace cbi = CGAL::Box_intersection_d;

/// CGAL box carrying our index as its id (ids break ties between equal coordinates).
class IndexedBox : public cbi::Box_d<double, 3, cbi::ID_NONE> {
 public:
  using ID = Index;
  IndexedBox(const CGAL::Bbox_3& box, Index index) : Box_d(box), index_(index) {}
  ID id() const { return index_; }

 private:
  Index index_;
};
}  // namespace

void cgal_find(const Boxes& b, PairList& out, const std::vector<Index>* group) {
  out.clear();
  const Index n = b.size();
  std::vector<IndexedBox> boxes;
  boxes.reserve(static_cast<std::size_t>(n));
  for (Index i = 0; i < n; ++i) {
    const Real* lo = &b.lo[3 * static_cast<std::size_t>(i)];
    const Real* hi = &b.hi[3 * static_cast<std::size_t>(i)];
    boxes.emplace_back(CGAL::Bbox_3(lo[0], lo[1], lo[2], hi[0], hi[1], hi[2]), i);
  }
  // CGAL sorts what it is given: pointers are cheaper to move than boxes.
  std::vector<const IndexedBox*> handles(boxes.size());
  for (std::size_t i = 0; i < boxes.size(); ++i) handles[i] = &boxes[i];
  auto report = [&](const IndexedBox* x, const IndexedBox* y) {
    const Index i = std::min(x->id(), y->id()), j = std::max(x->id(), y->id());
    if (!same_group(group, i, j)) out.emplace_back(i, j);
  };
  CGAL::box_self_intersection_d(handles.begin(), handles.end(), report, std::ptrdiff_t{10}, cbi::CLOSED);
  std::sort(out.begin(), out.end());
}

void brute_find(const Boxes& b, PairList& out, const std::vector<Index>* group) {
  out.clear();
  const Index n = b.size();
  for (Index i = 0; i < n; ++i)
    for (Index j = i + 1; j < n; ++j)
      if (!same_group(group, i, j) && overlap(b, i, j)) out.emplace_back(i, j);
}

}  // namespace dspdem::contact
