// The figures site that `dspdem figures --quick` wrote into BUILD/figures (the ctest fixture
// figures_quick), opened in headless Chromium with the network cut off: every page's images
// and videos load, no link leaves the site or points at a missing file, the index lists
// every scene, and a screenshot of the index is kept beside it (BUILD/figures/index.png).
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <regex>
#include <sstream>

#include "core/subprocess.hpp"
#include "scenes/registry.hpp"
#include "support/cli.hpp"

namespace fs = std::filesystem;
using dspdem::testsupport::shell;

namespace {
const fs::path kSite = fs::path(DSPDEM_BUILD_DIR) / "figures";

std::string slurp(const fs::path& p) {
  std::ifstream f(p);
  std::stringstream ss;
  ss << f.rdbuf();
  return ss.str();
}

std::vector<fs::path> pages() {
  std::vector<fs::path> out = {kSite / "index.html"};
  for (const auto& s : dspdem::scenes::all()) out.push_back(kSite / s.name / "report.html");
  return out;
}

// A browser profile of this test process's own: ctest -j runs the tests side by side, and two
// Chromiums on one profile refuse or join each other.
fs::path profile() { return fs::temp_directory_path() / ("dspdem_site_chromium_" + std::to_string(getpid())); }

// Chromium with no way out: every host resolves to nothing and a dead proxy takes the rest,
// so a page that needs the network shows it as broken images or videos.
std::string chromium(const std::string& args) {
  std::string bin = dspdem::find_on_path("chromium");
  if (bin.empty()) bin = dspdem::find_on_path("chromium-browser");
  if (bin.empty()) return "";
  return bin + " --headless=new --no-sandbox --disable-gpu --hide-scrollbars --no-first-run --mute-audio " +
         "--proxy-server=http://127.0.0.1:9 --host-resolver-rules='MAP * ~NOTFOUND' --user-data-dir=" +
         profile().string() + " --virtual-time-budget=20000 " + args;
}

int attr(const std::string& dom, const std::string& name) {
  std::smatch m;
  if (!std::regex_search(dom, m, std::regex(name + "=\"([0-9]+)\""))) return -1;
  return std::stoi(m[1]);
}

std::size_t count(const std::string& text, const std::string& what) {
  std::size_t n = 0;
  for (std::size_t i = 0; (i = text.find(what, i)) != std::string::npos; i += what.size()) ++n;
  return n;
}
}  // namespace

class FiguresSite : public ::testing::Test {
 protected:
  void SetUp() override {
    ASSERT_TRUE(fs::exists(kSite / "index.html")) << "no site in " << kSite << ": the fixture figures_quick failed";
    ASSERT_FALSE(chromium("").empty()) << "chromium is not installed (.ci/install-deps installs it)";
  }
  void TearDown() override { fs::remove_all(profile()); }
};

TEST_F(FiguresSite, EveryPageLoadsEveryImageAndVideoWithNoNetwork) {
  for (const auto& page : pages()) {
    ASSERT_TRUE(fs::exists(page)) << page;
    const auto r = shell(chromium("--dump-dom 'file://" + page.string() + "'"));
    ASSERT_EQ(r.code, 0) << r.out;
    // The page's own script marks <body> once the images are decoded and every video has its
    // metadata or has failed (report/html.cpp).
    ASSERT_EQ(attr(r.out, "data-checked"), 1) << page << ": the page's check did not finish";
    const std::string html = slurp(page);
    EXPECT_EQ(attr(r.out, "data-images-broken"), 0) << page;
    EXPECT_EQ(attr(r.out, "data-images-loaded"), static_cast<int>(count(html, "<img "))) << page;
    EXPECT_EQ(attr(r.out, "data-videos-broken"), 0) << page;
    EXPECT_EQ(attr(r.out, "data-videos-loaded"), static_cast<int>(count(html, "<video "))) << page;
  }
}

TEST_F(FiguresSite, EveryLinkStaysInTheSiteAndExists) {
  const std::regex link(R"re((src|href|poster)="([^"]*)")re");
  for (const auto& page : pages()) {
    const std::string html = slurp(page);
    int links = 0;
    for (auto it = std::sregex_iterator(html.begin(), html.end(), link); it != std::sregex_iterator(); ++it) {
      const std::string target = (*it)[2];
      if (target.empty() || target[0] == '#') continue;
      ++links;
      EXPECT_EQ(target.find("://"), std::string::npos) << page << " links outside: " << target;
      EXPECT_NE(target.rfind("//", 0), 0u) << page << " links outside: " << target;
      const fs::path file = fs::weakly_canonical(page.parent_path() / target);
      EXPECT_TRUE(fs::exists(file)) << page << " links a missing file: " << target;
      const std::string site = fs::weakly_canonical(kSite).string() + "/";
      EXPECT_EQ(file.string().rfind(site, 0), 0u) << page << " links outside the site folder: " << target;
    }
    EXPECT_GT(links, 3) << page;
  }
}

TEST_F(FiguresSite, TheIndexShowsEverySceneAgainstThePaper) {
  const std::string html = slurp(kSite / "index.html");
  EXPECT_EQ(html.find("report failed"), std::string::npos) << "a scene's report failed: see " << kSite / "logs";
  for (const auto& s : dspdem::scenes::all()) {
    EXPECT_NE(html.find("id=\"" + s.name + "\""), std::string::npos) << s.name << " missing from the index";
    EXPECT_TRUE(fs::exists(kSite / s.name / "headline.json")) << s.name;
  }
  EXPECT_NE(html.find("<th>paper</th><th>dspdem</th>"), std::string::npos);
  EXPECT_TRUE(fs::exists(kSite / "index.md"));
}

TEST_F(FiguresSite, ScreenshotOfTheIndex) {
  const fs::path shot = kSite / "index.png";
  fs::remove(shot);
  const auto r = shell(chromium("--window-size=1400,2400 --screenshot=" + shot.string() + " 'file://" +
                                (kSite / "index.html").string() + "'"));
  ASSERT_EQ(r.code, 0) << r.out;
  ASSERT_TRUE(fs::exists(shot)) << r.out;
  // A blank 1400x2400 page compresses to a few kB; the index with its table and thumbnails
  // is hundreds.
  EXPECT_GT(fs::file_size(shot), 100000u);
}
