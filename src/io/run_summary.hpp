// summary.json of a run folder: one struct written by `dspdem run` and read by every report,
// through nlohmann-json both ways, so a key cannot be written under one name and read under
// another. Unknown keys in a file are ignored (newer writers), missing ones are an error
// naming the file and key.
#pragma once
#include <cmath>
#include <string>
#include <utility>
#include <vector>

#include "core/types.hpp"

namespace dspdem {

struct EnergySummary {
  double kinetic = 0, internal = 0, external_work = 0, damping = 0, initial = 0;
  double joint_elastic = 0, fracture_I = 0, fracture_II = 0;
  double contact_elastic = 0, friction = 0, contact_damping = 0;
  /// Velocity Verlet's kick term (time/integrator.hpp, Energy::kick); NaN in run folders
  /// written before it was recorded.
  double kick = std::nan("");
  double balance_error = 0;
};

/// Contact pairs first found overlapping at a rebuild after the first
/// (contact/contact_system.hpp, BornOverlaps): how many, the spring energy of their overlaps
/// when found [J], the largest overlap / (r_a + r_b). Unknown (pairs -1, the rest NaN) in
/// runs without contact and in run folders written before they were recorded.
struct BornOverlapSummary {
  long pairs = -1;
  double energy = std::nan(""), max_ratio = std::nan("");
};

struct RunSummary {
  std::string case_name, case_file;
  std::string status;   ///< "completed", "failed" or "interrupted"
  std::string message;  ///< why it failed, or why it ended before [time] end
  std::string build;    ///< the dspdem that ran it (executable_id: version, commit, compiler, file CRC)
  long steps = 0;
  /// dt: the step at the end (extrinsic insertion lowers it as joints open; dt_start the
  /// first); dt_critical and its limiter: the critical step then.
  double dt = 0, dt_start = 0, dt_critical = 0;
  std::string dt_limiter;
  long dt_limiting_element = 0;
  double t_end = 0, wall_s = 0;
  int threads = 1;
  int processes = 1;  ///< MPI processes of a distributed run (mpirun -n)
  long nodes = 0, elements = 0, frames = 0, joints = 0, broken_joints = 0;
  double joint_added_compliance = 0, crack_area = 0;
  /// Per broken_joints / crack_area monitor: the joints its box holds, so that its column
  /// reads as a share ("79 % of the contact zone's joints broken"); read back sorted by name.
  std::vector<std::pair<std::string, long>> monitor_joints;
  long fragments = 0;
  double total_mass = 0;
  std::vector<double> largest_fragment_masses;  ///< the ten largest, descending [kg]
  double element_steps_per_s = 0;
  EnergySummary energy;
  /// Element pairs that had a joint between them, element pairs that had none (both start
  /// from that overlap), wall pairs (they push with it).
  BornOverlapSummary born_split, born_unseen, born_wall;
};

/// Writes `s` as JSON to `path` (atomically: a temporary file, then rename).
void write_run_summary(const std::string& path, const RunSummary& s);

/// Reads a summary.json; throws Error naming the file (and the key) when it is missing or
/// malformed.
RunSummary read_run_summary(const std::string& path);

}  // namespace dspdem
