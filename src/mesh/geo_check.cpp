#include "mesh/geo_check.hpp"

#include <algorithm>
#include <array>
#include <cctype>
#include <filesystem>
#include <string_view>

#include "core/error.hpp"
#include "core/file.hpp"
#include "mesh/msh_check.hpp"

namespace dspdem {

namespace {
namespace fs = std::filesystem;

// Commands that act outside the model: processes, files, the process itself.
constexpr std::array<std::string_view, 9> kRefused = {
    "SystemCall", "NonBlockingSystemCall", "OnelabRun", "Exit", "CreateDir", "DeleteFile", "RenameFile", "Save",
    "Print"};
// What a script may Include or Merge besides scripts and meshes: geometry to mesh.
constexpr std::array<std::string_view, 8> kDataFiles = {".step", ".stp", ".brep", ".iges",
                                                        ".igs",  ".stl", ".STEP", ".STP"};
// Nested includes deeper than this are refused (a file including itself would not end).
constexpr int kMostDepth = 16;

struct Scanner {
  const std::string& path;
  const std::string& text;
  std::size_t pos = 0;
  int line = 1;

  template <typename... A>
  [[noreturn]] void error(fmt::format_string<A...> f, A&&... a) const {
    fail("mesh file '{}': line {}: {}", path, line, fmt::format(f, std::forward<A>(a)...));
  }
  char at(std::size_t i) const { return i < text.size() ? text[i] : '\0'; }
  void advance() {
    if (text[pos] == '\n') ++line;
    ++pos;
  }
  // Past blanks and comments (// to the line's end, /* */).
  void skip_space() {
    while (pos < text.size()) {
      if (std::isspace(static_cast<unsigned char>(text[pos]))) {
        advance();
      } else if (text[pos] == '/' && at(pos + 1) == '/') {
        while (pos < text.size() && text[pos] != '\n') advance();
      } else if (text[pos] == '/' && at(pos + 1) == '*') {
        const int from = line;
        pos += 2;
        while (pos < text.size() && !(text[pos] == '*' && at(pos + 1) == '/')) advance();
        if (pos >= text.size()) line = from, error("a comment /* is never closed");
        pos += 2;
      } else {
        return;
      }
    }
  }
  // A quoted string starting at pos: its text (escapes kept as written), pos past it.
  std::string string_literal() {
    const int from = line;
    std::string s;
    for (advance(); pos < text.size() && text[pos] != '"'; advance()) {
      if (text[pos] == '\\' && pos + 1 < text.size()) s += text[pos], advance();
      s += text[pos];
    }
    if (pos >= text.size()) line = from, error("a string \" is never closed");
    advance();
    return s;
  }
};

void check_script(const std::string& path, const std::string& text, int depth);

// Whether the word just read names an option category ("Print.Width = 800;"), not a command.
bool option_category(const Scanner& sc) {
  std::size_t i = sc.pos;
  while (i < sc.text.size() && (sc.text[i] == ' ' || sc.text[i] == '\t')) ++i;
  return sc.at(i) == '.';
}

// A file a script includes or merges, named by `name` relative to the script's folder.
void check_included(const Scanner& sc, const std::string& command, const std::string& name, int depth) {
  if (name.find('\\') != std::string::npos)
    sc.error("{} \"{}\": a file name with an escape is not read (give the name as it is)", command, name);
  fs::path p(name);
  if (p.is_relative()) p = fs::path(sc.path).parent_path() / p;
  const std::string ext = p.extension().string();
  if (std::find(kDataFiles.begin(), kDataFiles.end(), ext) != kDataFiles.end()) return;
  if (ext != ".geo" && ext != ".msh")
    sc.error("{} \"{}\": dspdem lets a script read .geo, .msh, STEP, BREP, IGES and STL files only", command, name);
  if (!fs::exists(p)) sc.error("{} \"{}\": the file {} does not exist", command, name, p.string());
  if (depth >= kMostDepth) sc.error("{} \"{}\": scripts nested more than {} deep", command, name, kMostDepth);
  // The fault named in the file that has it, and where the case's own script includes it.
  try {
    const std::string inner = read_file(p.string(), "mesh file");
    if (ext == ".msh")
      check_msh_text(p.string(), inner);
    else
      check_script(p.string(), inner, depth + 1);
  } catch (const Error& e) {
    if (depth > 0) throw;  // named once, by the case's own script, not at every level
    sc.error("{} \"{}\": {}", command, name, e.what());
  }
}

void check_script(const std::string& path, const std::string& text, int depth) {
  Scanner sc{path, text};
  while (true) {
    sc.skip_space();
    if (sc.pos >= text.size()) return;
    const char ch = text[sc.pos];
    if (ch == '"') {
      sc.string_literal();
      continue;
    }
    if (!(std::isalpha(static_cast<unsigned char>(ch)) || ch == '_')) {
      sc.advance();
      continue;
    }
    const std::size_t from = sc.pos;
    while (sc.pos < text.size() && (std::isalnum(static_cast<unsigned char>(text[sc.pos])) || text[sc.pos] == '_'))
      ++sc.pos;
    const std::string_view word(text.data() + from, sc.pos - from);
    if (std::find(kRefused.begin(), kRefused.end(), word) != kRefused.end() && !option_category(sc))
      sc.error("the command {} acts outside the model (a program, a file or the process); dspdem does not run it",
               word);
    if (word == "Printf") {
      // Printf(...) prints; Printf(...) > "file" writes: a '>' past its closing parenthesis.
      int paren = 0;
      for (sc.skip_space(); sc.pos < text.size() && text[sc.pos] != ';'; sc.skip_space()) {
        const char c = text[sc.pos];
        if (c == '"') {
          sc.string_literal();
          continue;
        }
        if (c == '(') ++paren;
        if (c == ')') --paren;
        if (c == '>' && paren == 0) sc.error("Printf into a file: dspdem does not let a script write files");
        sc.advance();
      }
    } else if (word == "Include" || word == "Merge") {
      sc.skip_space();
      if (sc.at(sc.pos) != '"')
        sc.error("{} of a name made by the script: dspdem checks a file it reads, so give its name in quotes", word);
      const std::string name = sc.string_literal();
      sc.skip_space();
      if (sc.at(sc.pos) != ';')
        sc.error("{} \"{}\": expected ';' after the file name (a name made by the script is not checked)", word, name);
      check_included(sc, std::string(word), name, depth);
    }
  }
}
}  // namespace

void check_geo_script(const std::string& path, const std::string& text) { check_script(path, text, 0); }

}  // namespace dspdem
