// `dspdem figures`: every scene's report, then one static site over them (report/site.hpp).
#pragma once
#include <string>
#include <vector>

namespace dspdem {

struct FiguresArgs {
  std::vector<std::string> cases;  ///< empty: every scene's shipped case
  std::string out = "results/figures";
  bool quick = false;           ///< CI-sized runs (each scene's quick_args)
  bool study = true;            ///< full set: each report with its speed-against-error study
  std::string from_runs;        ///< reuse the report folders FROM/<scene> made earlier; run nothing
  int threads = 0;              ///< passed to each report process (0: its default)
  bool resume = false;          ///< each report with --resume: the runs a stopped figures left are kept or continued
  std::string checkpoint_wall;  ///< each report with --checkpoint-wall this (empty: the reports' default)
};

int figures_command(const FiguresArgs& a);

}  // namespace dspdem
