// Joint kernel throughput: every interior face of a jittered box, intact, the state of most
// joints in a loaded body; the optimised kernel (add_joint_forces) on 1 and 2 threads against
// the plain serial oracle. Faces: ~1e5 triangles (48000 tets) with Gauss points (the paper's,
// the sphere's) or nodal ones (the disc's, the Galvez beam's), or ~8e4 quadrilaterals (27000
// hexes) with Gauss points (the impact beam's), all under the paper's law (the coupled and
// mode I laws differ only in lean_update's elastic gate). Two sizes: that large box, whose joints
// stream from memory, and a small one of ~1e4 joints (the impact beam's count), which stays
// in cache and shows the arithmetic. Counter: joints_per_s. The same box with every point
// softening (BM_JointForcesSoftening: most of the sphere's joints once its stress wave has
// passed) and with every joint broken (BM_JointForcesBroken: a crushed zone).
//   build/tests/bench/bench_joint_forces --benchmark_min_time=2
#include <benchmark/benchmark.h>
#include <omp.h>

#include <algorithm>
#include <cmath>
#include <limits>

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

enum Faces { TriGauss = 0, TriNodal = 1, QuadGauss = 2 };
const char* const kFaceNames[] = {"tri_gauss", "tri_nodal", "quad_gauss"};

Setup make_setup(Faces faces, bool small) {
  Setup s;
  CaseConfig c = simple_case(30e9, 0.2, 2400);
  testsupport::make_fracturable(c, 3e6, 100, 10e6, 30, 1000);
  const int n = faces == QuadGauss ? (small ? 15 : 30) : (small ? 10 : 20);
  s.model = build_model(c, box_mesh(faces == QuadGauss ? CellType::Hex8 : CellType::Tet4, n, n, n, Vec3(1, 1, 1), 0.2));
  s.model.joints.quadrature.assign(s.model.joints.params.size(),
                                   faces == TriNodal ? joint::Quadrature::Nodal : joint::Quadrature::Gauss);
  s.x = s.model.fem.x0;
  // Small elastic jumps: every joint loaded, none softening (full_share, the points kept in
  // full because they left the elastic branch, reads 0). Each component of a node pair's
  // jump is at most twice the amplitude, its length 2 sqrt(3) times it, so 0.2 of the
  // smallest w_ft keeps every opening under 0.7 of it. (A fixed 1e-7 m, as before, softened
  // a fifth to a half of the points: a benchmark of the full law.)
  Real w_ft = std::numeric_limits<Real>::max();
  for (const joint::CohesiveParams& p : s.model.joints.params) w_ft = std::min(w_ft, p.ft / p.kn);
  for (std::size_t i = 0; i < s.x.size(); ++i) s.x[i] += 0.2 * w_ft * std::sin(0.37 * static_cast<double>(i));
  s.f.assign(s.x.size(), 0.0);
  return s;
}

Setup& setup(int faces, int small) {
  static Setup* s[3][2] = {};
  if (!s[faces][small]) s[faces][small] = new Setup(make_setup(static_cast<Faces>(faces), small != 0));
  return *s[faces][small];
}

// Times the kernel on js at positions x, one node moved back and forth between calls so that
// the joints' state changes (a benchmark of a state that cannot change would time a kernel
// that no run has). Counter: joints_per_s.
void time_with_a_node_moving(benchmark::State& state, joint::JointSet& js, std::vector<Real>& x) {
  std::vector<Real> f(x.size(), 0.0), slots;
  joint::add_joint_forces(js, x.data(), f.data(), slots);  // warm-up, gather built
  int k = 0;
  for (auto _ : state) {
    x[0] += (++k % 2 ? 1e-9 : -1e-9);
    joint::add_joint_forces(js, x.data(), f.data(), slots);
    benchmark::DoNotOptimize(f.data());
  }
  state.counters["joints_per_s"] =
      benchmark::Counter(static_cast<double>(js.size()), benchmark::Counter::kIsIterationInvariantRate);
}

void BM_JointForces(benchmark::State& state) {
  omp_set_num_threads(static_cast<int>(state.range(0)));
  Setup& s = setup(static_cast<int>(state.range(1)), static_cast<int>(state.range(2)));
  state.SetLabel(kFaceNames[state.range(1)]);
  joint::add_joint_forces(s.model.joints, s.x.data(), s.f.data(), s.slots);  // warm-up, gather built
  for (auto _ : state) {
    joint::add_joint_forces(s.model.joints, s.x.data(), s.f.data(), s.slots);
    benchmark::DoNotOptimize(s.f.data());
  }
  state.counters["joints_per_s"] =
      benchmark::Counter(static_cast<double>(s.model.joints.size()), benchmark::Counter::kIsIterationInvariantRate);
  const joint::JointSet& js = s.model.joints;
  double full = 0, points = 0;
  for (Index j = 0; j < js.size(); ++j)
    for (int g = 0; g < js.npf[j]; ++g) full += js.full[4 * static_cast<std::size_t>(j) + g], points += 1;
  state.counters["full_share"] = full / points;
}

