// A scene's headline: the few numbers a reader compares with the paper first, written by its
// report beside report.md as headline.json, and read by `dspdem figures` to build the index
// page of every scene (report/site.hpp). Paths are relative to the report's folder.
#pragma once
#include <string>
#include <utility>
#include <vector>

namespace dspdem::report {

struct HeadlineRow {
  std::string quantity;
  std::string paper;   ///< what the paper (or the experiment) reports, "-" when it gives nothing
  std::string dspdem;  ///< what this run gives
  std::string agrees;  ///< "yes", "no", or "" when there is nothing to agree with
  std::string test;    ///< the ctest test that checks this figure in CI ("" none)
};

struct Headline {
  std::string scene, title;
  std::string summary;  ///< one or two sentences: what the scene is and what was run
  std::vector<HeadlineRow> rows;
  std::vector<std::pair<std::string, std::string>> images;  ///< (caption, path): the thumbnails
  std::string animation;                                    ///< path without extension of .mp4/.ogv/.gif ("" none)
  double wall_s = 0;                                        ///< the report's whole time, runs included
};

/// "yes" or "no", for HeadlineRow::agrees.
inline std::string agrees(bool met) { return met ? "yes" : "no"; }

/// The row every scene has: the ledger's largest balance error, which agrees below 1 % of the
/// largest term (the brief's bound), checked by `test` ("" none).
HeadlineRow balance_row(double balance_max, const std::string& test,
                        const std::string& quantity = "energy balance, largest error");

/// The text of a headline.json (written with the report, Document::write).
std::string headline_json(const Headline& h);
/// Reads a headline.json; throws Error naming the file and key that is wrong.
Headline read_headline(const std::string& path);

}  // namespace dspdem::report
