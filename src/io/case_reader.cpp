// Strict TOML case reader: every key is looked up in the schema; unknown keys, wrong types
// and out-of-range values are errors naming file, line, section and key.
#include <toml++/toml.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <optional>
#include <set>
#include <sstream>
#include <string_view>

#include "contact/restitution.hpp"
#include "core/error.hpp"
#include "core/log.hpp"
#include "io/case_config.hpp"
#include "io/case_schema.hpp"

namespace dspdem {

namespace {
// A wall's or a monitor's name heads columns of series.csv: a comma, a quote or a line break
// in it, or no name at all, would shift every column after it (the render then refused the
// file, the run long done).
void check_column_name(const std::string& name, const std::string& where, const char* what) {
  const bool plain =
      !name.empty() && name.front() != ' ' && name.back() != ' ' && std::none_of(name.begin(), name.end(), [](char ch) {
        const auto u = static_cast<unsigned char>(ch);
        return ch == ',' || ch == '"' || u < 32 || u == 127;
      });
  DSPDEM_CHECK(plain,
               "{}: {} name '{}' heads columns of series.csv: it must not be empty, hold a comma, a quote or a "
               "control character, or start or end with a space",
               where, what, name);
}

namespace fs = std::filesystem;
using schema::Type;

// The source name of values given by --set (toml++ keeps a node's source when it is moved).
constexpr std::string_view kOverrideSource = "--set";

struct Ctx {
  std::string file;
  std::string where(const toml::source_region& src) const {
    if (src.path && *src.path == kOverrideSource) return file + " (--set)";
    // Not from the file nor --set: a table the file leaves out, filled in here. (Every such
    // place used to read "(--set)", naming an override that was never given.)
    if (src.begin.line == 0) return file;
    return fmt::format("{}:{}", file, src.begin.line);
  }
};

const schema::Key& find_key(const std::string& section, const std::string& key) {
  for (const auto& k : schema::keys())
    if (section == k.section && key == k.key) return k;
  static const schema::Key none{"", "", Type::Real, nullptr, 0, 0, false, false, "", nullptr, ""};
  return none;
}

std::string allowed_keys(const std::string& section) {
  std::string s;
  for (const auto& k : schema::keys())
    if (section == k.section) s += (s.empty() ? "" : ", ") + std::string(k.key);
  return s;
}

/// Reads the keys of one table against the schema section `pattern`; `label` is how the
/// table is named in messages ("[materials.rock]", "[[bodies]] #2").
// A --set value written as a number that TOML cannot read (1e400, .5, 2^64) is kept as a
// string (a bare word is one); a number key read from it says why, not "got a string": TOML's
// own words on it, or "" if it is not from --set or does not read as a number at all.
std::string unreadable_number(const toml::node& n) {
  const auto* str = n.as_string();
  if (!str || !n.source().path || *n.source().path != kOverrideSource) return {};
  const std::string& text = str->get();
  char* end = nullptr;
  std::strtod(text.c_str(), &end);
  if (text.empty() || end != text.c_str() + text.size()) return {};
  try {
    (void)toml::parse("v = " + text);
  } catch (const toml::parse_error& e) {
    return fmt::format("{} is not a number TOML reads: {}", text, e.description());
  }
  return {};
}

class Section {
 public:
  Section(const Ctx& ctx, toml::table& t, std::string pattern, std::string label)
      : ctx_(ctx), t_(t), pattern_(std::move(pattern)), label_(std::move(label)) {}

  bool has(const std::string& key) const { return t_.contains(key); }
  std::string where(const std::string& key) const {
    const toml::node* n = t_.get(key);
    // A key the file leaves out (its default filled in) is placed at its table.
    const bool given = n && (n->source().begin.line > 0 || n->source().path);
    return ctx_.where(given ? n->source() : t_.source());
  }
  std::string where() const { return ctx_.where(t_.source()); }

  Real real(const std::string& key) {
    const auto& k = spec(key, Type::Real);
    const toml::node* n = get_or_default(k);
    if (!n) return NAN;
    std::optional<double> v = n->value<double>();
    // toml++ gives no double for an integer beyond 2^53, which a double cannot hold exactly.
    if (!v && n->is_integer())
      fail("{}: {} key '{}' = {} is too large an integer to convert exactly: write it as a float (e.g. {:.3e})",
           where(key), label_, key, *n->value<int64_t>(), static_cast<double>(*n->value<int64_t>()));
    if (!v || !(n->is_integer() || n->is_floating_point())) wrong_type(key, "a number", *n);
    check_range(k, *v, key);
    return *v;
  }
  long integer(const std::string& key) {
    const auto& k = spec(key, Type::Int);
    const toml::node* n = get_or_default(k);
    if (!n->is_integer()) wrong_type(key, "an integer", *n);
    const long v = static_cast<long>(*n->value<int64_t>());
    check_range(k, static_cast<double>(v), key);
    return v;
  }
  bool boolean(const std::string& key) {
    const auto& k = spec(key, Type::Bool);
    const toml::node* n = get_or_default(k);
    if (!n->is_boolean()) fail("{}: {} key '{}' must be true or false, got {}", where(key), label_, key, type_of(*n));
    return *n->value<bool>();
  }
  std::string str(const std::string& key) {
    const auto& k = spec(key, Type::String);
    const toml::node* n = get_or_default(k);
    if (!n) return {};
    if (!n->is_string()) fail("{}: {} key '{}' must be a string, got {}", where(key), label_, key, type_of(*n));
    std::string v = *n->value<std::string>();
    check_choice(k, v, key);
    return v;
  }
  Vec3 vec3(const std::string& key) {
    const auto& k = spec(key, Type::Vec3);
    const toml::node* n = get_or_default(k);
    // An "auto" key left out has no node: its caller must ask has() first.
    if (!n) fail("internal: {} key '{}' is not given and has no default: ask has() first", label_, key);
    const toml::array* a = n->as_array();
    if (!a || a->size() != 3) fail("{}: {} key '{}' must be an array of 3 numbers [x, y, z]", where(key), label_, key);
    Vec3 v;
    for (int i = 0; i < 3; ++i) {
      auto d = a->get(i)->value<double>();
      if (!d || !std::isfinite(*d))
        fail("{}: {} key '{}' entry {} must be a finite number", where(key), label_, key, i + 1);
      check_range(k, *d, key);
      v(i) = *d;
    }
    return v;
  }
  std::vector<std::string> strings(const std::string& key) {
    const auto& k = spec(key, Type::StringList);
    const toml::node* n = get_or_default(k);
    const toml::array* a = n->as_array();
    if (!a) fail("{}: {} key '{}' must be a list of strings", where(key), label_, key);
    std::vector<std::string> out;
    for (const auto& e : *a) {
      if (!e.is_string()) fail("{}: {} key '{}' must be a list of strings", where(key), label_, key);
      out.push_back(*e.value<std::string>());
      check_choice(k, out.back(), key);
    }
    return out;
  }
  /// Errors on any key the schema does not know (`sub_table` names a nested table that
  /// is read separately).
  void finish(const std::string& sub_table = "") const {
    for (const auto& [key, node] : t_) {
      const std::string ks(key.str());
      if (!sub_table.empty() && ks == sub_table) continue;
      if (find_key(pattern_, ks).key[0] == '\0')
        fail("{}: {} has unknown key '{}' (known keys: {})", ctx_.where(node.source()), label_, ks,
             allowed_keys(pattern_));
    }
  }

