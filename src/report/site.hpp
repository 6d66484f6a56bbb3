// The figures site: one index page (HTML and Markdown) over several scenes' report folders,
// with every scene's headline numbers against the paper side by side, its thumbnails linking
// to its report page and its animation playing in the page. Links are relative, so the
// folder can be copied, zipped as a CI artefact or opened from disk with no network.
#pragma once
#include <cstddef>
#include <string>
#include <utility>
#include <vector>

namespace dspdem::report {

struct SiteInfo {
  std::string title = "dspdem figures";
  std::string made_by;  ///< the command line that made the site
  std::string set;      ///< "quick (CI-sized meshes)" or "full"
  double wall_s = 0;
  std::vector<std::pair<std::string, std::string>> failed;  ///< (scene, why) of reports that failed
};

struct SiteWritten {
  std::string index;       ///< the path of index.html
  std::size_t failed = 0;  ///< scenes listed as failed: given in SiteInfo, or found without a headline
};

/// Writes OUT/index.html and OUT/index.md over the report folders (each with report.html and
/// headline.json). A folder without a readable headline is listed as failed with the reason,
/// not skipped in silence. Links are relative: folders outside OUT (--from-runs elsewhere) are
/// linked with ../, so such a site moves only together with them.
SiteWritten write_site(const std::vector<std::string>& report_dirs, const std::string& out, SiteInfo info);

}  // namespace dspdem::report
