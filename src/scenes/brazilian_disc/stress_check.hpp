// The report's stress-field check: sigma_xx and sigma_yy along the loaded diameter on a
// mesh that resolves the concentrated loads. The scene's mesh (about the paper's 12335
// linear tets) is fine for the split and the strength but not for the field within 0.2 D of
// a plate, where the point-load solution goes as 1/r: there a constant-stress element
// averages a field that changes sign across it. The check keeps the scene (disc, plates,
// material, contact) and changes only what the field needs: no joints (the profile is
// taken before cracking, and joints on 1 mm faces cut the stable step 7x), a finer mesh,
// and plates 4x faster (on the default case the loading still takes 13x the disc's wave
// transit time; the report prints this ratio).
#pragma once
#include <string>

#include "io/case_config.hpp"
#include "report/report_args.hpp"
#include "scenes/brazilian_disc/analysis.hpp"

namespace dspdem {

/// The check's case from the scene's: mesh 0.66 size in the bulk and size/7.6 at the loaded
/// lines (5 mm and 1 mm for the default 7.6 mm), no joints, plates 4x faster, run until the
/// top plate carries the scene's profile load `P_target` (time.stop_reach), at most to 1.25x
/// the closure at which the scene carried it (reached at `t_target`).
CaseConfig stress_check_case(const CaseConfig& scene, Real t_target, Real P_target);

/// Runs the check's case `c` (from stress_check_case) under `dir` and analyses it at the load
/// it stops at, the scene's profile load (`c.stop_reach`; writing profile.csv and
/// profile_analytic.csv there). `runs`: report::run_or_resume.
DiscResult run_stress_check(const CaseConfig& c, const std::string& dir, const report::RunPolicy& runs = {});

}  // namespace dspdem
