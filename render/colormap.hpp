// What a field looks like on screen: its colour map (viridis for magnitudes, Moreland's
// cool-warm diverging map centred on zero for signed stresses: both perceptually ordered, so
// equal steps of the value look like equal steps of colour, also in grey print), its display
// unit (MPa, mm), and round numbers for tick labels and the scale bar.
#pragma once
#include <string>
#include <utility>
#include <vector>

class vtkLookupTable;

namespace dspdem::render {

struct FieldDisplay {
  bool is_signed = false;  ///< diverging map, range centred on zero
  double scale = 1.0;      ///< display value = field value x scale
  std::string title;       ///< with its unit, e.g. "von Mises stress [MPa]"
};

/// How `field` (a name of stress_fields()) is shown.
FieldDisplay field_display(const std::string& field);

/// Fills `lut` (256 entries) with the map for a signed or an unsigned field over [lo, hi].
void fill_lookup_table(vtkLookupTable* lut, bool is_signed, double lo, double hi);

/// Round tick values (1, 2 or 5 x 10^k apart) inside [lo, hi], between about 2/3 and 3/2 of
/// `target` of them: the step is the round number nearest (in ratio) to (hi - lo) / (target - 1).
std::vector<double> nice_ticks(double lo, double hi, int target);

/// The largest 1, 2 or 5 x 10^k not above `x` (> 0).
double nice_length(double x);

/// Palette indices of pieces numbered by size rank (0 the largest), given which pieces touch
/// (pairs of ranks): each takes rank % palette unless a larger piece it touches has that
/// colour, then the first colour no larger piece it touches has. So colours stay those of the
/// rank wherever that gives no clash, and touching pieces differ while the palette allows.
std::vector<int> piece_colours(std::size_t pieces, const std::vector<std::pair<int, int>>& touching, int palette);

}  // namespace dspdem::render
