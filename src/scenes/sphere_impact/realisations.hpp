// A velocity sweep run again on turned meshes (`--realisations`): per speed how many meshes
// show the paper's pattern, every run in orientations.csv, each mesh's first speed with a
// through crack and with a few large pieces, and how many show the pattern at every speed.
#pragma once
#include <string>
#include <vector>

#include "report/document.hpp"
#include "scenes/sphere_impact/analysis.hpp"

namespace dspdem::sphere {

/// One run of a speed: its mesh's orientation, and its result (null when it failed: `error`).
struct RealisationRun {
  int orientation = 0;
  const SphereImpactResult* result = nullptr;
  std::string error;
};

/// Where the runs are: the case's own orientation, the meshes per speed, the report's folder,
/// and as the text names them the folders the case's own mesh's runs and the turned meshes'
/// are in (earlier reports' with --from-run; report/earlier_reports.hpp).
struct RealisationSetup {
  int k0 = 0, realisations = 1;
  std::string dir;
  std::string speeds_folders, orientation_folders;
};

/// The meshes with the paper's pattern at every speed run that the paper describes (`speeds`;
/// count_every_speed), as text: "k of n (95 %: lo-hi)" (empty when no such speed was run or
/// no mesh has all its runs), and whether that is most. Issue 18 reads the paper's one mesh as
/// the pattern dspdem should give on most.
struct EverySpeed {
  std::string count;
  bool most = false;
  std::vector<double> speeds;
};

/// The meshes that show the paper's pattern at each of their runs: by orientation, those that
/// do, and those with a failed run (not counted); `known` the meshes counted.
struct MeshCount {
  std::vector<int> whole, failed;
  int known = 0;
};

/// Over every speed run (a speed between those the paper describes held to 7.5 m/s's pattern,
/// pattern.hpp), or with `described_only` over the speeds the paper describes alone: the count
/// issue 18 reads, which a merged sweep's extra speeds leave as it was.
MeshCount count_every_speed(const std::vector<double>& speeds, const std::vector<std::vector<RealisationRun>>& by_speed,
                            bool described_only);

/// The files the section writes, relative to the report's folder (only with --realisations:
/// the report sets an earlier report's aside, report.cpp).
inline constexpr const char* kOrientationsCsv = "orientations.csv";
inline constexpr const char* kBreakagePng = "images/breakage_probability.png";

/// Writes the section into `doc` and kOrientationsCsv (and with several speeds kBreakagePng)
/// into where.dir; by_speed[s]: the runs at speeds[s], the case's own mesh first.
EverySpeed realisation_tables(report::Document& doc, const std::vector<double>& speeds,
                              const std::vector<std::vector<RealisationRun>>& by_speed, const RealisationSetup& where);

}  // namespace dspdem::sphere
