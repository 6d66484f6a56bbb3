// Cracks read back from a run: the broken joints of a joints frame as area-weighted points,
// a crack traced as a polyline through them, and distances between polylines (to compare a
// crack path with a reference path or a stored one).
#pragma once
#include <string>
#include <vector>

#include "core/types.hpp"

namespace dspdem::report {

struct CrackPiece {
  Vec3 centroid;
  double area = 0;              ///< mid-surface area [m^2]
  Vec3 normal = Vec3::UnitZ();  ///< unit normal of the mid-surface (sign arbitrary)
  /// Crack width: |(max(opening, 0), slip)| [m] (0 in frames without them). A joint released
  /// to contact (its pieces apart) keeps the width it had when it was released.
  double jump = 0;
};

/// Joints of a joints_NNNN.vtu frame whose state is at least `min_state` (2: broken, the
/// default; 1: softening or broken, the whole damaged zone). Empty when the file has none.
std::vector<CrackPiece> broken_joints(const std::string& joints_vtu, int min_state = 2);

/// The state of every joint of a joints frame, in cell order (0 intact, 1 softening, 2
/// broken). The cells are the same joints in every frame of a run, so this indexes the
/// pieces of the first frame (`broken_joints(first, 0)`: every joint where it started).
std::vector<int> joint_states(const std::string& joints_vtu);

/// How far a body's cracks reach along a direction, by their area.
struct CrackReach {
  double area = 0;         ///< area of the joints counted [m^2]
  double at_quantile = 0;  ///< position s below which the quantile of that area lies [m]
  double furthest = 0;     ///< largest s of a joint counted [m]
};

/// The reach of the joints whose `states` entry is at least `min_state`, measured at the
/// positions `where` (a run's first joints frame, `broken_joints(first, 0)`, so that pieces
/// moving after they broke do not move the crack) along s = (centroid - origin) . dir with
/// `dir` a unit vector. `quantile` in (0, 1]: the smallest s of a counted joint below (or at)
/// which that fraction of the counted area lies. All zero when no joint counts. `where` and
/// `states` must index the same joints (Error otherwise).
CrackReach crack_reach(const std::vector<CrackPiece>& where, const std::vector<int>& states, const Vec3& origin,
                       const Vec3& dir, double quantile, int min_state = 2);

/// How many joints whose `states` entry is at least `min_state` lie in each band of s =
/// (centroid - origin) . dir at the positions `where` (as crack_reach's): band i holds
/// edges[i] <= s < edges[i + 1], the last also s = edges.back(); joints outside every band
/// are in none. `edges` ascending, at least two; `where` and `states` must index the same
/// joints (Error otherwise). With min_state 0, every joint: each band's own count.
std::vector<long> count_by_band(const std::vector<CrackPiece>& where, const std::vector<int>& states,
                                const Vec3& origin, const Vec3& dir, const std::vector<double>& edges,
                                int min_state = 2);

/// How the pieces of a slice are weighted in a traced path.
enum class PathWeight {
  Area,       ///< by area: every piece of the damaged zone counts alike
  AreaWidth,  ///< by area x crack width: the visible crack, where a damaged zone has more
              ///< than one branch (a wide crack and a band of barely softened joints beside it)
};

/// A crack traced along `along` (0, 1, 2 = x, y, z): the pieces with lo < p(along) < hi and
/// `keep` true, binned into `bins` equal slices; per non-empty slice the weighted mean of
/// the other coordinate `across` at the slice's mean position. Returns (along, across)
/// pairs in increasing `along`.
std::vector<std::pair<double, double>> trace_path(const std::vector<CrackPiece>& pieces, int along, int across,
                                                  double lo, double hi, int bins,
                                                  bool (*keep)(const Vec3&, const void*) = nullptr,
                                                  const void* ctx = nullptr, PathWeight weight = PathWeight::Area);

struct PathDistance {
  double mean = 0;       ///< mean over the points of `a` of the distance to polyline `b` [m]
  double hausdorff = 0;  ///< symmetric Hausdorff distance between the two point sets [m]
};

/// Distances between two 2D polylines (points in order). Both must have a point.
PathDistance path_distance(const std::vector<std::pair<double, double>>& a,
                           const std::vector<std::pair<double, double>>& b);

}  // namespace dspdem::report
