// Fracture on meshes not aligned with the crack (issue 15): the strength a facet crack reads
// must not depend on the mesh lining up with it. Runs the executable on an unstructured tet
// block in uniaxial tension (tests/data/tension_block.toml): the peak stress against f_t,
// with the coupled law and the inter-element shear parameters of cases/README.md, and with
// the paper's law and shear ratios (the bias it fixes). Tolerance: the 10 %.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <regex>
#include <sstream>
#include <string>
#include <vector>

#include "io/run_summary.hpp"
#include "support/cli.hpp"

namespace fs = std::filesystem;

namespace {
// Largest |value| of a column of series.csv.
double column_max_abs(const fs::path& csv, const std::string& col) {
  std::ifstream f(csv);
  std::string line;
  std::getline(f, line);
  std::vector<std::string> head;
  std::stringstream hs(line);
  for (std::string c; std::getline(hs, c, ',');) head.push_back(c);
  std::size_t k = 0;
  while (k < head.size() && head[k] != col) ++k;
  EXPECT_LT(k, head.size()) << col << " not in " << csv;
  double best = 0;
  while (std::getline(f, line)) {
    std::stringstream ls(line);
    std::string cell;
    for (std::size_t i = 0; i <= k && std::getline(ls, cell, ','); ++i) {
    }
    best = std::max(best, std::abs(std::stod(cell)));
  }
  return best;
}

fs::path run_case(const std::string& name, const std::string& case_file, const std::string& sets) {
  const fs::path out = fs::temp_directory_path() / ("dspdem_bias_" + name);
  fs::remove_all(out);
  const auto r = dspdem::testsupport::shell(std::string(DSPDEM_BIN) + " -q run " + DSPDEM_SOURCE_DIR + "/" + case_file +
                                            " --out " + out.string() + " " + sets);
  EXPECT_EQ(r.code, 0) << r.out;
  return out;
}

double block_strength_error(const fs::path& run) {
  const double area = 0.05 * 0.05, ft = 3e6;
  return column_max_abs(run / "series.csv", "force") / area / ft - 1;
}
}  // namespace

TEST(MeshBias, UnalignedTensionBlockReadsFtWithTheCoupledLaw) {
  const fs::path run = run_case("block", "tests/data/tension_block.toml", "");
  const double err = block_strength_error(run);
  EXPECT_LT(std::abs(err), 0.10) << "measured +6.4 %";  // the paper's law: +33 % (next test)
  const dspdem::RunSummary sum = dspdem::read_run_summary((run / "summary.json").string());
  EXPECT_GE(sum.fragments, 2);
  EXPECT_LT(sum.energy.balance_error, 0.01);
}

TEST(MeshBias, PapersLawOnTheSameBlockIsBiased) {
  // The bias the coupled law removes: the paper's law with its shear ratios (c = 8.7 f_t,
  // G_fII = 150 G_fI) on the same mesh. Measured +33 %; if this ever falls below +20 %, the
  // scene no longer shows the bias and the test above proves nothing.
  const fs::path run = run_case("block_paper", "tests/data/tension_block.toml",
                                "--set materials.concrete.joint_law=paper --set materials.concrete.cohesion=26.1e6 "
                                "--set materials.concrete.fracture_energy_II=1500");
  EXPECT_GT(block_strength_error(run), 0.20);
}
