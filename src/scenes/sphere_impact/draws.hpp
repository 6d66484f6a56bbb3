// Each run of a sweep again on the same mesh (`report --draws N`): chance on one mesh told
// from the mesh. An impact is chaotic, so the speed nudged by 1e-5 m/s changes every bit of
// the run within the first steps while the impact energy changes by about 2 (N - 1) 1e-5 / v
// of itself (under 3e-5 for ten draws at 7.5 m/s);
// what then changes with the draw is chance on that mesh, and what changes with the mesh but
// not the draw is the mesh's (issue 18: session 91 found a few large pieces at 7.5 m/s on one
// mesh in 9 of 10 such runs and on another in none).
#pragma once
#include <string>
#include <vector>

#include "report/document.hpp"
#include "scenes/sphere_impact/analysis.hpp"

namespace dspdem::sphere {

/// The impact speed's nudge per draw [m/s]: draw d runs at v + d * kDrawNudge.
inline constexpr double kDrawNudge = 1e-5;

/// One draw of a speed on a mesh: draw 0 is the sweep's own run (or the turned mesh's).
struct DrawRun {
  int orientation = 0, draw = 0;
  const SphereImpactResult* result = nullptr;  ///< null when it failed (`error`)
  std::string error;
};

/// The speed as the draw ran it.
inline double draw_speed(double v, int draw) { return v + draw * kDrawNudge; }

/// The file the section writes, relative to the report's folder (only with --draws).
inline constexpr const char* kDrawsCsv = "draws.csv";

/// Writes the section into `doc` and kDrawsCsv into `dir`: per speed, each mesh's share of its
/// draws with a crack through, a few large pieces and the paper's pattern, its largest piece,
/// and whether the meshes differ by more than chance (report/homogeneity.hpp). by_speed[s]:
/// every draw at speeds[s]; `folders` where the draws' runs are, as the text names them.
void draw_tables(report::Document& doc, const std::vector<double>& speeds,
                 const std::vector<std::vector<DrawRun>>& by_speed, int draws, const std::string& dir,
                 const std::string& folders);

}  // namespace dspdem::sphere
