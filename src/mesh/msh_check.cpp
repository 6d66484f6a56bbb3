#include "mesh/msh_check.hpp"

#include <algorithm>
#include <charconv>
#include <climits>
#include <cmath>
#include <string_view>
#include <unordered_set>
#include <vector>

#include "core/error.hpp"

namespace dspdem {

namespace {

/// gmsh element types 1-19 (GmshDefines.h): points, lines, triangles, quadrangles,
/// tetrahedra, hexahedra, prisms and pyramids of orders 1 and 2, as {dimension, nodes}.
struct Kind {
  int dim, nodes;
};
constexpr Kind kKinds[] = {{-1, 0}, {1, 2},  {2, 3},  {2, 4},  {3, 4},  {3, 8}, {3, 6}, {3, 5},  {1, 3},  {2, 6},
                           {2, 9},  {3, 10}, {3, 27}, {3, 18}, {3, 14}, {0, 1}, {2, 8}, {3, 20}, {3, 15}, {3, 13}};
constexpr long long kLastType = 19;
// gmsh reads the format 2 tags, and the entity tags of both formats, as int.
constexpr long long kIntMax = INT_MAX;
constexpr long long kBig = LLONG_MAX;

/// A token as shown in a message: at most 40 characters, unprintable bytes escaped.
std::string shown(std::string_view t) {
  std::string s;
  for (char c : t.substr(0, 40)) {
    const auto u = static_cast<unsigned char>(c);
    s += u >= 32 && u < 127 ? std::string(1, c) : fmt::format("\\x{:02x}", u);
  }
  return t.size() > 40 ? s + "..." : s;
}

class Checker {
 public:
  Checker(const std::string& path, const std::string& text, bool need_volume)
      : path_(path), text_(text), need_volume_(need_volume) {}

  void run() {
    // gmsh tells a mesh by its first line: a file that does not start with $MeshFormat
    // (a blank line first, say) it runs as a .geo script.
    if (!next() || (tok_.empty() && pos_ >= text_.size()))
      error("the file is empty (a .msh file starts with $MeshFormat)");
    if (!is("$MeshFormat"))
      error("the file must start with $MeshFormat (gmsh would run it as a script), got '{}'", shown(trimmed()));
    need("$MeshFormat");
    if (tok_.size() != 3) error("$MeshFormat must read 'version file-type data-size', e.g. '4.1 0 8'");
    const double version = real(0, "the format version");
    if (version == 4.1 || version == 4.0)
      v4_ = true, v40_ = version == 4.0;
    else if (!(version >= 2 && version < 3))
      error("format version {} is not read: dspdem reads 2.x, 4.0 and 4.1 (gmsh -save -format msh41)", shown(tok_[0]));
    const bool binary = integer(1, "the file type", 0, 1) == 1;
    integer(2, "the data size", 8, 8);
    if (binary) {
      // The integer 1 in binary follows the format line: its absence means a text file
      // marked binary, which gmsh would read as bytes. The rest of a binary file is left to
      // gmsh.
      const std::string_view one = std::string_view(text_).substr(std::min(pos_, text_.size()), 4);
      if (one != std::string_view("\1\0\0\0", 4) && one != std::string_view("\0\0\0\1", 4)) {
        ++no_;
        error("a binary file (file type 1) must have the integer 1 in binary here; is it a text file (file type 0)?");
      }
      return;
    }
    need("$MeshFormat");
    if (!is("$EndMeshFormat")) error("expected $EndMeshFormat, got '{}'", shown(trimmed()));

    int elements_line = 0;
    while (next_nonblank()) {
      const std::string_view h = trimmed();
      if (h.empty() || h[0] != '$')
        error("expected a section ($PhysicalNames, {}$Nodes, $Elements), got '{}'", v4_ ? "$Entities, " : "", shown(h));
      if (h == "$PhysicalNames") {
        once(seen_names_);
        physical_names();
      } else if (h == "$Entities" && v4_) {
        once(seen_entities_);
        entities();
      } else if (h == "$Nodes") {
        once(seen_nodes_);
        if (v4_ && !seen_entities_) error("$Nodes before $Entities (a format 4 file lists its entities first)");
        v4_ ? nodes4() : nodes2();
      } else if (h == "$Elements") {
        once(seen_elements_);
        if (!seen_nodes_) error("$Elements before $Nodes");
        elements_line = no_;
        v4_ ? elements4() : elements2();
      } else if (h == "$Comments") {
        skip_comments();
      } else {
        // gmsh would read other sections ($NodeData, $Periodic...) unchecked, and matches
        // section names by their first letters: refused rather than passed on.
        error(
            "section '{}' is not read by dspdem (it reads $MeshFormat, $PhysicalNames, {}$Nodes, $Elements and "
            "$Comments)",
            shown(h), v4_ ? "$Entities, " : "");
      }
    }
    if (!seen_nodes_) error("the file has no $Nodes section");
    if (!seen_elements_) error("the file has no $Elements section");
    if (need_volume_ && volume_elements_ == 0) {
      no_ = elements_line;
      error("$Elements holds no volume (3D) elements: a 3D mesh of tetrahedra or hexahedra is needed");
    }
  }

