// The sphere impact's numbers from one finished run (paper section 2.5): cracks over time,
// fragments and their mass distribution at the compared time, rebound, contact force on
// the plate and where the impact energy went. Used by `dspdem report` for this scene, once
// per speed of the sweep and per row of the study.
#pragma once
#include <array>
#include <cmath>
#include <string>
#include <vector>

#include "io/case_config.hpp"
#include "report/fragment_stats.hpp"

namespace dspdem {

/// A run's frame times, its series' times and its compared time come from one clock but
/// through different sums: two of them are the same time within this [s].
inline constexpr double kSameTime = 1e-12;

struct SphereImpactResult {
  std::string run_dir;
  /// Where the files derived from the run were written (empty: none): the run's folder for a
  /// report's own run, the report's folder at the run's place for one an earlier report ran.
  std::string files_dir;
  double speed = 0;  ///< impact speed [m/s] (the [[initial]] velocity's magnitude)
  double diameter = 0, mass = 0;
  double t_contact = -1;  ///< first series row with a force on the plate [s]
  double t_compare = 0;   ///< time of the analysed frame [s]: the frame nearest t_contact + the compared time
  Index frame = -1;
  report::FragmentStats fragments;  ///< at that frame
  /// A crack is "through" when it has cut off a piece of at least this fraction of the mass
  /// (below it, what comes off is crushed material at the contact, not a split sphere), or
  /// when the largest piece holds less than `intact_fraction` (the sphere is crushed).
  static constexpr double through_piece_fraction = 0.01, intact_fraction = 0.9;
  /// A "large piece" holds at least this fraction of the mass (the paper's "a few large
  /// pieces" at 7.5 m/s: REFERENCE.md, "Not found, and what the case and the scene chose").
  static constexpr double large_piece_fraction = 0.10;
  /// The two criteria, one definition for the compared frame and each frame of the history.
  static bool cut_through(double largest, double second) {
    return second >= through_piece_fraction || largest < intact_fraction;
  }
  /// "A few large pieces": 2 to 6 of at least large_piece_fraction (the paper's Fig. 22 shows
  /// three or four at 7.5 m/s).
  static bool few_large(int large_pieces) { return large_pieces >= 2 && large_pieces <= 6; }
  int pieces_1pct = 0, pieces_10pct = 0;  ///< fragments holding at least 1 % / large_piece_fraction of the mass
  bool through_crack = false;             ///< cut_through at the compared frame
  double second_fraction = 0;             ///< second largest piece over the mass
  long broken_joints = 0, joints = 0;
  /// Where the joints broke by the compared time: by height over the diameter above the
  /// lowest point, each joint where it was at the start (as crack_reach), in the bands
  /// height_bands: the contact (the lowest 0.1 D, 20 mm on the paper's sphere), three above it
  /// and the upper half, where the cracks that split the sphere must reach. Broken joints and
  /// all joints per band; empty without joints frames paired with the run's frames.
  static constexpr std::array<double, 6> height_bands = {0.0, 0.1, 0.2, 0.3, 0.5, 1.0};
  std::vector<long> broken_by_height, joints_by_height;
  double crack_area = 0;  ///< broken joints' area at the compared time [m^2]
  /// How far up the cracks reach at the compared time, over the diameter, from the sphere's
  /// lowest point along the impact's axis, with each joint where it was at the start:
  /// `reach_fraction` of the broken joints' area lies at or below `crack_reach`, and
  /// `crack_top` is the highest broken joint's centroid (-1: no joints frames paired with the
  /// run's frames).
  static constexpr double reach_fraction = 0.95;
  double crack_reach = -1, crack_top = -1;
  double t_first_broken = -1;     ///< first series row with a broken joint [s]
  double plate_force_peak = 0;    ///< largest |f_y| on the plate [N]
  double t_plate_force_peak = 0;  ///< when [s]
  double rebound_vy = 0;          ///< centre-of-mass velocity (y) at the compared time [m/s], + = away from the plate
  double restitution = 0;         ///< rebound_vy / speed
  double kinetic_start = 0;       ///< impact energy [J]
  /// Where the impact energy is at the compared time [J]: kinetic (of all pieces), elastic (elements,
  /// intact joints, contact springs), dissipated in fracture (mode I + II), friction,
  /// damping (mass/stiffness and contact damping).
  double kinetic_end = 0, elastic_end = 0, fracture = 0, friction = 0, damping = 0;
  double balance_max = 0;
  /// Spring energy of the contact pairs first found overlapping after the first build, up to
  /// the compared time [J] (series.csv; NaN for a run older than those columns): element
  /// pairs without a joint between them (an overlap no contact computed, forgiven) and wall
  /// pairs (they push with it). contact/contact_system.hpp, BornTotals.
  double born_unseen_energy = std::nan(""), born_wall_energy = std::nan("");
  /// The break-up frame by frame, from the first frame after the first contact to the
  /// compared one (the run's fragments.csv; empty for a run older than that file).
  struct PiecesAt {
    Index frame = -1;
    double after_contact = 0;        ///< [s]
    double largest = 0, second = 0;  ///< over the mass
    int large_pieces = 0;            ///< of at least large_piece_fraction
    long fragments = 0;
    double crack_reach = -1, crack_top = -1;  ///< as the result's, at this frame (-1: no joints frame)
    /// Broken joints in the lowest and the highest band of height_bands (-1: no joints frame).
    long broken_contact = -1, broken_upper = -1;
  };
  std::vector<PiecesAt> history;
  /// First frame of `history` with two large pieces or more, after the first contact [s]; -1:
  /// none. They may have broken up further by the compared frame.
  double t_two_large() const {
    for (const auto& h : history)
      if (h.large_pieces >= 2) return h.after_contact;
    return -1;
  }
  /// The compared frame's time after the first contact [s]: where `history` ends.
  double compared_after_contact() const { return t_compare - t_contact; }
  /// The last frame of `history` at or before `after_contact` [s]; nullptr when none.
  const PiecesAt* history_at(double after_contact) const {
    const PiecesAt* at = nullptr;
    for (const auto& h : history)
      if (h.after_contact <= after_contact + kSameTime) at = &h;
    return at;
  }
  double wall_s = 0, dt = 0;
  long steps = 0, elements = 0;
};

/// Analyses the run in `run_dir` of case `c` at `after_contact` seconds after the sphere
/// first touched the plate (the frame nearest that time; Error if the run ends before it or
/// never touches); with a `files_dir`, writes sphere_series.csv (time in ms, broken joints,
/// crack area in cm^2, plate force in kN, centre-of-mass vy, energies), pieces_time.csv
/// (`history`: frame, time and time after contact in ms, fragments, largest, second, large
/// pieces, crack reach and top over the diameter, broken joints in the lowest and the highest
/// band of height_bands) and fragment_masses.csv (the cumulative
/// mass distribution at that frame) there; `run_dir` itself is only read.
SphereImpactResult analyse_sphere_run(const CaseConfig& c, const std::string& run_dir, double after_contact,
                                      const std::string& files_dir);

}  // namespace dspdem
