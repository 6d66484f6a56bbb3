// Joint insertion by node duplication. Around every node, the element corners
// ("incidences") that are still connected through an unjointed shared face keep one node;
// each separate cluster gets its own copy. Joints everywhere give every element its own
// nodes; joints in a region split only the nodes inside it.
#include <algorithm>
#include <array>
#include <map>
#include <numeric>

#include "core/error.hpp"
#include "joint/joint_set.hpp"

namespace dspdem::joint {

const std::vector<std::vector<int>>& cell_faces(CellType t) {
  static const std::vector<std::vector<int>> tet = {{0, 2, 1}, {0, 1, 3}, {0, 3, 2}, {1, 2, 3}};
  static const std::vector<std::vector<int>> hex = {{0, 3, 2, 1}, {4, 5, 6, 7}, {0, 1, 5, 4},
                                                    {2, 3, 7, 6}, {1, 2, 6, 5}, {0, 4, 7, 3}};
  return t == CellType::Tet4 ? tet : hex;
}

namespace {
struct FaceRef {
  std::array<Index, 4> key;  ///< sorted node ids (-1 padded)
  Index elem;                ///< global element
  int block, local_elem, face;
};
}  // namespace

JointSet insert_joints(Mesh& mesh, const InsertionInput& in, InsertionReport* report) {
  JointSet js;
  // Global element numbering: blocks in order.
  std::vector<Index> offset;
  Index ne = 0;
  for (const auto& b : mesh.blocks) offset.push_back(ne), ne += b.size();
  DSPDEM_CHECK(static_cast<Index>(in.fracturable.size()) == ne, "internal: fracturable flags size");
  // Incidence numbering: one per element corner.
  std::vector<std::size_t> inc0(mesh.blocks.size());
  std::size_t n_inc = 0;
  for (std::size_t b = 0; b < mesh.blocks.size(); ++b) inc0[b] = n_inc, n_inc += mesh.blocks[b].conn.size();

  std::vector<FaceRef> faces;
  std::size_t n_faces = 0;
  for (const auto& blk : mesh.blocks) n_faces += static_cast<std::size_t>(blk.size()) * cell_faces(blk.type).size();
  faces.resize(n_faces);  // filled in place (also avoids a GCC 12 -Warray-bounds false positive in push_back)
  std::size_t nf = 0;
  for (std::size_t b = 0; b < mesh.blocks.size(); ++b) {
    const auto& blk = mesh.blocks[b];
    const auto& fl = cell_faces(blk.type);
    for (Index e = 0; e < blk.size(); ++e)
      for (int f = 0; f < static_cast<int>(fl.size()); ++f) {
        FaceRef& r = faces[nf++];
        r.key.fill(-1);
        for (std::size_t k = 0; k < fl[f].size(); ++k)
          r.key[k] = blk.conn[static_cast<std::size_t>(e) * blk.npe() + fl[f][k]];
        std::sort(r.key.begin(), r.key.begin() + static_cast<long>(fl[f].size()));
        r.elem = offset[b] + e, r.block = static_cast<int>(b), r.local_elem = e, r.face = f;
      }
  }
  std::sort(faces.begin(), faces.end(),
            [](const FaceRef& x, const FaceRef& y) { return x.key != y.key ? x.key < y.key : x.elem < y.elem; });

  std::vector<std::size_t> parent(n_inc);
  std::iota(parent.begin(), parent.end(), 0);
  auto find = [&](std::size_t i) {
    while (parent[i] != i) i = parent[i] = parent[parent[i]];
    return i;
  };
  auto corner = [&](const FaceRef& r, Index node) {
    const auto& blk = mesh.blocks[r.block];
    for (int i = 0; i < blk.npe(); ++i)
      if (blk.conn[static_cast<std::size_t>(r.local_elem) * blk.npe() + i] == node)
        return inc0[r.block] + static_cast<std::size_t>(r.local_elem) * blk.npe() + i;
    fail("internal: node {} not in element", node);
  };
  std::vector<std::pair<FaceRef, FaceRef>> jointed;
  std::vector<char> touched(mesh.n_nodes(), 0);  // node lies on a jointed face
  for (std::size_t i = 0; i + 1 < faces.size(); ++i) {
    if (faces[i].key != faces[i + 1].key) continue;
    const FaceRef &A = faces[i], &B = faces[i + 1];
    DSPDEM_CHECK(i + 2 >= faces.size() || faces[i + 2].key != A.key,
                 "mesh '{}': a face is shared by more than two elements (element {})", mesh.source,
                 mesh.blocks[A.block].tag[A.local_elem]);
    const bool joint = in.fracturable[A.elem] && in.fracturable[B.elem] && in.body[A.elem] == in.body[B.elem];
    if (joint) {
      jointed.emplace_back(A, B);
      for (Index n : A.key)
        if (n >= 0) touched[n] = 1;
    } else {
      for (Index n : A.key)
        if (n >= 0) {
          const std::size_t x = find(corner(A, n)), y = find(corner(B, n));
          if (x != y) parent[std::max(x, y)] = std::min(x, y);
        }
    }
    ++i;
  }
  // New nodes: per original node, one per incidence cluster, in incidence order.
  const Index nn_old = mesh.n_nodes();
  std::vector<std::vector<std::size_t>> node_inc(nn_old);
  for (std::size_t b = 0; b < mesh.blocks.size(); ++b)
    for (std::size_t k = 0; k < mesh.blocks[b].conn.size(); ++k)
      node_inc[mesh.blocks[b].conn[k]].push_back(inc0[b] + k);
  std::vector<Index> inc_node(n_inc, -1);
  std::vector<Real> x;
  std::vector<std::size_t> tags;
  std::vector<std::vector<Index>> copies(nn_old);
  std::map<std::size_t, Index> root_node;
  for (Index n = 0; n < nn_old; ++n) {
    root_node.clear();
    for (std::size_t i : node_inc[n]) {
      auto [it, fresh] = root_node.try_emplace(find(i), static_cast<Index>(tags.size()));
      if (fresh) {
        tags.push_back(mesh.node_tag[n]);
        for (int d = 0; d < 3; ++d) x.push_back(mesh.x[3 * n + d]);
        copies[n].push_back(it->second);
      }
      inc_node[i] = it->second;
    }
  }
  // Number the new nodes in the order the elements first use them: in a mesh with joints
  // everywhere each element then owns four (eight) consecutive nodes, and the element and
  // joint kernels read nodes that lie together in memory instead of scattered along the
  // original (gmsh) node order. Only storage moves: every node keeps its own forces and
  // every sum over a node's elements or joints keeps its order.
  {
    std::vector<Index> perm(tags.size(), -1);
    Index next = 0;
    for (std::size_t i = 0; i < n_inc; ++i)
      if (perm[inc_node[i]] < 0) perm[inc_node[i]] = next++;
    std::vector<Real> xp(x.size());
    std::vector<std::size_t> tp(tags.size());
    for (std::size_t o = 0; o < tags.size(); ++o) {
      tp[perm[o]] = tags[o];
      for (int d = 0; d < 3; ++d) xp[3 * static_cast<std::size_t>(perm[o]) + d] = x[3 * o + d];
    }
    x = std::move(xp), tags = std::move(tp);
    for (auto& i : inc_node) i = perm[i];
    for (auto& c : copies)
      for (auto& i : c) i = perm[i];
  }
  std::vector<std::vector<Index>> old_conn;
  for (std::size_t b = 0; b < mesh.blocks.size(); ++b) {
    old_conn.push_back(mesh.blocks[b].conn);
    for (std::size_t k = 0; k < mesh.blocks[b].conn.size(); ++k) mesh.blocks[b].conn[k] = inc_node[inc0[b] + k];
  }
  // Joints in element order (A is the lower element: faces sort by element within a key),
  // so that with elements in a spatial order (mesh/locality.hpp) neighbouring joints read
  // neighbouring nodes. Two elements share at most one face: the order is total.
  std::sort(jointed.begin(), jointed.end(), [](const auto& p, const auto& q) {
    return p.first.elem != q.first.elem ? p.first.elem < q.first.elem : p.second.elem < q.second.elem;
  });
  // Joints: side A as A's outward face, side B the same original nodes seen from B.
  for (const auto& [A, B] : jointed) {
    const auto& blkA = mesh.blocks[A.block];
    const auto& fl = cell_faces(blkA.type)[A.face];
    js.npf.push_back(static_cast<int>(fl.size()));
    std::array<Index, 4> a{-1, -1, -1, -1}, bb{-1, -1, -1, -1};
    Vec3 p[4];
    for (std::size_t k = 0; k < fl.size(); ++k) {
      const std::size_t ia = inc0[A.block] + static_cast<std::size_t>(A.local_elem) * blkA.npe() + fl[k];
      const Index orig = old_conn[A.block][static_cast<std::size_t>(A.local_elem) * blkA.npe() + fl[k]];
      a[k] = inc_node[ia];
      // the corner of B at the same original node
      const auto& blkB = mesh.blocks[B.block];
      for (int i = 0; i < blkB.npe(); ++i)
        if (old_conn[B.block][static_cast<std::size_t>(B.local_elem) * blkB.npe() + i] == orig)
          bb[k] = inc_node[inc0[B.block] + static_cast<std::size_t>(B.local_elem) * blkB.npe() + i];
      p[k] = node_pos(mesh.x, orig);
    }
    js.a.insert(js.a.end(), a.begin(), a.end());
    js.b.insert(js.b.end(), bb.begin(), bb.end());
    js.ea.push_back(A.elem);
    js.eb.push_back(B.elem);
    Vec3 area = Vec3::Zero();
    for (std::size_t k = 1; k + 1 < fl.size(); ++k) area += 0.5 * (p[k] - p[0]).cross(p[k + 1] - p[0]);
    js.area0.push_back(area.norm());
  }
  // Groups: a node stands for all its copies; a boundary face for the copies of the one
  // element that owns it.
  for (auto& g : mesh.groups) {
    std::vector<Index> nodes;
    for (Index n : g.nodes) nodes.insert(nodes.end(), copies[n].begin(), copies[n].end());
    std::sort(nodes.begin(), nodes.end());
    g.nodes = std::move(nodes);
    bool unmatched = false;
    auto remap_faces = [&](std::vector<Index>& f, int npf) {
      for (std::size_t i = 0; i < f.size(); i += static_cast<std::size_t>(npf)) {
        FaceRef probe;
        probe.key.fill(-1);
        for (int k = 0; k < npf; ++k) probe.key[k] = f[i + k];
        std::sort(probe.key.begin(), probe.key.begin() + npf);
        auto it = std::lower_bound(faces.begin(), faces.end(), probe,
                                   [](const FaceRef& x, const FaceRef& y) { return x.key < y.key; });
        if (it == faces.end() || it->key != probe.key) {  // not a cell face: cannot be remapped
          unmatched = true;
          continue;
        }
        const auto& blk = mesh.blocks[it->block];
        for (int k = 0; k < npf; ++k)
          for (int c = 0; c < blk.npe(); ++c)
            if (old_conn[it->block][static_cast<std::size_t>(it->local_elem) * blk.npe() + c] == f[i + k]) {
              f[i + k] = blk.conn[static_cast<std::size_t>(it->local_elem) * blk.npe() + c];
              break;
            }
      }
    };
    remap_faces(g.tri, 3);
    remap_faces(g.quad, 4);
    if (unmatched && report) report->unmatched_face_groups.push_back(g.name);
  }
  if (report) {
    report->joints = js.size();
    report->tri = static_cast<Index>(std::count(js.npf.begin(), js.npf.end(), 3));
    report->quad = report->joints - report->tri;
    report->nodes_before = nn_old;
    report->nodes_after = static_cast<Index>(tags.size());
    report->copies = copies;
    for (Index n = 0; n < nn_old; ++n) report->split_without_joint += copies[n].size() > 1 && !touched[n];
  }
  mesh.x = std::move(x);
  mesh.node_tag = std::move(tags);
  js.lean.assign(4 * static_cast<std::size_t>(js.size()), LeanPoint{});
  js.full.assign(4 * static_cast<std::size_t>(js.size()), 0);
  js.state.assign(4 * static_cast<std::size_t>(js.size()), CohesiveState{});
  js.status.assign(js.size(), JointStatus::Intact);
  js.released.assign(js.size(), 0);
  return js;
}

}  // namespace dspdem::joint
