// A scene's report.md, built in order: title, sections, paragraphs, figures, animations and
// tables, with links to the run's files relative to the report's folder (the run may be
// DIR/run or any folder given with --from-run). Written atomically, so a failed report never
// leaves half a file over an earlier one; report.html (the same, rendered) and, when the scene
// filled it, its headline.json for `dspdem figures` beside it.
#pragma once
#include <string>
#include <utility>
#include <vector>

#include "report/headline.hpp"

namespace dspdem::report {

class Document {
 public:
  /// `dir`: the report's folder; `run_dir`: the run whose files the report links.
  Document(const std::string& dir, const std::string& run_dir);

  Document& title(const std::string& text);
  Document& section(const std::string& text);
  Document& subsection(const std::string& text);
  Document& para(const std::string& text);
  /// Images side by side in one paragraph: (alt text, path inside the run folder).
  Document& figures(const std::vector<std::pair<std::string, std::string>>& images);
  Document& figure(const std::string& alt, const std::string& path_in_run) { return figures({{alt, path_in_run}}); }
  /// A Markdown table; every row must have the header's number of cells.
  Document& table(const std::vector<std::string>& header, const std::vector<std::vector<std::string>>& rows);
  /// An animation of a view, played in the page: `base_in_run` is the path without extension
  /// of its .mp4 / .ogv / .gif (those that exist are offered), `poster_in_run` its first frame.
  Document& animation(const std::string& caption, const std::string& base_in_run, const std::string& poster_in_run);
  /// Markdown written elsewhere (a study's table), taken as it is.
  Document& raw(const std::string& markdown);

  /// Link from the report's folder to a file of the run ("" gives the run folder itself).
  std::string run_link(const std::string& path_in_run) const;
  const std::string& text() const { return md_; }

  /// The scene's headline for the figures site; scene and title set mean "write it".
  Headline& headline() { return headline_; }
  /// Adds a picture of the run to the headline's thumbnails.
  Document& thumbnail(const std::string& caption, const std::string& path_in_run);

  /// Writes DIR/report.md, DIR/report.html and (with a headline) DIR/headline.json; returns
  /// the path of report.md.
  std::string write() const;

 private:
  std::string dir_, rel_, md_, title_;
  Headline headline_;
};

}  // namespace dspdem::report