 private:
  // ---- lines and tokens
  bool next() {
    if (pos_ > text_.size() || (pos_ == text_.size() && no_ > 0)) return false;
    const std::size_t e = text_.find('\n', pos_);
    const std::size_t end = e == std::string::npos ? text_.size() : e;
    line_ = std::string_view(text_).substr(pos_, end - pos_);
    pos_ = end + 1;
    ++no_;
    tok_.clear();
    for (std::size_t i = 0; i < line_.size();) {
      while (i < line_.size() && is_separator(line_[i])) ++i;
      std::size_t j = i;
      while (j < line_.size() && !is_separator(line_[j])) ++j;
      if (j > i) tok_.push_back(line_.substr(i, j - i));
      i = j;
    }
    return true;
  }
  bool next_nonblank() {
    while (next())
      if (!tok_.empty()) return true;
    return false;
  }
  /// The next line, which must exist: `inside` names the section being read.
  void need(const char* inside) {
    if (!next()) error("the file ends inside {}", inside);
  }
  // Fields are separated by spaces, as gmsh writes them: its format 4.0 reader fails on a tab
  // between an entity's bounding tags ("Could not read entities"), so a tab or another
  // control character stays in its field and makes it unreadable here, by line.
  static bool is_separator(char c) { return c == ' ' || c == '\r'; }
  static bool is_space(char c) { return c == ' ' || c == '\t' || c == '\r' || c == '\f' || c == '\v'; }
  /// The line without its trailing white space. Not its leading: gmsh takes a line for a
  /// section's start or end only when '$' is its first character.
  std::string_view trimmed() const {
    std::size_t e = line_.size();
    while (e > 0 && is_space(line_[e - 1])) --e;
    return line_.substr(0, e);
  }
  bool is(std::string_view s) const { return trimmed() == s; }
  bool section_line() const { return !tok_.empty() && tok_[0][0] == '$'; }

  template <typename... Args>
  [[noreturn]] void error(fmt::format_string<Args...> f, Args&&... args) const {
    fail("mesh file '{}': line {}: {}", path_, no_, fmt::format(f, std::forward<Args>(args)...));
  }

  long long integer(std::size_t i, std::string_view what, long long lo, long long hi) const {
    const std::string_view t = tok_[i];
    long long v = 0;
    const auto [p, ec] = std::from_chars(t.data(), t.data() + t.size(), v);
    if (ec != std::errc() || p != t.data() + t.size() || v < lo || v > hi) {
      if (hi == kBig) error("{} is '{}': expected an integer from {}", what, shown(t), lo);
      error("{} is '{}': expected an integer from {} to {}", what, shown(t), lo, hi);
    }
    return v;
  }
  double real(std::size_t i, std::string_view what) const {
    const std::string_view t = tok_[i];
    double v = 0;
    const auto [p, ec] = std::from_chars(t.data(), t.data() + t.size(), v);
    if (ec != std::errc() || p != t.data() + t.size() || !std::isfinite(v))
      error("{} is '{}': expected a finite number", what, shown(t));
    return v;
  }
  void tokens(std::size_t n, std::string_view what) const {
    if (tok_.size() != n) error("{} must have {} fields, it has {}", what, n, tok_.size());
  }
  void once(bool& seen) const {
    if (seen) error("a second {} section", shown(trimmed()));
    seen = true;
  }
  /// The line after a section's entries, which must close it.
  void close(const char* section, const char* end) {
    need(section);
    if (!is(end)) error("expected {} (the entries {} declares are all read), got '{}'", end, section, shown(trimmed()));
  }
  /// The next entry line of a section that declared `count` of them, `read` so far.
  void entry(const char* section, const char* what, long long count, long long read) {
    need(section);
    if (section_line())
      error("{} declares {} {} but lists {} before '{}'", section, count, what, read, shown(trimmed()));
    if (tok_.empty()) error("an empty line inside {}", section);
  }

