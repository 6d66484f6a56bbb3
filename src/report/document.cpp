#include "report/document.hpp"

#include <filesystem>

#include "core/error.hpp"
#include "io/staging.hpp"

namespace dspdem::report {

namespace fs = std::filesystem;

Document::Document(const std::string& dir, const std::string& run_dir)
    : dir_(dir), rel_(fs::relative(run_dir, dir).string()) {}

Document& Document::title(const std::string& text) {
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
Document& Document::raw(const std::string& markdown) {
  md_ += markdown;
  return *this;
}

std::string Document::run_link(const std::string& path_in_run) const { return rel_ + "/" + path_in_run; }

std::string Document::write() const {
  const std::string p = (fs::path(dir_) / "report.md").string();
  write_file_atomic(p, md_);
  return p;
}

}  // namespace dspdem::report
