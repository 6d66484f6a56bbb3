#include "mesh/geo_check.hpp"

#include <algorithm>
#include <array>
#include <cctype>
#include <filesystem>
#include <set>
#include <string_view>

#include "core/error.hpp"
#include "core/file.hpp"
#include "mesh/msh_check.hpp"

namespace dspdem {

namespace {
namespace fs = std::filesystem;

// Commands that act outside the model: processes, files, the process itself, and names of
// commands made at run time (gmsh 4.8's Gmsh.y: its general commands are matched by name).
constexpr std::array<std::string_view, 15> kRefused = {"SystemCall", "System",       "NonBlockingSystemCall",
                                                       "OnelabRun",  "OnelabAction", "SendToServer",
                                                       "Exit",       "Sleep",        "CreateDir",
                                                       "Save",       "Print",        "Plugin",
                                                       "S2N",        "StringToName", "MergeWithBoundingBox"};
// What Delete may not take: Options resets gmsh's own options (General.AbortOnError with them,
// so that an error no longer stops the script); All and Model free what the parser still reads.
constexpr std::array<std::string_view, 3> kRefusedDeletes = {"Options", "All", "Model"};
// Option categories a mesh script does not set.
constexpr std::array<std::string_view, 2> kRefusedOptions = {"General", "Solver"};
// What a script may Merge besides scripts and meshes: geometry to mesh, spelt as gmsh 4.8 knows
// it (GuessFileFormatFromFileName); any other spelling gmsh parses as a script.
constexpr std::array<std::string_view, 13> kDataFiles = {".stl", ".STL", ".step", ".STEP", ".stp", ".STP", ".brep",
                                                         ".brp", ".BRP", ".iges", ".IGES", ".igs", ".IGS"};
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
  // Past blanks and comments (// to the line's end, /* */), as gmsh's lexer.
  void skip_space() {
    while (pos < text.size()) {
      const char c = text[pos];
      if (c == ' ' || c == '\t' || c == '\n' || c == '\r' || c == '\f') {
        advance();
      } else if (c == '/' && at(pos + 1) == '/') {
        while (pos < text.size() && text[pos] != '\n') advance();
      } else if (c == '/' && at(pos + 1) == '*') {
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
  // A string in double or single quotes starting at pos: its text, pos past it. gmsh knows
  // no escapes: a backslash is a character like any other.
  std::string string_literal() {
    const int from = line;
    const char quote = text[pos];
    std::string s;
    for (advance(); pos < text.size() && text[pos] != quote; advance()) s += text[pos];
    if (pos >= text.size()) line = from, error("a string {} is never closed", quote);
    // gmsh's lexer cuts a string at 1023 characters and reads the rest as code.
    if (s.size() > 1023) line = from, error("a string of {} characters: gmsh reads at most 1023", s.size());
    advance();
    return s;
  }
  // Whether the word just read is followed, past any blanks, by `c` ('.': an option's
  // category, "Print.Width").
  bool before(char c) const { return next_after(text, pos) == c; }
  static char next_after(const std::string& t, std::size_t i) {
    while (i < t.size() && (t[i] == ' ' || t[i] == '\t' || t[i] == '\n' || t[i] == '\r' || t[i] == '\f')) ++i;
    return i < t.size() ? t[i] : '\0';
  }
};

// Files checked whole already (by command and name, and the option-file chains beside them):
// each is read once, however many times it is included (a chain of files each including the
// next ten times made 10^15 reads).
using Checked = std::set<std::string>;

void check_script(const std::string& path, const std::string& text, int depth, Checked& done);

// Mesh.MaxNumThreads1D, 2D, 3D: meshing on several threads.
bool threads_option(std::string_view word) { return word.rfind("MaxNumThreads", 0) == 0; }

// gmsh (FixRelativePath, SplitFileName) takes a backslash for a folder separator and "c:" for a drive,
// where std::filesystem on Linux reads them as characters of the name.
bool plain_file_name(const std::string& name) {
  return name.find('\\') == std::string::npos && !(name.size() >= 2 && name[1] == ':');
}
constexpr const char* kNotPlain =
    "a backslash or a drive letter in the name: gmsh takes them for folders, and would read another file than the one "
    "checked";

// gmsh reads a file it merges by its first line, whatever its name (gmsh 4.8's MergeFile):
// a mesh, checked as a mesh file (a surface mesh merged to build a volume has no volume
// elements); a script, checked as one; a post-processing view, which a mesh file may not hold.
void check_by_first_line(const std::string& path, const std::string& text, int depth, Checked& done) {
  switch (gmsh_reads_as(text)) {
    case GmshText::View:
      fail("mesh file '{}': a post-processing view ($PostFormat or $View), not a mesh or a script", path);
    case GmshText::Mesh:
      return check_msh_text(path, text, false);
    case GmshText::Script:
      return check_script(path, text, depth + 1, done);
  }
}

// gmsh merges "<file>.opt" beside every file it opens or merges, and merging that reads its
// own ".opt": "<file>.opt.opt" and on.
void check_companion(const std::string& file, int depth, Checked& done) {
  if (!done.insert("opt\n" + file).second) return;  // its chain checked already
  std::string opt = file + ".opt";
  for (int k = 0; fs::exists(opt); ++k, opt += ".opt") {
    DSPDEM_CHECK(k < kMostDepth, "gmsh option files beside '{}' chained more than {} deep", file, kMostDepth);
    check_by_first_line(opt, read_file(opt, "gmsh option file"), depth, done);
  }
}

// The words gmsh could still take for code where the reading above saw a string or a comment:
// its If, For and Macro skip text without reading strings ("If (0) x = "EndIf Exit; ..."),
// and a For's or a Macro's body is read again from the line after its header.
void check_hidden_words(const Scanner& sc, const std::set<std::size_t>& code_words) {
  const std::string& t = sc.text;
  for (std::size_t i = 0; i < t.size();) {
    const auto u = static_cast<unsigned char>(t[i]);
    if (!(std::isalpha(u) || t[i] == '_')) {
      ++i;
      continue;
    }
    const std::size_t from = i;
    while (i < t.size() && (std::isalnum(static_cast<unsigned char>(t[i])) || t[i] == '_')) ++i;
    const std::string_view word(t.data() + from, i - from);
    const bool command = std::find(kRefused.begin(), kRefused.end(), word) != kRefused.end() &&
                         !(word == "Print" && Scanner::next_after(t, i) == '.');
    const bool option = std::find(kRefusedOptions.begin(), kRefusedOptions.end(), word) != kRefusedOptions.end() &&
                        (Scanner::next_after(t, i) == '.' || Scanner::next_after(t, i) == '[');
    const bool reads = (word == "Include" || word == "Merge" || word == "Printf") && !code_words.count(from);
    const bool threads = threads_option(word);
    bool deletes = false;
    if (word == "Delete") {
      std::size_t k = i;
      while (k < t.size() && std::isspace(static_cast<unsigned char>(t[k]))) ++k;
      for (const std::string_view what : kRefusedDeletes) deletes = deletes || t.compare(k, what.size(), what) == 0;
    }
    if (command || option || reads || deletes || threads)
      fail(
          "mesh file '{}': line {}: '{}' in a string or a comment: gmsh's If, For and Macro skip text without "
          "reading its strings and may run it; dspdem refuses it there too (reword the string or comment)",
          sc.path, 1 + std::count(t.begin(), t.begin() + static_cast<long>(from), '\n'), word);
  }
}

// A file a script includes or merges, named by `name` relative to the script's folder.
void check_included(const Scanner& sc, const std::string& command, const std::string& name, int depth, Checked& done) {
  if (!plain_file_name(name)) sc.error("{} \"{}\": {}", command, name, kNotPlain);
  fs::path p(name);
  if (p.is_relative()) p = fs::path(sc.path).parent_path() / p;
  const std::string ext = p.extension().string();
  // gmsh parses any Include as a script; a Merge of a data file by its extension's exact
  // spelling, and of any other name by the file's first line (another spelling of a data
  // file's extension it parses as a script).
  const bool data = command == "Merge" && std::find(kDataFiles.begin(), kDataFiles.end(), ext) != kDataFiles.end();
  if (command == "Merge" && !data && ext != ".geo" && ext != ".msh")
    sc.error(
        "{} \"{}\": dspdem lets a script merge .geo, .msh, STEP, BREP, IGES and STL files only (extensions "
        "spelt as gmsh knows them)",
        command, name);
  if (!fs::is_regular_file(p)) sc.error("{} \"{}\": {} is not a file", command, name, p.string());
  if (depth >= kMostDepth) sc.error("{} \"{}\": scripts nested more than {} deep", command, name, kMostDepth);
  // Known by the command and the name as gmsh resolves it (lexically: a name through a link
  // reads its own folder's neighbours), so that each file gmsh would read is checked once.
  const std::string key = command + "\n" + p.lexically_normal().string();
  if (done.count(key)) return;
  // The fault named in the file that has it, and where the case's own script includes it.
  try {
    if (command == "Merge") check_companion(p.string(), depth, done);  // gmsh reads its .opt too
    if (!data) {
      const std::string inner = read_file(p.string(), "mesh file");
      if (command == "Include")
        check_script(p.string(), inner, depth + 1, done);
      else
        check_by_first_line(p.string(), inner, depth, done);
    }
    done.insert(key);
  } catch (const Error& e) {
    if (depth > 0) throw;  // named once, by the case's own script, not at every level
    sc.error("{} \"{}\": {}", command, name, e.what());
  }
}

void check_script(const std::string& path, const std::string& text, int depth, Checked& done) {
  Scanner sc{path, text};
  std::set<std::size_t> code_words;  // where Include, Merge and Printf were read as code
  // gmsh's lexer ends a string or a // comment at a NUL byte and reads on; this check would not.
  if (const std::size_t nul = text.find('\0'); nul != std::string::npos) {
    sc.line = 1 + static_cast<int>(std::count(text.begin(), text.begin() + static_cast<long>(nul), '\n'));
    sc.error("a NUL byte: a script is text");
  }
  while (true) {
    sc.skip_space();
    if (sc.pos >= text.size()) return check_hidden_words(sc, code_words);
    const char ch = text[sc.pos];
    const auto u = static_cast<unsigned char>(ch);
    if (u < 32 || u == 127)
      sc.error("a control character (byte {}) outside a string: a script is text", static_cast<int>(u));
    if (ch == '"' || ch == '\'') {
      sc.string_literal();
      continue;
    }
    if (!(std::isalpha(u) || ch == '_')) {
      sc.advance();
      continue;
    }
    const std::size_t from = sc.pos;
    while (sc.pos < text.size() && (std::isalnum(static_cast<unsigned char>(text[sc.pos])) || text[sc.pos] == '_'))
      ++sc.pos;
    const std::string_view word(text.data() + from, sc.pos - from);
    if (word == "Include" || word == "Merge" || word == "Printf") code_words.insert(from);
    if (word == "Delete") {
      sc.skip_space();
      const std::size_t w = sc.pos;
      while (sc.pos < text.size() && std::isalpha(static_cast<unsigned char>(text[sc.pos]))) ++sc.pos;
      const std::string_view what(text.data() + w, sc.pos - w);
      if (std::find(kRefusedDeletes.begin(), kRefusedDeletes.end(), what) != kRefusedDeletes.end())
        sc.error("Delete {} resets gmsh's options or frees its model while the script runs; dspdem does not run it",
                 what);
      continue;
    }
    if (threads_option(word))
      sc.error(
          "Mesh.{}: gmsh's threaded mesher makes another mesh each run, and in the process that meshes a script "
          "OpenMP runs one thread (its pool is not safe there); dspdem meshes on one thread, for the same mesh "
          "every run, and does not let a script set it",
          word);
    if (std::find(kRefusedOptions.begin(), kRefusedOptions.end(), word) != kRefusedOptions.end())
      sc.error(
          "{}.* options are gmsh's own, not the model's (General.AbortOnError ends the process on an error; "
          "dspdem sets General.NumThreads itself, for the same mesh every run); dspdem does not let a script "
          "set them",
          word);
    if (word == "Printf") {
      // Printf(...) prints; Printf(...) > "file" writes: a '>' past its closing parenthesis.
      int paren = 0;
      for (sc.skip_space(); sc.pos < text.size() && text[sc.pos] != ';'; sc.skip_space()) {
        const char c = text[sc.pos];
        if (c == '"' || c == '\'') {
          sc.string_literal();
          continue;
        }
        if (c == '(') ++paren;
        if (c == ')') --paren;
        if (c == '>' && paren == 0) sc.error("Printf into a file: dspdem does not let a script write files");
        sc.advance();
      }
      continue;
    }
    if (std::find(kRefused.begin(), kRefused.end(), word) != kRefused.end() && !(word == "Print" && sc.before('.')))
      sc.error(
          "{} acts outside the model (runs a program, writes files, ends or stalls the process, or names a command "
          "made at run time); dspdem does not run it",
          word);
    if (word == "Include" || word == "Merge") {
      sc.skip_space();
      if (sc.at(sc.pos) != '"' && sc.at(sc.pos) != '\'')
        sc.error("{} of a name made by the script: dspdem checks a file it reads, so give its name in quotes", word);
      const std::string name = sc.string_literal();
      sc.skip_space();
      if (sc.at(sc.pos) != ';')
        sc.error("{} \"{}\": expected ';' after the file name (a name made by the script is not checked)", word, name);
      check_included(sc, std::string(word), name, depth, done);
    }
  }
}
}  // namespace

GmshText gmsh_reads_as(const std::string& text) {
  // gmsh 4.8's MergeFile compares the start of the first line.
  const auto starts = [&](std::string_view h) { return text.compare(0, h.size(), h) == 0; };
  for (std::string_view h : {"$PTS", "$NO", "$PARA", "$ELM", "$MeshFormat", "$Comments"})
    if (starts(h)) return GmshText::Mesh;
  if (starts("$PostFormat") || starts("$View")) return GmshText::View;
  return GmshText::Script;
}

void check_geo_script(const std::string& path, const std::string& text) {
  DSPDEM_CHECK(plain_file_name(path), "mesh file '{}': {}", path, kNotPlain);
  // gmsh tells a mesh from a script by the first line, not by the name: a .geo holding a
  // mesh would be read as one, past the mesh's check (a probe's finding).
  const GmshText kind = gmsh_reads_as(text);
  DSPDEM_CHECK(kind == GmshText::Script,
               "mesh file '{}': it holds a {}, which gmsh reads by its first line whatever the file's name: name it "
               ".msh",
               path, kind == GmshText::Mesh ? "mesh" : "post-processing view");
  Checked done;
  check_script(path, text, 0, done);
}

void check_gmsh_option_file(const std::string& file) {
  DSPDEM_CHECK(plain_file_name(file), "mesh file '{}': {}", file, kNotPlain);
  Checked done;
  check_companion(file, 0, done);
}

}  // namespace dspdem
