#include "report/document.hpp"

#include <filesystem>

#include "core/error.hpp"
#include "io/staging.hpp"
#include "report/html.hpp"

namespace dspdem::report {

namespace fs = std::filesystem;

Document::Document(const std::string& dir, const std::string& run_dir)
    : dir_(dir), rel_(fs::relative(run_dir, dir).string()) {}

Document& Document::title(const std::string& text) {
  if (title_.empty()) title_ = text;
  md_ += "# " + text + "\n\n";
  return *this;
}
Document& Document::section(const std::string& text) {
  md_ += "## " + text + "\n\n";
  return *this;
}
Document& Document::subsection(const std::string& text) {
  md_ += "### " + text + "\n\n";
  return *this;
}
Document& Document::para(const std::string& text) {
  md_ += text + "\n\n";
  return *this;
}
Document& Document::figures(const std::vector<std::pair<std::string, std::string>>& images) {
  for (const auto& [alt, path] : images) md_ += "![" + alt + "](" + run_link(path) + ")\n";
  md_ += "\n";
  return *this;
}
Document& Document::table(const std::vector<std::string>& header, const std::vector<std::vector<std::string>>& rows) {
  auto line = [](const std::vector<std::string>& cells) {
    std::string s = "|";
    for (const auto& c : cells) s += " " + c + " |";
    return s + "\n";
  };
  md_ += line(header);
  md_ += "|";
  for (std::size_t i = 0; i < header.size(); ++i) md_ += "---|";
  md_ += "\n";
  for (const auto& r : rows) {
    DSPDEM_CHECK(r.size() == header.size(), "report table: a row of {} cells under {} headers", r.size(),
                 header.size());
    md_ += line(r);
  }
  md_ += "\n";
  return *this;
}
Document& Document::animation(const std::string& caption, const std::string& base_in_run,
                              const std::string& poster_in_run) {
  // Only the files that exist (ffmpeg writes .mp4 and .gif, VTK always the .ogv): a <source>
  // that is not there would be a broken link in the page.
  auto exists = [&](const std::string& ext) { return fs::exists(fs::path(dir_) / run_link(base_in_run + ext)); };
  std::string sources, links;
  for (const auto& [ext, type] : {std::pair<std::string, std::string>{".mp4", "video/mp4"}, {".ogv", "video/ogg"}})
    if (exists(ext)) sources += "<source src=\"" + url_path(run_link(base_in_run + ext)) + "\" type=\"" + type + "\">";
  for (const std::string ext : {".mp4", ".ogv", ".gif"})
    if (exists(ext)) links += " [" + ext.substr(1) + "](" + run_link(base_in_run + ext) + ")";
  if (links.empty()) return *this;
  if (!sources.empty())
    md_ += "<video controls loop muted preload=\"metadata\" poster=\"" + url_path(run_link(poster_in_run)) +
           "\" title=\"" + html_escape(caption) + "\">" + sources + "</video>\n\n";
  md_ += caption + ", animation:" + links + "\n\n";
  if (headline_.animation.empty()) headline_.animation = run_link(base_in_run);
  return *this;
}
Document& Document::thumbnail(const std::string& caption, const std::string& path_in_run) {
  headline_.images.emplace_back(caption, run_link(path_in_run));
  return *this;
}
Document& Document::raw(const std::string& markdown) {
  md_ += markdown;
  return *this;
}

std::string Document::run_link(const std::string& path_in_run) const { return rel_ + "/" + path_in_run; }

std::string Document::write() const {
  // All or none: a report that fails while writing leaves the earlier report's three files
  // together (and its optional files, report/files_aside.hpp, beside them), never a new
  // report.md beside an old report.html.
  const std::string p = (fs::path(dir_) / "report.md").string();
  std::vector<std::pair<std::string, std::string>> files = {
      {p, md_}, {(fs::path(dir_) / "report.html").string(), html_page(title_, markdown_to_html(md_))}};
  if (!headline_.scene.empty() && !headline_.title.empty())
    files.emplace_back((fs::path(dir_) / "headline.json").string(), headline_json(headline_));
  write_files_atomic(files);
  return p;
}

}  // namespace dspdem::report
