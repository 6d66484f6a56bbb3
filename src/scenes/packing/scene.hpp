// The packing (paper section 2.1, its efficiency case): `dspdem report` runs the case and
// writes report.md with the heap at rest (surface height, packing fraction, contacts per
// particle, escaped particles), the decay of the kinetic energy, the energy ledger, the
// final heap from two sides and the run's speed in particle-steps per second.
#pragma once
#include "io/case_config.hpp"
#include "report/report_args.hpp"

namespace dspdem {

int packing_report(const CaseConfig& c, const report::ReportArgs& a);

}  // namespace dspdem