  // ---- sections
  void physical_names() {
    need("$PhysicalNames");
    tokens(1, "the count of $PhysicalNames");
    const long long n = integer(0, "the count of $PhysicalNames", 0, kBig);
    for (long long i = 0; i < n; ++i) {
      entry("$PhysicalNames", "names", n, i);
      if (tok_.size() < 3) error("a physical name must read 'dimension tag \"name\"'");
      integer(0, "the dimension of a physical name", 0, 3);
      integer(1, "the tag of a physical name", 0, kIntMax);
      const std::string_view t = trimmed();
      const std::size_t q = t.find('"');
      if (q == std::string_view::npos || t.back() != '"' || q == t.size() - 1 || t.substr(q).size() < 2 ||
          t.find('"', q + 1) != t.size() - 1)
        error("a physical name must read 'dimension tag \"name\"' (one name in double quotes)");
    }
    close("$PhysicalNames", "$EndPhysicalNames");
  }

  void entities() {
    need("$Entities");
    tokens(4, "the header of $Entities (points, curves, surfaces, volumes)");
    long long count[4];
    for (int d = 0; d < 4; ++d) count[d] = integer(static_cast<std::size_t>(d), "an entity count", 0, kBig);
    const char* names[4] = {"points", "curves", "surfaces", "volumes"};
    for (int d = 0; d < 4; ++d)
      for (long long i = 0; i < count[d]; ++i) {
        entry("$Entities", names[d], count[d], i);
        // A point: tag x y z (4.0: a bounding box); the others: tag and bounding box; then
        // the physical tags and, but for points, the signed tags of the bounding entities
        // one dimension down.
        const std::size_t box = d == 0 && !v40_ ? 3 : 6, np_at = 1 + box;
        if (tok_.size() <= np_at) error("an entity of dimension {} must have at least {} fields", d, np_at + 1);
        const long long tag = integer(0, "an entity tag", 1, kIntMax);
        for (std::size_t k = 1; k <= box; ++k) real(k, "an entity coordinate");
        const long long np = integer(np_at, "the count of physical tags", 0, kBig);
        const std::size_t nb_at = np_at + 1 + static_cast<std::size_t>(std::min<long long>(np, 1 << 20));
        if (d == 0) {
          tokens(nb_at, "this point entity (with its physical tags)");
        } else {
          if (tok_.size() <= nb_at) error("entity {} of dimension {}: its bounding entities are missing", tag, d);
          const long long nb = integer(nb_at, "the count of bounding entities", 0, kBig);
          tokens(nb_at + 1 + static_cast<std::size_t>(std::min<long long>(nb, 1 << 20)),
                 "this entity (with its physical and bounding tags)");
          for (std::size_t k = nb_at + 1; k < tok_.size(); ++k) {
            const long long b = integer(k, "a bounding entity tag", -kIntMax, kIntMax);
            if (!entities_[d - 1].count(b < 0 ? -b : b))
              error("entity {} of dimension {} is bounded by entity {} of dimension {}, which is not listed before it",
                    tag, d, b, d - 1);
          }
        }
        for (std::size_t k = np_at + 1; k < nb_at; ++k) integer(k, "a physical tag", -kIntMax, kIntMax);
        if (!entities_[d].insert(tag).second) error("entity {} of dimension {} is listed twice", tag, d);
      }
    close("$Entities", "$EndEntities");
  }

  void nodes2() {
    need("$Nodes");
    tokens(1, "the count of $Nodes");
    const long long n = integer(0, "the count of $Nodes", 0, kIntMax);
    for (long long i = 0; i < n; ++i) {
      entry("$Nodes", "nodes", n, i);
      tokens(4, "a node ('tag x y z')");
      const long long tag = integer(0, "a node tag", 1, kIntMax);
      for (std::size_t k = 1; k < 4; ++k) real(k, "a node coordinate");
      if (!nodes_.insert(tag).second) error("node {} is listed twice", tag);
    }
    close("$Nodes", "$EndNodes");
  }

