// The Galvez beam's numbers from one finished run: load against CMOD and against the
// load-point deflection, the peak, the quasi-static check, the crack path traced from the
// broken joints (mid-plane and both faces) and where it starts and ends, fragments, energy
// ledger, cost. Used by `dspdem report` for this scene.
#pragma once
#include <string>
#include <utility>
#include <vector>

#include "io/case_config.hpp"

namespace dspdem {

struct GalvezResult {
  std::string run_dir;
  Real D = 0, B = 0, notch = 0, load_x = 0;  ///< depth, thickness, notch depth, loading line x [m]
  Real outer_x = 0;                          ///< the second top line's x [m]
  bool outer_held = false;                   ///< the second top line held in y (nonproportional) or not
  bool outer_driven = false;  ///< the second top line driven or loaded in y (neither of the test's kinds)
  Real P_peak = 0, t_peak = 0, cmod_peak = 0, defl_peak = 0;
  Real ke_ratio_max = 0;  ///< largest kinetic / internal energy from half the peak load to the peak
  Real ke_ratio_peak = 0;
  Real balance_max = 0, largest_energy = 0;
  // Crack path (damaged joints, softening or broken, of the last joints frame), as (y, x) in
  // metres from the notch tip upwards: mid-plane (|z| < B/6) and the two faces (outer sixths).
  std::vector<std::pair<double, double>> path_mid, path_front, path_back;
  Real crack_area = 0;
  Real start_x = 0, start_y = 0;  ///< centroid of the first damaged joints
  Real top_x = 0;                 ///< x where the mid-plane path is highest
  Real top_y = 0;
  Index first_crack_frame = -1, last_frame = -1;
  int fragments = 0;
  std::vector<double> mass_fractions;
  double wall_s = 0, dt = 0, dt_start = 0;  ///< dt: the last step, dt_start the first
  long steps = 0, elements = 0, joints = 0;
};

/// Whether the case holds the second top line (`load_outer`) in y: Galvez et al.'s
/// nonproportional loading, where that line's actuator keeps its place (a spring K = infinity);
/// free, the proportional one (K = 0).
bool outer_line_held(const CaseConfig& c);
/// Whether a condition moves or loads that line in y (a nonzero velocity or force).
bool outer_line_driven(const CaseConfig& c);

/// Analyses the run in `run_dir` of case `c`; with a `files_dir`, writes load.csv and
/// crack_path.csv there.
GalvezResult analyse_galvez_run(const CaseConfig& c, const std::string& run_dir, const std::string& files_dir);

}  // namespace dspdem
