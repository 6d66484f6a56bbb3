// Distributed runs (mpirun -n 2, and -n 4 oversubscribed on this 2-core box) against the
// one-process run of the same case, on three scenes: the double-edge-notched bar pulled until
// its joints break (joints only), the Brazilian disc (a coarse mesh) loaded by its jaws until
// it splits (joints, contact between the pieces, walls) and a packing of falling particles
// (contact only: hundreds of contacts between particles held by different processes). What
// must hold (par/subdomain.hpp, contact/contact_system.hpp): every node moves to the same bit,
// because each own node gets the same force terms in the same order, contact terms included;
// the wall forces too (added in the one-process order on every process); the ledger and the
// monitors are sums over nodes or pairs added in another order (per process, then over
// processes), so they agree to the rounding of those sums, far below the 10 digits
// series.csv prints.
#include <fmt/format.h>
#include <gtest/gtest.h>
#include <vtkCellData.h>
#include <vtkIdTypeArray.h>
#include <vtkIntArray.h>
#include <vtkNew.h>
#include <vtkPoints.h>
#include <vtkUnstructuredGrid.h>
#include <vtkXMLPUnstructuredGridReader.h>
#include <vtkXMLUnstructuredGridReader.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <map>
#include <sstream>

#include "io/run_summary.hpp"
#include "support/cli.hpp"

namespace fs = std::filesystem;
using dspdem::testsupport::shell;

