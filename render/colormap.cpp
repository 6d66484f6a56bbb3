#include "render/colormap.hpp"

#include <vtkColorTransferFunction.h>
#include <vtkLookupTable.h>
#include <vtkNew.h>

#include <algorithm>
#include <cmath>

namespace dspdem::render {

namespace {
// viridis (van der Walt and Smith, matplotlib; public domain, CC0) sampled at 33 evenly spaced
// points; linear interpolation between them stays within about 1/255 of the full table.
const double kViridis[33][3] = {
    {0.2670, 0.0049, 0.3294}, {0.2770, 0.0503, 0.3757}, {0.2823, 0.0950, 0.4173}, {0.2829, 0.1359, 0.4534},
    {0.2788, 0.1755, 0.4834}, {0.2706, 0.2141, 0.5071}, {0.2590, 0.2515, 0.5247}, {0.2450, 0.2877, 0.5373},
    {0.2297, 0.3224, 0.5457}, {0.2143, 0.3556, 0.5512}, {0.1994, 0.3876, 0.5546}, {0.1856, 0.4186, 0.5568},
    {0.1727, 0.4488, 0.5579}, {0.1607, 0.4785, 0.5581}, {0.1490, 0.5081, 0.5573}, {0.1378, 0.5375, 0.5549},
    {0.1276, 0.5669, 0.5506}, {0.1206, 0.5964, 0.5436}, {0.1206, 0.6258, 0.5335}, {0.1323, 0.6550, 0.5197},
    {0.1579, 0.6838, 0.5017}, {0.1966, 0.7118, 0.4792}, {0.2461, 0.7389, 0.4520}, {0.3041, 0.7647, 0.4199},
    {0.3692, 0.7889, 0.3829}, {0.4401, 0.8111, 0.3410}, {0.5160, 0.8312, 0.2943}, {0.5958, 0.8487, 0.2433},
    {0.6785, 0.8637, 0.1895}, {0.7624, 0.8764, 0.1371}, {0.8456, 0.8873, 0.0997}, {0.9261, 0.8973, 0.1041},
    {0.9932, 0.9062, 0.1439}};
}  // namespace

FieldDisplay field_display(const std::string& field) {
  if (field == "displacement") return {false, 1e3, "displacement |u| [mm]"};
  if (field == "von_mises") return {false, 1e-6, "von Mises stress [MPa]"};
  if (field == "max_principal") return {true, 1e-6, "largest principal stress [MPa]"};
  return {true, 1e-6, field + " [MPa]"};  // sigma_xx ... sigma_xz
}

void fill_lookup_table(vtkLookupTable* lut, bool is_signed, double lo, double hi) {
  const int n = 256;
  lut->SetNumberOfTableValues(n);
  lut->SetRange(lo, hi);
  vtkNew<vtkColorTransferFunction> ctf;
  if (is_signed) {
    // Moreland (2009), "Diverging color maps for scientific visualization": blue to red
    // through a neutral grey-white, interpolated in his Msh space.
    ctf->SetColorSpaceToDiverging();
    ctf->AddRGBPoint(0.0, 0.230, 0.299, 0.754);
    ctf->AddRGBPoint(1.0, 0.706, 0.016, 0.150);
  } else {
    ctf->SetColorSpaceToRGB();
    for (int i = 0; i < 33; ++i) ctf->AddRGBPoint(i / 32.0, kViridis[i][0], kViridis[i][1], kViridis[i][2]);
  }
  for (int i = 0; i < n; ++i) {
    double rgb[3];
    ctf->GetColor(static_cast<double>(i) / (n - 1), rgb);
    lut->SetTableValue(i, rgb[0], rgb[1], rgb[2], 1.0);
  }
}

double nice_length(double x) {
  if (!(x > 0) || !std::isfinite(x)) return 0;
  const double p = std::pow(10.0, std::floor(std::log10(x)));
  const double m = x / p;
  return (m >= 5 ? 5 : m >= 2 ? 2 : 1) * p;
}

std::vector<double> nice_ticks(double lo, double hi, int target) {
  std::vector<double> out;
  if (!(hi > lo) || target < 2) return out;
  // The step: the round number (1, 2 or 5 x 10^k) nearest (in ratio) to an even split into
  // `target - 1` parts, so there are between about 2/3 and 3/2 of `target` ticks.
  const double raw = (hi - lo) / (target - 1);
  double step = nice_length(raw);
  {
    const double p = std::pow(10.0, std::floor(std::log10(step)));
    const double m = step / p;
    const double next = (m < 2 ? 2 : m < 5 ? 5 : 10) * p;
    if (std::log(next / raw) < std::log(raw / step)) step = next;
  }
  // A range a few rounding steps wide, far from zero (a hand-set range), has no round ticks
  // that a counter could step through: none.
  if (!(step > 0) || std::abs(lo / step) > 1e12 || (hi - lo) / step > 1000) return out;
  // Multiples of the step, not a running sum: 0.1 + 0.1 + 0.1 would print 0.30000000000000004.
  for (long long k = std::llround(std::ceil(lo / step - 1e-9)); static_cast<double>(k) * step <= hi + 1e-9 * step; ++k)
    out.push_back(k == 0 ? 0.0 : static_cast<double>(k) * step);
  return out;
}

std::vector<int> piece_colours(std::size_t pieces, const std::vector<std::pair<int, int>>& touching, int palette) {
  std::vector<std::vector<int>> larger(pieces);  // per piece: the larger pieces it touches
  for (const auto& [a, b] : touching) {
    if (a == b || a < 0 || b < 0 || static_cast<std::size_t>(a) >= pieces || static_cast<std::size_t>(b) >= pieces)
      continue;
    larger[static_cast<std::size_t>(std::max(a, b))].push_back(std::min(a, b));
  }
  std::vector<int> colour(pieces);
  std::vector<char> used(static_cast<std::size_t>(palette));
  for (std::size_t r = 0; r < pieces; ++r) {
    std::fill(used.begin(), used.end(), 0);
    for (int n : larger[r]) used[static_cast<std::size_t>(colour[static_cast<std::size_t>(n)])] = 1;
    int c = static_cast<int>(r % static_cast<std::size_t>(palette));
    if (used[static_cast<std::size_t>(c)])
      for (int k = 0; k < palette; ++k)
        if (!used[static_cast<std::size_t>(k)]) {
          c = k;
          break;
        }
    colour[r] = c;
  }
  return colour;
}

}  // namespace dspdem::render
