// `dspdem report CASE.toml`: the report of the case's benchmark scene (scenes/registry).
#pragma once
#include "report/report_args.hpp"

namespace dspdem {

int report_command(const report::ReportArgs& a);

}  // namespace dspdem
