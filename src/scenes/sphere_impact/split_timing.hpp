// When the large pieces come free over the meshes of a sweep (`--realisations`) and over one
// mesh's draws (`--draws`): per speed, how many meshes' spheres have shown two pieces of at
// least 10 % of the mass by each time after the first contact, up to the compared frame. Why:
// the paper compares one moment (0.75 ms after the contact), and where many meshes' pieces come
// free just before it, the count at that moment hangs on the moment as much as on the speed.
#pragma once
#include <string>
#include <utility>
#include <vector>

#include "report/document.hpp"
#include "scenes/sphere_impact/realisations.hpp"

namespace dspdem::sphere {

/// One speed's meshes: when each first showed two large pieces, and up to when it was read.
struct SplitTiming {
  double speed = 0;
  /// Per run with a history, its first frame with two pieces of at least 10 % [s after the
  /// contact]; -1: none by its compared frame.
  std::vector<double> first;
  /// Per run, its compared time after the contact [s] (the frame nearest the case's compared
  /// time, so the runs' differ by up to a frame).
  std::vector<double> end;
  /// Runs left out: failed, or without a history (a run older than fragments.csv).
  int left_out = 0;

  int meshes() const { return static_cast<int>(first.size()); }
  /// Meshes that have shown two large pieces at some frame up to `before` ahead of their own
  /// compared frames; with 0, by the compared frames. A mesh whose pieces broke up further
  /// since counts too (the pattern's pieces_10pct, read at the compared frame, may be lower).
  int by_end(double before = 0) const;
};

/// From one speed's runs, each read up to its own compared frame.
SplitTiming split_timing(double speed, const std::vector<RealisationRun>& runs);

/// The times of `first` that are not -1 (the runs that came apart), in order.
std::vector<double> came_free(const std::vector<double>& first);

/// The count as a step curve: per distinct time of came_free(first), the meshes by then.
std::vector<std::pair<double, int>> steps(const SplitTiming& s);

/// One mesh's draws (`first` as SplitTiming's, -1 none): "lo-hi (k of n)" in ms after the
/// contact, "none (0 of n)", or "-" for no draw with a history.
std::string freed_range(const std::vector<double>& first);

/// How long before the compared time the report counts again.
inline constexpr double kLateWindow = 1e-4;

/// The files the section writes, relative to the report's folder (only with --realisations).
inline constexpr const char* kLargePiecesTimeCsv = "large_pieces_time.csv";
inline constexpr const char* kLargePiecesTimePng = "images/large_pieces_time.png";

/// Writes the section into `doc`, kLargePiecesTimeCsv into `dir` and, when any mesh shows
/// two large pieces, kLargePiecesTimePng; by_speed[s]: the runs at speeds[s].
void split_timing_section(report::Document& doc, const std::vector<double>& speeds,
                          const std::vector<std::vector<RealisationRun>>& by_speed, const std::string& dir);

}  // namespace dspdem::sphere
