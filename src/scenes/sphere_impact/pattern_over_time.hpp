// The paper's pattern read at earlier times than the compared one, from each run's history:
// when a sweep is run on past the paper's moment (`--set time.end=...`), per time from the
// paper's 0.75 ms on, how many meshes show the pattern at each speed the history can judge,
// and at all of them. Why: at 7.5 m/s dspdem's few large pieces come free over 0.5-1.8 ms
// after the contact (REFERENCE.md, sessions 93-94), so the count at one moment is one point
// of a curve; this gives the curve for the whole pattern, which needs every speed read at the
// same time.
#pragma once
#include <optional>
#include <string>
#include <vector>

#include "report/document.hpp"
#include "scenes/sphere_impact/realisations.hpp"

namespace dspdem::sphere {

/// Whether a run shows the paper's pattern for its speed at `after_contact` [s], read at the
/// last frame of its history at or before that time: no crack through up to 5 m/s, 2 to 6
/// pieces of at least 10 % at 7.5 m/s. Empty when the history cannot say: no history, the
/// time before its first frame or after its compared frame, or a speed whose pattern the
/// history does not keep (20 m/s and above need the single elements; a speed between is not
/// the paper's).
std::optional<bool> pattern_at(const SphereImpactResult& r, double after_contact);

/// The times read [s after the contact]: the paper's moment and every 0.25 ms after it, up to
/// half a step (0.125 ms) before `last`, the earliest compared frame of the runs (which may lie
/// a little either side of the compared time); empty when the runs were compared at the paper's
/// moment.
std::vector<double> reading_times(double last);

/// One run of a speed the history can judge, at one time: its mesh (orientation), speed, and
/// whether it shows the pattern; `read` false when it could not say (pattern_at empty: the run
/// failed, or has no history or no frame at that time), so such a run is told from one that is
/// not in the sweep.
struct PatternRead {
  int orientation = 0;
  double speed = 0;
  bool read = false, met = false;
};

/// One time's counts: per speed read, the meshes with the pattern and those read; and the
/// meshes read at every such speed, with those showing the pattern at all of them; and every
/// run of those speeds, read or not, in the order of the speeds and of their runs, so two
/// sweeps of the same meshes can be set side by side mesh by mesh.
struct PatternCount {
  double after_contact = 0;
  std::vector<int> met, read;
  int every_met = 0, every_read = 0;
  std::vector<PatternRead> runs;
};

/// At each of `times`, over `speeds` (by_speed[s] their runs, each with its orientation): a
/// mesh counts at a speed when its run there can be read (pattern_at), and towards every
/// speed when all its runs at `speeds` can.
std::vector<PatternCount> pattern_over_time(const std::vector<double>& times, const std::vector<double>& speeds,
                                            const std::vector<std::vector<RealisationRun>>& by_speed);

/// The files the section writes, relative to the report's folder (only for runs past the
/// paper's moment).
inline constexpr const char* kPatternOverTimeCsv = "pattern_over_time.csv";
inline constexpr const char* kPatternOverTimeRunsCsv = "pattern_over_time_runs.csv";

/// Writes the section into `doc` when the runs go on past the paper's moment and at the
/// paper's moment at least two meshes could be read at one speed the history can judge;
/// kPatternOverTimeCsv (the counts) and kPatternOverTimeRunsCsv (each run of those speeds, its
/// verdict empty where it could not be read) into `dir` (where the report sets an earlier
/// report's aside first, report.cpp).
void pattern_over_time_section(report::Document& doc, const std::vector<double>& speeds,
                               const std::vector<std::vector<RealisationRun>>& by_speed, const std::string& dir);

}  // namespace dspdem::sphere
