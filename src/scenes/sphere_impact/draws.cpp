#include "scenes/sphere_impact/draws.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>

#include "core/error.hpp"
#include "report/homogeneity.hpp"
#include "report/permutation_bound.hpp"
#include "scenes/sphere_impact/pattern.hpp"
#include "scenes/sphere_impact/split_timing.hpp"

namespace dspdem::sphere {

namespace {
namespace fs = std::filesystem;

// One mesh's draws at one speed, in the order the runs came.
struct Mesh {
  int orientation = 0;
  std::vector<bool> through, few, met;
  std::vector<double> largest;
  std::vector<double> freed;  // draws with a history: first two pieces of 10 % [s after contact], -1 none
};

std::string share(const std::vector<bool>& v) {
  return fmt::format("{} of {}", std::count(v.begin(), v.end(), true), v.size());
}

// The permutation test's relabellings: its p near 0.05 has a standard error of about 0.0015.
constexpr int kShuffles = 20000;

// A p to the digits its test can tell.
std::string p_text(double p) { return p < 0.001 ? std::string("< 0.001") : fmt::format("{:.3f}", p); }

std::vector<std::string> test_row(double v, const char* event, const std::vector<Mesh>& meshes,
                                  std::vector<bool> Mesh::*of) {
  std::vector<std::vector<bool>> groups;
  for (const auto& m : meshes) groups.push_back(m.*of);
  const report::Homogeneity h = report::homogeneity(groups, kShuffles);
  const std::string shown = fmt::format("{} of {}", h.shown, h.runs);
  if (h.groups < 2)
    return {fmt::format("{:g}", v), event, shown, "-", "one mesh with finished draws: nothing to compare", "-", "-"};
  if (h.shown == 0 || h.shown == h.runs)
    return {fmt::format("{:g}", v), event, shown, "-", h.shown == 0 ? "none shows it" : "every run shows it", "-", "-"};
  const std::string perm = h.as_extreme == 0 ? fmt::format("< {:.2g} (no shuffle of {} reached it)",
                                                           report::p_bound_when_none_reached(h.shuffles), h.shuffles)
                                             : fmt::format("{:.4f}", h.p_permutation);
  return {fmt::format("{:g}", v),
          event,
          shown,
          fmt::format("{:.1f} ({})", h.chi2, h.dof),
          h.chi2_valid ? p_text(h.p_chi2)
                       : fmt::format("{} (not valid: least expected count {:.1f})", p_text(h.p_chi2), h.min_expected),
          perm,
          fmt::format("{:.2f}", h.between_share)};
}

}  // namespace

void draw_tables(report::Document& doc, const std::vector<double>& speeds,
                 const std::vector<std::vector<DrawRun>>& by_speed, int draws, const std::string& dir,
                 const std::string& folders) {
  DSPDEM_CHECK(by_speed.size() == speeds.size(), "internal: {} speeds, draws for {}", speeds.size(), by_speed.size());
  std::ofstream csv(fs::path(dir) / kDrawsCsv);
  csv << "speed,speed_run,orientation,draw,through_crack,few_large_pieces,paper_pattern,pieces_10pct,largest,"
         "balance_max,two_large_after_contact_ms\n";
  std::vector<std::string> failed;
  std::vector<std::vector<std::string>> rows, tests;
  for (std::size_t si = 0; si < speeds.size(); ++si) {
    const double v = speeds[si];
    // Mesh by mesh in the order the meshes first come (draws.csv too), each mesh's draws in order.
    std::vector<std::vector<const DrawRun*>> of_mesh;
    for (const DrawRun& d : by_speed[si]) {
      auto g = std::find_if(of_mesh.begin(), of_mesh.end(),
                            [&](const auto& x) { return x.front()->orientation == d.orientation; });
      (g == of_mesh.end() ? of_mesh.emplace_back() : *g).push_back(&d);
    }
    std::vector<Mesh> meshes;
    for (auto& g : of_mesh) {
      std::stable_sort(g.begin(), g.end(), [](const DrawRun* x, const DrawRun* y) { return x->draw < y->draw; });
      Mesh& m = meshes.emplace_back(Mesh{g.front()->orientation, {}, {}, {}, {}, {}});
      for (const DrawRun* d : g) {
        if (d->result == nullptr) {
          failed.push_back(fmt::format("{:g} m/s, orientation {}, draw {}: {}", v, d->orientation, d->draw, d->error));
          continue;
        }
        // The pattern at the sweep's speed: a nudged run is a draw of it, not a speed between.
        SphereImpactResult r = *d->result;
        r.speed = v;
        m.through.push_back(r.through_crack), m.few.push_back(a_few_large_pieces(r)), m.met.push_back(pattern_met(r));
        m.largest.push_back(r.fragments.largest_fraction());
        if (!r.history.empty()) m.freed.push_back(r.t_two_large());
        csv << fmt::format("{:g},{:.17g},{},{},{},{},{},{},{:.6f},{:.3e},{}\n", v, d->result->speed, d->orientation,
                           d->draw, int(r.through_crack), int(a_few_large_pieces(r)), int(pattern_met(r)),
                           r.pieces_10pct, r.fragments.largest_fraction(), r.balance_max, two_large_csv(r));
      }
    }
    for (const Mesh& m : meshes) {
      if (m.largest.empty()) {
        rows.push_back({fmt::format("{:g}", v), std::to_string(m.orientation), "0", "-", "-", "-", "-", "-"});
        continue;
      }
      const auto [lo, hi] = std::minmax_element(m.largest.begin(), m.largest.end());
      double mean = 0;
      for (double x : m.largest) mean += x / m.largest.size();
      rows.push_back({fmt::format("{:g}", v), std::to_string(m.orientation), std::to_string(m.largest.size()),
                      share(m.through), share(m.few), share(m.met),
                      fmt::format("{:.3f} ({:.2f}-{:.2f})", mean, *lo, *hi), freed_range(m.freed)});
    }
    if (meshes.size() > 1) {
      tests.push_back(test_row(v, "a crack through", meshes, &Mesh::through));
      tests.push_back(test_row(v, "a few large pieces", meshes, &Mesh::few));
      // The paper's pattern is a crack through's opposite up to 5 m/s and a few large pieces
      // between (pattern_met): the same test again, left out then; in the crushed band it is an
      // outcome of its own.
      if (speed_band(v) == SpeedBand::Crushed) tests.push_back(test_row(v, "the paper's pattern", meshes, &Mesh::met));
    }
  }
  doc.subsection(fmt::format("Chance on one mesh against the mesh: {} draws of each run", draws));
  doc.para(fmt::format(
      "Each run of the sweep (on each mesh, with --realisations) was run {} more times with the impact speed raised "
      "by {:g} m/s per draw: the impact energy changes by at most {:.1e} of itself, far below any systematic effect "
      "of the speed, while every bit of the run changes within its first steps, as any rounding change would do. "
      "Draw 0 is the run itself; each draw is judged by the pattern at the sweep's speed. The draws on a mesh are "
      "read as independent trials of it: the largest piece's range shows how far they part. Folders: {}; every draw "
      "in `draws.csv`.",
      draws - 1, kDrawNudge, std::pow(1 + (draws - 1) * kDrawNudge / speeds.front(), 2) - 1, folders));
  if (!failed.empty()) {
    std::string f;
    for (const auto& e : failed) f += "\n- " + e;
    doc.para("Draws that failed (left out):" + f);
  }
  doc.table({"speed [m/s]", "orientation", "draws", "a crack through", "a few large pieces", "the paper's pattern",
             "largest piece: mean (range)",
             "two pieces >= 10 % first, by the compared frame [ms after contact]: range (draws that show them, of "
             "those with a history)"},
            rows);
  if (!tests.empty()) {
    doc.para(fmt::format(
        "Whether the meshes differ by more than chance on each mesh would make them: the chi-square test of "
        "homogeneity of the meshes' shares, its approximation valid by Cochran's rule (every expected count at least "
        "1, at most a fifth below 5), and the permutation test of the same statistic ({} random relabellings of the "
        "runs between the meshes: no large counts needed; its p has a standard error of about 0.0015 near 0.05). A "
        "small p says the outcome is partly the mesh's; the share of its variance between the meshes (the spread of "
        "the meshes' shares against p (1 - p) over all runs) says how much: 0 when every mesh draws alike, 1 when "
        "each mesh always gives the same outcome. It depends on the mix of meshes run. The paper's pattern is tested "
        "on its own only where it is neither a crack through's opposite (up to 5 m/s) nor a few large pieces (7.5 "
        "m/s).",
        kShuffles));
    doc.table({"speed [m/s]", "outcome", "runs that show it", "chi-square (degrees of freedom)", "p: chi-square",
               "p: permutation", "share of the variance between meshes"},
              tests);
  }
}

}  // namespace dspdem::sphere
