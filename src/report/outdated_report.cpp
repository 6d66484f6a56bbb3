#include "report/outdated_report.hpp"

#include <fmt/chrono.h>
#include <sys/stat.h>

#include <ctime>
#include <filesystem>
#include <utility>
#include <vector>

#include "core/file.hpp"
#include "core/log.hpp"
#include "io/run_place.hpp"
#include "io/staging.hpp"
#include "report/headline.hpp"
#include "report/html.hpp"

namespace dspdem::report {

namespace fs = std::filesystem;

std::optional<RunReplacement::FileId> RunReplacement::summary_id(const std::string& dir) {
  struct stat st {};
  if (::stat((fs::path(dir) / "summary.json").c_str(), &st) != 0) return std::nullopt;
  return FileId{static_cast<unsigned long long>(st.st_dev), static_cast<unsigned long long>(st.st_ino),
                static_cast<long long>(st.st_mtim.tv_sec) * 1000000000LL + st.st_mtim.tv_nsec};
}

namespace {
// Whether `dir` holds what a report derived from another run (an unreadable record counts).
bool derived(const std::string& dir) {
  try {
    return derived_from(dir).has_value();
  } catch (const std::exception&) {
    return true;
  }
}
}  // namespace

RunReplacement::RunReplacement(std::string run_dir) : dir_(std::move(run_dir)) {
  before_ = summary_id(dir_);
  derived_ = derived(dir_);
  // run.pvd without summary.json: a commit cut short, which moves the old summary.json aside
  // before it removes the rest.
  std::error_code ec;
  held_ = before_.has_value() || derived_ || fs::exists(fs::path(dir_) / "run.pvd", ec);
}

bool RunReplacement::replaced() const {
  if (!held_) return false;
  if (derived_ && !derived(dir_)) return true;
  const auto now = summary_id(dir_);
  return now && (!before_ || !(*now == *before_));
}

void mark_report_outdated(const std::string& dir, const std::string& replaced) {
  if (dir.empty()) return;
  const fs::path d(dir), md_path = d / "report.md";
  try {
    std::error_code ec;
    if (!fs::exists(md_path, ec)) return;
    const std::string md = read_file(md_path.string(), "report");
    if (md.rfind(kOutdatedMark, 0) == 0 || md.find(std::string("\n") + kOutdatedMark) != std::string::npos) return;
    const std::string rel = fs::relative(fs::path(replaced), d).string();
    const std::string when = fmt::format("{:%Y-%m-%d %H:%M} UTC", fmt::gmtime(std::time(nullptr)));
    const std::string mark = fmt::format(
        "{} A report started into this folder has replaced a run this text describes (`{}/`, at {}). Until a "
        "report into this folder finishes, the text and figures below may not match the runs beside them; if it "
        "stopped, the same report with `--resume` finishes it.",
        kOutdatedMark, rel, when);
    // Under the title (its first line, "# ..."), else at the top.
    std::string title, text;
    if (md.rfind("# ", 0) == 0) {
      const std::size_t eol = md.find('\n');
      title = md.substr(2, eol == std::string::npos ? std::string::npos : eol - 2);
      const std::size_t rest = eol == std::string::npos ? md.size() : eol + 1;
      text = md.substr(0, rest) + "\n" + mark + "\n" + md.substr(rest);
    } else {
      text = mark + "\n\n" + md;
    }
    std::vector<std::pair<std::string, std::string>> files = {
        {md_path.string(), text}, {(d / "report.html").string(), html_page(title, markdown_to_html(text))}};
    const fs::path hp = d / "headline.json";
    if (fs::exists(hp, ec)) {
      try {
        Headline h = read_headline(hp.string());
        h.summary = mark.substr(2) + " " + h.summary;  // without the blockquote's "> "
        files.emplace_back(hp.string(), headline_json(h));
      } catch (const std::exception& e) {
        log::warn("{}: not marked outdated with its report ({})", hp.string(), e.what());
      }
    }
    write_files_atomic(files);
    log::info("{}: marked outdated: this report has replaced its run in {}/", md_path.string(), rel);
  } catch (const std::exception& e) {
    log::warn("{}: could not mark it outdated ({}); this report has replaced its run in {}", md_path.string(), e.what(),
              replaced);
  }
}

}  // namespace dspdem::report
