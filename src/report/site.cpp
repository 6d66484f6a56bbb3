#include "report/site.hpp"

#include <fmt/format.h>

#include <filesystem>

#include "io/staging.hpp"
#include "report/headline.hpp"
#include "report/html.hpp"

namespace dspdem::report {

namespace fs = std::filesystem;

namespace {
struct Entry {
  Headline h;
  std::string rel;  ///< the report folder relative to the site's folder
};

std::string agrees_html(const std::string& a) {
  if (a.empty()) return "";
  return "<span class=\"" + std::string(a == "yes" ? "yes" : "no") + "\">" + html_escape(a) + "</span>";
}

// A cell may hold inline Markdown (`code`, **bold**): render it without the paragraph.
std::string inline_html(const std::string& md) {
  if (md == "-") return "&ndash;";  // Markdown would read a lone dash as a list
  std::string h = markdown_to_html(md);
  if (h.rfind("<p>", 0) == 0 && h.size() >= 8 && h.compare(h.size() - 5, 5, "</p>\n") == 0)
    h = h.substr(3, h.size() - 8);
  return h;
}

std::string md_cell(const std::string& s) {
  std::string out;
  for (char ch : s) {
    if (ch == '|') out += '\\';
    out += ch;
  }
  return out;
}
}  // namespace

SiteWritten write_site(const std::vector<std::string>& report_dirs, const std::string& out, SiteInfo info) {
  fs::create_directories(out);
  std::vector<Entry> entries;
  for (const auto& d : report_dirs) {
    const fs::path hp = fs::path(d) / "headline.json";
    if (!fs::exists(hp)) {
      info.failed.emplace_back(fs::path(d).filename().string(), "no headline.json in " + d);
      continue;
    }
    try {
      entries.push_back({read_headline(hp.string()), fs::relative(d, out).string()});
    } catch (const std::exception& e) {
      info.failed.emplace_back(fs::path(d).filename().string(), e.what());
    }
  }
  const std::string intro = fmt::format(
      "Each benchmark scene of the paper (Zhang et al. 2024, CJGE 46(9): the 3D deformable spheropolyhedral DEM) run "
      "by dspdem: what the paper or its experiment reports, and what dspdem gets, side by side. Set: {}. Made by `{}` "
      "in {:.0f} s. Every figure links to its scene's full report (method, plots, energy ledger, speed).",
      info.set, info.made_by, info.wall_s);

  // index.html
  std::string b = "<h1>" + html_escape(info.title) + "</h1>\n<p>" + inline_html(intro) + "</p>\n";
  b += "<h2>Every scene against the paper</h2>\n<p class=\"muted\">agrees: by the criterion of the CI test named "
       "in the last column, which checks it on its own CI-sized run.</p>\n<table>\n<tr><th>scene</th><th>quantity</th>"
       "<th>paper</th><th>dspdem</th><th>agrees</th><th>checked in CI by</th></tr>\n";
  for (const auto& e : entries) {
    const std::size_t n = std::max<std::size_t>(1, e.h.rows.size());
    b += fmt::format("<tr><td rowspan=\"{}\"><a href=\"#{}\">{}</a></td>", n, url_path(e.h.scene),
                     html_escape(e.h.title));
    if (e.h.rows.empty()) b += "<td colspan=\"5\">no headline figures</td></tr>\n";
    for (std::size_t i = 0; i < e.h.rows.size(); ++i) {
      const auto& r = e.h.rows[i];
      if (i) b += "<tr>";
      b += "<td>" + inline_html(r.quantity) + "</td><td>" + inline_html(r.paper) + "</td><td>" + inline_html(r.dspdem) +
           "</td><td>" + agrees_html(r.agrees) + "</td><td class=\"ci\">" +
           (r.test.empty() ? std::string() : "<code>" + html_escape(r.test) + "</code>") + "</td></tr>\n";
    }
  }
  for (const auto& [scene, why] : info.failed)
    b += "<tr><td>" + html_escape(scene) +
         "</td><td colspan=\"5\"><span class=\"no\">report failed</span>: " + html_escape(why) + "</td></tr>\n";
  b += "</table>\n";
  for (const auto& e : entries) {
    const std::string page = e.rel + "/report.html";
    b += fmt::format("<div class=\"scene\" id=\"{}\">\n<h2>{}</h2>\n<p>{}</p>\n<p class=\"thumbs\">",
                     url_path(e.h.scene), html_escape(e.h.title), inline_html(e.h.summary));
    for (const auto& [caption, path] : e.h.images)
      b += fmt::format("<a href=\"{}\"><img src=\"{}\" alt=\"{}\" title=\"{}\"></a>", url_path(page),
                       url_path(e.rel + "/" + path), html_escape(caption), html_escape(caption));
    b += "</p>\n";
    if (!e.h.animation.empty()) {
      const std::string base = e.rel + "/" + e.h.animation;
      std::string sources;
      for (const auto& [ext, type] : {std::pair<std::string, std::string>{".mp4", "video/mp4"}, {".ogv", "video/ogg"}})
        if (fs::exists(fs::path(out) / (base + ext)))
          sources += "<source src=\"" + url_path(base + ext) + "\" type=\"" + type + "\">";
      // The animation's first frame as its poster, when the frames lie beside it as a view's do.
      const std::string poster = base + "/frame_0000.png";
      const std::string poster_attr =
          fs::exists(fs::path(out) / poster) ? " poster=\"" + url_path(poster) + "\"" : std::string();
      if (!sources.empty())
        b += "<video controls loop muted preload=\"metadata\" width=\"640\"" + poster_attr + ">" + sources +
             "</video>\n";
    }
    b += fmt::format(
        "<p><a href=\"{}\">Full report</a> (<a href=\"{}/report.md\">Markdown</a>), made in {:.0f} s.</p>\n</div>\n",
        url_path(page), url_path(e.rel), e.h.wall_s);
  }
  const std::string index = (fs::path(out) / "index.html").string();
  write_file_atomic(index, html_page(info.title, b));

  // index.md: the same for a reader on a Markdown viewer.
  std::string m = "# " + info.title + "\n\n" + intro + "\n\n## Every scene against the paper\n\n";
  m += "| scene | quantity | paper | dspdem | agrees | checked in CI by |\n|---|---|---|---|---|---|\n";
  for (const auto& e : entries) {
    if (e.h.rows.empty())
      m += fmt::format("| [{}]({}/report.md) | no headline figures | | | | |\n", md_cell(e.h.title), e.rel);
    for (std::size_t i = 0; i < e.h.rows.size(); ++i) {
      const auto& r = e.h.rows[i];
      const std::string scene = i ? std::string() : fmt::format("[{}]({}/report.md)", md_cell(e.h.title), e.rel);
      m += fmt::format("| {} | {} | {} | {} | {} | {} |\n", scene, md_cell(r.quantity), md_cell(r.paper),
                       md_cell(r.dspdem), r.agrees, r.test.empty() ? std::string() : "`" + r.test + "`");
    }
  }
  for (const auto& [scene, why] : info.failed)
    m += fmt::format("| {} | report failed: {} | | | | |\n", scene, md_cell(why));
  m += "\n";
  for (const auto& e : entries) {
    m += "## " + e.h.title + "\n\n" + e.h.summary + "\n\n";
    for (const auto& [caption, path] : e.h.images) m += "![" + caption + "](" + e.rel + "/" + path + ")\n";
    m += "\n[Full report](" + e.rel + "/report.md)\n\n";
  }
  write_file_atomic((fs::path(out) / "index.md").string(), m);
  return {index, info.failed.size()};
}

}  // namespace dspdem::report
