// Fuzzed case files and meshes (issue 21): broken inputs are read or refused cleanly.
//
// A mutation-based generator with a fixed seed (std::mt19937_64, so every run reads the
// same inputs) takes the shipped valid inputs, the case files cases/*.toml and
// tests/data/*.toml and small gmsh meshes written here in the v2.2, v4.1 and v4.0 ASCII
// formats, and breaks them: byte flips, lines deleted or duplicated, truncation, numbers
// swapped for huge, negative, NaN, infinite or empty values, misspelt keys and section
// names, values of another type, garbage sections, unbalanced quotes and brackets,
// references to files or nodes that do not exist. Each mutant is written to a temporary
// folder and parsed only: read_case for case files (an accepted case is not run) and
// read_gmsh for .msh files (nothing is meshed). For every mutant:
//   - no crash: a fatal signal prints which input was being read before the test dies;
//   - no hang: an input must be read within kSlowSeconds, and a watchdog ends the test with
//     the input's name once one has taken kHangSeconds;
//   - no exception but dspdem::Error escapes (std::out_of_range, std::invalid_argument,
//     toml++'s or gmsh's own... are defects of the readers);
//   - every refusal names the file and a place in it: a line ("file:12:" or "line"), a key
//     or section, an element or a node; and, no --set being given, never blames one.
// The counts of accepted and refused mutants are printed; failing inputs are kept in
// $TMPDIR/dspdem_fuzz_failures for a rerun, and DSPDEM_FUZZ_LOG=<file> logs every outcome.
#include <cxxabi.h>
#include <fmt/format.h>
#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <array>
#include <atomic>
#include <chrono>
#include <condition_variable>
#include <csignal>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <functional>
#include <iostream>
#include <map>
#include <mutex>
#include <random>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include "core/error.hpp"
#include "io/case_config.hpp"
#include "io/case_schema.hpp"
#include "mesh/gmsh_reader.hpp"

using namespace dspdem;

namespace {
namespace fs = std::filesystem;
using Clock = std::chrono::steady_clock;

constexpr std::uint64_t kSeed = 0x2121'd5de'f022'0001ULL;  // issue 21; never changed, so runs compare
constexpr int kCaseMutants = 3000;
constexpr int kMeshMutants = 2000;
// DSPDEM_FUZZ_SCALE=<k>: k times as many mutants, for a longer campaign by hand (the first
// ones are the same; ctest runs the counts above).
int scaled(int n) {
  const char* k = std::getenv("DSPDEM_FUZZ_SCALE");
  return k && std::atoi(k) > 1 ? n * std::atoi(k) : n;
}
constexpr double kSlowSeconds = 5;   // an input read slower than this fails the test
constexpr double kHangSeconds = 30;  // the watchdog ends the process after this on one input
constexpr int kReportedFailures = 25;

// ---------------------------------------------------------------------------------------
// Crash and hang reports. A signal handler may only write(2) what is already in memory, so
// the name of the input being read is kept in a fixed buffer.

char g_current[2048] = "(none)";
std::atomic<std::int64_t> g_started_ns{0};  // when the current input started; 0: idle

std::int64_t now_ns() {
  return std::chrono::duration_cast<std::chrono::nanoseconds>(Clock::now().time_since_epoch()).count();
}

void write_stderr(const char* s) {
  const ssize_t r = ::write(2, s, std::strlen(s));
  (void)r;
}

extern "C" void on_fatal_signal(int sig) {
  write_stderr("\n[fuzz] fatal signal while reading ");
  write_stderr(g_current);
  write_stderr(" (the file is left in place)\n");
  std::signal(sig, SIG_DFL);
  std::raise(sig);
}

/// Installs the crash report for the signals a reader bug would raise, and the hang
/// watchdog; both are removed when it goes out of scope.
class Guard {
 public:
  Guard() {
    for (int i = 0; i < kN; ++i) old_[i] = std::signal(kSignals[i], on_fatal_signal);
    watchdog_ = std::thread([this] {
      std::unique_lock<std::mutex> lock(m_);
      while (!cv_.wait_for(lock, std::chrono::milliseconds(100), [this] { return stop_; })) {
        const std::int64_t t0 = g_started_ns.load();
        if (t0 != 0 && (now_ns() - t0) * 1e-9 > kHangSeconds) {
          write_stderr(fmt::format("\n[fuzz] no answer after {} s while reading ", kHangSeconds).c_str());
          write_stderr(g_current);
          write_stderr(" (the file is left in place)\n");
          std::_Exit(124);
        }
      }
    });
  }
  ~Guard() {
    {
      std::lock_guard<std::mutex> lock(m_);
      stop_ = true;
    }
    cv_.notify_all();
    watchdog_.join();
    for (int i = 0; i < kN; ++i) std::signal(kSignals[i], old_[i]);
  }
  Guard(const Guard&) = delete;
  Guard& operator=(const Guard&) = delete;

 private:
  static constexpr int kN = 5;
  static constexpr int kSignals[kN] = {SIGSEGV, SIGBUS, SIGFPE, SIGILL, SIGABRT};
  void (*old_[kN])(int) = {};
  std::thread watchdog_;
  std::mutex m_;
  std::condition_variable cv_;
  bool stop_ = false;
};

// ---------------------------------------------------------------------------------------
// Random choices. below() is the raw 64-bit draw modulo n: its bias is negligible here and,
// unlike std::uniform_int_distribution, it gives the same inputs with every standard library.

class Rng {
 public:
  explicit Rng(std::uint64_t seed) : g_(seed) {}
  std::size_t below(std::size_t n) { return n == 0 ? 0 : static_cast<std::size_t>(g_() % n); }
  bool percent(unsigned p) { return below(100) < p; }
  template <class T>
  const T& pick(const std::vector<T>& v) {
    return v[below(v.size())];
  }

