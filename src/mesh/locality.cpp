#include "mesh/locality.hpp"

#include <CGAL/Hilbert_policy_tags.h>
#include <CGAL/Hilbert_sort_3.h>
#include <CGAL/Simple_cartesian.h>
#include <CGAL/Spatial_sort_traits_adapter_3.h>

#include <algorithm>
#include <numeric>

namespace dspdem {

namespace {
using Kernel = CGAL::Simple_cartesian<double>;
using Point = Kernel::Point_3;

// New position of each element of a block along the Hilbert curve: order[k] = old index.
std::vector<Index> hilbert_order(const Mesh& mesh, const ElementBlock& blk) {
  const Index ne = blk.size();
  std::vector<Point> centroid;
  centroid.reserve(static_cast<std::size_t>(ne));
  for (Index e = 0; e < ne; ++e) {
    const Vec3 c = element_centroid(mesh, blk, e);
    centroid.emplace_back(c(0), c(1), c(2));
  }
  std::vector<std::size_t> order(static_cast<std::size_t>(ne));
  std::iota(order.begin(), order.end(), 0);
  // The sorter itself, without hilbert_sort's random pre-shuffle: the same order every time.
  using Map = CGAL::Pointer_property_map<Point>::type;
  using Traits = CGAL::Spatial_sort_traits_adapter_3<Kernel, Map>;
  CGAL::Hilbert_sort_3<Traits, CGAL::Hilbert_sort_median_policy> sort(Traits(CGAL::make_property_map(centroid)));
  sort(order.begin(), order.end());
  return {order.begin(), order.end()};
}
}  // namespace

void order_for_locality(Mesh& mesh) {
  std::vector<std::vector<Index>> new_of_old_elem(mesh.blocks.size());
  for (std::size_t b = 0; b < mesh.blocks.size(); ++b) {
    ElementBlock& blk = mesh.blocks[b];
    const std::vector<Index> order = hilbert_order(mesh, blk);
    const std::size_t npe = static_cast<std::size_t>(blk.npe());
    std::vector<Index> conn(blk.conn.size());
    std::vector<std::size_t> tag(blk.tag.size());
    new_of_old_elem[b].resize(order.size());
    for (std::size_t k = 0; k < order.size(); ++k) {
      const std::size_t old = static_cast<std::size_t>(order[k]);
      std::copy_n(blk.conn.begin() + static_cast<long>(old * npe), npe, conn.begin() + static_cast<long>(k * npe));
      tag[k] = blk.tag[old];
      new_of_old_elem[b][old] = static_cast<Index>(k);
    }
    blk.conn = std::move(conn);
    blk.tag = std::move(tag);
  }
  // Nodes in order of first use.
  const Index nn = mesh.n_nodes();
  std::vector<Index> new_of_old(static_cast<std::size_t>(nn), -1);
  Index next = 0;
  for (const auto& blk : mesh.blocks)
    for (Index n : blk.conn)
      if (new_of_old[n] < 0) new_of_old[n] = next++;
  for (Index n = 0; n < nn; ++n)
    if (new_of_old[n] < 0) new_of_old[n] = next++;
  std::vector<Real> x(mesh.x.size());
  std::vector<std::size_t> node_tag(mesh.node_tag.size());
  for (Index n = 0; n < nn; ++n) {
    const Index m = new_of_old[n];
    for (int d = 0; d < 3; ++d) x[3 * m + d] = mesh.x[3 * n + d];
    node_tag[m] = mesh.node_tag[n];
  }
  mesh.x = std::move(x);
  mesh.node_tag = std::move(node_tag);
  for (auto& blk : mesh.blocks)
    for (Index& n : blk.conn) n = new_of_old[n];
  for (Group& g : mesh.groups) {
    for (Index& n : g.nodes) n = new_of_old[n];
    std::sort(g.nodes.begin(), g.nodes.end());
    for (Index& n : g.tri) n = new_of_old[n];
    for (Index& n : g.quad) n = new_of_old[n];
    for (std::size_t b = 0; b < g.elements.size() && b < mesh.blocks.size(); ++b) {
      for (Index& e : g.elements[b]) e = new_of_old_elem[b][e];
      std::sort(g.elements[b].begin(), g.elements[b].end());
    }
  }
}

}  // namespace dspdem
