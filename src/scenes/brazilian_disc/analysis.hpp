// The Brazilian disc's numbers from one finished run: plate load and splitting strength,
// sigma_xx and sigma_yy along the loaded diameter against the analytic solution (before
// the first broken joint), fragments, energy ledger, cost. Used by `dspdem report`.
#pragma once
#include <string>
#include <vector>

#include "core/types.hpp"
#include "io/case_config.hpp"

namespace dspdem {

// The paper plots the stresses along the diameter at 33.0 kN of its 40.6 kN peak.
constexpr Real kProfileFraction = 33.0 / 40.6;

struct DiscResult {
  std::string run_dir;
  Real D = 0, L = 0, ft = 0;
  Real P_peak = 0, t_peak = 0, split = 0, split_err = 0;
  Real P_profile = 0, t_profile = 0;
  Real l2_xx = 0, l2_yy = 0, centre_xx = 0, centre_yy = 0;  ///< against the field's element means
  Real l2_xx_centroid = 0;       ///< sigma_xx against the field at the element centroids instead
  Real face_xx = 0, mid_xx = 0;  ///< sigma_xx near the centre on the end faces / mid-plane, vs 2D
  Index profile_frame = -1, init_frame = -1, last_frame = -1, split_frame = -1;
  Real t_init = -1;
  Real balance_max = 0, largest_energy = 0;
  // Crack path, from the broken joints at the split (the first frame after the peak with
  // less than half its load; else the last frame), area-weighted over their
  // mid-surface polygons): mean distance of their centroids from the loaded plane x = 0, and
  // the share of broken area within D/4 of a plate (crushing under the plates rather than
  // splitting). Negative when the run has no joints frame.
  Real crack_mean_x = -1, crack_near_plates = -1, crack_area = 0;
  // The same broken joints traced along y in about D/h slices (area-weighted mean x per
  // slice): mean and largest |x| of that path over the slices that hold broken joints.
  Real crack_path_mean_x = -1, crack_path_max_x = -1;
  int crack_path_slices = 0, crack_path_bins = 0;
  // Softening or broken joints at the first frame at or after the peak: mean |x|.
  Real peak_damage_mean_x = -1;
  Index peak_frame = -1;
  int fragments = 0;
  std::vector<double> mass_fractions;
  double wall_s = 0, dt = 0, dt_start = 0;  ///< dt: the last step, dt_start the first
  long steps = 0, elements = 0, joints = 0;
};

/// Analyses the run in `run_dir` of case `c`; with a `files_dir`, also writes load.csv,
/// profile.csv and profile_analytic.csv there. The stress profile is taken at the frame whose
/// load is closest to `profile_load` [N] when it is > 0 (another run's profile load), else
/// at kProfileFraction of this run's peak.
DiscResult analyse_disc_run(const CaseConfig& c, const std::string& run_dir, const std::string& files_dir,
                            Real profile_load = 0);

/// "+1.2 %"
std::string pct(Real x);

}  // namespace dspdem