namespace {

const std::string kCase = std::string(DSPDEM_SOURCE_DIR) + "/tests/data/notched_bar.toml";
const std::string kFields = " --set 'output.fields=[\"displacement\", \"element\", \"stress\", \"von_mises\"]'";

struct Scene {
  std::string name, args;
  int last_frame;  ///< the frame compared cell by cell
};
// `run` of a case file with --set overrides and the fields the comparison reads.
std::string run_args(const std::string& file, const std::string& sets) { return "run " + file + " " + sets + kFields; }
const std::string kCases = std::string(DSPDEM_SOURCE_DIR) + "/cases/";
// To 0.56 ms: past the peak force (0.40 ms) and the split into two halves (by 0.55 ms: 0.383
// and 0.381 kg; checked below); frames at 0, 0.28 and 0.56 ms.
const Scene kBar{"bar", run_args(kCase, "--set time.end=5.6e-4 --set output.frame_interval=2.8e-4"), 2};
// 20 mm elements (1034 tetrahedra): the peak load at 2.9 ms, the disc in pieces by 3.7 ms,
// where the case's stop rule ends it (the load fallen to 40 % of the peak); 34298 steps.
const Scene kDisc{
    "disc",
    run_args(kCases + "brazilian_disc.toml", "--set mesh.brazilian_disc.size=0.02 --set output.frame_interval=1e-3"),
    4};
// 200 particles for 1.6 s: the first land at 0.8 s; at 1.6 s some 400 contacts, between
// particles and with the floor.
const Scene kPacking{"packing",
                     run_args(kCases + "packing.toml",
                              "--set mesh.packing.count=200 --set time.end=1.6 --set output.frame_interval=0.8"),
                     2};

fs::path work_path() { return fs::temp_directory_path() / ("dspdem_mpi_" + std::to_string(getpid())); }

fs::path work() {
  static const fs::path d = [] {
    const fs::path p = work_path();
    fs::remove_all(p);
    fs::create_directories(p);
    return p;
  }();
  return d;
}

// ctest runs each test in a process of its own, so each leaves a folder of its own: removed
// when the process's tests passed (every CI run left one per test in /tmp before), kept for a
// look when one failed.
class RemoveWorkFolder : public ::testing::Environment {
 public:
  void TearDown() override {
    const fs::path p = work_path();
    if (!fs::exists(p)) return;
    if (::testing::UnitTest::GetInstance()->Passed()) {
      std::error_code ec;
      fs::remove_all(p, ec);
    } else {
      std::cerr << "test_mpi_run: the runs are kept in " << p.string() << "\n";
    }
  }
};
const auto* const kRemoveWorkFolder = ::testing::AddGlobalTestEnvironment(new RemoveWorkFolder);

std::string mpirun(int n) {
  // Root in containers and CI; more processes than cores is fine for correctness. A waiting
  // process yields its core (four processes on two cores: the disc's run 15 s instead of 18).
  return fmt::format(
      "env OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 OMPI_MCA_rmaps_base_oversubscribe=1 "
      "OMPI_MCA_mpi_yield_when_idle=1 mpirun -n {} ",
      n);
}

// The one-process run, then the distributed ones, each once per test program.
const fs::path& run_dir(const Scene& sc, int n) {
  static std::map<std::string, fs::path> dirs;
  const std::string key = fmt::format("{}_n{}", sc.name, n);
  auto it = dirs.find(key);
  if (it != dirs.end()) return it->second;
  const fs::path d = work() / key;
  const std::string cmd = fmt::format("{}{} -t 1 -q {} --no-progress --out {}", n == 0 ? std::string() : mpirun(n),
                                      DSPDEM_BIN, sc.args, d.string());
  const auto r = shell(cmd);
  EXPECT_EQ(r.code, 0) << cmd << "\n" << r.out;
  return dirs[key] = d;
}

struct Series {
  std::vector<std::string> names;
  std::vector<std::vector<double>> rows;
};

Series read_series(const fs::path& p) {
  Series s;
  std::ifstream f(p);
  std::string line;
  std::getline(f, line);
  std::stringstream h(line);
  for (std::string c; std::getline(h, c, ',');) s.names.push_back(c);
  while (std::getline(f, line)) {
    std::vector<double> row;
    std::stringstream l(line);
    for (std::string c; std::getline(l, c, ',');) row.push_back(std::stod(c));
    s.rows.push_back(row);
  }
  return s;
}

// Per element tag, its cell's corner positions.
std::map<long, std::vector<double>> cells_by_element(vtkUnstructuredGrid* g) {
  std::map<long, std::vector<double>> out;
  auto* tag = vtkIdTypeArray::SafeDownCast(g->GetCellData()->GetArray("element"));
  EXPECT_NE(tag, nullptr) << "no cell field 'element'";
  if (!tag) return out;
  for (vtkIdType c = 0; c < g->GetNumberOfCells(); ++c) {
    std::vector<double> xs;
    vtkIdType np = 0;
    const vtkIdType* ids = nullptr;
    g->GetCellPoints(c, np, ids);
    for (vtkIdType k = 0; k < np; ++k) {
      double p[3];
      g->GetPoint(ids[k], p);
      xs.insert(xs.end(), p, p + 3);
    }
    EXPECT_TRUE(out.emplace(static_cast<long>(tag->GetValue(c)), xs).second)
        << "element " << tag->GetValue(c) << " twice";
  }
  return out;
}

// What every scene must show on n processes: the series, the last compared frame's cells,
// each element's fragment and fragments.csv as on one process.
void compare_dirs(const fs::path& one, const fs::path& many, int n, int last_frame) {
  ASSERT_TRUE(fs::exists(many / "summary.json")) << "no distributed run in " << many;
  const dspdem::RunSummary sn = dspdem::read_run_summary((many / "summary.json").string());
  const dspdem::RunSummary s1 = dspdem::read_run_summary((one / "summary.json").string());
  EXPECT_EQ(sn.processes, n);
  EXPECT_EQ(s1.processes, 1);
  // Contact pairs first found overlapping: each counted once, by one process, the same
  // pairs at the same positions (the energy sum is compared as series.csv's column below).
  // (Unknown, pairs -1, in a run without contact.)
  for (auto [b1, bn] : {std::pair{&s1.born_split, &sn.born_split}, std::pair{&s1.born_unseen, &sn.born_unseen},
                        std::pair{&s1.born_wall, &sn.born_wall}}) {
    EXPECT_EQ(bn->pairs, b1->pairs);
    if (b1->pairs >= 0) {
      EXPECT_EQ(bn->max_ratio, b1->max_ratio);
    }
  }

  const Series a = read_series(one / "series.csv"), b = read_series(many / "series.csv");
  ASSERT_EQ(a.names, b.names);
  ASSERT_EQ(a.rows.size(), b.rows.size());
  ASSERT_GT(a.rows.size(), 10u);
  for (std::size_t k = 0; k < a.names.size(); ++k) {
    double scale = 0;
    for (const auto& r : a.rows) scale = std::max(scale, std::abs(r[k]));
    for (std::size_t i = 0; i < a.rows.size(); ++i)
      // 10 printed digits: a sum added in another order may round the last one otherwise.
      EXPECT_LE(std::abs(a.rows[i][k] - b.rows[i][k]), 2e-10 * scale)
          << a.names[k] << " at row " << i << ": one process " << a.rows[i][k] << ", " << n << " processes "
          << b.rows[i][k];
  }

  // The last frame: every element once over the pieces, at the same positions to the bit.
  vtkNew<vtkXMLUnstructuredGridReader> r1;
  const std::string frame = fmt::format("frame_{:04d}", last_frame);
  r1->SetFileName((one / "frames" / (frame + ".vtu")).c_str());
  r1->Update();
  vtkNew<vtkXMLPUnstructuredGridReader> rn;
  rn->SetFileName((many / "frames" / (frame + ".pvtu")).c_str());
  rn->Update();
  vtkUnstructuredGrid* g1 = r1->GetOutput();
  vtkUnstructuredGrid* gn = rn->GetOutput();
  ASSERT_GT(g1->GetNumberOfCells(), 150);
  ASSERT_EQ(gn->GetNumberOfCells(), g1->GetNumberOfCells());
  auto* rank = vtkIntArray::SafeDownCast(gn->GetCellData()->GetArray("rank"));
  ASSERT_NE(rank, nullptr);
  std::vector<int> per_rank(static_cast<std::size_t>(n), 0);
  for (vtkIdType c = 0; c < gn->GetNumberOfCells(); ++c) {
    const int r = rank->GetValue(c);
    ASSERT_TRUE(r >= 0 && r < n);
    ++per_rank[r];
  }
  for (int r = 0; r < n; ++r)
    EXPECT_GT(per_rank[r], g1->GetNumberOfCells() / (2 * n)) << "process " << r << " owns too few elements";
  const auto c1 = cells_by_element(g1), cn = cells_by_element(gn);
  ASSERT_EQ(c1.size(), cn.size());
  long moved = 0, differ = 0;
  for (const auto& [tag, xs] : c1) {
    const auto it = cn.find(tag);
    ASSERT_NE(it, cn.end()) << "element " << tag << " missing from the pieces";
    if (it->second != xs && differ++ < 3)
      ADD_FAILURE() << "element " << tag << " is elsewhere on " << n << " processes";
    ++moved;
  }
  EXPECT_EQ(differ, 0) << "of " << moved << " elements";

  // The same pieces, named alike: each element's fragment id, and fragments.csv (count, ids
  // and element counts exactly; masses and centroids to rounding, summed per process first).
  auto fragment_of = [](vtkUnstructuredGrid* g) {
    std::map<long, int> out;
    auto* tag = vtkIdTypeArray::SafeDownCast(g->GetCellData()->GetArray("element"));
    auto* frag = vtkIntArray::SafeDownCast(g->GetCellData()->GetArray("fragment"));
    EXPECT_TRUE(tag && frag) << "no cell fields 'element' and 'fragment'";
    for (vtkIdType c = 0; tag && frag && c < g->GetNumberOfCells(); ++c)
      out[static_cast<long>(tag->GetValue(c))] = frag->GetValue(c);
    return out;
  };
  EXPECT_TRUE(fragment_of(g1) == fragment_of(gn)) << "fragment ids differ on " << n << " processes";
  const Series f1 = read_series(one / "fragments.csv"), fn = read_series(many / "fragments.csv");
  ASSERT_EQ(f1.rows.size(), fn.rows.size());
  ASSERT_FALSE(f1.rows.empty());
  for (std::size_t i = 0; i < f1.rows.size(); ++i)
    for (std::size_t k = 0; k < f1.names.size(); ++k) {
      const bool exact = f1.names[k] == "count" || f1.names[k] == "id" || f1.names[k] == "elements";
      EXPECT_LE(std::abs(f1.rows[i][k] - fn.rows[i][k]), exact ? 0.0 : 1e-9 * std::abs(f1.rows[i][k]))
          << "fragments.csv " << f1.names[k] << " at row " << i;
    }
}

void compare_runs(const Scene& sc, int n) { compare_dirs(run_dir(sc, 0), run_dir(sc, n), n, sc.last_frame); }

// The last row of series.csv's column `name` (one-process run).
double last(const Series& s, const std::string& name) {
  for (std::size_t k = 0; k < s.names.size(); ++k)
    if (s.names[k] == name) return s.rows.back()[k];
  ADD_FAILURE() << "no column " << name;
  return 0;
}

}  // namespace

