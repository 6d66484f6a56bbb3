// Contact step on a loose pile of single cubes (6 tet4 each, side a = 1 cm, turned by up to
// 5 degrees about a random axis, on a cubic lattice of spacing a jittered by +-5 %) with
// about 1e3, 1e4 and 1e5 surface elements: the per-element cost should not grow with the
// pile. Neighbours touch face to face with small overlaps, as in a settled pile.
//   BM_ContactStep:    positions fixed, so after the first call (the broad-phase build,
//                      outside the timed loop) each call is the narrow phase, the force law
//                      and the scatter.
//   BM_ContactRebuild: the whole pile moves rigidly by 2a and back on alternate calls (more
//                      than half the skin), which forces a broad-phase rebuild every call
//                      through the public API while keeping the same pairs and contacts.
// Counters: time_per_surface_element (wall time of one call / surface elements),
// time_per_pair (/ broad-phase pairs), surface_elements, pairs, contacts, their ratios to
// the surface elements, max_overlap (/ (r_a + r_b)), build_s (pile and build_model, once).
// The pile's outer layer has fewer neighbours, so pairs per element grow with the size.
//   OMP_NUM_THREADS=1 build/tests/bench/bench_contact --benchmark_min_time=1
#include <benchmark/benchmark.h>
#include <fmt/format.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <map>
#include <memory>
#include <random>
#include <string>
#include <vector>

#include "support/model_builder.hpp"
#include "support/scene.hpp"

using namespace dspdem;
using namespace dspdem::testsupport;

namespace {
constexpr Real kSide = 0.01;     // cube side a [m]
constexpr Real kSpacing = 1.0;   // lattice spacing / a
constexpr Real kTilt = 0.01;     // random rotation angle, up to [rad]
constexpr Real kJitter = 0.005;  // lattice jitter, +- fraction of a per axis
constexpr Real kDt = 1e-6;

struct Pile {
  Model model;
  std::vector<Real> x, v, f;
  double build_s = 0;
};

// Parts on the first `parts` sites of an n^3 lattice (n = ceil(cbrt(parts))), layer by layer.
Pile& pile(Index target_surface_elements) {
  static std::map<Index, std::unique_ptr<Pile>> cache;
  auto it = cache.find(target_surface_elements);
  if (it != cache.end()) return *it->second;
  const auto t0 = std::chrono::steady_clock::now();
  const Index parts = std::max<Index>(1, static_cast<Index>(std::lround(target_surface_elements / 6.0)));
  const int n = static_cast<int>(std::ceil(std::cbrt(static_cast<double>(parts)) - 1e-9));
  const Mesh part = box_mesh(CellType::Tet4, 1, 1, 1, Vec3(kSide, kSide, kSide));
  const Vec3 centre = Vec3::Constant(0.5 * kSide);
  std::mt19937 rng(12345);
  std::uniform_real_distribution<Real> jitter(-kJitter * kSide, kJitter * kSide);
  std::normal_distribution<Real> gauss(0.0, 1.0);
  Mesh mesh;
  mesh.source = "bench_contact pile";
  for (Index p = 0; p < parts; ++p) {
    const int i = static_cast<int>(p % n), j = static_cast<int>((p / n) % n), k = static_cast<int>(p / (n * n));
    const Vec3 at = kSpacing * kSide * Vec3(i, j, k) + Vec3(jitter(rng), jitter(rng), jitter(rng));
    const Vec3 axis = Vec3(gauss(rng), gauss(rng), gauss(rng)).normalized();
    const Mat3 rot(Eigen::AngleAxis<Real>(kTilt * std::uniform_real_distribution<Real>(0, 1)(rng), axis));
    add_part(mesh, part, fmt::format("p{}", p), centre, at, rot);
  }
  CaseConfig c = simple_case(1e7, 0.25, 1000);
  c.contact.enabled = true;
  c.contact_materials = {contact::ContactMaterial{}};
  auto s = std::make_unique<Pile>();
  s->model = build_model(c, std::move(mesh));
  s->x = s->model.fem.x0;
  s->v.assign(s->x.size(), 0.0);
  s->f.assign(s->x.size(), 0.0);
  s->build_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  return *cache.emplace(target_surface_elements, std::move(s)).first->second;
}

void report(benchmark::State& state, const Pile& s) {
  const contact::ContactTotals t = s.model.contact.totals();
  const double ns = static_cast<double>(t.surface_elements);
  if (t.contacts <= 0) state.SkipWithError("no active contacts in the pile");
  state.SetItemsProcessed(state.iterations() * t.surface_elements);
  // Seconds per surface element; the console prints it with an SI prefix (e.g. "1.2us").
  state.counters["time_per_surface_element"] =
      benchmark::Counter(ns, benchmark::Counter::kIsIterationInvariantRate | benchmark::Counter::kInvert);
  state.counters["surface_elements"] = ns;
  state.counters["pairs"] = static_cast<double>(t.pairs);
  state.counters["pairs_per_surface_element"] = static_cast<double>(t.pairs) / ns;
  state.counters["time_per_pair"] = benchmark::Counter(
      static_cast<double>(t.pairs), benchmark::Counter::kIsIterationInvariantRate | benchmark::Counter::kInvert);
  state.counters["contacts"] = static_cast<double>(t.contacts);
  state.counters["contacts_per_surface_element"] = static_cast<double>(t.contacts) / ns;
  state.counters["max_overlap"] = t.max_overlap;
  state.counters["build_s"] = s.build_s;
}

void BM_ContactStep(benchmark::State& state) {
  Pile& s = pile(static_cast<Index>(state.range(0)));
  Model& m = s.model;
  m.contact.add_forces(m.mesh, m.joints, s.x.data(), s.v.data(), kDt, s.f.data());  // broad-phase build
  const Index rebuilds = m.contact.totals().rebuilds;
  for (auto _ : state) {
    m.contact.add_forces(m.mesh, m.joints, s.x.data(), s.v.data(), kDt, s.f.data());
    benchmark::DoNotOptimize(s.f.data());
    benchmark::ClobberMemory();
  }
  if (m.contact.totals().rebuilds != rebuilds) state.SkipWithError("unexpected broad-phase rebuild");
  report(state, s);
}

void BM_ContactRebuild(benchmark::State& state) {
  Pile& s = pile(static_cast<Index>(state.range(0)));
  Model& m = s.model;
  std::vector<Real> shifted = s.x;
  for (std::size_t i = 0; i < shifted.size(); i += 3) shifted[i] += 2 * kSide;
  const Real* xs[2] = {s.x.data(), shifted.data()};
  m.contact.add_forces(m.mesh, m.joints, xs[0], s.v.data(), kDt, s.f.data());
  const Index rebuilds = m.contact.totals().rebuilds;
  std::size_t k = 0;
  for (auto _ : state) {
    m.contact.add_forces(m.mesh, m.joints, xs[++k & 1], s.v.data(), kDt, s.f.data());
    benchmark::DoNotOptimize(s.f.data());
    benchmark::ClobberMemory();
  }
  if (m.contact.totals().rebuilds - rebuilds != static_cast<Index>(k))
    state.SkipWithError("the shift did not force a rebuild every call");
  report(state, s);
}
}  // namespace

BENCHMARK(BM_ContactStep)->Arg(1000)->Arg(10000)->Arg(100000)->UseRealTime()->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_ContactRebuild)->Arg(1000)->Arg(10000)->Arg(100000)->UseRealTime()->Unit(benchmark::kMicrosecond);
BENCHMARK_MAIN();
