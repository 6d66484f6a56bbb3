// The paper's pattern at the sphere impact (section 2.5, Fig. 22) speed by speed, and one
// run read against it: pure functions of a run's numbers, shared by the sweep's table, the
// realisations and the headline.
#pragma once
#include <string>

#include "scenes/sphere_impact/analysis.hpp"

namespace dspdem::sphere {

/// The paper's speed bands: it describes up to 5 m/s, 7.5 m/s, and 20 m/s and above. A
/// speed between 5 and 20 m/s other than 7.5 is held to 7.5 m/s's pattern (FewLargeAssumed),
/// and the report says that this is an assumption, not the paper's.
enum class SpeedBand { Whole, FewLarge, FewLargeAssumed, Crushed };

/// The paper's compared time, after the first contact (its Fig. 22) [s].
inline constexpr double kPaperTime = 0.75e-3;

SpeedBand speed_band(double v);
/// The paper's description at a speed: what dspdem should show.
std::string expected_pattern(double v);
/// 2 to 6 pieces of at least 10 % of the mass.
bool a_few_large_pieces(const SphereImpactResult& r);
/// The run shows what the paper describes at its speed.
bool pattern_met(const SphereImpactResult& r);
/// The first frame with two large pieces, in ms after the first contact: "-" when none by
/// the compared time, `unknown` for a run without history (older than fragments.csv).
std::string two_large_ms(const SphereImpactResult& r, const char* unknown);
/// The same for a CSV column (orientations.csv, draws.csv): "-1.000" when none by the
/// compared time, "nan" without a history.
std::string two_large_csv(const SphereImpactResult& r);

}  // namespace dspdem::sphere