 private:
  const schema::Key& spec(const std::string& key, Type t) const {
    const auto& k = find_key(pattern_, key);
    if (k.key[0] == '\0' || k.type != t)
      fail("internal: schema has no {} key '{}.{}'", schema::type_name(t), pattern_, key);
    return k;
  }
  /// The node for a key, inserting the schema default when absent (so the resolved case
  /// shows it). Required keys that are missing are errors; "auto" keys return nullptr.
  const toml::node* get_or_default(const schema::Key& k) {
    if (const toml::node* n = t_.get(k.key)) return n;
    if (!k.def) fail("{}: {} is missing required key '{}' ({})", where(), label_, k.key, k.doc);
    if (std::string(k.def) == "auto") return nullptr;
    toml::table parsed = toml::parse(std::string("v = ") + k.def);
    t_.insert(k.key, *parsed.get("v"));
    return t_.get(k.key);
  }
  // A number key given something else: a --set number TOML cannot read says why, not "got a string".
  [[noreturn]] void wrong_type(const std::string& key, const char* what, const toml::node& n) const {
    if (const std::string why = unreadable_number(n); !why.empty())
      fail("{}: {} key '{}' must be {}; {}", where(key), label_, key, what, why);
    fail("{}: {} key '{}' must be {}, got {}", where(key), label_, key, what, type_of(n));
  }
  void check_range(const schema::Key& k, double v, const std::string& key) const {
    const bool lo_ok = k.lo_open ? v > k.lo : v >= k.lo;
    const bool hi_ok = k.hi_open ? v < k.hi : v <= k.hi;
    if (!std::isfinite(v) || !lo_ok || !hi_ok) {
      // A vector's entries take its range: range_text gives none for a [x, y, z] key.
      schema::Key scalar = k;
      scalar.type = Type::Real;
      fail("{}: {} key '{}' = {} is out of range: must be {}{}", where(key), label_, key, v, schema::range_text(scalar),
           k.unit[0] ? fmt::format(" ({})", k.unit) : "");
    }
  }
  void check_choice(const schema::Key& k, const std::string& v, const std::string& key) const {
    if (!k.choices) return;
    std::stringstream ss(k.choices);
    std::string c;
    while (std::getline(ss, c, '|'))
      if (c == v) return;
    fail("{}: {} key '{}' = \"{}\" is not one of: {}", where(key), label_, key, v, k.choices);
  }
  static std::string type_of(const toml::node& n) {
    switch (n.type()) {
      case toml::node_type::string: {
        const std::string v = *n.value<std::string>();
        return fmt::format("the string \"{}\"", v.size() > 40 ? v.substr(0, 37) + "..." : v);
      }
      case toml::node_type::integer:
        return "an integer";
      case toml::node_type::floating_point:
        return "a number";
      case toml::node_type::boolean:
        return "a boolean";
      case toml::node_type::array:
        return "an array";
      case toml::node_type::table:
        return "a table";
      default:
        return "a date/time";
    }
  }
  const Ctx& ctx_;
  toml::table& t_;
  std::string pattern_, label_;
};

toml::table& sub_table(const Ctx& ctx, toml::table& root, const std::string& name) {
  toml::node* n = root.get(name);
  if (!n) {
    root.insert(name, toml::table{});
    n = root.get(name);
  }
  toml::table* t = n->as_table();
  if (!t) fail("{}: '{}' must be a table [{}]", ctx.where(n->source()), name, name);
  return *t;
}

toml::array* array_of_tables(const Ctx& ctx, toml::table& root, const std::string& name) {
  toml::node* n = root.get(name);
  if (!n) return nullptr;
  toml::array* a = n->as_array();
  if (!a || !a->is_array_of_tables())
    fail("{}: '{}' must be an array of tables [[{}]]", ctx.where(n->source()), name, name);
  return a;
}

void apply_override(toml::table& root, const std::string& ov) {
  const auto eq = ov.find('=');
  DSPDEM_CHECK(eq != std::string::npos && eq > 0, "--set '{}': expected section.key=value", ov);
  const std::string path = ov.substr(0, eq), text = ov.substr(eq + 1);
  std::vector<std::string> parts;
  std::stringstream ss(path);
  for (std::string p; std::getline(ss, p, '.');) parts.push_back(p);
  DSPDEM_CHECK(parts.size() >= 2, "--set '{}': the key needs a section, e.g. time.end=0.01", ov);
  toml::node* value = nullptr;
  toml::table holder;
  try {
    holder = toml::parse("v = " + text, kOverrideSource);
    // A value followed by more lines ("2e-3\nbogus = 1") read as more keys, left unread.
    DSPDEM_CHECK(holder.size() == 1,
                 "--set '{}': the value holds more TOML than one value (a line break, then keys or tables); give "
                 "each key a --set of its own",
                 log::printable(ov));
  } catch (const toml::parse_error&) {
    holder = toml::parse("v = \"\"", kOverrideSource);  // a bare word is a string
    *holder.get_as<std::string>("v") = text;
  }
  value = holder.get("v");
  toml::node* cur = &root;
  for (std::size_t i = 0; i + 1 < parts.size(); ++i) {
    const std::string& p = parts[i];
    if (toml::array* a = cur->as_array()) {
      char* end = nullptr;
      const long idx = std::strtol(p.c_str(), &end, 10);
      DSPDEM_CHECK(*end == '\0' && idx >= 0 && static_cast<std::size_t>(idx) < a->size(),
                   "--set '{}': '{}' is not an index of that array (size {})", ov, p, a->size());
      cur = a->get(static_cast<std::size_t>(idx));
      continue;
    }
    toml::table* t = cur->as_table();
    DSPDEM_CHECK(t != nullptr, "--set '{}': '{}' is not a table", ov, p);
    if (!t->contains(p)) t->insert(p, toml::table{});
    cur = t->get(p);
  }
  if (toml::array* a = cur->as_array()) {  // walls.1={...}: the whole element of an array
    char* end = nullptr;
    const long idx = std::strtol(parts.back().c_str(), &end, 10);
    // One past the end appends, so a study variant can add a condition or a wall
    // (boundary.3={group="load_outer", type="fixed", dofs="y"}).
    DSPDEM_CHECK(*end == '\0' && idx >= 0 && static_cast<std::size_t>(idx) <= a->size(),
                 "--set '{}': '{}' is not an index of that array (size {}; {} appends)", ov, parts.back(), a->size(),
                 a->size());
    if (static_cast<std::size_t>(idx) == a->size()) {
      DSPDEM_CHECK(a->is_array_of_tables() && !a->empty(),
                   "--set '{}': only an array of tables the case has ([[...]]) takes an appended element; '{}' is past "
                   "the end of this one (size {})",
                   ov, parts.back(), a->size());
      DSPDEM_CHECK(value->is_table(), "--set '{}': an element appended to an array of tables must be a table {{...}}",
                   ov);
      a->push_back(std::move(*value));
    } else {
      a->replace(a->cbegin() + idx, std::move(*value));  // moved: keeps its --set source
    }
    return;
  }
  toml::table* t = cur->as_table();
  DSPDEM_CHECK(t != nullptr, "--set '{}': the parent of the key is not a table", ov);
  t->insert_or_assign(parts.back(), std::move(*value));  // moved: keeps its --set source
}

int component_index(const std::string& c) { return c == "x" ? 0 : c == "y" ? 1 : c == "z" ? 2 : 3; }

/// A box given as two corner keys (a body's joint zone, a joint monitor's region): both or
/// neither, the lower corner below the upper on every axis. `what` names the table's entry in
/// messages ("[[bodies]] 'sphere'").
std::optional<Eigen::AlignedBox<Real, 3>> read_box(Section& s, const std::string& what, const std::string& lo_key,
                                                   const std::string& hi_key) {
  if (!s.has(lo_key) && !s.has(hi_key)) return std::nullopt;
  if (!s.has(lo_key) || !s.has(hi_key))
    fail("{}: {}: {} and {} come together", s.where(s.has(lo_key) ? lo_key : hi_key), what, lo_key, hi_key);
  const Vec3 lo = s.vec3(lo_key), hi = s.vec3(hi_key);
  for (int i = 0; i < 3; ++i)
    if (!(lo(i) < hi(i)))
      fail("{}: {}: {} must lie above {} on every axis ({} is {:g}, not above {:g})", s.where(hi_key), what, hi_key,
           lo_key, "xyz"[i], hi(i), lo(i));
  return Eigen::AlignedBox<Real, 3>(lo, hi);
}
}  // namespace

CaseConfig read_case(const std::string& path, const std::vector<std::string>& overrides) {
  DSPDEM_CHECK(fs::exists(path), "case file '{}' does not exist", path);
  DSPDEM_CHECK(!fs::is_directory(path), "case file '{}' is a folder: give a case's .toml file", path);
  Ctx ctx{path};
  toml::table root;
  try {
    root = toml::parse_file(path);
  } catch (const toml::parse_error& e) {
    fail("{}:{}:{}: TOML syntax error: {}", path, e.source().begin.line, e.source().begin.column, e.description());
  }
  // A bad --set names the case it was applied to: a study or a sweep applies its overrides
  // to cases it resolved itself, and the user should see which one refused them.
  for (const auto& ov : overrides) {
    try {
      apply_override(root, ov);
    } catch (const Error& e) {
      fail("{}: {}", path, e.what());
    }
  }

  for (const auto& [key, node] : root) {
    const std::string k(key.str());
    bool known = false;
    for (const char* s : schema::sections()) {
      std::string base(s);
      if (auto p = base.find_first_of(".["); p != std::string::npos) base = base.substr(0, p);
      known = known || base == k;
    }
    if (!known) {
      std::string list;
      for (const char* s : schema::sections()) list += (list.empty() ? "" : ", ") + std::string(s);
      fail("{}: unknown section or key '{}' (known: {})", ctx.where(node.source()), k, list);
    }
  }

  CaseConfig c;
  c.path = path;
  c.overrides = overrides;
  c.dir = fs::absolute(path).parent_path().string();
  {
    Section s(ctx, sub_table(ctx, root, "case"), "case", "[case]");
    c.name = s.has("name") ? s.str("name") : fs::path(path).stem().string();
    // The name is a folder under results/ (the run's default --out): one component, so that
    // "../x" or "" cannot put a run's files beside other runs or outside results/.
    DSPDEM_CHECK(!c.name.empty() && c.name != "." && c.name != ".." && c.name.front() != '.' &&
                     c.name.find_first_of("/\\") == std::string::npos,
                 "{}: case name '{}' is not a plain folder name (it names the run's folder under results/: no "
                 "'/' or '\\', not empty, not starting with '.')",
                 s.has("name") ? s.where("name") : path, c.name);
    c.description = s.str("description");
    if (s.has("scene")) c.scene = s.str("scene");
    s.finish();
  }
  {
    toml::table& mt = sub_table(ctx, root, "mesh");
    Section s(ctx, mt, "mesh", "[mesh]");
    if (s.has("file") == s.has("generator"))
      fail("{}: [mesh] needs exactly one of 'file' (a .msh or .geo) or 'generator'", s.where());
    c.mesh_cache = s.boolean("cache");
    if (s.has("file")) {
      c.mesh_file = s.str("file");
      c.mesh_time_limit = s.real("time_limit");
      const fs::path p(c.mesh_file);
      if (p.is_relative()) c.mesh_file = (fs::path(c.dir) / p).lexically_normal().string();
      s.finish();
    } else {
      c.mesh_generator = s.str("generator");
      s.finish(c.mesh_generator);
      const std::string pattern = "mesh." + c.mesh_generator;
      Section g(ctx, sub_table(ctx, mt, c.mesh_generator), pattern, "[" + pattern + "]");
      for (const auto& k : schema::keys()) {
        if (pattern != k.section) continue;
        if (k.type == Type::String)
          c.mesh_str[k.key] = g.str(k.key);
        else if (k.type == Type::Int)
          c.mesh_num[k.key] = static_cast<double>(g.integer(k.key));
        else
          c.mesh_num[k.key] = g.real(k.key);
      }
      g.finish();
    }
  }
  {
    Section s(ctx, sub_table(ctx, root, "physics"), "physics", "[physics]");
    c.gravity = s.vec3("gravity");
    s.finish();
  }
  {
    toml::table& mats = sub_table(ctx, root, "materials");
    DSPDEM_CHECK(!mats.empty(), "{}: no [materials.<name>] table: at least one material is needed", path);
    for (auto& [name, node] : mats) {
      const std::string mname(name.str());
      toml::table* t = node.as_table();
      if (!t) fail("{}: materials.{} must be a table", ctx.where(node.source()), mname);
      Section s(ctx, *t, "materials.<name>", "[materials." + mname + "]");
      Material m;
      m.name = mname;
      m.density = s.real("density");
      m.E = s.real("E");
      m.nu = s.real("nu");
      m.alpha = s.real("damping_alpha");
      m.beta = s.real("damping_beta");
      const Real ratio = s.real("damping_ratio");
      const std::string mode = s.str("damping_mode");
      if (ratio > 0) {
        if (!s.has("damping_frequency"))
          fail("{}: [materials.{}] damping_ratio > 0 needs damping_frequency (Hz)", s.where("damping_ratio"), mname);
        const Real w = 2 * M_PI * s.real("damping_frequency");
        if (mode == "mass")
          m.alpha += 2 * ratio * w;
        else
          m.beta += 2 * ratio / w;
      } else if (s.has("damping_frequency")) {
        s.real("damping_frequency");
      }
      JointMaterial jm;
      const std::string law = s.str("joint_law");
      jm.coupled = law == "coupled", jm.mode_i = law == "mode_I", jm.residual = law == "paper_residual";
      if (jm.mode_i) {
        // Opening only: the shear stays elastic until the joint breaks, so a cohesion or a
        // mode-II energy would be ignored; say so instead of ignoring it.
        for (const char* k : {"cohesion", "fracture_energy_II"})
          if (s.has(k))
            fail(
                "{}: [materials.{}] joint_law = \"mode_I\" fails joints in opening only (the shear stays elastic "
                "until they break): '{}' does not apply, remove it",
                s.where(k), mname, k);
        int given = 0;
        for (const char* k : {"tensile_strength", "fracture_energy_I", "friction_angle"}) given += s.has(k);
        if (given > 0 && given < 3)
          fail(
              "{}: [materials.{}] joint parameters come together: with joint_law = \"mode_I\" give "
              "tensile_strength, fracture_energy_I and friction_angle (friction of broken faces)",
              s.where(), mname);
        if (given == 3) {
          jm.given = true;
          jm.ft = s.real("tensile_strength");
          jm.GfI = s.real("fracture_energy_I");
          jm.phi_deg = s.real("friction_angle");
        }
      }
      const char* jkeys[] = {"tensile_strength", "fracture_energy_I", "cohesion", "friction_angle",
                             "fracture_energy_II"};
      int present = 0;
      for (const char* k : jkeys) present += s.has(k);
      if (!jm.mode_i && present > 0 && present < 5)
        fail(
            "{}: [materials.{}] joint parameters come together: give all of tensile_strength, fracture_energy_I, "
            "cohesion, friction_angle, fracture_energy_II",
            s.where(), mname);
      if (!jm.mode_i && present == 5) {
        jm.given = true;
        jm.ft = s.real("tensile_strength");
        jm.GfI = s.real("fracture_energy_I");
        jm.c = s.real("cohesion");
        jm.phi_deg = s.real("friction_angle");
        jm.GfII = s.real("fracture_energy_II");
        // The paper's eq. 5 lowers the shear strength by tension down to c - f_t tan(phi) at
        // the cut-off; the coupled law does not (its onset criterion carries the interaction).
        const Real cut = jm.coupled ? 0.0 : jm.ft * std::tan(jm.phi_deg * M_PI / 180.0);
        if (!(jm.c > cut))
          fail(
              "{}: [materials.{}] cohesion = {:g} Pa must exceed tensile_strength x tan(friction_angle) = {:g} Pa: "
              "the shear strength at the tension cut-off, c - f_t tan(phi) (README M2, eq. 5), must stay positive",
              s.where("cohesion"), mname, jm.c, cut);
      }
      jm.penalty = s.real("joint_penalty");
      jm.nodal_quadrature = s.str("joint_quadrature") == "nodal";
      // A resolved case (case.resolved.toml) writes every key, so the default is accepted
      // under any law; another value would be ignored, so it is refused.
      const bool mixed_mode_default =
          fmt::format("\"{}\"", s.str("mixed_mode")) == find_key("materials.<name>", "mixed_mode").def;
      if (s.has("mixed_mode") && !jm.coupled && !mixed_mode_default)
        fail("{}: [materials.{}] mixed_mode applies to joint_law = \"coupled\" only (this material's law is \"{}\")",
             s.where("mixed_mode"), mname, law);
      jm.energy_mixed_mode = s.str("mixed_mode") == "energy";  // after has(): str() fills in the default
      if (s.has("joint_kn")) jm.kn = s.real("joint_kn");
      if (s.has("joint_ks")) jm.ks = s.real("joint_ks");
      contact::ContactMaterial cm;
      if (s.has("contact_radius")) cm.radius = s.real("contact_radius");
      cm.radius_fraction = s.real("contact_radius_fraction");
      cm.penalty = s.real("contact_penalty");
      if (s.has("contact_kn")) cm.kn = s.real("contact_kn");
      cm.kt_ratio = s.real("contact_kt_ratio");
      cm.friction = s.real("friction");
      // The default is a restitution, not a damping ratio: a damped contact lets a resting
      // contact settle (an elastic one bounces for ever on its spring), and e is what a user
      // of DEM knows (cases/README.md, "Contacts that come to rest").
      if (s.has("contact_damping") && s.has("contact_restitution"))
        fail(
            "{}: [materials.{}] give contact_restitution or contact_damping, not both (one sets the other; to "
            "change a case that gives contact_restitution, set contact_restitution)",
            s.where("contact_damping"), mname);
      cm.damping_ratio = s.has("contact_damping") ? s.real("contact_damping")
                                                  : contact::damping_for_restitution(s.real("contact_restitution"));
      s.finish();
      c.materials.push_back(m);
      c.joint_materials.push_back(jm);
      c.contact_materials.push_back(cm);
    }
  }
  auto material_index = [&](const std::string& name, const std::string& where) {
    for (std::size_t i = 0; i < c.materials.size(); ++i)
      if (c.materials[i].name == name) return static_cast<Index>(i);
    std::string list;
    for (const auto& m : c.materials) list += (list.empty() ? "" : ", ") + m.name;
    fail("{}: material '{}' is not defined (defined: {})", where, name, list);
  };
  if (toml::array* a = array_of_tables(ctx, root, "bodies")) {
    int i = 0;
    for (auto& n : *a) {
      Section s(ctx, *n.as_table(), "bodies[]", fmt::format("[[bodies]] #{}", ++i));
      BodyConfig b;
      b.name = s.str("name");
      b.groups = s.strings("groups");
      DSPDEM_CHECK(!b.groups.empty(), "{}: [[bodies]] '{}' lists no groups", s.where("groups"), b.name);
      b.material = s.str("material");
      material_index(b.material, s.where("material"));
      const std::string kin = s.str("kinematics");
      b.kinematics = kin == "small_strain" ? Kinematics::SmallStrain
                     : kin == "rigid"      ? Kinematics::Rigid
                                           : Kinematics::Corotational;
      b.split_components = s.boolean("split_components");
      const std::string fr = s.str("fracture");
      b.fracture = fr == "all"      ? BodyConfig::Fracture::All
                   : fr == "groups" ? BodyConfig::Fracture::Groups
                                    : BodyConfig::Fracture::None;
      b.fracture_groups = s.strings("fracture_groups");
      b.extrinsic = s.str("fracture_insertion") == "extrinsic";
      if (b.extrinsic && b.fracture == BodyConfig::Fracture::None)
        fail("{}: [[bodies]] '{}' has fracture_insertion = \"extrinsic\" but no joints (fracture = \"none\")",
             s.where("fracture_insertion"), b.name);
      if (b.fracture == BodyConfig::Fracture::Groups && b.fracture_groups.empty())
        fail("{}: [[bodies]] '{}' has fracture = \"groups\" but no fracture_groups", s.where("fracture"), b.name);
      if (b.fracture != BodyConfig::Fracture::None && b.kinematics == Kinematics::Rigid)
        fail("{}: [[bodies]] '{}' is rigid and cannot fracture (remove fracture, or make it deformable)",
             s.where("fracture"), b.name);
      if (b.fracture != BodyConfig::Fracture::None) {
        const Index mi = material_index(b.material, s.where("material"));
        if (!c.joint_materials[mi].given)
          fail(
              "{}: [[bodies]] '{}' is fracturable but [materials.{}] has no joint parameters (tensile_strength, "
              "fracture_energy_I, cohesion, friction_angle, fracture_energy_II)",
              s.where("fracture"), b.name, b.material);
      }
      b.zone_groups = s.strings("zone_groups");
      b.zone_material = s.str("zone_material");
      b.zone_box = read_box(s, fmt::format("[[bodies]] '{}'", b.name), "zone_box_min", "zone_box_max");
      const bool zone = !b.zone_groups.empty() || b.zone_box;
      if (zone || !b.zone_material.empty()) {
        if (!b.zone_groups.empty() && b.zone_material.empty())
          fail("{}: [[bodies]] '{}': zone_groups and zone_material come together", s.where(), b.name);
        if (b.zone_box && b.zone_material.empty())
          fail("{}: [[bodies]] '{}': a zone box (zone_box_min, zone_box_max) needs zone_material", s.where(), b.name);
        if (!zone)
          fail("{}: [[bodies]] '{}': zone_material needs zone_groups or a zone box (zone_box_min, zone_box_max)",
               s.where("zone_material"), b.name);
        if (b.fracture == BodyConfig::Fracture::None)
          fail("{}: [[bodies]] '{}' has a joint zone but no joints (fracture = \"none\")",
               s.where(b.zone_groups.empty() ? "zone_box_min" : "zone_groups"), b.name);
        const Index zi = material_index(b.zone_material, s.where("zone_material"));
        if (!c.joint_materials[zi].given)
          fail("{}: [[bodies]] '{}': zone_material '{}' has no joint parameters", s.where("zone_material"), b.name,
               b.zone_material);
      }
      for (const auto& o : c.bodies)
        DSPDEM_CHECK(o.name != b.name, "{}: body name '{}' used twice", s.where("name"), b.name);
      s.finish();
      c.bodies.push_back(b);
    }
  }
  DSPDEM_CHECK(!c.bodies.empty(), "{}: no [[bodies]]: at least one body is needed", path);
  if (toml::array* a = array_of_tables(ctx, root, "boundary")) {
    int i = 0;
    for (auto& n : *a) {
      Section s(ctx, *n.as_table(), "boundary[]", fmt::format("[[boundary]] #{}", ++i));
      BoundaryConfig b;
      b.where = s.where();
      b.group = s.str("group");
      const std::string type = s.str("type");
      b.type = type == "fixed"      ? BoundaryConfig::Type::Fixed
               : type == "velocity" ? BoundaryConfig::Type::Velocity
                                    : BoundaryConfig::Type::Force;
      const std::string dofs = s.str("dofs");
      DSPDEM_CHECK(!dofs.empty() && dofs.find_first_not_of("xyz") == std::string::npos,
                   "{}: [[boundary]] #{} key 'dofs' = \"{}\" must be made of x, y, z", s.where("dofs"), i, dofs);
      for (int d = 0; d < 3; ++d) b.dof[d] = dofs.find("xyz"[d]) != std::string::npos;
      b.value = s.vec3("value");
      b.ramp = s.real("ramp");
      s.finish();
      c.boundaries.push_back(b);
    }
  }
  if (toml::array* a = array_of_tables(ctx, root, "initial")) {
    int i = 0;
    for (auto& n : *a) {
      Section s(ctx, *n.as_table(), "initial[]", fmt::format("[[initial]] #{}", ++i));
      InitialConfig ic;
      ic.where = s.where();
      ic.group = s.str("group");
      ic.velocity = s.vec3("velocity");
      ic.angular_velocity = s.vec3("angular_velocity");
      ic.center = s.vec3("center");
      s.finish();
      c.initial.push_back(ic);
    }
  }
  {
    Section s(ctx, sub_table(ctx, root, "contact"), "contact", "[contact]");
    c.contact.enabled = s.boolean("enabled");
    if (s.has("skin")) c.contact.settings.skin = s.real("skin");
    c.contact.settings.step_fraction = s.real("step_fraction");
    s.finish();
  }
  if (toml::array* a = array_of_tables(ctx, root, "walls")) {
    int i = 0;
    for (auto& n : *a) {
      Section s(ctx, *n.as_table(), "walls[]", fmt::format("[[walls]] #{}", ++i));
      WallConfig wc;
      wc.where = s.where();
      contact::Wall& w = wc.wall;
      w.name = s.str("name");
      check_column_name(w.name, s.where("name"), "wall");
      for (const auto& o : c.walls)
        DSPDEM_CHECK(o.wall.name != w.name, "{}: wall name '{}' used twice", s.where("name"), w.name);
      const std::string type = s.str("type");
      w.type = type == "box"        ? contact::Wall::Type::Box
               : type == "jaw"      ? contact::Wall::Type::Jaw
               : type == "cylinder" ? contact::Wall::Type::Cylinder
                                    : contact::Wall::Type::Plane;
      w.centre = s.vec3("point");
      const Vec3 nrm = s.vec3("normal");
      if (w.type != contact::Wall::Type::Box && !(nrm.norm() > 0))
        fail("{}: [[walls]] '{}' key 'normal' must not be zero", s.where("normal"), w.name);
      if (nrm.norm() > 0) w.normal0 = nrm.normalized();
      w.half = s.vec3("half_size");
      if (w.type == contact::Wall::Type::Box && !(w.half.minCoeff() > 0))
        fail("{}: [[walls]] '{}' is a box: half_size needs three positive extents", s.where("half_size"), w.name);
      if (w.type == contact::Wall::Type::Cylinder) {
        if (!s.has("radius") || !s.has("length"))
          fail("{}: [[walls]] '{}' is a cylinder: give its radius and length", s.where(), w.name);
        w.radius = s.real("radius");
        w.half_length = 0.5 * s.real("length");
        const Vec3 ax = s.vec3("axis");
        if (!(ax.norm() > 0)) fail("{}: [[walls]] '{}' key 'axis' must not be zero", s.where("axis"), w.name);
        w.axis0 = ax.normalized();
        s.real("half_angle");
      } else if (w.type == contact::Wall::Type::Jaw) {
        if (!s.has("radius")) fail("{}: [[walls]] '{}' is a jaw: give its radius", s.where(), w.name);
        w.radius = s.real("radius");
        const Vec3 ax = s.vec3("axis");
        if (!(ax.norm() > 0)) fail("{}: [[walls]] '{}' key 'axis' must not be zero", s.where("axis"), w.name);
        w.axis0 = ax.normalized();
        if (std::abs(w.axis0.dot(w.normal0)) > 1e-9)
          fail("{}: [[walls]] '{}': a jaw's normal (from its axis to the arc) must be normal to its axis",
               s.where("normal"), w.name);
        w.cos_half_angle = std::cos(s.real("half_angle") * M_PI / 180.0);
      } else {
        if (s.has("radius"))
          fail("{}: [[walls]] '{}': key 'radius' is for jaws and cylinders only", s.where("radius"), w.name);
        s.vec3("axis"), s.real("half_angle");  // defaults written to case.resolved.toml; unused
      }
      if (w.type != contact::Wall::Type::Cylinder && s.has("length"))
        fail("{}: [[walls]] '{}': key 'length' is for cylinders only", s.where("length"), w.name);
      {}
      w.velocity_target = s.vec3("velocity");
      w.ramp = s.real("ramp");
      w.free = s.boolean("free");
      if (w.free) {
        if (w.type != contact::Wall::Type::Box && w.type != contact::Wall::Type::Cylinder)
          fail("{}: [[walls]] '{}': only boxes and cylinders can be free (planes and jaws have no mass)",
               s.where("free"), w.name);
        if (s.has("density") == s.has("mass"))
          fail("{}: [[walls]] '{}' is free: give its density or its mass (one of the two)", s.where("free"), w.name);
        const Real volume = w.type == contact::Wall::Type::Cylinder ? M_PI * w.radius * w.radius * 2 * w.half_length
                                                                    : (2 * w.half).prod();
        // A given mass is spread uniformly over the solid (inertia of a uniform cylinder or box).
        const Real rho = s.has("mass") ? s.real("mass") / volume : s.real("density");
        w.inertia_body = Mat3::Zero();
        if (w.type == contact::Wall::Type::Cylinder) {
          // A solid cylinder of the wall's radius and length (its contact ends are rounded).
          const Real R = w.radius, L = 2 * w.half_length;
          w.mass = rho * M_PI * R * R * L;
          const Real ia = 0.5 * w.mass * R * R, it = w.mass * (3 * R * R + L * L) / 12;
          const Mat3 aa = w.axis0 * w.axis0.transpose();
          w.inertia_body = it * (Mat3::Identity() - aa) + ia * aa;
        } else {
          const Vec3 d = 2 * w.half;
          w.mass = rho * d.prod();
          w.inertia_body(0, 0) = w.mass * (d(1) * d(1) + d(2) * d(2)) / 12;
          w.inertia_body(1, 1) = w.mass * (d(0) * d(0) + d(2) * d(2)) / 12;
          w.inertia_body(2, 2) = w.mass * (d(0) * d(0) + d(1) * d(1)) / 12;
        }
        w.velocity = w.velocity_target;
      } else if (s.has("density") || s.has("mass")) {
        fail("{}: [[walls]] '{}': key '{}' is for free walls only (set free = true)",
             s.where(s.has("mass") ? "mass" : "density"), w.name, s.has("mass") ? "mass" : "density");
      }
      if (s.has("friction")) w.mu = s.real("friction");
      if (s.has("kn")) w.kn = s.real("kn");
      s.finish();
      c.walls.push_back(wc);
    }
  }
  if (!c.walls.empty() && !c.contact.enabled)
    fail("{}: [[walls]] are given but [contact] enabled = false: walls act only through contact", path);
  {
    Section s(ctx, sub_table(ctx, root, "time"), "time", "[time]");
    c.t_end = s.real("end");
    c.dt = s.has("dt") ? s.real("dt") : 0.0;  // 0: automatic
    c.safety = s.real("safety");
    c.allow_unstable = s.boolean("allow_unstable");
    c.max_steps = s.integer("max_steps");
    c.insertion_interval = s.integer("insertion_interval");
    c.insertion_stress = s.str("insertion_stress") == "mean" ? joint::FaceStress::Mean : joint::FaceStress::Larger;
    c.insertion_cut_front = s.str("insertion_front") == "cut";
    if (s.has("stop_series")) c.stop_series = s.str("stop_series");
    c.stop_fraction = s.real("stop_fraction");
    c.stop_min_peak = s.real("stop_min_peak");
    c.stop_delay = s.real("stop_delay");
    c.stop_reach = s.real("stop_reach");
    if (c.stop_reach > 0 && c.stop_series.empty())
      fail("{}: [time] stop_reach = {} needs stop_series, the series.csv column it watches", s.where(), c.stop_reach);
    s.finish();
  }
  {
    Section s(ctx, sub_table(ctx, root, "output"), "output", "[output]");
    c.frame_interval = s.has("frame_interval") ? s.real("frame_interval") : c.t_end / 20;
    c.series_interval = s.has("series_interval") ? s.real("series_interval") : c.frame_interval / 10;
    c.fields = s.strings("fields");
    c.compress = s.boolean("compress");
    s.finish();
  }
  if (toml::array* a = array_of_tables(ctx, root, "monitors")) {
    int i = 0;
    for (auto& n : *a) {
      Section s(ctx, *n.as_table(), "monitors[]", fmt::format("[[monitors]] #{}", ++i));
      MonitorConfig m;
      m.where = s.where();
      m.name = s.str("name");
      check_column_name(m.name, s.where("name"), "monitor");
      const std::string type = s.str("type");
      using MT = MonitorConfig::Type;
      m.type = type == "reaction"                  ? MT::Reaction
               : type == "displacement"            ? MT::Displacement
               : type == "displacement_difference" ? MT::DisplacementDifference
               : type == "velocity"                ? MT::Velocity
               : type == "momentum"                ? MT::Momentum
               : type == "broken_joints"           ? MT::BrokenJoints
               : type == "crack_area"              ? MT::CrackArea
                                                   : MT::MaxDisplacement;
      if (m.counts_joints()) {
        // Joints are counted where they lie (a box), not by a node group; a component
        // of a count means nothing.
        for (const char* k : {"group", "group2", "component"})
          if (s.has(k))
            fail("{}: [[monitors]] '{}': a {} monitor counts joints in a box (box_min, box_max) and takes no {}",
                 s.where(k), m.name, type, k);
        m.box = read_box(s, fmt::format("[[monitors]] '{}'", m.name), "box_min", "box_max");
      } else {
        for (const char* k : {"box_min", "box_max"})
          if (s.has(k))
            fail("{}: [[monitors]] '{}': {} is for broken_joints and crack_area monitors, not {}", s.where(k), m.name,
                 k, type);
        if (s.has("group"))
          m.group = s.str("group");
        else
          DSPDEM_CHECK(m.type == MT::MaxDisplacement || m.type == MT::Momentum, "{}: [[monitors]] '{}' needs a group",
                       s.where(), m.name);
        if (s.has("group2"))
          m.group2 = s.str("group2");
        else
          DSPDEM_CHECK(m.type != MT::DisplacementDifference, "{}: [[monitors]] '{}' needs group2", s.where(), m.name);
        m.component = component_index(s.str("component"));
      }
      for (const auto& o : c.monitors)
        DSPDEM_CHECK(o.name != m.name, "{}: monitor name '{}' used twice", s.where("name"), m.name);
      s.finish();
      c.monitors.push_back(m);
    }
  }
  {
    Section s(ctx, sub_table(ctx, root, "render"), "render", "[render]");
    RenderConfig& r = c.render;
    r.views = s.strings("views");
    r.field = s.str("field");
    r.magnify = s.real("magnify");
    r.auto_min = !s.has("range_min");
    r.auto_max = !s.has("range_max");
    if (!r.auto_min) r.range_min = s.real("range_min");
    if (!r.auto_max) r.range_max = s.real("range_max");
    if (!r.auto_min && !r.auto_max && !(r.range_min < r.range_max))
      fail("{}: [render] range_min must be below range_max", s.where("range_max"));
    r.camera = s.str("camera");
    r.fit = s.str("fit");
    r.cut = s.str("cut");
    r.width = static_cast<int>(s.integer("width"));
    r.height = static_cast<int>(s.integer("height"));
    r.background = s.vec3("background");
    r.animation = s.boolean("animation");
    r.edges = s.boolean("edges");
    r.fps = static_cast<int>(s.integer("fps"));
    r.plots = s.strings("plots");
    for (const auto& p : r.plots)
      if (p.find(':') == std::string::npos || p.find(':') == 0 || p.back() == ':')
        fail("{}: [render] plots entry \"{}\" must read \"x:y1,y2\"", s.where("plots"), p);
    r.plot_reference = s.str("plot_reference");
    if (!r.plot_reference.empty() && fs::path(r.plot_reference).is_relative())
      r.plot_reference = (fs::path(c.dir) / r.plot_reference).lexically_normal().string();
    s.finish();
  }
  {
    Section s(ctx, sub_table(ctx, root, "checks"), "checks", "[checks]");
    c.energy_blowup_factor = s.real("energy_blowup_factor");
    c.energy_balance_warn = s.real("energy_balance_warn");
    c.contact.settings.overlap_limit = s.real("contact_overlap_limit");
    s.finish();
  }
  std::ostringstream os;
  os << kResolvedFrom << path << kResolvedFromEnd << "\n" << root << "\n";
  c.resolved_toml = os.str();
  return c;
}

std::string case_schema_markdown() {
  std::string out = "| section | key | type | default | range | unit | meaning |\n|---|---|---|---|---|---|---|\n";
  for (const auto& k : schema::keys()) {
    std::string range = schema::range_text(k);
    for (auto& ch : range)
      if (ch == '|') ch = '/';
    out += fmt::format("| `{}` | `{}` | {} | {} | {} | {} | {} |\n", k.section, k.key, schema::type_name(k.type),
                       k.def ? fmt::format("`{}`", k.def) : "required", range, k.unit, k.doc);
  }
  return out;
}

Real mesh_param(const CaseConfig& c, const std::string& key) {
  const auto it = c.mesh_num.find(key);
  if (it == c.mesh_num.end())
    fail("{}: [mesh.{}] has no numeric parameter '{}'", c.path, c.mesh_generator.empty() ? "?" : c.mesh_generator, key);
  return it->second;
}

std::string override_of(const std::string& key, Real v) { return fmt::format("{}={:.17g}", key, v); }
std::string override_of(const std::string& key, const Vec3& v) {
  return fmt::format("{}=[{:.17g},{:.17g},{:.17g}]", key, v(0), v(1), v(2));
}
std::string override_of(const std::string& key, const std::string& v) { return fmt::format("{}=\"{}\"", key, v); }

CaseConfig reread_with(const CaseConfig& base, const std::vector<std::string>& extra) {
  std::vector<std::string> all = base.overrides;
  all.insert(all.end(), extra.begin(), extra.end());
  return read_case(base.path, all);
}

}  // namespace dspdem
