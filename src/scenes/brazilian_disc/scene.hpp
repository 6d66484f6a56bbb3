// The Brazilian disc (paper section 2.2): `dspdem report` runs the case, then writes
// report.md with the plate load and splitting strength against f_t, the stresses along the
// loaded diameter against the point-load solution (and on a load-resolving mesh), the crack
// path, frames, the energy ledger and, with --study, the speed-against-error sweep.
#pragma once
#include "io/case_config.hpp"
#include "report/report_args.hpp"

namespace dspdem {

int brazilian_disc_report(const CaseConfig& c, const report::ReportArgs& a);

}  // namespace dspdem
