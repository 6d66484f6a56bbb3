// When the large pieces come free over the meshes of a sweep (`--realisations`): per speed,
// how many meshes' spheres have shown two pieces of at least 10 % of the mass by each time
// after the first contact, up to the compared time. Why: the paper compares one moment
// (0.75 ms after the contact), and where many meshes' pieces come free just before it, the
// count at that moment hangs on the moment as much as on the speed.
#pragma once
#include <string>
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
  /// Per run, its compared frame [s after the contact]: the frame nearest the compared time,
  /// so the runs' ends differ by up to a frame.
  std::vector<double> end;
  /// Runs left out: failed, or without a history (a run older than fragments.csv).
  int left_out = 0;

  int meshes() const { return static_cast<int>(first.size()); }
  /// Meshes with two large pieces by `before` ahead of their own compared frames: with 0,
  /// those the compared frames show, as the pattern's count reads them.
  int by_end(double before = 0) const;
  /// The times of `first` that are not -1, in order.
  std::vector<double> times() const;
};

/// From one speed's runs, each read up to its own compared frame.
SplitTiming split_timing(double speed, const std::vector<RealisationRun>& runs);

/// How long before the compared time the report counts again: four of the case's frames
/// (0.025 ms apart).
inline constexpr double kLateWindow = 1e-4;

/// Writes the section into `doc`, large_pieces_time.csv into `dir` and, when any mesh shows
/// two large pieces, images/large_pieces_time.png; by_speed[s]: the runs at speeds[s].
void split_timing_section(report::Document& doc, const std::vector<double>& speeds,
                          const std::vector<std::vector<RealisationRun>>& by_speed, const std::string& dir);

}  // namespace dspdem::sphere
