// Reading a .msh in the sandboxed child process (mesh/gmsh_reader: fork, gmsh reads, the
// model comes back through a pipe and is loaded into this process's gmsh) against gmsh reading
// it here, as read_gmsh did before the sandbox. Both give the same Mesh. A box of tetrahedra
// at two sizes, and the sandbox's own cost (a child that returns nothing). Counter:
// time_per_element (wall time of one read / elements).
//   build/tests/bench/bench_mesh_read --benchmark_min_time=1
#include <benchmark/benchmark.h>
#include <gmsh.h>
#include <unistd.h>

#include <filesystem>
#include <map>

#include "core/sandbox.hpp"
#include "mesh/gmsh_reader.hpp"

using namespace dspdem;

namespace {
// A unit box meshed with tetrahedra of size h, written once per size.
const std::string& box_msh(double h) {
  static std::map<double, std::string> files;
  auto it = files.find(h);
  if (it != files.end()) return it->second;
  const auto path = std::filesystem::temp_directory_path() /
                    ("dspdem_bench_box_" + std::to_string(getpid()) + "_" + std::to_string(files.size()) + ".msh");
  {
    GmshSession session;
    gmsh::model::add("box");
    gmsh::model::occ::addBox(0, 0, 0, 1, 1, 1);
    gmsh::model::occ::synchronize();
    gmsh::model::addPhysicalGroup(3, {1}, 1);
    gmsh::option::setNumber("Mesh.MeshSizeMax", h);
    gmsh::option::setNumber("Mesh.MeshSizeMin", h);
    gmsh::model::mesh::generate(3);
    gmsh::write(path.string());
  }
  return files.emplace(h, path.string()).first->second;
}

void report(benchmark::State& state, const Mesh& m) {
  state.counters["elements"] = static_cast<double>(m.n_elements());
  state.counters["time_per_element"] = benchmark::Counter(
      static_cast<double>(m.n_elements()), benchmark::Counter::kIsIterationInvariantRate | benchmark::Counter::kInvert);
}

double size_of(const benchmark::State& state) { return 1.0 / static_cast<double>(state.range(0)); }

void BM_ReadHere(benchmark::State& state) {
  const std::string& f = box_msh(size_of(state));
  Mesh m;
  for (auto _ : state) {
    GmshSession session;
    gmsh::open(f);
    m = mesh_from_gmsh_model(f);
    benchmark::DoNotOptimize(m.x.data());
  }
  report(state, m);
}

void BM_ReadSandboxed(benchmark::State& state) {
  const std::string& f = box_msh(size_of(state));
  Mesh m;
  for (auto _ : state) {
    m = read_gmsh_unchecked(f);
    benchmark::DoNotOptimize(m.x.data());
  }
  report(state, m);
}
}  // namespace

// 1/h = 12 and 30: about 10 thousand and 160 thousand tetrahedra.
// Wall time: the child's work is not this process's CPU time.
BENCHMARK(BM_ReadHere)->Arg(12)->Arg(30)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(BM_ReadSandboxed)->Arg(12)->Arg(30)->Unit(benchmark::kMillisecond)->UseRealTime();

namespace {
void BM_EmptySandbox(benchmark::State& state) {
  for (auto _ : state) benchmark::DoNotOptimize(dspdem::run_sandboxed([] { return std::string(); }, 10).status);
}
}  // namespace
BENCHMARK(BM_EmptySandbox)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK_MAIN();
