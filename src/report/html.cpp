#include "report/html.hpp"

#include <cmark-gfm-core-extensions.h>
#include <cmark-gfm.h>
#include <fmt/format.h>

#include <cctype>
#include <cstdlib>
#include <memory>

#include "core/error.hpp"

namespace dspdem::report {

std::string markdown_to_html(const std::string& markdown) {
  cmark_gfm_core_extensions_ensure_registered();
  const int options = CMARK_OPT_UNSAFE;  // our own Markdown: keep its <video> blocks
  std::unique_ptr<cmark_parser, void (*)(cmark_parser*)> parser(cmark_parser_new(options), cmark_parser_free);
  for (const char* name : {"table", "autolink", "strikethrough"}) {
    cmark_syntax_extension* ext = cmark_find_syntax_extension(name);
    DSPDEM_CHECK(ext != nullptr, "cmark-gfm has no '{}' extension", name);
    cmark_parser_attach_syntax_extension(parser.get(), ext);
  }
  cmark_parser_feed(parser.get(), markdown.data(), markdown.size());
  std::unique_ptr<cmark_node, void (*)(cmark_node*)> doc(cmark_parser_finish(parser.get()), cmark_node_free);
  char* html = cmark_render_html(doc.get(), options, cmark_parser_get_syntax_extensions(parser.get()));
  std::string out(html);
  std::free(html);
  return out;
}

std::string html_escape(const std::string& text) {
  std::string out;
  out.reserve(text.size());
  for (char c : text) switch (c) {
      case '&':
        out += "&amp;";
        break;
      case '<':
        out += "&lt;";
        break;
      case '>':
        out += "&gt;";
        break;
      case '"':
        out += "&quot;";
        break;
      default:
        out += c;
    }
  return out;
}

std::string url_path(const std::string& path) {
  std::string out;
  for (unsigned char c : path) {
    if (std::isalnum(c) || c == '-' || c == '.' || c == '_' || c == '~' || c == '/')
      out += static_cast<char>(c);
    else
      out += fmt::format("%{:02X}", c);
  }
  return out;
}

std::string html_page(const std::string& title, const std::string& body) {
  // The style is inline and the script tiny: the page must read offline, copied anywhere.
  static const char* kStyle = R"(
body { font-family: "DejaVu Sans", Helvetica, Arial, sans-serif; max-width: 72rem; margin: 1.5rem auto;
       padding: 0 1rem; color: #222; line-height: 1.45; }
h1 { font-size: 1.6rem; } h2 { font-size: 1.3rem; margin-top: 2rem; border-bottom: 1px solid #ddd; }
h3 { font-size: 1.1rem; }
table { border-collapse: collapse; margin: 0.8rem 0; font-size: 0.92rem; }
th, td { border: 1px solid #ccc; padding: 0.25rem 0.5rem; text-align: left; vertical-align: top; }
th { background: #f2f2f2; }
img { max-width: 100%; height: auto; border: 1px solid #eee; }
p img { max-width: 32%; margin-right: 0.5%; }
p img:only-child { max-width: 75%; }
video { max-width: 75%; height: auto; border: 1px solid #eee; }
code { background: #f4f4f4; padding: 0 0.2rem; font-size: 0.9em; }
.yes { color: #1a7f37; font-weight: bold; } .no { color: #c62828; font-weight: bold; }
.scene { margin: 1.5rem 0; padding-top: 0.5rem; border-top: 2px solid #ddd; }
.thumbs a img { width: 31%; margin-right: 1%; }
.muted { color: #666; font-size: 0.9rem; }
td.ci { max-width: 15rem; overflow-wrap: anywhere; } td.ci code { font-size: 0.75rem; background: none; }
)";
  // Marks on <body> how many images and videos loaded, once every video has its metadata or
  // has failed (or after 8 s): what tests/figures/test_site.cpp reads in a headless browser.
  static const char* kScript = R"(
window.addEventListener('load', function () {
  var ok = 0, bad = 0, vok = 0, vbad = 0, done = false;
  document.querySelectorAll('img').forEach(function (i) { if (i.complete && i.naturalWidth > 0) ok++; else bad++; });
  var videos = Array.prototype.slice.call(document.querySelectorAll('video')), pending = videos.length;
  function finish() {
    if (done) return; done = true;
    var b = document.body;
    b.setAttribute('data-images-loaded', ok); b.setAttribute('data-images-broken', bad);
    b.setAttribute('data-videos-loaded', vok); b.setAttribute('data-videos-broken', vbad + pending);
    b.setAttribute('data-checked', '1');
  }
  function settle(good) { if (done) return; if (good) vok++; else vbad++; if (--pending === 0) finish(); }
  videos.forEach(function (v) {
    if (v.readyState >= 1) { settle(true); return; }
    var once = false, mark = function (g) { if (!once) { once = true; settle(g); } };
    v.addEventListener('loadedmetadata', function () { mark(true); });
    v.addEventListener('error', function () { mark(false); });
    var s = v.querySelectorAll('source');
    if (s.length) s[s.length - 1].addEventListener('error', function () { mark(false); });
  });
  if (pending === 0) finish(); else setTimeout(finish, 8000);
});
)";
  return "<!DOCTYPE html>\n<html lang=\"en\">\n<head>\n<meta charset=\"utf-8\">\n<title>" + html_escape(title) +
         "</title>\n<meta name=\"viewport\" content=\"width=device-width, initial-scale=1\">\n<style>" + kStyle +
         "</style>\n<script>" + kScript + "</script>\n</head>\n<body>\n" + body + "\n</body>\n</html>\n";
}

}  // namespace dspdem::report
