// HTML for reports and the figures site: Markdown (GitHub's, with tables) rendered by
// cmark-gfm, and one page template with the style inline, so a page reads with no network
// and from any folder it is copied to.
#pragma once
#include <string>

namespace dspdem::report {

/// Markdown to an HTML fragment. Raw HTML in the Markdown is kept: reports embed <video>.
std::string markdown_to_html(const std::string& markdown);

/// &, <, >, " escaped.
std::string html_escape(const std::string& text);

/// A relative path as a URL: every byte but letters, digits and - . _ ~ / percent-encoded, so
/// a folder named with #, ?, % or a space still links.
std::string url_path(const std::string& path);

/// A whole page: `body` (HTML) under the given title. The page marks on <body> how many of its
/// images and videos loaded (data-images-loaded, data-images-broken, data-videos-loaded,
/// data-videos-broken) once the window has loaded, which a headless browser test reads.
std::string html_page(const std::string& title, const std::string& body);

}  // namespace dspdem::report
