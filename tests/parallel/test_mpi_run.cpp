// Distributed runs (mpirun -n 2, and -n 4 oversubscribed on this 2-core box) against the
// one-process run of the same case: the double-edge-notched bar pulled until its joints
// break. What must hold (par/subdomain.hpp): every node moves to the same bit, because each
// own node gets the same force terms in the same order; the ledger and the monitors are sums
// over nodes added in another order (per process, then over processes), so they agree to the
// rounding of those sums, far below the 10 digits series.csv prints.
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
#include <map>
#include <sstream>

#include "io/run_summary.hpp"
#include "support/cli.hpp"

namespace fs = std::filesystem;
using dspdem::testsupport::shell;

namespace {

const std::string kCase = std::string(DSPDEM_SOURCE_DIR) + "/tests/data/notched_bar.toml";
// To 0.56 ms: past the peak force (0.40 ms) and the split into two halves (by 0.55 ms: 0.383
// and 0.381 kg; checked below); frames at 0, 0.28 and 0.56 ms.
const std::string kArgs =
    " -t 1 -q run " + kCase +
    " --set time.end=5.6e-4 --set output.frame_interval=2.8e-4"
    " --set 'output.fields=[\"displacement\", \"element\", \"stress\", \"von_mises\"]' --no-progress --out ";

fs::path work() {
  static const fs::path d = [] {
    const fs::path p = fs::temp_directory_path() / ("dspdem_mpi_" + std::to_string(getpid()));
    fs::remove_all(p);
    fs::create_directories(p);
    return p;
  }();
  return d;
}

std::string mpirun(int n) {
  // Root in containers and CI; more processes than cores is fine for correctness.
  return fmt::format(
      "env OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 OMPI_MCA_rmaps_base_oversubscribe=1 mpirun -n {} ",
      n);
}

// The one-process run, then the distributed ones, each once per test program.
const fs::path& run_dir(int n) {
  static std::map<int, fs::path> dirs;
  auto it = dirs.find(n);
  if (it != dirs.end()) return it->second;
  const fs::path d = work() / fmt::format("n{}", n);
  const std::string cmd = fmt::format("{}{}{}{}", n == 0 ? std::string() : mpirun(n), DSPDEM_BIN, kArgs, d.string());
  const auto r = shell(cmd);
  EXPECT_EQ(r.code, 0) << cmd << "\n" << r.out;
  return dirs[n] = d;
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

void compare_with_one_process(int n) {
  const fs::path& one = run_dir(0);
  const fs::path& many = run_dir(n);
  ASSERT_TRUE(fs::exists(many / "summary.json")) << "no distributed run in " << many;
  EXPECT_EQ(dspdem::read_run_summary((many / "summary.json").string()).processes, n);
  EXPECT_EQ(dspdem::read_run_summary((one / "summary.json").string()).processes, 1);

  const Series a = read_series(one / "series.csv"), b = read_series(many / "series.csv");
  ASSERT_EQ(a.names, b.names);
  ASSERT_EQ(a.rows.size(), b.rows.size());
  ASSERT_GT(a.rows.size(), 10u);
  std::size_t broken = 0;
  for (std::size_t k = 0; k < a.names.size(); ++k) {
    if (a.names[k] == "broken_joints") broken = k;
    double scale = 0;
    for (const auto& r : a.rows) scale = std::max(scale, std::abs(r[k]));
    for (std::size_t i = 0; i < a.rows.size(); ++i)
      // 10 printed digits: a sum added in another order may round the last one otherwise.
      EXPECT_LE(std::abs(a.rows[i][k] - b.rows[i][k]), 2e-10 * scale)
          << a.names[k] << " at row " << i << ": one process " << a.rows[i][k] << ", " << n << " processes "
          << b.rows[i][k];
  }
  ASSERT_GT(broken, 0u);
  EXPECT_GT(a.rows.back()[broken], 40) << "the bar must have cracked in the window the test compares";
  EXPECT_EQ(a.rows.back()[broken], b.rows.back()[broken]);

  // The last frame: every element once over the pieces, at the same positions to the bit.
  vtkNew<vtkXMLUnstructuredGridReader> r1;
  r1->SetFileName((one / "frames" / "frame_0002.vtu").c_str());
  r1->Update();
  vtkNew<vtkXMLPUnstructuredGridReader> rn;
  rn->SetFileName((many / "frames" / "frame_0002.pvtu").c_str());
  rn->Update();
  vtkUnstructuredGrid* g1 = r1->GetOutput();
  vtkUnstructuredGrid* gn = rn->GetOutput();
  ASSERT_GT(g1->GetNumberOfCells(), 1000);
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
  // Columns frame,time,count,rank,id,mass,...: at the last frame, ranks 1 and 2 are the halves.
  int halves = 0;
  for (const auto& r : f1.rows)
    if (r[0] == f1.rows.back()[0] && r[3] <= 2 && r[5] > 0.3) ++halves;
  EXPECT_EQ(halves, 2) << "the bar must be in two halves at the last frame";
  for (std::size_t i = 0; i < f1.rows.size(); ++i)
    for (std::size_t k = 0; k < f1.names.size(); ++k) {
      const bool exact = f1.names[k] == "count" || f1.names[k] == "id" || f1.names[k] == "elements";
      EXPECT_LE(std::abs(f1.rows[i][k] - fn.rows[i][k]), exact ? 0.0 : 1e-9 * std::abs(f1.rows[i][k]))
          << "fragments.csv " << f1.names[k] << " at row " << i;
    }

  // The renderer reads the pieces as one grid: the same picture as the one-process run's.
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

}  // namespace

// One test for both counts: the one-process run is then made once.
TEST(Mpi, TwoAndFourProcessesMoveEveryNodeAsOneProcess) {
  compare_with_one_process(2);
  compare_with_one_process(4);
}

TEST(Mpi, UnsupportedFeaturesAndCommandsAreRefusedByName) {
  // A case with contact: a clear message and a non-zero exit, on every process.
  const std::string contact = std::string(DSPDEM_SOURCE_DIR) + "/tests/data/split_block.toml";
  auto r = shell(fmt::format("{}{} -q run {} --set contact.enabled=true --out {}", mpirun(2), DSPDEM_BIN, contact,
                             (work() / "refused").string()));
  EXPECT_NE(r.code, 0);
  EXPECT_NE(r.out.find("[contact] is not yet supported in a distributed run"), std::string::npos) << r.out;
  EXPECT_FALSE(fs::exists(work() / "refused" / "summary.json"));
  // Only `run` is distributed.
  r = shell(fmt::format("{}{} keys", mpirun(2), DSPDEM_BIN));
  EXPECT_NE(r.code, 0);
  EXPECT_NE(r.out.find("only `dspdem run` runs on several processes"), std::string::npos) << r.out;
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
