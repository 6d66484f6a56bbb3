// Broad phase of contact detection: which axis-aligned boxes overlap.
//
// The grid is linear in the number of boxes for bounded size ratios (README M3:
// no binary search, O(n)): boxes are binned into every cell of a uniform grid they touch
// (cell size from the mean box extent), and a pair is reported only by the cell holding
// the lower corner of the two boxes' intersection, so each pair comes out once without a
// set. Cells are found by counting sort on a hashed cell index, not by a tree.
#pragma once
#include <cstdint>
#include <utility>
#include <vector>

#include "core/types.hpp"

namespace dspdem::contact {

/// n boxes, lo/hi = 3 x n (xyz interleaved). Boxes may have zero extent.
struct Boxes {
  std::vector<Real> lo, hi;
  Index size() const { return static_cast<Index>(lo.size() / 3); }
};

using PairList = std::vector<std::pair<Index, Index>>;

/// Pairs (i < j) of overlapping (closed) boxes, sorted by (i, j). `group` (optional, one per
/// box) drops pairs whose two boxes carry the same group id (same fragment).
class GridBroadPhase {
 public:
  void find(const Boxes& b, PairList& out, const std::vector<Index>* group = nullptr);
  Real cell_size() const { return cell_; }

 private:
  /// One (box, cell) incidence: the cell's packed key, with flags in the top bits for the
  /// axes on which the box starts in that cell.
  struct Entry {
    std::uint64_t key;
    Index box;
  };

  Real choose_cell(const Boxes& b, Index& entries);
  Real measure(const Boxes& b, Real h);
  void bin(Index n, Index entries);
  void collect(const Boxes& b, PairList& out, const std::vector<Index>* group);

  Real cell_ = 0;
  Real origin_[3] = {0, 0, 0};
  int hash_shift_ = 64;  ///< bucket = top bits of the multiplied cell key
  // Work arrays kept between calls (no allocation in steady state).
  std::vector<Index> cell_of_entry_;  ///< bucket of each entry, box-major order
  std::vector<Entry> entries_;        ///< entries grouped by bucket
  std::vector<Index> start_;          ///< bucket b holds entries [start_[b], start_[b+1])
  std::vector<Index> candidates_;     ///< partners of one entry that pass the cell test
  std::vector<Index> order_;          ///< counting-sort offsets for the output pairs
  std::vector<Index> box_cells_;      ///< per box: i0 j0 k0 i1 j1 k1
  PairList scratch_;
};

/// The same result by CGAL's box_intersection_d (for the benchmark and as a cross-check).
void cgal_find(const Boxes& b, PairList& out, const std::vector<Index>* group = nullptr);

/// The same result by testing every pair, O(n^2) (for tests).
void brute_find(const Boxes& b, PairList& out, const std::vector<Index>* group = nullptr);

}  // namespace dspdem::contact
