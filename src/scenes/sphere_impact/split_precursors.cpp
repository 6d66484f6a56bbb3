#include "scenes/sphere_impact/split_precursors.hpp"

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>

#include "report/permutation_bound.hpp"

namespace dspdem::sphere {

namespace {
namespace fs = std::filesystem;

std::string rho_text(const report::RankCorrelation& c) {
  if (!c.defined) return "- (one value on every mesh)";
  if (c.as_extreme == 0)
    return fmt::format("{:+.2f} (p < {:.2g}: no pairing of {} reached it)", c.rho,
                       report::p_bound_when_none_reached(c.shuffles), c.shuffles);
  return fmt::format("{:+.2f} (p {:.2g})", c.rho, c.p_permutation);
}
}  // namespace

SplitPrecursors split_precursors(double speed, const std::vector<RealisationRun>& runs) {
  SplitPrecursors s;
  s.speed = speed;
  struct Read {
    int orientation;
    double first, end, reach, fragments;
  };
  std::vector<Read> read;
  double latest = -INFINITY;  // the latest first two large pieces of a mesh read
  for (const RealisationRun& run : runs) {
    const SphereImpactResult* r = run.result;
    if (r == nullptr || r->history.empty()) {
      ++s.not_read;
      continue;
    }
    // Every history tells whether its mesh came apart by the early read, read there or not.
    const double t = r->t_two_large();
    s.apart_early += t >= 0 && t <= kEarlyRead + kSameTime;
    // The history ends at the compared frame (analysis.hpp): one compared before the early
    // read would be read at its last frame, not at kEarlyRead.
    const double end = r->compared_after_contact();
    const SphereImpactResult::PiecesAt* at = end >= kEarlyRead - kSameTime ? r->history_at(kEarlyRead) : nullptr;
    if (at == nullptr || at->crack_reach < 0) {
      ++s.not_read;
      continue;
    }
    read.push_back({run.orientation, t < 0 ? INFINITY : t, end, at->crack_reach, static_cast<double>(at->fragments)});
    if (t >= 0) latest = std::max(latest, t);
  }
  for (const Read& m : read) {
    // A mesh not apart by its compared frame ranks as later than every other only if that
    // frame lies past every time a mesh read came apart.
    if (std::isinf(m.first) && m.end < latest - kSameTime) {
      ++s.not_read;
      continue;
    }
    s.orientation.push_back(m.orientation);
    s.first.push_back(m.first), s.reach.push_back(m.reach), s.fragments.push_back(m.fragments);
    s.compared.push_back(m.end);
    s.came_apart += !std::isinf(m.first);
  }
  if (s.readable()) {
    s.with_reach = report::spearman(s.reach, s.first);
    s.with_fragments = report::spearman(s.fragments, s.first);
  }
  return s;
}

void split_precursors_section(report::Document& doc, const std::vector<double>& speeds,
                              const std::vector<std::vector<RealisationRun>>& by_speed, const std::string& dir) {
  std::vector<SplitPrecursors> all;
  bool any = false;
  for (std::size_t si = 0; si < speeds.size(); ++si) {
    all.push_back(split_precursors(speeds[si], by_speed[si]));
    any = any || all.back().readable();
  }
  if (!any) return;
  std::ofstream csv(fs::path(dir) / kSplitPrecursorsCsv);
  csv << fmt::format("speed,orientation,two_large_ms,compared_ms,crack_reach_{0:g}ms,fragments_{0:g}ms\n",
                     1e3 * kEarlyRead);
  std::vector<std::vector<std::string>> rows;
  std::vector<std::string> left;
  for (const SplitPrecursors& s : all) {
    for (int i = 0; i < s.meshes(); ++i)
      csv << fmt::format("{:g},{},{},{:.6f},{:.4f},{:g}\n", s.speed, s.orientation[i],
                         std::isinf(s.first[i]) ? std::string() : fmt::format("{:.6f}", 1e3 * s.first[i]),
                         1e3 * s.compared[i], s.reach[i], s.fragments[i]);
    if (!s.readable()) {
      left.push_back(s.apart_early > 0 ? fmt::format("{:g} m/s ({} came apart by then)", s.speed, s.apart_early)
                     : s.meshes() < SplitPrecursors::kMinMeshes
                         ? fmt::format("{:g} m/s ({} meshes read)", s.speed, s.meshes())
                         : fmt::format("{:g} m/s ({} came apart)", s.speed, s.came_apart));
      continue;
    }
    rows.push_back({fmt::format("{:g}", s.speed), std::to_string(s.meshes()),
                    fmt::format("{} of {}", s.came_apart, s.meshes()), rho_text(s.with_reach),
                    rho_text(s.with_fragments), s.not_read > 0 ? std::to_string(s.not_read) : "-"});
  }
  doc.para(fmt::format(
      "What the time goes with. Per speed, over the meshes, the time the large pieces come free (as above; a mesh "
      "without them by its compared frame counts as later than every other) against two measures read {0:g} ms "
      "after the contact, before any mesh has come apart: how far up the cracks reach (95 % of the broken area below "
      "it, over the diameter) and how many fragments there are (at the contact, mostly single elements crushed off). "
      "Spearman's rank correlation with its two-sided permutation p ({1} pairings, a fixed seed). A negative rho with "
      "the reach: the meshes whose cracks have climbed furthest by then tend to come apart first; a positive one "
      "with the fragments: those that have crushed most tend to come apart last. Two measures at several speeds: a p "
      "here is a lead to "
      "test on other meshes, not a finding. A speed is read where at least {2} meshes were, at least two came apart, "
      "and none by {0:g} ms. A run is not read when it failed, has no history or no joints frame by then, was compared "
      "before then, or did not come apart and was compared before the latest mesh that did (it cannot be ranked after "
      "it). Every mesh read is in `split_precursors.csv`.{3}",
      1e3 * kEarlyRead, report::kSpearmanShuffles, SplitPrecursors::kMinMeshes,
      left.empty() ? "" : fmt::format(" Not read: {}.", fmt::join(left, "; "))));
  doc.table({"speed [m/s]", "meshes read", "came apart by the compared frame",
             fmt::format("rho with the cracks' reach at {:g} ms (p)", 1e3 * kEarlyRead),
             fmt::format("rho with the fragments at {:g} ms (p)", 1e3 * kEarlyRead), "runs not read"},
            rows);
}

}  // namespace dspdem::sphere
