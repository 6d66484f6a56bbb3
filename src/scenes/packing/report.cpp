#include <fmt/format.h>

#include <filesystem>

#include "core/error.hpp"
#include "core/log.hpp"
#include "core/timer.hpp"
#include "report/document.hpp"
#include "report/report_dirs.hpp"
#include "report/run_data.hpp"
#include "report/run_figures.hpp"
#include "run/montage.hpp"
#include "scenes/packing/analysis.hpp"
#include "scenes/packing/scene.hpp"

namespace dspdem {

namespace {
namespace fs = std::filesystem;

// The paper's times for this case (section 2.1), on its machine: its method and FDEM.
constexpr double kPaperSeconds = 62060, kPaperFdemSeconds = 117813;

// What a particle is made of: one tet4 (the paper's), or a meshed polyhedron (refined).
std::string particle_kind(const CaseConfig& c) {
  const long refine = std::lround(mesh_param(c, "refine"));
  if (refine == 0) return "single-tetrahedron";
  return fmt::format("meshed tetrahedral ({} elements each, mesh.packing.refine = {})", 1L << (3 * refine), refine);
}
}  // namespace

int packing_report(const CaseConfig& c, const report::ReportArgs& a) {
  Timer total;
  const report::ReportDirs dirs = report::prepare_report_run(c, a);
  const std::string &dir = dirs.dir, &run_dir = dirs.run_dir, &files = dirs.files_dir;
  const PackingResult r = analyse_packing_run(c, run_dir, files);
  const fs::path img = fs::path(files) / "images";
  const report::RunPlots plots(dirs);
  auto plot = [&](const std::string& y, const std::string& title, const std::string& png) {
    plots("packing_series.csv", "time", {y}, title, png);
  };
  plot("log10_kinetic_over_released", "log10(kinetic energy / potential energy released) against time [s]",
       "kinetic_decay.png");
  plot("contacts_per_particle", "feature contacts per particle against time [s]", "contacts.png");
  plot("floor_force_over_weight", "floor force over the particles' weight against time [s]", "floor_force.png");
  report::draw_run_frames(dirs, a);  // the case's views over all frames, with the animation
  if (!a.no_render) {
    for (const char* cam : {"front", "side", "iso"}) {
      MontageArgs m;
      m.run_dirs = {run_dir}, m.labels = {fmt::format("final heap, {} view", cam)};
      m.rows = {"fragments"}, m.camera = cam, m.width = 1000, m.height = 600;
      m.frame_walls = true;  // the first frame is the column of particles, twice the box's height
      m.out = (img / fmt::format("heap_{}.png", cam)).string();
      write_montage(m);
    }
  }

  const bool rest = r.t_rest >= 0;
  report::Document doc(dir, files);
  doc.title("Packing (paper section 2.1): report");
  doc.para(fmt::format(
      "Case `{}` ({}), run in `{}`: {} {} particles fall under gravity into a rigid open box "
      "{:.1f} x {:.1f} m (footprint) x {:.1f} m (height). Reference data and sources: src/scenes/packing/REFERENCE.md "
      "in dspdem. The paper uses this case for speed only: 5346 tetrahedra, {:.0f} s with its method against {:.0f} s "
      "with FDEM, on its own machine; it reports no heap geometry.",
      c.path, c.name, dirs.run_from_dir(), r.particles, particle_kind(c), r.box_x, r.box_z, r.box_height, kPaperSeconds,
      kPaperFdemSeconds));
  doc.section("The heap at the end");
  const double ratio = r.released > 0 ? r.kinetic_end / r.released : 1.0;
  doc.table(
      {"quantity", "value", "note"},
      {{"time simulated", fmt::format("{:.2f} s", r.t_end), ""},
       {"potential energy released", fmt::format("{:.4g} J", r.released), "work of gravity"},
       {"kinetic energy / released", fmt::format("{:.2e}", ratio),
        fmt::format("at rest below {:.0e}: {}", PackingResult::rest_ratio, rest ? "yes" : "no")},
       {"at rest from", rest ? fmt::format("{:.2f} s", r.t_rest) : "-", "and to the end"},
       {"particles outside the box", std::to_string(r.escaped), "centroid outside the footprint or below the floor"},
       {"heap surface, mean", fmt::format("{:.3f} m", r.surface_mean),
        fmt::format("highest vertex per {:.2f} m cell, over the footprint", r.cell)},
       {"heap surface, highest", fmt::format("{:.3f} m", r.surface_max), ""},
       {"packing fraction", fmt::format("{:.3f}", r.packing_fraction),
        "solid volume / (footprint x mean surface height): a lower bound, the surface is the highest vertices"},
       {"contacts per particle", fmt::format("{:.2f}", r.contacts_end / static_cast<double>(r.particles)),
        "feature contacts (a face flat on a face counts 3)"},
       {"energy balance, largest error", fmt::format("{:.1e}", r.balance_max), "of the largest term"}});
  doc.figures({{"kinetic energy decay", "images/plots/kinetic_decay.png"},
               {"contacts per particle", "images/plots/contacts.png"}});
  doc.figure("floor force over weight", "images/plots/floor_force.png");
  if (!a.no_render) {
    doc.section("The final heap");
    doc.figures({{"heap, front", "images/heap_front.png"}, {"heap, side", "images/heap_side.png"}});
    doc.figure("heap, from above at an angle", "images/heap_iso.png");
    doc.animation("the fall, every frame", "images/fragments", "images/fragments/frame_0000.png");
  }
  doc.section("Speed");
  doc.para(fmt::format(
      "{} steps of {:.3g} s in {:.1f} s wall time on {} thread(s): {:.3g} particle-steps per second over the whole "
      "run (free fall and settled bed together).",
      r.steps, r.dt, r.wall_s, report::RunData::open(run_dir).summary.threads, r.particle_steps_per_s));
  // The headline for the figures site. The paper uses this case for speed only.
  report::Headline& h = doc.headline();
  h.scene = "packing", h.title = "Packing (paper 2.1)";
  h.summary = fmt::format(
      "{} {} particles fall under gravity into a rigid open box and come to rest. The paper reports only its run "
      "time (5346 tetrahedra: {:.0f} s with its method, {:.0f} s with FDEM, on its machine), no heap geometry.",
      r.particles, particle_kind(c), kPaperSeconds, kPaperFdemSeconds);
  h.rows = {{"particles at rest in the box", "yes (shown in a figure)",
             rest ? fmt::format("yes, from {:.2f} s; kinetic / released energy {:.1e}; {} outside the box", r.t_rest,
                                ratio, r.escaped)
                  : fmt::format("no: kinetic / released energy {:.1e} at the end ({:.2f} s)", ratio, r.t_end),
             report::agrees(rest && r.escaped == 0), "Packing.ParticlesComeToRestInTheBoxWithTheLedgerClosed"},
            {"speed", fmt::format("{:.0f} s for 5346 particles (its machine)", kPaperSeconds),
             fmt::format("{:.3g} particle-steps/s: {:.1f} s for {} particles, {} steps", r.particle_steps_per_s,
                         r.wall_s, r.particles, r.steps),
             "", ""},
            report::balance_row(r.balance_max, "Packing.ParticlesComeToRestInTheBoxWithTheLedgerClosed")};
  if (!a.no_render) {
    doc.thumbnail("the heap, front", "images/heap_front.png");
    doc.thumbnail("the heap, from above at an angle", "images/heap_iso.png");
  }
  doc.thumbnail("kinetic energy decay", "images/plots/kinetic_decay.png");
  h.wall_s = total.seconds();
  doc.write();
  log::info("report: {}/report.md ({:.1f} s)", dir, total.seconds());
  return 0;
}

}  // namespace dspdem
