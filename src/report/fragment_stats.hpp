// Fragment statistics of one frame of a run, for any scene: how many pieces, how heavy,
// and how the mass is distributed over piece sizes (the cumulative mass distribution that
// comminution studies plot). Read back from the frame itself (its `fragment` cell field),
// so any frame of any finished run can be analysed, not only the ones a scene planned for.
#pragma once
#include <string>
#include <utility>
#include <vector>

namespace dspdem::report {

struct FragmentStats {
  std::vector<double> masses;  ///< every fragment's mass [kg], largest first
  std::vector<int> elements;   ///< elements in each, same order
  double total_mass = 0;

  int count() const { return static_cast<int>(masses.size()); }
  /// Mass of the largest fragment over the total (1 for an intact body).
  double largest_fraction() const { return masses.empty() ? 0.0 : masses.front() / total_mass; }
  /// Fragments holding at least `fraction` of the total mass each.
  int count_at_least(double fraction) const;
  /// Fragments of a single element: the crushed material, below what the mesh resolves.
  int single_element() const;
};

/// The fragments of a frame (a run's frames/frame_NNNN.vtu): cells grouped by their
/// `fragment` id, each cell's mass its volume in the reference configuration (points minus
/// the `displacement` field, so deformation does not change it) times the density of its
/// `material` (index into `density_by_material`, the case's [materials] in order). Throws
/// Error naming the file and the missing field, or the material index out of range.
FragmentStats fragment_stats(const std::string& frame_vtu, const std::vector<double>& density_by_material);

/// Cumulative mass distribution: (fragment mass m, fraction of the total mass held by
/// fragments of mass <= m), one point per fragment in increasing mass. Ends at (largest, 1).
std::vector<std::pair<double, double>> cumulative_mass_distribution(const FragmentStats& s);

/// Writes the distribution as CSV with columns `columns` = {mass column, fraction column}
/// (through a temporary name); the header names them so several runs can share one plot.
void write_mass_distribution_csv(const std::string& path, const FragmentStats& s,
                                 const std::pair<std::string, std::string>& columns = {"mass_kg", "cumulative"});

}  // namespace dspdem::report
