#include "mesh/gmsh_model_dump.hpp"

#include <gmsh.h>

#include <cstdint>
#include <cstring>
#include <string_view>
#include <type_traits>
#include <vector>

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

// Every count is checked against the bytes left before anything is allocated for it.
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
    DSPDEM_CHECK(n <= (b_.size() - pos_) / sizeof(T), "mesh '{}': the mesh read in its own process came back cut short",
                 source_);
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
  void take(void* dst, std::size_t n) {
    DSPDEM_CHECK(n <= b_.size() - pos_, "mesh '{}': the mesh read in its own process came back cut short", source_);
    if (n > 0) std::memcpy(dst, b_.data() + pos_, n);
    pos_ += n;
  }
  const std::string& b_;
  const std::string& source_;
  std::size_t pos_ = 0;
};
}  // namespace

std::string dump_gmsh_model() {
  Writer w;
  w.out.append(kMagic);
  for (const char* name : kWriteOptions) {
    double v = 0;
    gmsh::option::getNumber(name, v);
    w.put(v);
  }
  std::vector<std::pair<int, int>> ents;
  gmsh::model::getEntities(ents);
  w.put<std::uint64_t>(ents.size());
  for (auto [dim, tag] : ents) {
    w.put<std::int32_t>(dim);
    w.put<std::int32_t>(tag);
    std::vector<std::size_t> ntags;
    std::vector<double> coord, param;
    gmsh::model::mesh::getNodes(ntags, coord, param, dim, tag, false, false);
    w.put(ntags);
    w.put(coord);
    std::vector<int> types;
    std::vector<std::vector<std::size_t>> etags, enodes;
    gmsh::model::mesh::getElements(types, etags, enodes, dim, tag);
    w.put(types);
    for (std::size_t k = 0; k < types.size(); ++k) {
      w.put(etags[k]);
      w.put(enodes[k]);
    }
  }
  std::vector<std::pair<int, int>> phys;
  gmsh::model::getPhysicalGroups(phys);
  w.put<std::uint64_t>(phys.size());
  for (auto [dim, tag] : phys) {
    w.put<std::int32_t>(dim);
    w.put<std::int32_t>(tag);
    std::string name;
    gmsh::model::getPhysicalName(dim, tag, name);
    w.put(name);
    std::vector<int> members;
    gmsh::model::getEntitiesForPhysicalGroup(dim, tag, members);
    w.put(members);
  }
  return std::move(w.out);
}

GmshOptions load_gmsh_model(const std::string& bytes, const std::string& source) {
  Reader r(bytes, source);
  r.expect(kMagic);
  double options[std::size(kWriteOptions)];
  for (double& v : options) v = r.get<double>();
  struct Entity {
    int dim, tag;
    std::vector<std::size_t> ntags;
    std::vector<double> coord;
    std::vector<int> types;
    std::vector<std::vector<std::size_t>> etags, enodes;
  };
  // Counts are not reserved for: a false one runs out of bytes at the next read instead.
  std::vector<Entity> ents;
  for (auto n = r.get<std::uint64_t>(); n > 0; --n) {
    Entity& e = ents.emplace_back();
    e.dim = r.get<std::int32_t>();
    e.tag = r.get<std::int32_t>();
    DSPDEM_CHECK(e.dim >= 0 && e.dim <= 3, "mesh '{}': the mesh read in its own process came back garbled", source);
    e.ntags = r.get_vec<std::size_t>();
    e.coord = r.get_vec<double>();
    e.types = r.get_vec<int>();
    for (std::size_t k = 0; k < e.types.size(); ++k) {
      e.etags.push_back(r.get_vec<std::size_t>());
      e.enodes.push_back(r.get_vec<std::size_t>());
    }
  }
  struct Physical {
    int dim, tag;
    std::string name;
    std::vector<int> members;
  };
  std::vector<Physical> phys;
  for (auto n = r.get<std::uint64_t>(); n > 0; --n) {
    Physical& p = phys.emplace_back();
    p.dim = r.get<std::int32_t>();
    p.tag = r.get<std::int32_t>();
    p.name = r.get_string();
    p.members = r.get_vec<int>();
  }
  DSPDEM_CHECK(r.done(), "mesh '{}': the mesh read in its own process came back with bytes left over", source);

  // Entities first, all of them, then the nodes, then the elements (which name nodes of
  // other entities: a volume's elements use its faces' nodes).
  gmsh::model::add("dspdem");
  for (const Entity& e : ents) gmsh::model::addDiscreteEntity(e.dim, e.tag);
  for (const Entity& e : ents)
    if (!e.ntags.empty()) gmsh::model::mesh::addNodes(e.dim, e.tag, e.ntags, e.coord);
  for (const Entity& e : ents)
    if (!e.types.empty()) gmsh::model::mesh::addElements(e.dim, e.tag, e.types, e.etags, e.enodes);
  for (const Physical& p : phys) {
    gmsh::model::addPhysicalGroup(p.dim, p.members, p.tag);
    if (!p.name.empty()) gmsh::model::setPhysicalName(p.dim, p.tag, p.name);
  }
  GmshOptions set;
  for (std::size_t k = 0; k < std::size(kWriteOptions); ++k) set.emplace_back(kWriteOptions[k], options[k]);
  return set;
}

}  // namespace dspdem
