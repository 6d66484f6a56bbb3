// The sphere's realisations read as a single-particle impact test: the breakage probability
// against the impact energy per mass (report/breakage_probability.hpp), fitted over every run
// of every speed, for a crack through and for a sphere broken.
#pragma once
#include <string>
#include <vector>

#include "report/document.hpp"
#include "scenes/sphere_impact/realisations.hpp"

namespace dspdem::sphere {

/// Writes the subsection into `doc` and its plot to `image` (a PNG); by_speed[s]: the runs at
/// speeds[s]. Failed runs are left out. Needs two speeds or more.
void breakage_tables(report::Document& doc, const std::vector<double>& speeds,
                     const std::vector<std::vector<RealisationRun>>& by_speed, const std::string& image,
                     const std::string& image_in_doc);

}  // namespace dspdem::sphere
