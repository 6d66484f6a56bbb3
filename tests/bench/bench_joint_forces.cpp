// Joint kernel throughput: ~1e5 triangular joints (every interior face of a jittered box of
// 48000 tets), intact, the state of most joints in a loaded body; the optimised kernel
// (add_joint_forces) on 1 and 2 threads against the plain serial oracle. Counter:
// joints_per_s.
//   build/tests/bench/bench_joint_forces --benchmark_min_time=2
#include <benchmark/benchmark.h>
#include <omp.h>

#include <cmath>

#include "joint/joint_forces.hpp"
#include "support/box_mesh.hpp"
#include "support/model_builder.hpp"

using namespace dspdem;
using namespace dspdem::testsupport;

namespace {
struct Setup {
  Model model;
  std::vector<Real> x, f, slots;
};

Setup& setup() {
  static Setup* s = [] {
    auto* s = new Setup;
    CaseConfig c = simple_case(30e9, 0.2, 2400);
    testsupport::make_fracturable(c, 3e6, 100, 10e6, 30, 1000);
    s->model = build_model(c, box_mesh(CellType::Tet4, 20, 20, 20, Vec3(1, 1, 1), 0.2));
    s->x = s->model.fem.x0;
    // Small elastic jumps (well below w_ft): every joint loaded, none softening.
    for (std::size_t i = 0; i < s->x.size(); ++i) s->x[i] += 1e-7 * std::sin(0.37 * static_cast<double>(i));
    s->f.assign(s->x.size(), 0.0);
    return s;
  }();
  return *s;
}

void BM_JointForces(benchmark::State& state) {
  omp_set_num_threads(static_cast<int>(state.range(0)));
  Setup& s = setup();
  joint::add_joint_forces(s.model.joints, s.x.data(), s.f.data(), s.slots);  // warm-up, gather built
  for (auto _ : state) {
    joint::add_joint_forces(s.model.joints, s.x.data(), s.f.data(), s.slots);
    benchmark::DoNotOptimize(s.f.data());
  }
  state.counters["joints_per_s"] =
      benchmark::Counter(static_cast<double>(s.model.joints.size()), benchmark::Counter::kIsIterationInvariantRate);
}

void BM_JointForcesReference(benchmark::State& state) {
  Setup& s = setup();
  for (auto _ : state) {
    joint::add_joint_forces_reference(s.model.joints, s.x.data(), s.f.data());
    benchmark::DoNotOptimize(s.f.data());
  }
  state.counters["joints_per_s"] =
      benchmark::Counter(static_cast<double>(s.model.joints.size()), benchmark::Counter::kIsIterationInvariantRate);
}
}  // namespace

BENCHMARK(BM_JointForces)->Arg(1)->Arg(2)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(BM_JointForcesReference)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK_MAIN();
