// The speed-against-error sweep of `dspdem report --study`: three mesh sizes at the
// reference settings, then each knob that trades speed for accuracy moved alone (joint
// penalty, loading rate, kinematics, joints only in a band, mesh alignment).
#pragma once
#include <string>

#include "io/case_config.hpp"
#include "report/report_args.hpp"
#include "scenes/brazilian_disc/analysis.hpp"

namespace dspdem {

/// Runs every variant of `base` under `dir`/study/<variant> (the reference row reuses
/// `reference`, the analysed run of `base`; the elastic row reuses `check`, the report's
/// stress check, when given), writes study.csv there and plots/study.png under `image_dir`;
/// returns the markdown table and the recommendation. `runs`: report::run_or_resume.
std::string run_study(const CaseConfig& base, const DiscResult& reference, const DiscResult* check,
                      const std::string& dir, const std::string& image_dir, const report::RunPolicy& runs);

}  // namespace dspdem
