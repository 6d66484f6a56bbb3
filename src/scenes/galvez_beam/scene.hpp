// The Galvez notched beam (paper section 2.3): `dspdem report` runs the case, then writes
// report.md with load against CMOD and against the load-point deflection, the peak, the
// crack path from the broken joints, the quasi-static check, frames, the energy ledger and,
// with --study, the speed-against-error sweep.
#pragma once
#include "io/case_config.hpp"
#include "report/report_args.hpp"

namespace dspdem {

int galvez_beam_report(const CaseConfig& c, const report::ReportArgs& a);

}  // namespace dspdem