// One test per scene for both counts: the one-process run is then made once.
TEST(Mpi, TwoAndFourProcessesMoveEveryNodeAsOneProcess) {
  compare_runs(kBar, 2);
  compare_runs(kBar, 4);
  const fs::path& one = run_dir(kBar, 0);
  const Series a = read_series(one / "series.csv");
  EXPECT_GT(last(a, "broken_joints"), 40) << "the bar must have cracked in the window the test compares";
  // The notches' joint monitor: its column is compared with the distributed runs' above (each
  // process counts its own joints; counting a joint on two would show there). Here, in the
  // one-process run: every broken joint lies between the notches (measured 59 of 59).
  EXPECT_EQ(last(a, "notch_cracks"), last(a, "broken_joints")) << "the crack must run between the notches";
  // Columns frame,time,count,rank,id,mass,...: at the last frame, ranks 1 and 2 are the halves.
  const Series f1 = read_series(one / "fragments.csv");
  int halves = 0;
  for (const auto& r : f1.rows)
    if (r[0] == f1.rows.back()[0] && r[3] <= 2 && r[5] > 0.3) ++halves;
  EXPECT_EQ(halves, 2) << "the bar must be in two halves at the last frame";

  // The renderer reads the pieces as one grid: the same picture as the one-process run's.
  const fs::path& many = run_dir(kBar, 4);
  for (const fs::path* d : {&one, &many}) {
    const auto r =
        shell(fmt::format("{} -q render {} --view stress --frames last --size 480x320", DSPDEM_BIN, d->string()));
    ASSERT_EQ(r.code, 0) << r.out;
  }
  const fs::path png = fs::path("images") / "stress" / "frame_0002.png";
  const auto diff = shell(fmt::format("{} imgdiff {} {} --diff {}", DSPDEM_BIN, (one / png).string(),
                                      (many / png).string(), (many / "stress_diff.png").string()));
  EXPECT_EQ(diff.code, 0) << diff.out;
}

