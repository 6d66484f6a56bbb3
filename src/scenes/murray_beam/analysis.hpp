// The impact beam's numbers from one finished run (paper section 2.4): fragments and their
// masses over time, the cracks through the beam (where, when they start and on which face,
// when they are through), deflection at mid-span and its largest value over the bottom
// face, impactor velocities, impactor and support forces, energy ledger, cost. Used by
// `dspdem report` for this scene.
#pragma once
#include <string>
#include <vector>

#include "io/case_config.hpp"

namespace dspdem {

/// A crack across the beam: broken joints on one plane x = const of the mesh.
struct BeamCrack {
  double x = 0;               ///< plane position [m]
  double t_first = -1;        ///< time of the first joints frame with a broken joint on it [s]
  double y_first = 0;         ///< mean height of those first broken joints [m] (beam centre y = 0)
  double y_lo = 0, y_hi = 0;  ///< lowest and highest of those first broken joints' centres [m]
  double t_through = -1;      ///< first frame with at least `through_fraction` of the section broken [s]
  double final_fraction = 0;  ///< broken fraction of the section at the end
};

/// A piece at the end of the run.
struct BeamPiece {
  double mass = 0, fraction = 0;  ///< [kg], of the beam's mass
  double x = 0, y = 0;            ///< centroid [m]
};

struct MurrayResult {
  std::string run_dir;
  double L = 0, H = 0, W = 0, span = 0, gap = 0;  ///< beam length, depth, width, span, impactor spacing [m]
  double total_mass = 0;
  static constexpr double main_piece_fraction = 0.05;  ///< a "main piece" holds at least this of the mass
  static constexpr double through_fraction = 0.9;      ///< a crack is through when this of the section broke
  int fragments = 0, main_pieces = 0;
  double t_main5 = -1;                              ///< first frame time with 5 or more main pieces [s]
  std::vector<BeamPiece> pieces;                    ///< main pieces at the end, largest first
  std::vector<BeamCrack> cracks;                    ///< by time of first break
  double max_deflection = 0, t_max_deflection = 0;  ///< largest of the max_deflection monitor, and when
  double midspan_at_end = 0;
  double impact_force_peak = 0, support_force_peak = 0;  ///< largest |fy| over both impactors / supports [N]
  double v_impactor_end = 0;                             ///< mean of the two impactors' vy at the end [m/s]
  double balance_max = 0, largest_energy = 0;
  /// Momentum check (y): largest |p(t) - p(0) + support impulse(t)| over the run, p the beam's
  /// (monitor beam_momentum) plus the free impactors' m v, relative to |p(0)|; -1 without
  /// the monitor. Every other force is internal to beam + impactors.
  double momentum_error = -1;
  double support_impulse = 0;  ///< the supports' impulse on the beam over the run [N s]
  double fracture_energy = 0, kinetic_start = 0, kinetic_end = 0;
  Index last_frame = -1;
  Index first_crack_frame = -1, main5_frame = -1;  ///< frames at the first broken joint and at 5 main pieces
  double wall_s = 0, dt = 0, dt_start = 0;         ///< dt: the last step, dt_start the first
  long steps = 0, elements = 0, joints = 0;
};

/// Analyses the run in `run_dir` of case `c`; with a `files_dir`, writes murray_series.csv
/// (times in ms, deflections in mm, forces in kN), fragments_time.csv and cracks.csv there.
MurrayResult analyse_murray_run(const CaseConfig& c, const std::string& run_dir, const std::string& files_dir);

}  // namespace dspdem
