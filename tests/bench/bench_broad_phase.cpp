// Broad phase on a loose pile of n cubes (sides 0.5-1.5, random centres, ~6 neighbours per
// box): the hashed grid against CGAL's box_intersection_d, both giving the sorted pair list.
// Counters: time_per_box (wall time of one call / n), pairs_per_box.
//   build/tests/bench/bench_broad_phase --benchmark_min_time=0.5
#include <benchmark/benchmark.h>

#include <cmath>
#include <map>
#include <random>

#include "contact/broad_phase.hpp"

using namespace dspdem;
using namespace dspdem::contact;

namespace {

// Two cubes of sides a, b overlap when their centres are within (a + b) / 2 on each axis:
// a volume of E[(a + b)^3] = 9 for sides uniform in [0.5, 1.5]. A density of 2/3 boxes per
// unit volume then gives ~6 neighbours per box.
const Boxes& pile(Index n) {
  static std::map<Index, Boxes> cache;
  auto it = cache.find(n);
  if (it != cache.end()) return it->second;
  std::mt19937 rng(12345);
  const Real side = std::cbrt(1.5 * static_cast<Real>(n));
  std::uniform_real_distribution<Real> centre(0, side), size(0.5, 1.5);
  Boxes b;
  for (Index i = 0; i < n; ++i) {
    const Real half = 0.5 * size(rng);
    for (int k = 0; k < 3; ++k) {
      const Real c = centre(rng);
      b.lo.push_back(c - half), b.hi.push_back(c + half);
    }
  }
  return cache.emplace(n, std::move(b)).first->second;
}

void report(benchmark::State& state, Index n, std::size_t pairs) {
  const double boxes = static_cast<double>(n);
  state.SetItemsProcessed(state.iterations() * n);
  // Seconds per box; the console prints it with an SI prefix (e.g. "344ns").
  state.counters["time_per_box"] =
      benchmark::Counter(boxes, benchmark::Counter::kIsIterationInvariantRate | benchmark::Counter::kInvert);
  state.counters["pairs_per_box"] = static_cast<double>(pairs) / boxes;
}

void BM_Grid(benchmark::State& state) {
  const Index n = static_cast<Index>(state.range(0));
  const Boxes& b = pile(n);
  GridBroadPhase grid;
  PairList pairs;
  grid.find(b, pairs);  // warm-up: work arrays reach their steady-state size
  for (auto _ : state) {
    grid.find(b, pairs);
    benchmark::DoNotOptimize(pairs.data());
  }
  report(state, n, pairs.size());
}

void BM_Cgal(benchmark::State& state) {
  const Index n = static_cast<Index>(state.range(0));
  const Boxes& b = pile(n);
  PairList pairs;
  for (auto _ : state) {
    cgal_find(b, pairs);
    benchmark::DoNotOptimize(pairs.data());
  }
  report(state, n, pairs.size());
}

}  // namespace

BENCHMARK(BM_Grid)->Arg(1000)->Arg(10000)->Arg(100000)->UseRealTime()->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_Cgal)->Arg(1000)->Arg(10000)->Arg(100000)->UseRealTime()->Unit(benchmark::kMicrosecond);
BENCHMARK_MAIN();
