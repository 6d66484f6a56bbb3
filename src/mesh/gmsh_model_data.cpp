#include "mesh/gmsh_model_data.hpp"

#include <gmsh.h>

#include <cstdint>
#include <cstring>
#include <string_view>
#include <type_traits>

#include "core/error.hpp"

namespace dspdem {

namespace {
constexpr std::string_view kMagic = "dspdem gmsh model 1\n";
constexpr const char* kWriteOptions[] = {"Mesh.SaveAll", "Mesh.MshFileVersion", "Mesh.Binary"};

class Writer {
 public:
  template <typename T>
  void put(const T& v) {
    static_assert(std::is_trivially_copyable_v<T>);
    out.append(reinterpret_cast<const char*>(&v), sizeof v);
  }
  template <typename T>
  void put(const std::vector<T>& v) {
    put<std::uint64_t>(v.size());
    out.append(reinterpret_cast<const char*>(v.data()), v.size() * sizeof(T));
  }
  void put(const std::string& s) {
    put<std::uint64_t>(s.size());
    out += s;
  }
  std::string out;
};

class Reader {
 public:
  Reader(const std::string& bytes, const std::string& source) : b_(bytes), source_(source) {}
  template <typename T>
  T get() {
    T v;
    take(&v, sizeof v);
    return v;
  }
  template <typename T>
  std::vector<T> get_vec() {
    const auto n = get<std::uint64_t>();
    if (n > (b_.size() - pos_) / sizeof(T)) short_();
    std::vector<T> v(n);
    take(v.data(), n * sizeof(T));
    return v;
  }
  std::string get_string() {
    const auto v = get_vec<char>();
    return {v.begin(), v.end()};
  }
  void expect(std::string_view s) {
    DSPDEM_CHECK(b_.compare(pos_, s.size(), s) == 0, "mesh '{}': the mesh read in its own process came back garbled",
                 source_);
    pos_ += s.size();
  }
  bool done() const { return pos_ == b_.size(); }

 private:
  [[noreturn]] void short_() const { fail("mesh '{}': the mesh read in its own process came back cut short", source_); }
  void take(void* dst, std::size_t n) {
    if (n > b_.size() - pos_) short_();
    if (n > 0) std::memcpy(dst, b_.data() + pos_, n);
    pos_ += n;
  }
  const std::string& b_;
  const std::string& source_;
  std::size_t pos_ = 0;
};
}  // namespace

GmshModelData gmsh_model_data() {
  GmshModelData m;
  for (const char* name : kWriteOptions) {
    double v = 0;
    gmsh::option::getNumber(name, v);
    m.write_options.emplace_back(name, v);
  }
  std::vector<std::pair<int, int>> ents;
  gmsh::model::getEntities(ents);
  for (auto [dim, tag] : ents) {
    GmshEntity& e = m.entities.emplace_back();
    e.dim = dim;
    e.tag = tag;
    std::vector<double> param;
    gmsh::model::mesh::getNodes(e.node_tags, e.coord, param, dim, tag, false, false);
    gmsh::model::mesh::getElements(e.types, e.elem_tags, e.elem_nodes, dim, tag);
  }
  std::vector<std::pair<int, int>> phys;
  gmsh::model::getPhysicalGroups(phys);
  for (auto [dim, tag] : phys) {
    GmshPhysical& p = m.physicals.emplace_back();
    p.dim = dim;
    p.tag = tag;
    gmsh::model::getPhysicalName(dim, tag, p.name);
    gmsh::model::getEntitiesForPhysicalGroup(dim, tag, p.entities);
  }
  return m;
}

std::string to_bytes(const GmshModelData& m) {
  Writer w;
  w.out.append(kMagic);
  w.put<std::uint64_t>(m.write_options.size());
  for (const auto& [name, v] : m.write_options) {
    w.put(name);
    w.put(v);
  }
  w.put<std::uint64_t>(m.entities.size());
  for (const GmshEntity& e : m.entities) {
    w.put<std::int32_t>(e.dim);
    w.put<std::int32_t>(e.tag);
    w.put(e.node_tags);
    w.put(e.coord);
    w.put(e.types);
    for (std::size_t k = 0; k < e.types.size(); ++k) {
      w.put(e.elem_tags[k]);
      w.put(e.elem_nodes[k]);
    }
  }
  w.put<std::uint64_t>(m.physicals.size());
  for (const GmshPhysical& p : m.physicals) {
    w.put<std::int32_t>(p.dim);
    w.put<std::int32_t>(p.tag);
    w.put(p.name);
    w.put(p.entities);
  }
  return std::move(w.out);
}

GmshModelData from_bytes(const std::string& bytes, const std::string& source) {
  auto garbled = [&](bool ok) {
    DSPDEM_CHECK(ok, "mesh '{}': the mesh read in its own process came back garbled", source);
  };
  Reader r(bytes, source);
  r.expect(kMagic);
  GmshModelData m;
  // Counts are not reserved for: a false one runs out of bytes at the next read instead.
  for (auto n = r.get<std::uint64_t>(); n > 0; --n) {
    std::string name = r.get_string();
    const double v = r.get<double>();
    m.write_options.emplace_back(std::move(name), v);
  }
  garbled(m.write_options.size() == std::size(kWriteOptions));
  for (std::size_t k = 0; k < std::size(kWriteOptions); ++k) garbled(m.write_options[k].first == kWriteOptions[k]);
  for (auto n = r.get<std::uint64_t>(); n > 0; --n) {
    GmshEntity& e = m.entities.emplace_back();
    e.dim = r.get<std::int32_t>();
    e.tag = r.get<std::int32_t>();
    garbled(e.dim >= 0 && e.dim <= 3);
    e.node_tags = r.get_vec<std::size_t>();
    e.coord = r.get_vec<double>();
    garbled(e.coord.size() == 3 * e.node_tags.size());
    e.types = r.get_vec<int>();
    for (std::size_t k = 0; k < e.types.size(); ++k) {
      e.elem_tags.push_back(r.get_vec<std::size_t>());
      e.elem_nodes.push_back(r.get_vec<std::size_t>());
    }
  }
  for (auto n = r.get<std::uint64_t>(); n > 0; --n) {
    GmshPhysical& p = m.physicals.emplace_back();
    p.dim = r.get<std::int32_t>();
    p.tag = r.get<std::int32_t>();
    garbled(p.dim >= 0 && p.dim <= 3);
    p.name = r.get_string();
    p.entities = r.get_vec<int>();
  }
  garbled(r.done());
  return m;
}

void load_into_gmsh(const GmshModelData& m) {
  // Entities first, all of them, then the nodes, then the elements (which name nodes of
  // other entities: a volume's elements use its faces' nodes).
  gmsh::model::add("dspdem");
  for (const GmshEntity& e : m.entities) gmsh::model::addDiscreteEntity(e.dim, e.tag);
  for (const GmshEntity& e : m.entities)
    if (!e.node_tags.empty()) gmsh::model::mesh::addNodes(e.dim, e.tag, e.node_tags, e.coord);
  for (const GmshEntity& e : m.entities)
    if (!e.types.empty()) gmsh::model::mesh::addElements(e.dim, e.tag, e.types, e.elem_tags, e.elem_nodes);
  for (const GmshPhysical& p : m.physicals) {
    gmsh::model::addPhysicalGroup(p.dim, p.entities, p.tag);
    if (!p.name.empty()) gmsh::model::setPhysicalName(p.dim, p.tag, p.name);
  }
}

}  // namespace dspdem
