// Internal-force kernel throughput for ~1e5 tet4 and ~1e5 hex8 elements, one and two
// threads, both kinematics; and a STREAM-style triad for the machine's memory bandwidth.
// Counters: elem_per_s (element updates per second), bytes_per_elem (compulsory traffic of
// one update: every array the kernel and the gather read or write, divided by elements),
// GBps (elem_per_s x bytes_per_elem) to set against the triad's bandwidth.
//   build/tests/bench/bench_internal_force --benchmark_min_time=2
#include <benchmark/benchmark.h>
#include <omp.h>

#include "fem/fem_model.hpp"
#include "support/box_mesh.hpp"

using namespace dspdem;

namespace {
struct Setup {
  Mesh mesh;
  FemModel fem;
  std::vector<Real> x, v, f;
  double bytes_per_elem = 0;
};

Setup& setup(CellType type, Kinematics kin) {
  static std::map<std::pair<int, int>, Setup> cache;
  auto key = std::make_pair(static_cast<int>(type), static_cast<int>(kin));
  auto it = cache.find(key);
  if (it != cache.end()) return it->second;
  Setup s;
  // ~1e5 elements: 26 x 26 x 25 cells x 6 tets = 101400, or 47 x 46 x 46 hexes = 99452.
  s.mesh = type == CellType::Tet4 ? testsupport::box_mesh(type, 26, 26, 25, Vec3(1, 1, 1), 0.2)
                                  : testsupport::box_mesh(type, 47, 46, 46, Vec3(1, 1, 1), 0.2);
  Material m;
  m.name = "m", m.E = 30e9, m.nu = 0.2, m.density = 2500;
  const Index ne = s.mesh.n_elements();
  s.fem = build_fem_model(s.mesh, {m}, std::vector<Index>(ne, 0), std::vector<Index>(ne, 0), {kin});
  s.x = s.mesh.x;
  for (std::size_t i = 0; i < s.x.size(); ++i) s.x[i] += 1e-4 * std::sin(0.37 * static_cast<double>(i));
  s.v.assign(s.x.size(), 0.0);
  s.f.assign(s.x.size(), 0.0);
  const FemBlock& b = s.fem.blocks.at(0);
  const double n = ne, npe = b.npe(), nn = s.fem.n_nodes;
  double bytes = npe * 4                                          // connectivity
                 + 3 * npe * 8 + 4 * 8                            // gradients, vol, lambda, mu, beta
                 + (type == CellType::Hex8 ? (32 + 144) * 8 : 0)  // gamma, K_hg
                 + 2 * npe * 3 * 8                                // x and x0 of its nodes
                 + 3 * npe * 8 + 8 + 4                            // force slots written, energy, elem id
                 + 3 * npe * 8 + npe * 4;                         // gather: slots read, slot index
  bytes += (nn * 3 * 8 + (nn + 1) * 4) / n;                       // nodal force written, CSR pointer
  s.bytes_per_elem = bytes;
  return cache.emplace(key, std::move(s)).first->second;
}

void BM_InternalForce(benchmark::State& state, CellType type, Kinematics kin) {
  const int threads = static_cast<int>(state.range(0));
  omp_set_num_threads(threads);
  Setup& s = setup(type, kin);
  internal_forces(s.fem, s.x.data(), s.v.data(), s.f.data());  // warm-up
  for (auto _ : state) {
    internal_forces(s.fem, s.x.data(), s.v.data(), s.f.data());
    benchmark::DoNotOptimize(s.f.data());
    benchmark::ClobberMemory();
  }
  const double ne = s.fem.n_elements;
  state.counters["elements"] = ne;
  state.counters["elem_per_s"] = benchmark::Counter(ne, benchmark::Counter::kIsIterationInvariantRate);
  state.counters["bytes_per_elem"] = s.bytes_per_elem;
  state.counters["GBps"] =
      benchmark::Counter(ne * s.bytes_per_elem * 1e-9, benchmark::Counter::kIsIterationInvariantRate);
}

void BM_StreamTriad(benchmark::State& state) {
  const int threads = static_cast<int>(state.range(0));
  omp_set_num_threads(threads);
  const long n = 20'000'000;  // 3 x 160 MB: far beyond any cache
  std::vector<double> a(n, 0.0), b(n, 1.0), c(n, 2.0);
  for (auto _ : state) {
#pragma omp parallel for schedule(static)
    for (long i = 0; i < n; ++i) a[i] = b[i] + 0.5 * c[i];
    benchmark::DoNotOptimize(a.data());
    benchmark::ClobberMemory();
  }
  // 24 bytes per index as STREAM counts it (write-allocate traffic not counted).
  state.counters["GBps"] = benchmark::Counter(n * 24e-9, benchmark::Counter::kIsIterationInvariantRate);
}
}  // namespace

BENCHMARK_CAPTURE(BM_InternalForce, tet4_corotational, CellType::Tet4, Kinematics::Corotational)
    ->Arg(1)
    ->Arg(2)
    ->UseRealTime()
    ->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_InternalForce, tet4_small_strain, CellType::Tet4, Kinematics::SmallStrain)
    ->Arg(1)
    ->Arg(2)
    ->UseRealTime()
    ->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_InternalForce, hex8_corotational, CellType::Hex8, Kinematics::Corotational)
    ->Arg(1)
    ->Arg(2)
    ->UseRealTime()
    ->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_InternalForce, hex8_small_strain, CellType::Hex8, Kinematics::SmallStrain)
    ->Arg(1)
    ->Arg(2)
    ->UseRealTime()
    ->Unit(benchmark::kMillisecond);
BENCHMARK(BM_StreamTriad)->Arg(1)->Arg(2)->UseRealTime()->Unit(benchmark::kMillisecond);
BENCHMARK_MAIN();
