// The impact beam (paper section 2.4, Murray et al. 2007): `dspdem report` runs the case,
// then writes report.md with the pieces and their masses over time, the cracks in the order
// they appear, deflection, impactor velocities and contact forces, frames, the energy ledger
// and, with --study, the speed-against-error sweep with the hard cases (2x and 4x the speed).
#pragma once
#include "io/case_config.hpp"
#include "report/report_args.hpp"

namespace dspdem {

int murray_beam_report(const CaseConfig& c, const report::ReportArgs& a);

}  // namespace dspdem
