// The speed-against-error sweep every scene's `--study` runs: variants of the scene's case
// as `--set` overrides, each run into its own folder, a failure kept as that row's text
// while the other rows go on.
#pragma once
#include <functional>
#include <string>
#include <vector>

#include "io/case_config.hpp"
#include "report/report_args.hpp"

namespace dspdem::report {

struct Variant {
  std::string name, knob;         ///< row name and what it changes (for the table)
  std::vector<std::string> sets;  ///< overrides on top of the base's (read when it runs)
  bool reuse = false;             ///< not run: the scene fills its row from a run it already has
};

struct VariantOutcome {
  std::string run_dir;  ///< DIR/study/<name> (empty for reused rows)
  std::string error;    ///< empty when the variant ran and was analysed
};

/// Runs the variants in order. For each one not reused, `run` gets its index and folder and
/// does the work (typically run_variant_case, then the scene's analysis); what it throws
/// (a case the reader refuses, numerical trouble, an analysis that finds no peak) becomes
/// that row's error.
std::vector<VariantOutcome> run_variants(const std::vector<Variant>& variants, const std::string& dir,
                                         const std::function<void(std::size_t, const std::string&)>& run);

/// The study table's rows in the variants' order: `row(i)` for each variant that ran, and for
/// one that failed its name, its knob and "failed: <why>" in a row `width` columns wide.
std::vector<std::vector<std::string>> study_rows(const std::vector<Variant>& variants,
                                                 const std::vector<VariantOutcome>& out, std::size_t width,
                                                 const std::function<std::vector<std::string>(std::size_t)>& row);

/// The base case re-read with the variant's overrides and run into `run_dir` as `runs` says
/// (run_or_resume); returns the case as run (its case.resolved.toml is in the folder).
CaseConfig run_variant_case(const CaseConfig& base, const Variant& v, const std::string& run_dir,
                            const RunPolicy& runs);

/// The overrides of a study's extrinsic-insertion row (issue 20): every fracturing body of
/// `base` extrinsic (the crack front cut, time.insertion_front's default), checked every 10
/// steps, its joint materials' penalty 2 (opened joints only, so it can be low; on the disc 2
/// reads -4.0 % of the intrinsic strength and 3 +2.3 %, cases/README.md). Empty when no body
/// fractures.
std::vector<std::string> extrinsic_overrides(const CaseConfig& base);

}  // namespace dspdem::report
