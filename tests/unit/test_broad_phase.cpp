// Broad phase: the hashed grid, CGAL's box_intersection_d and the O(n^2) reference must give
// exactly the same sorted pair lists, including touching boxes (closed intervals), boxes of
// zero extent, a few much larger boxes and group filtering.
#include <gtest/gtest.h>

#include <random>

#include "contact/broad_phase.hpp"

using namespace dspdem;
using namespace dspdem::contact;

namespace {

void add_box(Boxes& b, const Real lo[3], const Real hi[3]) {
  for (int k = 0; k < 3; ++k) b.lo.push_back(lo[k]), b.hi.push_back(hi[k]);
}

// Coordinates on a lattice of step 1/4, so many boxes share a face coordinate exactly and
// touch. Sizes 0.25-1.5, one box in 50 twenty times larger, one in 10 flat or a point.
Boxes random_boxes(int n, unsigned seed) {
  std::mt19937 rng(seed);
  const Real side = std::cbrt(static_cast<Real>(n)) * 1.2;
  std::uniform_int_distribution<int> corner(0, static_cast<int>(4 * side));
  std::uniform_int_distribution<int> size(1, 6);
  std::uniform_int_distribution<int> kind(0, 99);
  Boxes b;
  for (int i = 0; i < n; ++i) {
    const int what = kind(rng);
    Real lo[3], hi[3];
    for (int k = 0; k < 3; ++k) {
      lo[k] = 0.25 * corner(rng);
      Real extent = 0.25 * size(rng);
      if (what < 2) extent *= 20;
      if (what >= 90 && (what % 3 == 0 || k == what % 3)) extent = 0;  // points and plates
      hi[k] = lo[k] + extent;
    }
    add_box(b, lo, hi);
  }
  return b;
}

std::vector<Index> random_groups(Index n, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_int_distribution<Index> g(0, std::max<Index>(1, n / 5));
  std::vector<Index> group(n);
  for (auto& x : group) x = g(rng);
  return group;
}

void expect_all_agree(GridBroadPhase& grid, const Boxes& b, const std::vector<Index>* group) {
  PairList by_grid, by_cgal, by_brute;
  grid.find(b, by_grid, group);
  cgal_find(b, by_cgal, group);
  brute_find(b, by_brute, group);
  EXPECT_EQ(by_grid, by_brute);
  EXPECT_EQ(by_cgal, by_brute);
}

}  // namespace

TEST(BroadPhase, RandomBoxesAgreeWithBruteForceAndCgal) {
  GridBroadPhase grid;  // one instance: work arrays are reused between calls
  for (unsigned seed = 1; seed <= 8; ++seed) {
    SCOPED_TRACE(seed);
    const Boxes b = random_boxes(200 * static_cast<int>(seed), seed);
    PairList pairs;
    brute_find(b, pairs);
    ASSERT_GT(pairs.size(), b.lo.size() / 3);  // the test means something: many contacts
    expect_all_agree(grid, b, nullptr);
    const std::vector<Index> group = random_groups(b.size(), seed + 100);
    expect_all_agree(grid, b, &group);
  }
}

TEST(BroadPhase, TouchingFacesEdgesAndCornersCount) {
  // A 3 x 3 x 3 block of unit cubes meeting face to face: every two cubes whose indices
  // differ by at most one on each axis touch.
  Boxes b;
  for (int z = 0; z < 3; ++z)
    for (int y = 0; y < 3; ++y)
      for (int x = 0; x < 3; ++x) {
        const Real lo[3] = {Real(x), Real(y), Real(z)}, hi[3] = {x + 1.0, y + 1.0, z + 1.0};
        add_box(b, lo, hi);
      }
  GridBroadPhase grid;
  PairList pairs;
  grid.find(b, pairs);
  std::size_t expected = 0;
  for (int i = 0; i < 27; ++i)
    for (int j = i + 1; j < 27; ++j)
      if (std::abs(i % 3 - j % 3) <= 1 && std::abs(i / 3 % 3 - j / 3 % 3) <= 1 && std::abs(i / 9 - j / 9) <= 1)
        ++expected;
  EXPECT_EQ(pairs.size(), expected);
  expect_all_agree(grid, b, nullptr);
}

TEST(BroadPhase, HugeBoxCoarsensTheGridButStaysExact) {
  Boxes b = random_boxes(1000, 42);
  const Real floor_lo[3] = {-1e4, -1e4, -1}, floor_hi[3] = {1e4, 1e4, 0.5};
  add_box(b, floor_lo, floor_hi);
  GridBroadPhase grid;
  expect_all_agree(grid, b, nullptr);
  EXPECT_GT(grid.cell_size(), 10.0);  // (2e4 / 1)^2 cells would not fit in 32 entries per box
}

TEST(BroadPhase, IdenticalBoxesAllOverlap) {
  Boxes b;
  const Real lo[3] = {1, 2, 3}, hi[3] = {2, 3, 4};
  for (int i = 0; i < 40; ++i) add_box(b, lo, hi);
  GridBroadPhase grid;
  PairList pairs;
  grid.find(b, pairs);
  EXPECT_EQ(pairs.size(), 40u * 39u / 2);
  expect_all_agree(grid, b, nullptr);
  std::vector<Index> group(40);
  for (Index i = 0; i < 40; ++i) group[i] = i % 4;
  expect_all_agree(grid, b, &group);
}

TEST(BroadPhase, IdenticalPointsAllOverlap) {
  Boxes b;
  const Real p[3] = {0.5, 0.5, 0.5};
  for (int i = 0; i < 10; ++i) add_box(b, p, p);
  GridBroadPhase grid;
  PairList pairs;
  grid.find(b, pairs);
  EXPECT_EQ(pairs.size(), 45u);
  expect_all_agree(grid, b, nullptr);
}

TEST(BroadPhase, ScatteredPointsOnALattice) {
  // Zero-extent boxes only: the mean extent is zero, the cell size falls back to spacing.
  std::mt19937 rng(7);
  std::uniform_int_distribution<int> c(0, 9);
  Boxes b;
  for (int i = 0; i < 500; ++i) {
    const Real p[3] = {Real(c(rng)), Real(c(rng)), Real(c(rng))};
    add_box(b, p, p);
  }
  GridBroadPhase grid;
  expect_all_agree(grid, b, nullptr);
  EXPECT_GT(grid.cell_size(), 0.0);
}

TEST(BroadPhase, EmptyAndSingleInput) {
  GridBroadPhase grid;
  PairList pairs{{0, 1}};
  Boxes b;
  grid.find(b, pairs);
  EXPECT_TRUE(pairs.empty());
  expect_all_agree(grid, b, nullptr);
  const Real lo[3] = {0, 0, 0}, hi[3] = {1, 1, 1};
  add_box(b, lo, hi);
  expect_all_agree(grid, b, nullptr);
}