  /// What the 4.x $Nodes and $Elements share: the section's header (blocks, count and, in
  /// 4.1, the smallest and largest tag), each block's dimension and entity, each tag against
  /// the header's range, and at the end the count and range against what the blocks held.
  /// `one` is "node" or "element", `block` "a node block" or "an element block".
  struct Blocks4 {
    const char* section;
    const char* one;
    long long blocks = 0, n = 0, lo = 1, hi = kBig;
    int header = 0;
    long long read = 0, min_tag = kBig, max_tag = 0;
  };
  Blocks4 header4(const char* section, const char* one) {
    Blocks4 b{section, one};
    tokens(v40_ ? 2 : 4, v40_ ? fmt::format("the header of {} (blocks, {}s)", section, one)
                              : fmt::format("the header of {} (blocks, {}s, smallest and largest tag)", section, one));
    b.blocks = integer(0, fmt::format("the count of {} blocks", one), 0, kBig);
    b.n = integer(1, fmt::format("the count of {}s", one), 0, kBig);
    if (!v40_) {
      b.lo = integer(2, fmt::format("the smallest {} tag", one), 0, kBig);
      b.hi = integer(3, fmt::format("the largest {} tag", one), 0, kBig);
    }
    b.header = no_;
    return b;
  }
  /// A block header's dimension (its entity must be in $Entities).
  int block_dimension(const char* block) {
    const int dim = static_cast<int>(integer(v40_ ? 1 : 0, fmt::format("the dimension of {}", block), 0, 3));
    const long long ent = integer(v40_ ? 0 : 1, fmt::format("the entity of {}", block), 1, kIntMax);
    if (!entities_[dim].count(ent))
      error("{} on entity {} of dimension {}, which $Entities does not list", block, ent, dim);
    return dim;
  }
  void block_tag(Blocks4& b, long long tag) {
    if (tag < b.lo || tag > b.hi)
      error("{} tag {} is outside the range {} to {} of the header", b.one, tag, b.lo, b.hi);
    b.min_tag = std::min(b.min_tag, tag), b.max_tag = std::max(b.max_tag, tag);
  }
  void close4(const Blocks4& b, const char* end) {
    if (b.read != b.n || (!v40_ && b.n > 0 && (b.min_tag != b.lo || b.max_tag != b.hi))) {
      no_ = b.header;
      if (v40_) error("the header of {} says {} {}s; its blocks hold {}", b.section, b.n, b.one, b.read);
      error("the header of {} says {} {}s tagged {} to {}; its blocks hold {} tagged {} to {}", b.section, b.n, b.one,
            b.lo, b.hi, b.read, b.read ? b.min_tag : 0, b.read ? b.max_tag : 0);
    }
    close(b.section, end);
  }

  /// Format 4: blocks of nodes, one block per entity. 4.1 lists a block's tags, then their
  /// coordinates, and gives the smallest and largest tag in the header; 4.0 lists each node
  /// as 'tag x y z' and puts the entity's tag before its dimension.
  void nodes4() {
    need("$Nodes");
    Blocks4 bl = header4("$Nodes", "node");
    std::vector<long long> tags;
    for (long long b = 0; b < bl.blocks; ++b) {
      entry("$Nodes", "entity blocks", bl.blocks, b);
      tokens(4, v40_ ? "a node block header ('entity dimension parametric count')"
                     : "a node block header ('dimension entity parametric count')");
      const int dim = block_dimension("a node block");
      const bool parametric = integer(2, "the parametric flag", 0, 1) == 1;
      const long long m = integer(3, "the node count of a block", 0, kBig);
      const std::size_t coords = 3 + (parametric ? static_cast<std::size_t>(dim) : 0);
      tags.clear();
      for (long long i = 0; i < m; ++i) {
        entry("$Nodes", "nodes in this block", m, i);
        const long long tag = integer(0, "a node tag", 1, kBig);
        if (v40_ && tok_.size() != 1 + coords)
          error("node {} must read 'tag' and {} coordinates, it has {} fields", tag, coords, tok_.size());
        if (!v40_) tokens(1, "a node tag line");
        block_tag(bl, tag);
        if (!nodes_.insert(tag).second) error("node {} is listed twice", tag);
        for (std::size_t k = 1; k < tok_.size(); ++k) real(k, "a node coordinate");
        tags.push_back(tag);
      }
      for (long long i = 0; i < m && !v40_; ++i) {
        entry("$Nodes", "node coordinates in this block", m, i);
        if (tok_.size() != coords)
          error("node {} must have {} coordinates, it has {}", tags[static_cast<std::size_t>(i)], coords, tok_.size());
        for (std::size_t k = 0; k < coords; ++k) real(k, "a node coordinate");
      }
      bl.read += m;
    }
    close4(bl, "$EndNodes");
  }

