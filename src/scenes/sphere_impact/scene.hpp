// The sphere impact (paper section 2.5): `dspdem report` runs the case at every speed of a
// sweep (separate processes, -j at a time), then writes report.md with the fragment
// statistics per speed against the paper's description, the montage of all speeds at the
// compared time (the paper's Fig. 22), the fragment mass distributions, cracks and plate
// force over time, where the impact energy went and, with --study, the speed-against-error
// rows at 7.5 and 20 m/s.
#pragma once
#include "io/case_config.hpp"
#include "report/report_args.hpp"

namespace dspdem {

int sphere_impact_report(const CaseConfig& c, const report::ReportArgs& a);

}  // namespace dspdem
