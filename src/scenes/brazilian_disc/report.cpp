#include <cmath>
#include <filesystem>
#include <fstream>

#include "core/error.hpp"
#include "core/log.hpp"
#include "core/timer.hpp"
#include "io/case_config.hpp"
#include "io/staging.hpp"
#include "render/plot.hpp"
#include "report/document.hpp"
#include "report/report_dirs.hpp"
#include "report/run_data.hpp"
#include "report/run_figures.hpp"
#include "run/run_case.hpp"
#include "scenes/brazilian_disc/analysis.hpp"
#include "scenes/brazilian_disc/loading.hpp"
#include "scenes/brazilian_disc/scene.hpp"
#include "scenes/brazilian_disc/stress_check.hpp"
#include "scenes/brazilian_disc/study.hpp"

namespace dspdem {

namespace fs = std::filesystem;

int brazilian_disc_report(const CaseConfig& c, const report::ReportArgs& a) {
  Timer total;
  const report::ReportDirs dirs = report::prepare_report_run(c, a);
  const std::string &dir = dirs.dir, &run_dir = dirs.run_dir, &files = dirs.files_dir;
  const DiscResult r = analyse_disc_run(c, run_dir, files);
  const fs::path img = fs::path(files) / "images";
  report::draw_run_frames(dirs, a, {"stress", "fragments"});
  const report::RunPlots plot(dirs);
  // The case's own loading words: the shipped case loads through the ISRM's curved jaws, the
  // paper and the study's flat_plates row through flat plates.
  const std::string by = loads_through_jaws(c) ? "jaw" : "plate";
  plot("load.csv", "time_ms", {"load_kN"}, by + " load [kN] against time [ms]", "load_time.png");
  plot("load.csv", "closure_mm", {"load_kN"}, fmt::format("{0} load [kN] against {0} closure [mm]", by),
       "load_closure.png");
  plot("profile.csv", "y_mm", {"sigma_xx_MPa", "sigma_yy_MPa"},
       fmt::format("stresses along the loaded diameter at {:.1f} kN [MPa]; dashed: analytic", 1e-3 * r.P_profile),
       "profile.png", (fs::path(files) / "profile_analytic.csv").string(), "stress [MPa]");
  plot("series.csv", "time", {"balance_error"}, "energy balance error (fraction of the largest term)",
       "balance_error.png");

  // The field check on a load-resolving mesh, at the scene's profile load.
  DiscResult check;
  CaseConfig check_case;
  // A run too short to load the disc (profile at t = 0) has nothing to check; a check that
  // fails is reported, and the scene's report is still written.
  std::string check_note;
  bool checked = !a.no_stress_check && r.t_profile > 0;
  if (!a.no_stress_check && !checked)
    check_note = "Stress check skipped: the run has no frame with load on the disc before the first broken joint.";
  const fs::path check_dir = fs::path(dir) / "stress_check";
  if (checked) {
    try {
      check_case = stress_check_case(c, r.t_profile, r.P_profile);
      check = run_stress_check(check_case, check_dir.string(), a.runs);
    } catch (const Interrupted&) {
      throw;  // the user stopped the report: not a failed check, and no study after it
    } catch (const std::exception& e) {
      checked = false;
      check_note = fmt::format("Stress check failed: {}", e.what());
    }
  }
  if (!check_note.empty()) log::warn("{}", check_note);
  // Quasi-static enough? The check's loading time against the disc's bar-wave transit time
  // D / sqrt(E / rho) (plates 4x faster than the scene, which may itself be sped up).
  Real transit = 0;
  for (std::size_t m = 0; m < c.materials.size(); ++m)
    for (const auto& b : c.bodies)
      if (b.material == c.materials[m].name) transit = r.D / std::sqrt(c.materials[m].E / c.materials[m].density);
  const Real load_ratio = checked && transit > 0 ? check.t_profile / transit : 0;
  if (checked && load_ratio < 10)
    log::warn("stress check: loaded in only {:.1f}x the disc's wave transit time; inertia is not negligible",
              load_ratio);
  if (checked && std::abs(check.P_profile / r.P_profile - 1) > 0.1)
    log::warn("stress check: read at {:.2f} kN, not near the scene's {:.2f} kN", 1e-3 * check.P_profile,
              1e-3 * r.P_profile);
  if (checked) {
    render::PlotSpec s{"y_mm",
                       {"sigma_xx_MPa", "sigma_yy_MPa"},
                       (check_dir / "profile_analytic.csv").string(),
                       fmt::format("stress check: along the loaded diameter at {:.1f} kN [MPa]; dashed: analytic",
                                   1e-3 * check.P_profile)};
    s.y_title = "stress [MPa]";
    render::plot_csv((check_dir / "profile.csv").string(), s, (img / "plots" / "profile_check.png").string());
  }
  const std::string study_md =
      a.study ? run_study(c, r, checked ? &check : nullptr, dir, img.string(), a.runs) : std::string();

  // report.md
  report::Document doc(dir, files);
  doc.title("Brazilian disc: report");
  doc.para(fmt::format(
      "Case `{}` ({}), run in `{}`. Paper: section 2.2 (dspdem's README, "
      "M5); reference data, analytic solution and sources: src/scenes/brazilian_disc/REFERENCE.md in dspdem.",
      c.path, c.name, dirs.run_from_dir()));
  doc.para(
      fmt::format("Disc D = {:.1f} mm, L = {:.1f} mm, {} elements, {} joints; {}s closing at {:.3g} m/s "
                  "in all; input f_t = {:.2f} MPa. Run: {} steps of {}, {:.1f} s wall time.",
                  1e3 * r.D, 1e3 * r.L, r.elements, r.joints, by,
                  c.walls[0].wall.velocity_target.norm() + c.walls[1].wall.velocity_target.norm(), 1e-6 * r.ft, r.steps,
                  report::step_text(r.dt_start, r.dt), r.wall_s));
  doc.section("Load and splitting strength");
  doc.para(
      fmt::format("Peak {} load P = {:.2f} kN at t = {:.3f} ms. Splitting strength 2P/(pi D L) = {:.3f} MPa, {} "
                  "against the input f_t = {:.2f} MPa (the paper, through flat plates: 40.6 kN, 2.54 MPa for 2.3 "
                  "MPa, +10 %).",
                  by, 1e-3 * r.P_peak, 1e3 * r.t_peak, 1e-6 * r.split, pct(r.split_err), 1e-6 * r.ft));
  doc.figures(
      {{"load against time", "images/plots/load_time.png"}, {"load against closure", "images/plots/load_closure.png"}});
  doc.section("Stresses along the loaded diameter");
  if (!(r.P_peak > 0))  // a run stopped before the jaws met the disc: no profile to compare
    doc.para("No load reached the disc in the run: no stress profile is compared.");
  else
    doc.para(fmt::format(
        "At P = {:.2f} kN ({:.0f} % of the peak; the paper uses 33.0 of 40.6 kN = 81 %; never after the first broken "
        "joint), frame {} (t = {:.3f} ms). "
        "Elements within half an element size of x = 0, averaged in 16 bins over the central 80 % of the diameter, "
        "against the point-load solution (paper eqs. 24-25 on the axis). Each element's constant stress is compared "
        "with the mean of the full two-load field over that element, averaged in the same bins: near a load the field "
        "curves across an element, and a constant-stress element approximates its mean, not a point value. Relative "
        "L2 error: sigma_xx {:.1f} %, sigma_yy {:.1f} % (sigma_xx against the field at the element centroids "
        "instead: {:.1f} %). "
        "At the centre: sigma_xx {}, sigma_yy {}. The disc is 3D and the reference is plane stress: through the "
        "thickness at the centre (|y| < h), sigma_xx is {} on the end faces (outer half-element layer) and {} on "
        "the mid-plane against the 2D value{}.",
        1e-3 * r.P_profile, 100 * r.P_profile / r.P_peak, r.profile_frame, 1e3 * r.t_profile, 100 * r.l2_xx,
        100 * r.l2_yy, 100 * r.l2_xx_centroid, pct(r.centre_xx), pct(r.centre_yy), pct(r.face_xx), pct(r.mid_xx),
        r.face_xx > 0 && r.face_xx > r.mid_xx ? ": the faces reach f_t first, below the nominal 2P/(pi D L) = f_t"
                                              : ""));
  if (r.P_peak > 0) doc.figure("profile", "images/plots/profile.png");
  if (checked) {
    doc.subsection("Stress check on a mesh that resolves the loads");
    doc.para(fmt::format(
        "The scene's mesh is sized for the split ({} elements; the paper's has 12335); within 0.2 D of "
        "the loads the point-load field goes as 1/r and changes sign across an element of that size, so sigma_xx there "
        "is off by the figure above. The check (in `stress_check/`) is the same disc and contact, loaded through the "
        "paper's flat plates (the point-load solution is theirs; curved jaws spread the load over an arc), elastic "
        "(no joints: the profile is taken before cracking), meshed at {:.1f} mm with {:.1f} mm at the loaded lines "
        "({} elements), plates 4x faster than the scene (loading to the profile takes {:.1f}x the disc's wave "
        "transit time D / sqrt(E / rho)), {:.1f} s "
        "wall time. At P = {:.2f} kN (frame {}, t = {:.3f} ms), measured as above: L2 error sigma_xx {:.1f} %, "
        "sigma_yy {:.1f} % (sigma_xx against the centroid values: {:.1f} %); at the centre sigma_xx {}, sigma_yy "
        "{}.",
        r.elements, 1e3 * check_case.mesh_num.at("size"), 1e3 * check_case.mesh_num.at("load_size"), check.elements,
        load_ratio, check.wall_s, 1e-3 * check.P_profile, check.profile_frame, 1e3 * check.t_profile, 100 * check.l2_xx,
        100 * check.l2_yy, 100 * check.l2_xx_centroid, pct(check.centre_xx), pct(check.centre_yy)));
    doc.figure("profile, stress check", "images/plots/profile_check.png");
  }
  if (!check_note.empty()) doc.para(check_note);
  doc.section("Fracture");
  std::string fr;
  for (std::size_t i = 0; i < std::min<std::size_t>(4, r.mass_fractions.size()); ++i)
    fr += fmt::format("{}{:.3f}", i ? ", " : "", r.mass_fractions[i]);
  doc.para(fmt::format(
      "{} fragments; largest mass fractions {}. {}", r.fragments, fr,
      r.init_frame >= 0 ? fmt::format("First broken joint at t = {:.3f} ms (frame {}).", 1e3 * r.t_init, r.init_frame)
                        : std::string("No joint broke in the run.")));
  if (r.crack_mean_x >= 0)
    doc.para(fmt::format(
        "Crack path (broken joints at the split, frame {}, {:.0f} cm^2): their centroids lie {:.1f} mm from the loaded "
        "plane x = 0 on average (area-weighted; an element is {:.1f} mm); {:.0f} % of the broken area is within D/4 "
        "of a {}.",
        r.split_frame, 1e4 * r.crack_area, 1e3 * r.crack_mean_x, 1e3 * c.mesh_num.at("size"), 100 * r.crack_near_plates,
        by));
  if (r.crack_path_mean_x >= 0)
    doc.para(fmt::format(
        "Traced along the loaded diameter (area-weighted mean x of the broken joints in each of {} slices of y, {} "
        "of them cracked), the crack runs {:.1f} mm from x = 0 on average and {:.1f} mm at most. A slice with breaks "
        "on both sides of x = 0 averages between them: the broken joints' mean distance above says how far they lie.",
        r.crack_path_bins, r.crack_path_slices, 1e3 * r.crack_path_mean_x, 1e3 * r.crack_path_max_x));
  if (r.peak_damage_mean_x >= 0)
    doc.para(
        fmt::format("At the peak (frame {}) the damaged joints (softening or broken) lie {:.1f} mm from x = 0 "
                    "on average.",
                    r.peak_frame, 1e3 * r.peak_damage_mean_x));
  if (!a.no_render) {
    for (const std::string view : {"fragments", "stress"}) {
      doc.para(view + ": start, crack initiation, failure");
      doc.figures({{"", "images/" + view + "/frame_0000.png"},
                   {"", fmt::format("images/{}/frame_{:04d}.png", view, std::max<Index>(0, r.init_frame))},
                   {"", fmt::format("images/{}/frame_{:04d}.png", view, r.last_frame)}});
      doc.animation(view + ", every frame", "images/" + view, "images/" + view + "/frame_0000.png");
    }
  }
  doc.section("Energy ledger");
  doc.para(fmt::format("Largest balance error over the run {:.2e} of the largest energy term ({:.4g} J).",
                       r.balance_max, r.largest_energy));
  doc.figures({{"energy", "images/plots/energy.png"}, {"balance", "images/plots/balance_error.png"}});
  if (a.study) {
    doc.section("Speed against error");
    doc.raw(study_md + "\n");
    doc.figure("error against wall time", "images/plots/study.png");
  }
  // The headline for the figures site: the paper's numbers beside this run's.
  report::Headline& h = doc.headline();
  h.scene = "brazilian_disc", h.title = "Brazilian disc (paper 2.2)";
  h.summary = fmt::format(
      "A rock disc D = {:.0f} mm, L = {:.0f} mm between two {}s, {} elements with a cohesive joint on every "
      "interior face ({} joints), input tensile strength f_t = {:.2f} MPa. The splitting strength 2P/(pi D L) "
      "should read f_t, and the crack run along the loaded diameter.",
      1e3 * r.D, 1e3 * r.L, by, r.elements, r.joints, 1e-6 * r.ft);
  const auto yes = report::agrees;
  // The criteria of the test named beside them (tests/verification/test_disc_unaligned.cpp).
  const bool two_halves = r.mass_fractions.size() >= 2 && r.mass_fractions[1] > 0.35;
  const bool crosses = r.crack_path_slices > r.crack_path_bins / 2;
  h.rows = {
      {"splitting strength against the input f_t", "2.54 MPa for 2.30 MPa: +10 %",
       fmt::format("{:.2f} MPa for {:.2f} MPa: {}", 1e-6 * r.split, 1e-6 * r.ft, pct(r.split_err)),
       yes(std::abs(r.split_err) < 0.15), "DiscUnaligned.SplitsAlongTheDiameterWithinFifteenPercentOfTheStrength"},
      {"peak " + by + " load", "40.6 kN (flat plates)", fmt::format("{:.1f} kN", 1e-3 * r.P_peak),
       yes(std::abs(r.P_peak / 40.6e3 - 1) <= 0.15), ""},
      {"crack", "one crack along the loaded diameter, two halves",
       r.crack_path_mean_x >= 0
           // The traced path (per slice of y, the broken joints' mean x) and, beside it, the broken
           // joints' own mean |x|: a slice with breaks on both sides of x = 0 averages to near it,
           // so the path alone read closer to the diameter than the pictures show.
           ? fmt::format("path mean {:.1f} mm, at most {:.1f} mm from the diameter; broken joints' mean |x| {:.1f} "
                         "mm (element {:.0f} mm); largest pieces {:.2f}, {:.2f}",
                         1e3 * r.crack_path_mean_x, 1e3 * r.crack_path_max_x, 1e3 * r.crack_mean_x,
                         1e3 * c.mesh_num.at("size"), r.mass_fractions.empty() ? 0.0 : r.mass_fractions[0],
                         r.mass_fractions.size() < 2 ? 0.0 : r.mass_fractions[1])
           : "no crack",
       yes(two_halves && crosses && r.crack_path_mean_x >= 0 && r.crack_path_mean_x < c.mesh_num.at("size")),
       "DiscUnaligned.SplitsAlongTheDiameterWithinFifteenPercentOfTheStrength"},
      {"stresses along the loaded diameter, L2 error against the point-load solution", "eqs. 24-25, shown",
       r.P_peak > 0 ? fmt::format("sigma_xx {:.1f} %, sigma_yy {:.1f} %", 100 * r.l2_xx, 100 * r.l2_yy)
                    : std::string("no load reached the disc"),
       "", "DiscField.SigmaAlongTheDiameterWithinFivePercentOnTheCheckMesh"},
      report::balance_row(r.balance_max, "")};
  if (!a.no_render) {
    doc.thumbnail("fragments at the end", fmt::format("images/fragments/frame_{:04d}.png", r.last_frame));
    doc.thumbnail(r.init_frame >= 0 ? "stress at crack initiation" : "stress at the start (no joint broke)",
                  fmt::format("images/stress/frame_{:04d}.png", std::max<Index>(0, r.init_frame)));
  }
  doc.thumbnail("load against closure", "images/plots/load_closure.png");
  h.wall_s = total.seconds();
  doc.write();
  log::info("report: {}/report.md ({:.1f} s)", dir, total.seconds());
  return 0;
}

}  // namespace dspdem