  /// The node tags of an element, from token `first` on, must be listed in $Nodes.
  void element_nodes(long long tag, std::size_t first) {
    for (std::size_t k = first; k < tok_.size(); ++k) {
      const long long node = integer(k, "a node tag of an element", 1, kBig);
      if (!nodes_.count(node)) error("element {} refers to node {}, which $Nodes does not list", tag, node);
    }
  }
  const Kind& kind(std::size_t i) const {
    return kKinds[integer(i, "the element type (gmsh types 1 to 19: points to pyramids, orders 1 and 2)", 1,
                          kLastType)];
  }

  void elements2() {
    need("$Elements");
    tokens(1, "the count of $Elements");
    const long long n = integer(0, "the count of $Elements", 0, kIntMax);
    for (long long i = 0; i < n; ++i) {
      entry("$Elements", "elements", n, i);
      if (tok_.size() < 3) error("an element must read 'tag type tag-count tags... nodes...'");
      const long long tag = integer(0, "an element tag", 1, kIntMax);
      const Kind& k = kind(1);
      const long long nt = integer(2, "the tag count of an element", 0, kIntMax);
      if (static_cast<long long>(tok_.size()) != 3 + nt + k.nodes)
        error("element {} must have {} fields (3, its {} tags and {} nodes), it has {}", tag, 3 + nt + k.nodes, nt,
              k.nodes, tok_.size());
      // Tags: physical, elementary, then the partition count and the partitions.
      const std::size_t tags = static_cast<std::size_t>(nt);
      for (std::size_t t = 0; t < tags; ++t)
        integer(3 + t, "an element's tag", t < 3 ? 0 : -kIntMax, t == 2 ? static_cast<long long>(tags) - 3 : kIntMax);
      element_nodes(tag, 3 + tags);
      if (!element_tags_.insert(tag).second) error("element {} is listed twice", tag);
      volume_elements_ += k.dim == 3;
    }
    close("$Elements", "$EndElements");
  }

  /// Format 4: blocks of elements of one type on one entity (4.0: the entity's tag before
  /// its dimension, and no tag range in the header).
  void elements4() {
    need("$Elements");
    Blocks4 bl = header4("$Elements", "element");
    for (long long b = 0; b < bl.blocks; ++b) {
      entry("$Elements", "entity blocks", bl.blocks, b);
      tokens(4, v40_ ? "an element block header ('entity dimension type count')"
                     : "an element block header ('dimension entity type count')");
      const int dim = block_dimension("an element block");
      const Kind& k = kind(2);
      if (k.dim != dim) error("element type {} has dimension {}, the block dimension {}", shown(tok_[2]), k.dim, dim);
      const long long m = integer(3, "the element count of a block", 0, kBig);
      for (long long i = 0; i < m; ++i) {
        entry("$Elements", "elements in this block", m, i);
        const long long tag = integer(0, "an element tag", 1, kBig);
        if (static_cast<long long>(tok_.size()) != 1 + k.nodes)
          error("element {} must have {} fields (its tag and {} nodes), it has {}", tag, 1 + k.nodes, k.nodes,
                tok_.size());
        block_tag(bl, tag);
        element_nodes(tag, 1);
        if (!element_tags_.insert(tag).second) error("element {} is listed twice", tag);
      }
      bl.read += m;
      volume_elements_ += dim == 3 ? m : 0;
    }
    close4(bl, "$EndElements");
  }

  void skip_comments() {
    for (;;) {
      need("$Comments");
      if (is("$EndComments")) return;
      // gmsh ends a skipped section at the first line that starts with '$'.
      if (section_line()) error("'{}' inside $Comments (expected $EndComments)", shown(trimmed()));
    }
  }

  const std::string& path_;
  const std::string& text_;
  const bool need_volume_;
  std::size_t pos_ = 0;
  int no_ = 0;  // number of the current line, from 1
  std::string_view line_;
  std::vector<std::string_view> tok_;
  bool v4_ = false, v40_ = false, seen_names_ = false, seen_entities_ = false, seen_nodes_ = false,
       seen_elements_ = false;
  std::unordered_set<long long> entities_[4], nodes_, element_tags_;
  long long volume_elements_ = 0;
};

}  // namespace

void check_msh_text(const std::string& path, const std::string& text, bool need_volume) {
  Checker(path, text, need_volume).run();
}

}  // namespace dspdem
