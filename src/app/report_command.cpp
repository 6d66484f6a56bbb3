#include "app/report_command.hpp"

#include "io/case_config.hpp"
#include "scenes/registry.hpp"

namespace dspdem {

int report_command(const report::ReportArgs& a) {
  const CaseConfig c = read_case(a.case_file, a.sets);
  return scenes::of_case(c).report(c, a);
}

}  // namespace dspdem
