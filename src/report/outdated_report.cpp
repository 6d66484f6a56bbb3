#include "report/outdated_report.hpp"

#include <fmt/chrono.h>

#include <ctime>
#include <filesystem>
#include <utility>
#include <vector>

#include "core/file.hpp"
#include "core/log.hpp"
#include "io/staging.hpp"
#include "report/headline.hpp"
#include "report/html.hpp"

namespace dspdem::report {

namespace fs = std::filesystem;

bool holds_finished_run(const std::string& run_dir) {
  std::error_code ec;
  return fs::exists(fs::path(run_dir) / "summary.json", ec);
}

void mark_report_outdated(const std::string& dir, const std::string& replaced) {
  if (dir.empty()) return;
  const fs::path d(dir), md_path = d / "report.md";
  const auto md = read_file_if(md_path.string());
  if (!md) return;
  const bool marked =
      md->rfind(kOutdatedMark, 0) == 0 || md->find(std::string("\n") + kOutdatedMark) != std::string::npos;
  if (marked) return;
  const std::string rel = fs::relative(fs::path(replaced), d).string();
  const std::string when = fmt::format("{:%Y-%m-%d %H:%M} UTC", fmt::gmtime(std::time(nullptr)));
  const std::string mark = fmt::format(
      "{} A report started into this folder has replaced a run this text describes (`{}/`, at {}). Until that "
      "report writes its own report here, the text and figures below may not match the runs beside them; if it "
      "stopped, the same report with `--resume` finishes it.",
      kOutdatedMark, rel, when);
  // Under the title (its first line, "# ..."), else at the top.
  std::string title, text;
  if (md->rfind("# ", 0) == 0) {
    const std::size_t eol = md->find('\n');
    title = md->substr(2, eol == std::string::npos ? std::string::npos : eol - 2);
    const std::size_t rest = eol == std::string::npos ? md->size() : eol + 1;
    text = md->substr(0, rest) + "\n" + mark + "\n" + md->substr(rest);
  } else {
    text = mark + "\n\n" + *md;
  }
  std::vector<std::pair<std::string, std::string>> files = {
      {md_path.string(), text}, {(d / "report.html").string(), html_page(title, markdown_to_html(text))}};
  try {
    const fs::path hp = d / "headline.json";
    if (fs::exists(hp)) {
      Headline h = read_headline(hp.string());
      h.summary = mark.substr(2) + " " + h.summary;  // without the blockquote's "> "
      files.emplace_back(hp.string(), headline_json(h));
    }
    write_files_atomic(files);
    log::info("{}: marked outdated: this report has replaced its run in {}/", md_path.string(), rel);
  } catch (const std::exception& e) {
    log::warn("{}: could not mark it outdated ({}); this report has replaced its run in {}/", md_path.string(),
              e.what(), rel);
  }
}

}  // namespace dspdem::report
