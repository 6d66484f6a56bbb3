#include "par/partition.hpp"

#include <metis.h>

#include <algorithm>

#include "contact/broad_phase.hpp"
#include "core/error.hpp"

namespace dspdem::par {

namespace {
// Pieces with nothing between them (loose particles, separate bodies) have no edge in the
// graph, and METIS would share them out regardless of where they are: each process would
// then lend its pieces to every other (contact/contact_share.cpp: a 1000-particle packing
// on 2 processes lent all 500 each way). Elements of different connected parts of the graph
// whose boxes, grown by the mean element size (loose particles lie a size or so apart), meet
// are joined, so that near pieces go to the same process, as through a face (then 42 and 25).
void proximity_edges(const Mesh& mesh, std::vector<std::vector<int>>& adj) {
  const Index ne = static_cast<Index>(adj.size());
  std::vector<Index> part(static_cast<std::size_t>(ne), -1);
  std::vector<Index> stack;
  for (Index s = 0; s < ne; ++s) {
    if (part[s] >= 0) continue;
    part[s] = s, stack.assign(1, s);
    while (!stack.empty()) {
      const Index e = stack.back();
      stack.pop_back();
      for (int n : adj[e])
        if (part[n] < 0) part[n] = s, stack.push_back(n);
    }
  }
  contact::Boxes boxes;
  boxes.lo.reserve(3 * static_cast<std::size_t>(ne)), boxes.hi.reserve(3 * static_cast<std::size_t>(ne));
  Real size = 0;
  for (const auto& b : mesh.blocks)
    for (Index e = 0; e < b.size(); ++e) {
      Vec3 lo = Vec3::Constant(INFINITY), hi = Vec3::Constant(-INFINITY);
      for (int i = 0; i < b.npe(); ++i) {
        const Vec3 x = node_pos(mesh.x, b.conn[static_cast<std::size_t>(e) * b.npe() + i]);
        lo = lo.cwiseMin(x), hi = hi.cwiseMax(x);
      }
      size += (hi - lo).maxCoeff();
      for (int d = 0; d < 3; ++d) boxes.lo.push_back(lo(d)), boxes.hi.push_back(hi(d));
    }
  const Real grow = ne > 0 ? size / ne : 0.0;
  for (auto* v : {&boxes.lo, &boxes.hi})
    for (Real& c : *v) c += v == &boxes.lo ? -grow : grow;
  contact::PairList pairs;
  contact::GridBroadPhase().find(boxes, pairs, &part);
  for (auto [a, b] : pairs) adj[a].push_back(static_cast<int>(b)), adj[b].push_back(static_cast<int>(a));
}
}  // namespace

void element_graph(const Model& m, std::vector<int>& xadj, std::vector<int>& adjncy) {
  const Mesh& mesh = m.mesh;
  idx_t ne = static_cast<idx_t>(mesh.n_elements());
  // The mesh's own adjacency (elements sharing three nodes: a face of a tet, three corners of
  // a hex face) from METIS; where joints split the nodes, their element pairs join the rest.
  std::vector<idx_t> eptr{0}, eind;
  for (const auto& b : mesh.blocks) {
    for (Index e = 0; e < b.size(); ++e) {
      for (int i = 0; i < b.npe(); ++i)
        eind.push_back(static_cast<idx_t>(b.conn[static_cast<std::size_t>(e) * b.npe() + i]));
      eptr.push_back(static_cast<idx_t>(eind.size()));
    }
  }
  idx_t nn = static_cast<idx_t>(mesh.n_nodes()), ncommon = 3, numflag = 0;
  idx_t *dx = nullptr, *da = nullptr;
  if (ne > 0) {
    const int rc = METIS_MeshToDual(&ne, &nn, eptr.data(), eind.data(), &ncommon, &numflag, &dx, &da);
    DSPDEM_CHECK(rc == METIS_OK, "METIS_MeshToDual failed (code {}) on a mesh of {} elements", rc, ne);
  }
  std::vector<std::vector<int>> adj(static_cast<std::size_t>(ne));
  for (idx_t e = 0; e < ne; ++e)
    for (idx_t k = dx[e]; k < dx[e + 1]; ++k) adj[e].push_back(static_cast<int>(da[k]));
  if (dx) METIS_Free(dx);
  if (da) METIS_Free(da);
  const joint::JointSet& js = m.joints;
  for (Index j = 0; j < js.size(); ++j) {
    adj[js.ea[j]].push_back(static_cast<int>(js.eb[j]));
    adj[js.eb[j]].push_back(static_cast<int>(js.ea[j]));
  }
  if (m.contact.enabled()) proximity_edges(mesh, adj);
  xadj.assign(1, 0);
  adjncy.clear();
  for (auto& a : adj) {
    std::sort(a.begin(), a.end());
    a.erase(std::unique(a.begin(), a.end()), a.end());
    adjncy.insert(adjncy.end(), a.begin(), a.end());
    xadj.push_back(static_cast<int>(adjncy.size()));
  }
}

std::vector<int> partition_elements(const Model& m, int parts) {
  const Index ne = m.mesh.n_elements();
  std::vector<int> part(static_cast<std::size_t>(ne), 0);
  if (parts <= 1 || ne == 0) return part;
  DSPDEM_CHECK(ne >= parts, "{} processes for a model of {} elements: run on at most {}", parts, ne, ne);
  std::vector<int> xadj, adjncy;
  element_graph(m, xadj, adjncy);
  std::vector<idx_t> xa(xadj.begin(), xadj.end()), ad(adjncy.begin(), adjncy.end()), out(static_cast<std::size_t>(ne));
  idx_t nv = static_cast<idx_t>(ne), ncon = 1, np = parts, cut = 0;
  idx_t opt[METIS_NOPTIONS];
  METIS_SetDefaultOptions(opt);
  opt[METIS_OPTION_SEED] = 1;  // the same partition on every process and every run
  opt[METIS_OPTION_CONTIG] = 0;
  const int rc = METIS_PartGraphKway(&nv, &ncon, xa.data(), ad.data(), nullptr, nullptr, nullptr, &np, nullptr, nullptr,
                                     opt, &cut, out.data());
  DSPDEM_CHECK(rc == METIS_OK, "METIS_PartGraphKway failed (code {}) cutting {} elements into {} parts", rc, ne, parts);
  for (Index e = 0; e < ne; ++e) part[e] = static_cast<int>(out[e]);
  return part;
}

}  // namespace dspdem::par