 private:
  std::mt19937_64 g_;
};

// ---------------------------------------------------------------------------------------
// Text helpers.

std::string slurp(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

void spit(const fs::path& p, const std::string& text) {
  std::ofstream out(p, std::ios::binary | std::ios::trunc);
  out << text;
}

/// Lines with their '\n' kept, so that joining them gives the text back.
std::vector<std::string> split_lines(const std::string& s) {
  std::vector<std::string> out;
  std::size_t b = 0;
  while (b < s.size()) {
    const std::size_t e = s.find('\n', b);
    const std::size_t end = e == std::string::npos ? s.size() : e + 1;
    out.push_back(s.substr(b, end - b));
    b = end;
  }
  return out;
}

std::string join(const std::vector<std::string>& lines) {
  std::string s;
  for (const auto& l : lines) s += l;
  return s;
}

bool is_word_char(char c) { return std::isalnum(static_cast<unsigned char>(c)) || c == '_'; }
bool is_digit(char c) { return c >= '0' && c <= '9'; }

/// Spans [begin, end) of the number tokens of a text (not digits inside a word).
std::vector<std::pair<std::size_t, std::size_t>> number_spans(const std::string& s) {
  std::vector<std::pair<std::size_t, std::size_t>> out;
  for (std::size_t i = 0; i < s.size();) {
    const bool starts =
        (is_digit(s[i]) || ((s[i] == '-' || s[i] == '+' || s[i] == '.') && i + 1 < s.size() && is_digit(s[i + 1]))) &&
        (i == 0 || !is_word_char(s[i - 1]));
    if (!starts) {
      ++i;
      continue;
    }
    std::size_t j = i + 1;
    while (j < s.size() && (is_digit(s[j]) || std::strchr(".eE+-_", s[j]) != nullptr)) ++j;
    out.emplace_back(i, j);
    i = j;
  }
  return out;
}

// ---------------------------------------------------------------------------------------
// The mutator. Generic operations on text, with format-specific replacement tables.

enum class Format { Toml, Msh };

class Mutator {
 public:
  Mutator(Rng& rng, Format f) : rng_(rng), f_(f) {}

  /// One to three mutations of `text`, and what was done (for failure reports).
  std::string mutate(std::string text, std::string& log) {
    const unsigned r = static_cast<unsigned>(rng_.below(100));
    const int n = r < 55 ? 1 : r < 85 ? 2 : 3;
    for (int i = 0; i < n; ++i) {
      const char* what = nullptr;
      text = once(std::move(text), what);
      log += (log.empty() ? "" : ", ") + std::string(what);
    }
    return text;
  }

 private:
  std::string once(std::string s, const char*& what) {
    // Weights: the operations that keep the syntax valid are the ones that reach the
    // schema and the mesh checks, so they come more often than byte noise.
    const std::size_t k = rng_.below(100);
    if (k < 8) return what = "byte flip", flip_byte(std::move(s));
    if (k < 16) return what = "line deleted", delete_line(std::move(s));
    if (k < 22) return what = "line duplicated", duplicate_line(std::move(s));
    if (k < 26) return what = "truncated", truncate(std::move(s));
    if (k < 48) return what = "number swapped", swap_number(std::move(s));
    if (k < 58) return what = "key misspelt", misspell_key(std::move(s));
    if (k < 68) return what = "type changed", change_type(std::move(s));
    if (k < 76) return what = "garbage inserted", insert_garbage(std::move(s));
    if (k < 82) return what = "quotes/brackets unbalanced", unbalance(std::move(s));
    if (f_ == Format::Toml) return what = "file reference", file_reference(std::move(s));
    if (k < 91) return what = "dangling node", dangling_node(std::move(s));
    return what = "section count", section_count(std::move(s));
  }

  std::string flip_byte(std::string s) {
    if (s.empty()) return s;
    const std::size_t p = rng_.below(s.size());
    if (rng_.percent(50))
      s[p] = static_cast<char>(s[p] ^ (1 << rng_.below(8)));
    else
      s[p] = static_cast<char>(rng_.below(256));
    return s;
  }

  std::string delete_line(std::string s) {
    auto lines = split_lines(s);
    if (lines.empty()) return s;
    lines.erase(lines.begin() + static_cast<std::ptrdiff_t>(rng_.below(lines.size())));
    return join(lines);
  }

  std::string duplicate_line(std::string s) {
    auto lines = split_lines(s);
    if (lines.empty()) return s;
    const std::string l = lines[rng_.below(lines.size())];
    const std::size_t at = rng_.percent(50) ? rng_.below(lines.size() + 1) : std::min(lines.size(), rng_.below(2));
    lines.insert(lines.begin() + static_cast<std::ptrdiff_t>(at), l.back() == '\n' ? l : l + "\n");
    return join(lines);
  }

  std::string truncate(std::string s) { return s.substr(0, rng_.below(s.size() + 1)); }

  std::string swap_number(std::string s) {
    static const std::vector<std::string> toml = {"nan",
                                                  "+nan",
                                                  "-nan",
                                                  "inf",
                                                  "-inf",
                                                  "1e999",
                                                  "-1e999",
                                                  "1.0e308",
                                                  "-1.7976931348623157e308",
                                                  "4.9e-324",
                                                  "1e-400",
                                                  "0",
                                                  "0.0",
                                                  "-0.0",
                                                  "-1",
                                                  "-1.0",
                                                  "-2500.0",
                                                  "1",
                                                  "2",
                                                  "3",
                                                  "9223372036854775807",
                                                  "9223372036854775808",
                                                  "-9223372036854775808",
                                                  "99999999999999999999",
                                                  "2147483648",
                                                  "0x7fffffff",
                                                  "0o777",
                                                  "0b101",
                                                  "1_000",
                                                  "1__0",
                                                  "1.",
                                                  ".5",
                                                  "1e",
                                                  "--1",
                                                  "",
                                                  "\"1.0\"",
                                                  "true",
                                                  "1.0.0",
                                                  "1979-05-27"};
    static const std::vector<std::string> msh = {"nan",
                                                 "inf",
                                                 "-inf",
                                                 "1e400",
                                                 "-1e400",
                                                 "0",
                                                 "-0",
                                                 "-1",
                                                 "-2",
                                                 "1",
                                                 "2",
                                                 "3",
                                                 "4",
                                                 "5",
                                                 "6",
                                                 "8",
                                                 "11",
                                                 "13",
                                                 "15",
                                                 "17",
                                                 "99",
                                                 "65535",
                                                 "2147483647",
                                                 "2147483648",
                                                 "4294967295",
                                                 "4294967296",
                                                 "9223372036854775807",
                                                 "18446744073709551615",
                                                 "99999999999999999999",
                                                 "1.5",
                                                 "2.2",
                                                 "4.1",
                                                 "5.0",
                                                 "",
                                                 "x",
                                                 "0x10",
                                                 "1e308"};
    const auto spans = number_spans(s);
    if (spans.empty()) return s;
    const auto [b, e] = spans[rng_.below(spans.size())];
    return s.replace(b, e - b, rng_.pick(f_ == Format::Toml ? toml : msh));
  }

  static std::string misspell(std::string w, Rng& rng) {
    if (w.empty()) return "x";
    const std::size_t p = rng.below(w.size());
    switch (rng.below(6)) {
      case 0:
        return w.erase(p, 1);
      case 1:
        return w.insert(p, 1, w[p]);
      case 2:
        if (w.size() > 1) std::swap(w[p], w[(p + 1) % w.size()]);
        return w;
      case 3:
        w[p] =
            static_cast<char>(std::isupper(static_cast<unsigned char>(w[p])) ? std::tolower(w[p]) : std::toupper(w[p]));
        return w;
      case 4:
        return w + "s";
      default:
        for (auto& c : w)
          if (c == '_') c = '-';
        return w + "_";
    }
  }

  std::string misspell_key(std::string s) {
    auto lines = split_lines(s);
    std::vector<std::size_t> cand;
    for (std::size_t i = 0; i < lines.size(); ++i) {
      const std::string& l = lines[i];
      const std::size_t b = l.find_first_not_of(" \t");
      if (b == std::string::npos) continue;
      if (f_ == Format::Toml && (std::isalpha(static_cast<unsigned char>(l[b])) || l[b] == '[')) cand.push_back(i);
      if (f_ == Format::Msh && l[b] == '$') cand.push_back(i);
    }
    if (cand.empty()) return s;
    std::string& l = lines[rng_.pick(cand)];
    // The name: letters, digits, '_', '.' after any leading '[' or '$'.
    std::size_t b = l.find_first_not_of(" \t[$");
    if (b == std::string::npos) return s;
    std::size_t e = b;
    while (e < l.size() && (is_word_char(l[e]) || l[e] == '.')) ++e;
    l.replace(b, e - b, misspell(l.substr(b, e - b), rng_));
    return join(lines);
  }

  std::string change_type(std::string s) {
    static const std::vector<std::string> toml = {"\"text\"",
                                                  "''",
                                                  "\"\"",
                                                  "true",
                                                  "false",
                                                  "42",
                                                  "4.2",
                                                  "-7",
                                                  "[]",
                                                  "[1.0, 2.0]",
                                                  "[1.0, 2.0, 3.0]",
                                                  "[1.0, 2.0, 3.0, 4.0]",
                                                  "[1, \"a\", true]",
                                                  "[\"a\", \"b\"]",
                                                  "[[1.0], [2.0], [3.0]]",
                                                  "[nan, inf, -inf]",
                                                  "[1e999, 0.0, 0.0]",
                                                  "{ x = 1 }",
                                                  "{}",
                                                  "[{ a = 1 }]",
                                                  "1979-05-27T07:32:00Z",
                                                  "07:32:00",
                                                  "\"\"\"two\nlines\"\"\"",
                                                  "'''raw'''",
                                                  "\"\\u00e9\\t\\\\\"",
                                                  "\"bad escape \\q\"",
                                                  "\"x:\"",
                                                  "\":y\""};
    static const std::vector<std::string> msh = {"",
                                                 "\"text\"",
                                                 "1 2",
                                                 "1.5 2.5 3.5",
                                                 "-",
                                                 "$",
                                                 "$End",
                                                 "0 0 0 0 0 0 0 0 0 0 0 0 0 0 0 0",
                                                 "1 4 2 1 1 1 2 3 4",
                                                 "1 0 0 0",
                                                 "nan nan nan nan",
                                                 "\t \t"};
    auto lines = split_lines(s);
    if (lines.empty()) return s;
    if (f_ == Format::Msh) {
      std::string& l = lines[rng_.below(lines.size())];
      l = rng_.pick(msh) + "\n";
      return join(lines);
    }
    std::vector<std::size_t> cand;
    for (std::size_t i = 0; i < lines.size(); ++i)
      if (lines[i].find('=') != std::string::npos && lines[i].find_first_not_of(" \t") != std::string::npos &&
          lines[i][lines[i].find_first_not_of(" \t")] != '#')
        cand.push_back(i);
    if (cand.empty()) return s;
    std::string& l = lines[rng_.pick(cand)];
    l = l.substr(0, l.find('=') + 1) + " " + rng_.pick(toml) + "\n";
    return join(lines);
  }

  std::string insert_garbage(std::string s) {
    static const std::vector<std::string> toml = {
        "[garbage]\nkey = 1\n",
        "[[materials]]\nname = \"x\"\n",
        "[materials.rock.inner]\nx = 1\n",
        "[materials.extra]\n",
        "[materials.\"\"]\ndensity = 1.0\nE = 1.0\nnu = 0.1\n",
        "[case]\nname = \"again\"\n",
        "[[bodies]]\n",
        "[[bodies]]\nname = \"b2\"\ngroups = []\nmaterial = \"nothing\"\n",
        "[[walls]]\nname = \"w\"\ntype = \"box\"\n",
        "[[walls]]\nname = \"c\"\ntype = \"cylinder\"\nradius = 1.0\nlength = 1.0\nfree = true\nmass = 1.0\n",
        "[[walls]]\nname = \"j\"\ntype = \"jaw\"\nradius = 1.0\naxis = [0.0, 0.0, 1.0]\nnormal = [0.0, 0.0, 1.0]\n",
        "[[monitors]]\nname = \"m\"\ntype = \"displacement_difference\"\ngroup = \"g\"\n",
        "[[boundary]]\ngroup = \"g\"\ntype = \"velocity\"\ndofs = \"\"\n",
        "[[initial]]\ngroup = \"g\"\nvelocity = [1.0, \"2\", 3.0]\n",
        "[contact]\nenabled = true\n",
        "[mesh.galvez_beam]\nwidth = 1.0\n",
        "[mesh.nonexistent_generator]\n",
        "[render]\nrange_min = 1.0\nrange_max = 0.0\nplots = [\"x:\", \":y\", \"xy\"]\n",
        "[time]\nend = 1.0\n",
        "a.b.c = 1\n",
        "\"quoted key\" = 1\n",
        "= 1\n",
        "key =\n",
        "[\n",
        "]]\n",
        "[[]]\n",
        "[ case . name ]\n",
        "x = [1, 2,\n",
        "y = { a = 1, a = 2 }\n",
        "\t\t  \n",
        std::string("nul = \"a\0b\"\n", 12),
        "bad = \"\xff\xfe\"\n",
        "\xef\xbb\xbf# BOM\n",
        std::string(5000, '['),
        std::string(20000, 'x') + " = 1\n"};
    static const std::vector<std::string> msh = {"$Garbage\n1 2 3\n$EndGarbage\n",
                                                 "$Comments\nanything\n$EndComments\n",
                                                 "$Nodes\n",
                                                 "$EndNodes\n",
                                                 "$Elements\n",
                                                 "$EndElements\n",
                                                 "$MeshFormat\n4.1 0 8\n$EndMeshFormat\n",
                                                 "$MeshFormat\n2.2 0 8\n$EndMeshFormat\n",
                                                 "$PhysicalNames\n1\n3 7 \"extra\"\n$EndPhysicalNames\n",
                                                 "$PhysicalNames\n1\n3 2 \"block\"\n$EndPhysicalNames\n",
                                                 "$PhysicalNames\n2\n3 2 \"dup\"\n3 3 \"dup\"\n$EndPhysicalNames\n",
                                                 "$NodeData\n1\n\"u\"\n1\n0.0\n3\n0\n3\n1\n1 0 0 0\n$EndNodeData\n",
                                                 "$Periodic\n1\n2 1 1\n0\n$EndPeriodic\n",
                                                 "$Nodes\n1\n99 1 2 3\n$EndNodes\n",
                                                 "$Elements\n1\n99 4 2 2 1 1 2 3 4\n$EndElements\n",
                                                 "$Elements\n1\n99 29 2 2 1 1 2 3 4 5 6 7 8 9 10 11 12 13 14 15 16 "
                                                 "17 18 19 20\n$EndElements\n",
                                                 std::string("\0\0\0\0", 4),
                                                 "\xff\xfe\xfd\n",
                                                 std::string(5000, '9') + "\n",
                                                 "\n\n\n"};
    auto lines = split_lines(s);
    const std::size_t at = rng_.below(lines.size() + 1);
    lines.insert(lines.begin() + static_cast<std::ptrdiff_t>(at), rng_.pick(f_ == Format::Toml ? toml : msh));
    return join(lines);
  }

  std::string unbalance(std::string s) {
    static const std::vector<std::string> ins = {"\"", "'", "[", "]", "{", "}", "\"\"\"", "[[", "'''", "\\"};
    if (rng_.percent(50)) {
      std::vector<std::size_t> pos;
      for (std::size_t i = 0; i < s.size(); ++i)
        if (std::strchr("\"'[]{}", s[i]) != nullptr && s[i] != '\0') pos.push_back(i);
      if (!pos.empty()) return s.erase(rng_.pick(pos), 1);
    }
    return s.insert(rng_.below(s.size() + 1), rng_.pick(ins));
  }

  std::string file_reference(std::string s) {
    static const std::vector<std::string> paths = {
        "\"/nonexistent/dir/mesh.msh\"",         "\"missing.msh\"", "\"missing.geo\"",  "\"\"", "\"meshes\"",
        "\"../../../../../../nonexistent.csv\"", "\"mesh.txt\"",    "\"a\\u0000b.msh\""};
    auto lines = split_lines(s);
    std::vector<std::size_t> cand;
    for (std::size_t i = 0; i < lines.size(); ++i) {
      const std::string& l = lines[i];
      const std::size_t b = l.find_first_not_of(" \t");
      if (b != std::string::npos && (l.compare(b, 4, "file") == 0 || l.compare(b, 14, "plot_reference") == 0 ||
                                     l.compare(b, 9, "generator") == 0))
        cand.push_back(i);
    }
    if (cand.empty()) return s + "[render]\nplot_reference = " + rng_.pick(paths) + "\n";
    std::string& l = lines[rng_.pick(cand)];
    l = (rng_.percent(70) ? l.substr(0, l.find('=') + 1) : std::string("file =")) + " " + rng_.pick(paths) + "\n";
    return join(lines);
  }

  /// An element's node replaced by one that is not in $Nodes (or not a node at all).
  std::string dangling_node(std::string s) {
    static const std::vector<std::string> tags = {"0", "-3", "13", "999", "4294967297", "1e3", "x"};
    auto lines = split_lines(s);
    std::vector<std::size_t> cand;
    bool in = false;
    for (std::size_t i = 0; i < lines.size(); ++i) {
      if (lines[i].rfind("$Elements", 0) == 0) in = true;
      if (lines[i].rfind("$EndElements", 0) == 0) in = false;
      if (in && std::count(lines[i].begin(), lines[i].end(), ' ') >= 3) cand.push_back(i);
    }
    if (cand.empty()) return s;
    std::string& l = lines[rng_.pick(cand)];
    std::string body = l.substr(0, l.find_last_not_of("\n ") + 1);
    const std::size_t sp = body.rfind(' ');
    l = body.substr(0, sp + 1) + rng_.pick(tags) + "\n";
    return join(lines);
  }

  /// The count under a section header changed: too small, too large, absurd.
  std::string section_count(std::string s) {
    static const std::vector<std::string> counts = {"0",          "-1",         "1",          "2",
                                                    "1000000000", "2147483648", "4294967296", "9223372036854775807"};
    auto lines = split_lines(s);
    std::vector<std::size_t> cand;
    for (std::size_t i = 0; i + 1 < lines.size(); ++i)
      if (lines[i].rfind("$Nodes", 0) == 0 || lines[i].rfind("$Elements", 0) == 0 ||
          lines[i].rfind("$PhysicalNames", 0) == 0 || lines[i].rfind("$Entities", 0) == 0)
        cand.push_back(i + 1);
    if (cand.empty()) return s;
    std::string& l = lines[rng_.pick(cand)];
    const std::size_t sp = l.find(' ');
    const std::string rest = sp == std::string::npos ? "\n" : l.substr(sp);
    if (sp != std::string::npos && rng_.percent(40)) {  // v4: the other numbers of the header
      auto fields = number_spans(l);
      const auto [b, e] = fields[rng_.below(fields.size())];
      l.replace(b, e - b, rng_.pick(counts));
    } else {
      l = rng_.pick(counts) + rest;
    }
    return join(lines);
  }

  Rng& rng_;
  Format f_;
};

// ---------------------------------------------------------------------------------------
// Seed meshes: two unit cubes side by side, as two hex8 or twelve tet4, with a volume group
// "block" and a surface group "left" (the faces at x = 0), written as gmsh v2.2, v4.1 and v4.0.

struct SeedMesh {
  std::vector<std::array<double, 3>> nodes;  // tag = index + 1
  int volume_type = 5;                       // 4 tet4, 5 hex8
  std::vector<std::vector<int>> volume, surface;
  int surface_type = 3;  // 2 tri3, 3 quad4
};

SeedMesh seed_mesh(bool hexes) {
  SeedMesh m;
  for (int k = 0; k < 2; ++k)
    for (int j = 0; j < 2; ++j)
      for (int i = 0; i < 3; ++i) m.nodes.push_back({double(i), double(j), double(k)});
  auto id = [](int i, int j, int k) { return 1 + i + 3 * (j + 2 * k); };
  for (int i = 0; i < 2; ++i) {
    // gmsh order: bottom face counter-clockwise seen from above, then the top face.
    const int c[8] = {id(i, 0, 0), id(i + 1, 0, 0), id(i + 1, 1, 0), id(i, 1, 0),
                      id(i, 0, 1), id(i + 1, 0, 1), id(i + 1, 1, 1), id(i, 1, 1)};
    if (hexes) {
      m.volume.push_back(std::vector<int>(c, c + 8));
      continue;
    }
    // Six positive tets about the diagonal 0-6 (the split of mesh.cpp's element_volume).
    const int t[6][4] = {{0, 1, 2, 6}, {0, 2, 3, 6}, {0, 3, 7, 6}, {0, 7, 4, 6}, {0, 4, 5, 6}, {0, 5, 1, 6}};
    for (const auto& q : t) m.volume.push_back({c[q[0]], c[q[1]], c[q[2]], c[q[3]]});
  }
  const int l[4] = {id(0, 0, 0), id(0, 1, 0), id(0, 1, 1), id(0, 0, 1)};
  m.volume_type = hexes ? 5 : 4;
  m.surface_type = hexes ? 3 : 2;
  if (hexes)
    m.surface.push_back({l[0], l[1], l[2], l[3]});
  else
    m.surface = {{l[0], l[1], l[2]}, {l[0], l[2], l[3]}};
  return m;
}

std::string ints(const std::vector<int>& v) {
  std::string s;
  for (int x : v) s += fmt::format(" {}", x);
  return s;
}

std::string write_msh2(const SeedMesh& m) {
  std::string s = "$MeshFormat\n2.2 0 8\n$EndMeshFormat\n";
  s += "$PhysicalNames\n2\n2 1 \"left\"\n3 2 \"block\"\n$EndPhysicalNames\n";
  s += fmt::format("$Nodes\n{}\n", m.nodes.size());
  for (std::size_t i = 0; i < m.nodes.size(); ++i)
    s += fmt::format("{} {} {} {}\n", i + 1, m.nodes[i][0], m.nodes[i][1], m.nodes[i][2]);
  s += fmt::format("$EndNodes\n$Elements\n{}\n", m.surface.size() + m.volume.size());
  int tag = 0;
  for (const auto& e : m.surface) s += fmt::format("{} {} 2 1 1{}\n", ++tag, m.surface_type, ints(e));
  for (const auto& e : m.volume) s += fmt::format("{} {} 2 2 1{}\n", ++tag, m.volume_type, ints(e));
  return s + "$EndElements\n";
}

/// Format 4.1, or 4.0 (each node on one line, entity tags before dimensions, no tag ranges).
std::string write_msh4(const SeedMesh& m, bool v40) {
  std::string s = fmt::format("$MeshFormat\n{} 0 8\n$EndMeshFormat\n", v40 ? "4" : "4.1");
  s += "$PhysicalNames\n2\n2 1 \"left\"\n3 2 \"block\"\n$EndPhysicalNames\n";
  // One surface (physical 1) and one volume (physical 2) bounded by it.
  s += "$Entities\n0 0 1 1\n1 0 0 0 0 1 1 1 1 0\n1 0 0 0 2 1 1 1 2 1 1\n$EndEntities\n";
  // The nodes at x = 0 are classified on the surface, the others on the volume.
  std::vector<int> on_surface, inside;
  for (std::size_t i = 0; i < m.nodes.size(); ++i) (m.nodes[i][0] == 0 ? on_surface : inside).push_back(int(i) + 1);
  s += v40 ? fmt::format("$Nodes\n2 {}\n", m.nodes.size())
           : fmt::format("$Nodes\n2 {} 1 {}\n", m.nodes.size(), m.nodes.size());
  auto xyz = [&](int t) {
    const auto& x = m.nodes[static_cast<std::size_t>(t - 1)];
    return fmt::format("{} {} {}", x[0], x[1], x[2]);
  };
  for (const auto& [dim, block] : {std::pair{2, &on_surface}, std::pair{3, &inside}}) {
    s += v40 ? fmt::format("1 {} 0 {}\n", dim, block->size()) : fmt::format("{} 1 0 {}\n", dim, block->size());
    if (v40) {
      for (int t : *block) s += fmt::format("{} {}\n", t, xyz(t));
      continue;
    }
    for (int t : *block) s += fmt::format("{}\n", t);
    for (int t : *block) s += xyz(t) + "\n";
  }
  const std::size_t n = m.surface.size() + m.volume.size();
  s += v40 ? fmt::format("$EndNodes\n$Elements\n2 {}\n", n) : fmt::format("$EndNodes\n$Elements\n2 {} 1 {}\n", n, n);
  int tag = 0;
  // Block headers: 4.1 "dimension entity type count", 4.0 "entity dimension type count".
  auto block = [&](int dim, int type, std::size_t count) {
    return v40 ? fmt::format("1 {} {} {}\n", dim, type, count) : fmt::format("{} 1 {} {}\n", dim, type, count);
  };
  s += block(2, m.surface_type, m.surface.size());
  for (const auto& e : m.surface) s += fmt::format("{}{}\n", ++tag, ints(e));
  s += block(3, m.volume_type, m.volume.size());
  for (const auto& e : m.volume) s += fmt::format("{}{}\n", ++tag, ints(e));
  return s + "$EndElements\n";
}

// ---------------------------------------------------------------------------------------
// Checking one mutant.

/// Does a refusal name the file and a place in it: "file:<line>", "line", one of `places`
/// (key and section names, "element", "node"...)?
bool names_a_place(const std::string& msg, const std::string& path, const std::vector<std::string>& places) {
  bool named = false;
  for (std::size_t p = msg.find(path); p != std::string::npos; p = msg.find(path, p + 1)) {
    named = true;
    const std::size_t q = p + path.size();
    if (q + 1 < msg.size() && msg[q] == ':' && is_digit(msg[q + 1])) return true;
  }
  if (!named) return false;
  if (msg.find("line") != std::string::npos) return true;
  for (const auto& w : places)
    if (msg.find(w) != std::string::npos) return true;
  return false;
}

/// The names a case-file refusal may point at: every schema key, quoted or as a word long
/// enough not to match by chance, and every section.
std::vector<std::string> case_places() {
  std::vector<std::string> out;
  for (const auto& k : schema::keys()) {
    out.push_back(fmt::format("'{}'", k.key));
    if (std::strlen(k.key) >= 5) out.push_back(k.key);
  }
  for (const char* s : schema::sections()) {
    std::string base(s);
    base = base.substr(0, base.find_first_of(".["));
    for (const char* f : {"[{}", "[[{}]]", "'{}'"}) out.push_back(fmt::format(fmt::runtime(f), base));
  }
  return out;
}

const std::vector<std::string>& mesh_places() {
  static const std::vector<std::string> p = {"element",   "node",           "$MeshFormat",
                                             "$Nodes",    "$Elements",      "$PhysicalNames",
                                             "$Entities", "physical group", "volume group"};
  return p;
}

std::string demangle(const char* name) {
  int status = 0;
  char* d = abi::__cxa_demangle(name, nullptr, nullptr, &status);
  std::string out = status == 0 && d ? d : name;
  std::free(d);
  return out;
}

/// A printable excerpt of an input for failure messages.
std::string excerpt(const std::string& s, std::size_t max = 600) {
  std::string out;
  for (char c : s.substr(0, max)) {
    const auto u = static_cast<unsigned char>(c);
    out += (u >= 32 && u < 127) || c == '\n' ? std::string(1, c) : fmt::format("\\x{:02x}", u);
  }
  return s.size() > max ? out + "..." : out;
}

struct Tally {
  int accepted = 0, rejected = 0, failed = 0;  // each input in exactly one
  double slowest = 0;
  int slowest_index = -1;
};

/// A problem with numbers and the file's name taken out, so that the same defect met by
/// many mutants is counted as one.
std::string problem_kind(std::string p, const std::string& path) {
  for (std::size_t q = p.find(path); q != std::string::npos; q = p.find(path, q)) p.replace(q, path.size(), "<file>");
  std::string out;
  for (std::size_t i = 0; i < p.size(); ++i) {
    if (!is_digit(p[i])) {
      out += p[i];
      continue;
    }
    out += 'N';
    while (i + 1 < p.size() && is_digit(p[i + 1])) ++i;
  }
  return out.substr(0, 300);
}

class Fuzzer {
 public:
  Fuzzer(const char* kind, std::string ext, std::function<void(const std::string&)> read,
         std::vector<std::string> places)
      : kind_(kind), ext_(std::move(ext)), read_(std::move(read)), places_(std::move(places)) {
    dir_ = fs::temp_directory_path() / fmt::format("dspdem_fuzz_{}_{}", kind_, ::getpid());
    keep_ = fs::temp_directory_path() / "dspdem_fuzz_failures";
    fs::create_directories(dir_);
    file_ = dir_ / ("mutant" + ext_);
    // DSPDEM_FUZZ_LOG=<file>: every mutant's outcome and message, to review what the
    // readers say.
    if (const char* log = std::getenv("DSPDEM_FUZZ_LOG")) log_.open(fmt::format("{}.{}", log, kind_));
  }
  ~Fuzzer() {
    std::error_code ec;
    if (tally_.failed == 0) fs::remove_all(dir_, ec);
  }
  Fuzzer(const Fuzzer&) = delete;
  Fuzzer& operator=(const Fuzzer&) = delete;

  /// Writes `text` to the mutant file and reads it; records the outcome, and any failure
  /// with the input kept for a rerun.
  void run(int index, const std::string& origin, const std::string& how, const std::string& text) {
    spit(file_, text);
    std::snprintf(g_current, sizeof g_current, "%s mutant #%d (%s of %s) at %s", kind_, index, how.c_str(),
                  origin.c_str(), file_.c_str());
    const std::string path = file_.string();
    std::string problem, message = "(accepted)";
    const std::int64_t t0 = now_ns();
    g_started_ns = t0;
    try {
      read_(path);
    } catch (const Error& e) {
      message = e.what();
      if (!names_a_place(message, path, places_))
        problem = fmt::format("the refusal names no place in the file: \"{}\"", message);
      else if (message.find("(--set)") != std::string::npos)  // no overrides are given here
        problem = fmt::format("the refusal blames a --set override that was not given: \"{}\"", message);
    } catch (const std::exception& e) {
      message = e.what();
      problem = fmt::format("{} escaped the reader: \"{}\"", demangle(typeid(e).name()), message);
    } catch (...) {
      message = "?";
      problem = "an exception of a non-standard type escaped the reader";
    }
    g_started_ns = 0;
    const double s = (now_ns() - t0) * 1e-9;
    if (s > tally_.slowest) tally_.slowest = s, tally_.slowest_index = index;
    if (s > kSlowSeconds)
      problem += (problem.empty() ? "" : "; ") + fmt::format("read in {:.1f} s (limit {} s)", s, kSlowSeconds);
    if (log_)
      log_ << index << " [" << how << " of " << origin << "] " << (problem.empty() ? "ok" : "FAIL") << ": " << message
           << "\n";
    if (problem.empty()) {
      ++(message == "(accepted)" ? tally_.accepted : tally_.rejected);
      return;
    }
    ++tally_.failed;
    auto& k = kinds_[problem_kind(problem, path)];
    if (k.first++ == 0) k.second = index;
    fs::create_directories(keep_);
    const fs::path kept = keep_ / fmt::format("{}_{}{}", kind_, index, ext_);
    spit(kept, text);
    if (tally_.failed <= kReportedFailures)
      ADD_FAILURE() << kind_ << " mutant #" << index << " (" << how << " of " << origin << "): " << problem
                    << "\n  kept as " << kept.string() << "\n--- input ---\n"
                    << excerpt(text) << "\n-------------";
  }

  const Tally& tally() const { return tally_; }
  void report(int n, double seconds) const {
    const std::string line = fmt::format(
        "[fuzz] {} mutants: {}, {} read ({} accepted, {} refused cleanly, {} failed) in {:.2f} s; slowest #{} {:.3f} s",
        kind_, n, tally_.accepted + tally_.rejected + tally_.failed, tally_.accepted, tally_.rejected, tally_.failed,
        seconds, tally_.slowest_index, tally_.slowest);
    std::cout << line << std::endl;
    for (const auto& [what, count] : kinds_)
      std::cout << fmt::format("[fuzz]   {} x (first #{}): {}", count.first, count.second, what) << std::endl;
    ::testing::Test::RecordProperty(fmt::format("{}_mutants", kind_), n);
    ::testing::Test::RecordProperty(fmt::format("{}_accepted", kind_), tally_.accepted);
    ::testing::Test::RecordProperty(fmt::format("{}_rejected", kind_), tally_.rejected);
  }

 private:
  const char* kind_;
  std::string ext_;
  std::function<void(const std::string&)> read_;
  std::vector<std::string> places_;
  fs::path dir_, keep_, file_;
  std::ofstream log_;
  Tally tally_;
  std::map<std::string, std::pair<int, int>> kinds_;  // problem -> (count, first mutant)
};

std::vector<fs::path> sorted_files(const fs::path& dir, const std::string& ext) {
  std::vector<fs::path> out;
  for (const auto& e : fs::directory_iterator(dir))
    if (e.is_regular_file() && e.path().extension() == ext) out.push_back(e.path());
  std::sort(out.begin(), out.end());
  return out;
}

// Runs n mutants of randomly chosen seeds through the fuzzer (same seed, same mutants),
// reports them and checks that each was either accepted or refused; returns n.
int run_mutants(Fuzzer& fuzz, const std::vector<std::pair<std::string, std::string>>& seeds, std::uint64_t seed,
                Format format, int n) {
  Guard guard;
  Rng rng(seed);
  Mutator mut(rng, format);
  const auto t0 = Clock::now();
  for (int i = 0; i < n; ++i) {
    const auto& [name, text] = seeds[rng.below(seeds.size())];
    std::string how;
    const std::string m = mut.mutate(text, how);
    fuzz.run(i, name, how, m);
  }
  const double s = std::chrono::duration<double>(Clock::now() - t0).count();
  fuzz.report(n, s);
  EXPECT_EQ(fuzz.tally().accepted + fuzz.tally().rejected, n);
  return n;
}

}  // namespace

TEST(FuzzInputs, CaseFiles) {
  std::vector<std::pair<std::string, std::string>> seeds;  // (name, text)
  for (const char* d : {"cases", "tests/data"})
    for (const auto& p : sorted_files(fs::path(DSPDEM_SOURCE_DIR) / d, ".toml"))
      seeds.emplace_back(fmt::format("{}/{}", d, p.filename().string()), slurp(p));
  ASSERT_GE(seeds.size(), 8u) << "the shipped case files were not found under " << DSPDEM_SOURCE_DIR;

  Fuzzer fuzz(
      "case", ".toml", [](const std::string& p) { read_case(p); }, case_places());
  // The seeds themselves are valid: a mutant's refusal is then the mutation's doing.
  for (const auto& [name, text] : seeds) {
    spit(fs::temp_directory_path() / "dspdem_fuzz_seed.toml", text);
    EXPECT_NO_THROW(read_case((fs::temp_directory_path() / "dspdem_fuzz_seed.toml").string())) << name;
  }
  fs::remove(fs::temp_directory_path() / "dspdem_fuzz_seed.toml");

  const int n = run_mutants(fuzz, seeds, kSeed, Format::Toml, scaled(kCaseMutants));
  // The mutations must reach past the TOML parser into the schema, and some must survive it.
  EXPECT_GT(fuzz.tally().accepted, n / 20);
  EXPECT_GT(fuzz.tally().rejected, n / 2);
}

TEST(FuzzInputs, GmshMeshes) {
  std::vector<std::pair<std::string, std::string>> seeds = {
      {"v2.2 hex8", write_msh2(seed_mesh(true))},        {"v2.2 tet4", write_msh2(seed_mesh(false))},
      {"v4.1 hex8", write_msh4(seed_mesh(true), false)}, {"v4.1 tet4", write_msh4(seed_mesh(false), false)},
      {"v4.0 hex8", write_msh4(seed_mesh(true), true)},  {"v4.0 tet4", write_msh4(seed_mesh(false), true)}};
  const fs::path seed_file = fs::temp_directory_path() / fmt::format("dspdem_fuzz_seed_{}.msh", ::getpid());
  for (const auto& [name, text] : seeds) {
    spit(seed_file, text);
    try {
      const Mesh m = read_gmsh(seed_file.string());
      EXPECT_EQ(m.n_nodes(), 12) << name;
      EXPECT_EQ(m.n_elements(), name.find("hex8") != std::string::npos ? 2 : 12) << name;
      ASSERT_NE(m.find_group("left"), nullptr) << name;
      EXPECT_EQ(m.find_group("left")->nodes.size(), 4u) << name;
      ASSERT_NE(m.find_group("block"), nullptr) << name;
    } catch (const Error& e) {
      ADD_FAILURE() << "seed mesh " << name << " refused: " << e.what() << "\n" << text;
    }
  }
  fs::remove(seed_file);

  Fuzzer fuzz(
      "mesh", ".msh", [](const std::string& p) { read_gmsh(p); }, mesh_places());
  const int n = run_mutants(fuzz, seeds, kSeed + 1, Format::Msh, scaled(kMeshMutants));
  // Mesh mutants break structure more often than case mutants break meaning.
  EXPECT_GT(fuzz.tally().accepted, n / 100);
  EXPECT_GT(fuzz.tally().rejected, n / 2);
}