// Contact between pieces held by different processes, loaded through rigid walls: the
// jaws' forces (the disc's load) are the same to the bit, and so are the pieces.
TEST(Mpi, TheBrazilianDiscSplitsAsOnOneProcess) {
  compare_runs(kDisc, 2);
  compare_runs(kDisc, 4);
  const Series a = read_series(run_dir(kDisc, 0) / "series.csv");
  double peak = 0;
  for (std::size_t k = 0; k < a.names.size(); ++k)
    if (a.names[k] == "jaw_top_fy")
      for (const auto& r : a.rows) peak = std::max(peak, r[k]);
  EXPECT_GT(peak, 2.0e4) << "the jaws must load the disc";  // some 35 kN
  EXPECT_GT(last(a, "broken_joints"), 100) << "the disc must have split in the window compared";
  EXPECT_GT(last(a, "contacts"), 10) << "contact must carry the pieces";
  // The split's neighbours are first found overlapping (their compression): counted alike on
  // every process count (compare_runs), so the count must not be zero here.
  EXPECT_GT(dspdem::read_run_summary((run_dir(kDisc, 0) / "summary.json").string()).born_split.pairs, 0);
  const Series f = read_series(run_dir(kDisc, 0) / "fragments.csv");
  EXPECT_GE(f.rows.back()[2], 2) << "the disc must be in pieces at the last frame";
}

// Contact only, hundreds of contacts, particles moving from one process's part to another's.
TEST(Mpi, APackingSettlesAsOnOneProcess) {
  compare_runs(kPacking, 2);
  compare_runs(kPacking, 4);
  const Series a = read_series(run_dir(kPacking, 0) / "series.csv");
  EXPECT_GT(last(a, "contacts"), 200);
  EXPECT_GT(last(a, "friction"), 0);
}

TEST(Mpi, UnsupportedFeaturesAndCommandsAreRefusedByName) {
  // Extrinsic insertion: a clear message and a non-zero exit, on every process.
  auto r = shell(fmt::format("{}{} -q run {} --set 'bodies.0.fracture_insertion=\"extrinsic\"' --out {}", mpirun(2),
                             DSPDEM_BIN, kCase, (work() / "refused").string()));
  EXPECT_NE(r.code, 0);
  EXPECT_NE(r.out.find("extrinsic joint insertion is not yet supported in a distributed run"), std::string::npos)
      << r.out;
  EXPECT_FALSE(fs::exists(work() / "refused" / "summary.json"));
  // Only `run` is distributed.
  r = shell(fmt::format("{}{} keys", mpirun(2), DSPDEM_BIN));
  EXPECT_NE(r.code, 0);
  EXPECT_NE(r.out.find("only `dspdem run` runs on several processes"), std::string::npos) << r.out;
}