// Every joint broken, its points in full: the crushed zone of an impact, where the kernel runs
// each point's residual friction (a vector on the face's frame) rather than the lean path.
// The same box and jumps as above, ten times larger: about half the points are pressed, the
// others open. Between calls only one node moves, so almost every point takes an elastic
// (sticking) step: this times the broken point's path, not its sliding. Counter:
// joints_per_s.
void BM_JointForcesBroken(benchmark::State& state) {
  omp_set_num_threads(static_cast<int>(state.range(0)));
  const Setup& base = setup(static_cast<int>(state.range(1)), static_cast<int>(state.range(2)));
  state.SetLabel(kFaceNames[state.range(1)]);
  joint::JointSet js = base.model.joints;
  for (Index j = 0; j < js.size(); ++j) {
    js.status[j] = joint::JointStatus::Broken;
    for (int g = 0; g < js.npf[j]; ++g)
      js.full_point(4 * static_cast<std::size_t>(j) + g).status = joint::JointStatus::Broken;
  }
  std::vector<Real> x = base.x;
  // Jumps ten times the intact benchmark's: broken faces slide and press well past w_ft.
  for (std::size_t i = 0; i < x.size(); ++i) x[i] = base.model.fem.x0[i] + 10 * (base.x[i] - base.model.fem.x0[i]);
  time_with_a_node_moving(state, js, x);
}

// Every point kept in full and softening, none broken: a body after its stress wave, most of
// whose joints have passed their strength somewhere (the sphere at 7.5 m/s: nearly every joint
// holds a point in full by 0.5 ms, a tenth are broken at the end), where the kernel runs each
// point's full law on its unbroken branch. Each point is given a history of an opening 1.5
// w_ft (its secant branch; far below w_ft + w_GI), under the jumps of BM_JointForces. Counters:
// joints_per_s, softening_share (1 unless a point broke or healed, which cannot happen).
void BM_JointForcesSoftening(benchmark::State& state) {
  omp_set_num_threads(static_cast<int>(state.range(0)));
  const Setup& base = setup(static_cast<int>(state.range(1)), static_cast<int>(state.range(2)));
  state.SetLabel(kFaceNames[state.range(1)]);
  joint::JointSet js = base.model.joints;
  for (Index j = 0; j < js.size(); ++j) {
    const joint::CohesiveParams& p = js.params[js.param[j]];
    for (int g = 0; g < js.npf[j]; ++g) {
      joint::CohesiveState& st = js.full_point(4 * static_cast<std::size_t>(j) + g);
      st.dn_max = 1.5 * p.ft / p.kn;
      st.status = joint::JointStatus::Softening;
    }
  }
  std::vector<Real> x = base.x;
  time_with_a_node_moving(state, js, x);
  double softening = 0, points = 0;
  for (Index j = 0; j < js.size(); ++j)
    for (int g = 0; g < js.npf[j]; ++g)
      softening += js.state[4 * static_cast<std::size_t>(j) + g].status == joint::JointStatus::Softening, points += 1;
  state.counters["softening_share"] = softening / points;
}

void BM_JointForcesReference(benchmark::State& state) {
  Setup& s = setup(static_cast<int>(state.range(0)), static_cast<int>(state.range(1)));
  state.SetLabel(kFaceNames[state.range(0)]);
  // Its own copy: the oracle keeps every point in full, and on the shared joints it would
  // leave BM_JointForces timing the full law from then on.
  joint::JointSet js = s.model.joints;
  for (auto _ : state) {
    joint::add_joint_forces_reference(js, s.x.data(), s.f.data());
    benchmark::DoNotOptimize(s.f.data());
  }
  state.counters["joints_per_s"] =
      benchmark::Counter(static_cast<double>(s.model.joints.size()), benchmark::Counter::kIsIterationInvariantRate);
}
}  // namespace

BENCHMARK(BM_JointForces)
    ->ArgsProduct({{1, 2}, {TriGauss, TriNodal, QuadGauss}, {0, 1}})
    ->ArgNames({"threads", "faces", "small"})
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();
BENCHMARK(BM_JointForcesBroken)
    ->ArgsProduct({{1}, {TriGauss, QuadGauss}, {0, 1}})
    ->ArgNames({"threads", "faces", "small"})
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();
BENCHMARK(BM_JointForcesSoftening)
    ->ArgsProduct({{1}, {TriGauss, QuadGauss}, {0, 1}})
    ->ArgNames({"threads", "faces", "small"})
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();
BENCHMARK(BM_JointForcesReference)
    ->ArgsProduct({{TriGauss, TriNodal, QuadGauss}, {0, 1}})
    ->ArgNames({"faces", "small"})
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();
BENCHMARK_MAIN();
