// The packing end to end (issue 19): `dspdem report cases/packing.toml` on 200 particles
// (one layer over the floor) to 3 s (the run of the figures site, the scene's quick_args, read
// here: support/quick_report.hpp), and the same case on 1 and 2 threads.
// - The particles come to rest (kinetic energy below 1e-4 of the potential energy
//   released, from some time to the end), none leaves the box, and the energy ledger closes
//   within 1 % of its largest term.
// - At rest the floor carries the weight: one layer leans on no wall, so the floor force
//   equals m g to within 1 % (the resting contacts' springs hold it exactly; the 1 % covers
//   the last creep of the series row).
// - The variant with particles as small meshed polyhedra (mesh.packing.refine = 1: 8 tets
//   each, one deformable body per particle): 24 particles dropped on the floor come to rest,
//   counted as 24 particles (their cells grouped by body), with the floor carrying them.
// - Contact is evaluated in parallel and added up in a fixed order: with a few hundred
//   candidate pairs (the parallel path) the series of 1 and 2 threads are bitwise equal.
#include <gtest/gtest.h>

#include <filesystem>

#include "core/file.hpp"
#include "report/run_data.hpp"
#include "scenes/packing/analysis.hpp"
#include "support/cli.hpp"
#include "support/quick_report.hpp"

namespace fs = std::filesystem;
using namespace dspdem;

namespace {
const std::string kCase = std::string(DSPDEM_SOURCE_DIR) + "/cases/packing.toml";
const std::string kSmall = " --set mesh.packing.count=200";

// "" for a file that is not there: the comparisons then name it.
std::string slurp(const fs::path& p) { return dspdem::read_file_if(p).value_or(""); }
}  // namespace

TEST(Packing, ParticlesComeToRestInTheBoxWithTheLedgerClosed) {
  const fs::path out = testsupport::quick_report("packing");
  ASSERT_TRUE(fs::exists(out / "report.md"));
  const CaseConfig c = read_case((out / "run" / "case.resolved.toml").string());
  ASSERT_EQ(c.t_end, 3.0) << "the run is not the one this test is for";
  const PackingResult r = analyse_packing_run(c, (out / "run").string(), "");
  RecordProperty("t_rest", std::to_string(r.t_rest));
  RecordProperty("balance", std::to_string(r.balance_max));
  EXPECT_EQ(r.particles, 200);
  EXPECT_GE(r.t_rest, 0.0) << "kinetic / released at the end " << r.kinetic_end / r.released;
  EXPECT_EQ(r.escaped, 0);
  EXPECT_LT(r.balance_max, 0.01);
  const report::Series s((out / "run" / "packing_series.csv").string());
  EXPECT_NEAR(s["floor_force_over_weight"].back(), 1.0, 0.01);
}

TEST(Packing, OneAndTwoThreadsGiveTheSameBits) {
  const fs::path out = fs::temp_directory_path() / "dspdem_packing_threads";
  fs::remove_all(out);
  for (int t : {1, 2}) {
    const auto run = testsupport::shell(std::string(DSPDEM_BIN) + " -q -t " + std::to_string(t) + " run " + kCase +
                                        " --out " + (out / std::to_string(t)).string() + kSmall +
                                        " --set time.end=1.6 --set output.frame_interval=0.4");
    ASSERT_EQ(run.code, 0) << run.out;
  }
  const std::string a = slurp(out / "1" / "series.csv"), b = slurp(out / "2" / "series.csv");
  EXPECT_GT(a.size(), 1000u);
  EXPECT_EQ(a, b);
  // The comparison means something only if contact was busy: many touches at the end.
  const report::Series s((out / "1" / "series.csv").string());
  EXPECT_GT(s["contacts"].back(), 200);
}

TEST(Packing, MeshedParticlesComeToRestOnTheFloor) {
  const fs::path out = fs::temp_directory_path() / "dspdem_packing_meshed";
  fs::remove_all(out);
  const auto run =
      testsupport::shell(std::string(DSPDEM_BIN) + " -q -t 1 report " + kCase + " --no-render --out " + out.string() +
                         " --set mesh.packing.count=24 --set mesh.packing.refine=1 --set time.end=3.0");
  ASSERT_EQ(run.code, 0) << run.out;
  const CaseConfig c = read_case((out / "run" / "case.resolved.toml").string());
  const PackingResult r = analyse_packing_run(c, (out / "run").string(), "");
  EXPECT_EQ(r.particles, 24);  // 192 cells, 8 per particle
  EXPECT_GE(r.t_rest, 0.0) << "kinetic / released at the end " << r.kinetic_end / r.released;
  EXPECT_EQ(r.escaped, 0);
  EXPECT_LT(r.balance_max, 0.01);
  const report::Series s((out / "run" / "packing_series.csv").string());
  EXPECT_NEAR(s["floor_force_over_weight"].back(), 1.0, 0.01);
}