// A real SIGTERM to each process while the disc is loaded (as a batch system sends one to
// every task of a job): the processes see it at different steps, agree on one, write one
// checkpoint file each and end with status 5. A restart on another number of processes is
// refused by name; on the same number it ends as the one-process run, to the bit.
TEST(Mpi, ASignalledRunRestartsOnAsManyProcessesAsTheUninterruptedRun) {
  const fs::path dir = work() / "signalled";
  const std::string cmd =
      fmt::format("{}{} -t 1 -q {} --no-progress --out {}", mpirun(2), DSPDEM_BIN, kDisc.args, dir.string());
  // Started in the background; once its second frame (1 ms of 3.7) is there, each dspdem
  // process of this run (not mpirun: it would end them its own way) gets a SIGTERM.
  const auto r = shell(fmt::format(
      "({} > {}/log.txt 2>&1; echo $? > {}/status) & "
      "for i in $(seq 600); do ls {}/.staging-*/frames/frame_0001.pvtu >/dev/null 2>&1 && break; sleep 0.2; done; "
      "for p in $(pgrep -f -- '--out {}'); do [ \"$(cat /proc/$p/comm)\" = dspdem ] && kill -TERM $p; done; wait",
      cmd, work().string(), dir.string(), dir.string(), dir.string()));
  ASSERT_EQ(r.code, 0) << r.out;
  std::ifstream st(dir / "status");
  int status = -1;
  st >> status;
  EXPECT_NE(status, 0) << "the run was not stopped";
  ASSERT_TRUE(fs::exists(dir / "interrupted_run" / "checkpoint.bin"))
      << shell("cat " + (work() / "log.txt").string()).out;
  ASSERT_TRUE(fs::exists(dir / "interrupted_run" / "checkpoint.1.bin"));
  EXPECT_EQ(dspdem::read_run_summary((dir / "interrupted_run" / "summary.json").string()).status, "interrupted");

  auto one = shell(fmt::format("{} -t 1 -q run --restart {} --no-progress", DSPDEM_BIN, dir.string()));
  EXPECT_NE(one.code, 0);
  EXPECT_NE(one.out.find("restart it on as many (mpirun -n 2 dspdem run --restart ...)"), std::string::npos) << one.out;
  ASSERT_TRUE(fs::exists(dir / "interrupted_run" / "checkpoint.bin")) << "a refused restart must keep the checkpoint";
  // A copy missing a piece of a frame its .pvtu lists: refused, naming it (a review's: the
  // pieces were listed from the folder, so a piece gone passed into the "completed" run).
  const fs::path cut = work() / "signalled_piece_gone";
  fs::copy(dir, cut, fs::copy_options::recursive);
  fs::remove(cut / "interrupted_run" / "frames" / "frame_0001_1.vtu");
  const auto gone =
      shell(fmt::format("{}{} -t 1 -q run --restart {} --no-progress", mpirun(2), DSPDEM_BIN, cut.string()));
  EXPECT_NE(gone.code, 0);
  EXPECT_NE(gone.out.find("frame_0001_1.vtu' of the checkpoint's run is missing"), std::string::npos) << gone.out;
  EXPECT_TRUE(fs::exists(cut / "interrupted_run" / "checkpoint.bin"));

  const auto again =
      shell(fmt::format("{}{} -t 1 -q run --restart {} --no-progress", mpirun(2), DSPDEM_BIN, dir.string()));
  ASSERT_EQ(again.code, 0) << again.out;
  EXPECT_FALSE(fs::exists(dir / "interrupted_run"));
  compare_dirs(run_dir(kDisc, 0), dir, 2, kDisc.last_frame);
}

// Hard case: an unstable step blows the bar up. Whichever process sees it first (a node's
// non-finite position is seen by its owner only), every process must end, with the failure
// named and a non-zero exit, not wait for the others for ever.
TEST(Mpi, ANumericalFailureOnOneProcessEndsThemAll) {
  const auto r = shell(fmt::format(
      "timeout 300 {}{} -t 1 run {} --set time.dt=1.2e-7 --set time.allow_unstable=true --set time.end=2e-4 "
      "--no-progress --out {}",
      mpirun(2), DSPDEM_BIN, kCase, (work() / "unstable").string()));
  EXPECT_NE(r.code, 0);
  EXPECT_NE(r.code, 124) << "timed out: a process waited for ever\n" << r.out;
  EXPECT_NE(r.out.find("numerical failure"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("of 2; frames so far in"), std::string::npos) << r.out;
  EXPECT_FALSE(fs::exists(work() / "unstable" / "summary.json"));
}
