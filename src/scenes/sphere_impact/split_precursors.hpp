// What a mesh's split time goes with: per speed, over the meshes of a sweep (`--realisations`),
// the time its large pieces come free against two measures read early, before any has come
// free: how far up its cracks reach, and how many fragments it has (at the contact, mostly
// single elements crushed off). Why: at 7.5 m/s the meshes' pieces come free over 0.5-1.8 ms
// after the contact (21 of 80 not by 2 ms), long after the plate force's peak, and four
// measures sought for what sets a mesh's time, two of the mesh and two of the contact's early
// load, held on no new meshes (REFERENCE.md, sessions 69, 91, 92 and 94); this reads the
// sphere's own cracking early on.
#pragma once
#include <string>
#include <vector>

#include "report/document.hpp"
#include "report/rank_correlation.hpp"
#include "scenes/sphere_impact/realisations.hpp"

namespace dspdem::sphere {

/// When the early measures are read [s after the first contact]: at 7.5 m/s the plate force
/// has peaked on every one of eighty meshes by then (0.05-0.28 ms) and none has come apart
/// (the first at 0.51 ms; REFERENCE.md, sessions 94-95).
inline constexpr double kEarlyRead = 3e-4;

/// One speed's meshes read at kEarlyRead.
struct SplitPrecursors {
  double speed = 0;
  std::vector<int> orientation;
  /// Per mesh read: its first two large pieces [s after the contact], +infinity when none by
  /// its compared frame (later than every mesh that came apart); its cracks' reach (over the
  /// diameter) and its fragments at kEarlyRead.
  std::vector<double> first, reach, fragments;
  std::vector<double> compared;  ///< per mesh read, its compared time [s after the contact]
  int came_apart = 0;            ///< meshes read whose pieces came free by their compared frames
  /// Runs with a history, read or not, whose pieces came free by kEarlyRead: the measures are
  /// then not ahead of the time.
  int apart_early = 0;
  /// Runs failed, without a history or a joints frame by kEarlyRead, compared before it, or not
  /// apart and compared before the latest mesh read that came apart (not rankable after it).
  int not_read = 0;
  report::RankCorrelation with_reach, with_fragments;  ///< Spearman against `first`

  int meshes() const { return static_cast<int>(first.size()); }
  /// Read when at least kMinMeshes meshes were, two of them came apart, and none by kEarlyRead.
  bool readable() const { return meshes() >= kMinMeshes && came_apart >= 2 && apart_early == 0; }
  /// With six meshes the least two-sided p a permutation can give is 2 / 720, below 0.01.
  static constexpr int kMinMeshes = 6;
};

/// From one speed's runs; the correlations only when readable().
SplitPrecursors split_precursors(double speed, const std::vector<RealisationRun>& runs);

/// The file the section writes, relative to the report's folder (only with --realisations).
inline constexpr const char* kSplitPrecursorsCsv = "split_precursors.csv";

/// When some speed is readable, writes the section into `doc` and kSplitPrecursorsCsv into
/// `dir`: every mesh read at every speed, its time in ms (blank: none by its compared frame),
/// its compared time, reach and fragments; otherwise nothing. by_speed[s]: the runs at speeds[s].
void split_precursors_section(report::Document& doc, const std::vector<double>& speeds,
                              const std::vector<std::vector<RealisationRun>>& by_speed, const std::string& dir);

}  // namespace dspdem::sphere
