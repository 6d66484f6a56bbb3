// `dspdem report CASE.toml`: runs the Brazilian disc scene and writes DIR/report.md with
// its figures: load curves and splitting strength against f_t, stresses along the loaded
// diameter against the analytic solution, frames and animation, the energy ledger, and
// (with --study) a speed-against-error table over mesh sizes and the accuracy knobs.
#pragma once
#include <string>
#include <vector>

namespace dspdem {

struct ReportArgs {
  std::string case_file, out_dir;
  std::vector<std::string> sets;
  bool study = false;            ///< also run the speed-against-error sweep
  bool no_render = false;        ///< skip images (numbers and plots only)
  std::string from_run;          ///< analyse this finished run of the same case instead of running it
  bool no_stress_check = false;  ///< skip the elastic run on a load-resolving mesh
};

int report_command(const ReportArgs& a);

}  // namespace dspdem
