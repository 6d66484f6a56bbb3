// The packing's numbers from one finished run (paper section 2.1): whether the particles
// came to rest in the box and stayed in it, the heap they made (surface height, packing
// fraction), contacts per particle, the energy ledger and the speed of the run.
#pragma once
#include <string>

#include "io/case_config.hpp"

namespace dspdem {

struct PackingResult {
  std::string run_dir;
  long particles = 0, steps = 0;
  double dt = 0, wall_s = 0, t_end = 0;
  double box_x = 0, box_z = 0, box_height = 0;
  /// At rest: kinetic energy below this fraction of the potential energy released so far.
  static constexpr double rest_ratio = 1e-4;
  double released = 0;     ///< work of gravity at the end = potential energy released [J]
  double kinetic_end = 0;  ///< [J]
  double t_rest = -1;      ///< from this series row on the heap stays at rest (-1: never)
  long escaped = 0;        ///< particles whose centroid is outside the box (footprint, floor)
  /// Heap surface on a grid of square cells of side `cell` over the footprint: per cell the
  /// highest vertex of the particles whose centroid lies in it; mean and max over cells.
  double cell = 0, surface_mean = 0, surface_max = 0, centroid_max = 0;
  double solid_volume = 0;      ///< particles' volume at the end [m^3]
  double packing_fraction = 0;  ///< solid volume / (footprint area x mean surface height)
  double contacts_end = 0;      ///< feature contacts at the end (a face on a face counts 3)
  double balance_max = 0;
  double particle_steps_per_s = 0;
};

/// Analyses the run in `run_dir` of case `c` (the packing generator's box and particles).
/// With a `files_dir`, writes packing_series.csv (time, kinetic / released, contacts per
/// particle, floor force over the heap's weight) and heap_surface.csv (the surface grid)
/// there. Throws Error naming the run and what is missing.
PackingResult analyse_packing_run(const CaseConfig& c, const std::string& run_dir, const std::string& files_dir);

}  // namespace dspdem
