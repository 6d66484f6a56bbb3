#include "par/subdomain.hpp"

#include <algorithm>

#include "core/error.hpp"

namespace dspdem::par {

namespace {
// Per-joint arrays of `per` values each, the kept joints' in their order.
template <class T>
std::vector<T> pick(const std::vector<T>& a, const std::vector<Index>& keep, std::size_t per) {
  if (a.empty()) return {};
  std::vector<T> out;
  out.reserve(keep.size() * per);
  for (Index j : keep)
    for (std::size_t k = 0; k < per; ++k) out.push_back(a[per * static_cast<std::size_t>(j) + k]);
  return out;
}
}  // namespace

Subdomain make_subdomain(const Model& g, const std::vector<int>& part, int r) {
  const Mesh& gm = g.mesh;
  const Index nn = gm.n_nodes(), ne = gm.n_elements();
  DSPDEM_CHECK(static_cast<Index>(part.size()) == ne, "internal: a partition of {} elements for a model of {}",
               part.size(), ne);
  DSPDEM_CHECK(g.rigid.empty() && g.joints.closed.empty(),
               "internal: make_subdomain on a model with rigid bodies or closed joints");
  std::vector<Index> block_off;
  {
    Index off = 0;
    for (const auto& b : gm.blocks) block_off.push_back(off), off += b.size();
  }
  auto each_element = [&](auto&& fn) {
    for (std::size_t b = 0; b < gm.blocks.size(); ++b) {
      const ElementBlock& blk = gm.blocks[b];
      for (Index e = 0; e < blk.size(); ++e)
        fn(block_off[b] + e, &blk.conn[static_cast<std::size_t>(e) * blk.npe()], blk.npe());
    }
  };
  // A node's owner: the process of the first element using it.
  std::vector<int> owner(static_cast<std::size_t>(nn), 0);
  std::vector<char> seen(static_cast<std::size_t>(nn), 0);
  each_element([&](Index e, const Index* c, int npe) {
    for (int i = 0; i < npe; ++i)
      if (!seen[c[i]]) seen[c[i]] = 1, owner[c[i]] = part[e];
  });
  // Elements here: own ones, those touching an own node, and those across a joint that
  // touches an own node (their nodes feed the joint).
  std::vector<char> here(static_cast<std::size_t>(ne), 0);
  each_element([&](Index e, const Index* c, int npe) {
    bool h = part[e] == r;
    for (int i = 0; i < npe && !h; ++i) h = owner[c[i]] == r;
    here[e] = h;
  });
  const joint::JointSet& gj = g.joints;
  Subdomain sd;
  for (Index j = 0; j < gj.size(); ++j) {
    bool touch = false;
    for (int k = 0; k < gj.npf[j] && !touch; ++k) touch = owner[gj.a[4 * j + k]] == r || owner[gj.b[4 * j + k]] == r;
    if (!touch) continue;
    sd.joint_global.push_back(j);
    here[gj.ea[j]] = here[gj.eb[j]] = 1;
  }
  std::vector<char> node_here(static_cast<std::size_t>(nn), 0);
  each_element([&](Index e, const Index* c, int npe) {
    if (here[e])
      for (int i = 0; i < npe; ++i) node_here[c[i]] = 1;
  });
  // Own nodes first, then the ghosts, each in global order.
  std::vector<Index> g2l(static_cast<std::size_t>(nn), -1);
  for (int pass = 0; pass < 2; ++pass)
    for (Index n = 0; n < nn; ++n)
      if (node_here[n] && (owner[n] == r) == (pass == 0)) {
        g2l[n] = static_cast<Index>(sd.node_global.size());
        sd.node_global.push_back(n);
        if (pass == 1) sd.ghost_owner.push_back(owner[n]);
      }
  Model& m = sd.local;
  m.owned_nodes = static_cast<Index>(sd.node_global.size() - sd.ghost_owner.size());

  // The mesh: blocks keep their places (groups list elements per block), elements their order.
  Mesh& lm = m.mesh;
  lm.source = gm.source;
  for (Index n : sd.node_global) {
    for (int d = 0; d < 3; ++d) lm.x.push_back(gm.x[3 * static_cast<std::size_t>(n) + d]);
    lm.node_tag.push_back(gm.node_tag[n]);
  }
  std::vector<Index> e2l(static_cast<std::size_t>(ne), -1);
  std::vector<Index> local_off;
  for (std::size_t b = 0; b < gm.blocks.size(); ++b) {
    const ElementBlock& gb = gm.blocks[b];
    ElementBlock lb;
    lb.type = gb.type;
    local_off.push_back(static_cast<Index>(sd.elem_global.size()));
    for (Index e = 0; e < gb.size(); ++e) {
      const Index ge = block_off[b] + e;
      if (!here[ge]) continue;
      e2l[ge] = static_cast<Index>(sd.elem_global.size());
      sd.elem_global.push_back(ge);
      sd.elem_owner.push_back(part[ge]);
      for (int i = 0; i < gb.npe(); ++i) lb.conn.push_back(g2l[gb.conn[static_cast<std::size_t>(e) * gb.npe() + i]]);
      lb.tag.push_back(gb.tag[e]);
    }
    lm.blocks.push_back(std::move(lb));
  }
  for (const Group& gg : gm.groups) {
    Group lg;
    lg.name = gg.name, lg.dim = gg.dim;
    for (Index n : gg.nodes)
      if (g2l[n] >= 0) lg.nodes.push_back(g2l[n]);
    std::sort(lg.nodes.begin(), lg.nodes.end());
    lg.elements.resize(gg.elements.size());
    for (std::size_t b = 0; b < gg.elements.size(); ++b)
      for (Index e : gg.elements[b])
        if (const Index l = e2l[block_off[b] + e]; l >= 0) lg.elements[b].push_back(l - local_off[b]);
    auto faces = [&](const std::vector<Index>& in, int k, std::vector<Index>& out) {
      for (std::size_t f = 0; f + k <= in.size(); f += k) {
        bool all = true;
        for (int i = 0; i < k; ++i) all = all && g2l[in[f + i]] >= 0;
        if (all)
          for (int i = 0; i < k; ++i) out.push_back(g2l[in[f + i]]);
      }
    };
    faces(gg.tri, 3, lg.tri);
    faces(gg.quad, 4, lg.quad);
    lm.groups.push_back(std::move(lg));
  }

  // Elements: built again on the share (their reference data are per element); the nodal
  // masses are the whole model's, so a ghost moves with its true mass.
  m.materials = g.materials;
  m.gravity = g.gravity;
  m.body_names = g.body_names;
  std::vector<Kinematics> body_kin(g.body_names.size(), Kinematics::Corotational);
  for (const auto& b : g.fem.blocks)
    for (Index e : b.elem) body_kin[g.fem.elem_body[e]] = b.kin;
  std::vector<Index> mat, body;
  for (Index ge : sd.elem_global) mat.push_back(g.fem.elem_material[ge]), body.push_back(g.fem.elem_body[ge]);
  m.fem = build_fem_model(lm, m.materials, mat, body, body_kin);
  for (std::size_t l = 0; l < sd.node_global.size(); ++l) {
    m.fem.mass[l] = g.fem.mass[sd.node_global[l]];
    m.fem.node_alpha[l] = g.fem.node_alpha[sd.node_global[l]];
  }
  m.elem_owned.resize(sd.elem_global.size());
  for (std::size_t l = 0; l < sd.elem_global.size(); ++l) m.elem_owned[l] = part[sd.elem_global[l]] == r;

  // Joints: their state and parameters as they are, nodes and elements renumbered.
  joint::JointSet& lj = m.joints;
  const auto& keep = sd.joint_global;
  lj.npf = pick(gj.npf, keep, 1);
  lj.a = pick(gj.a, keep, 4), lj.b = pick(gj.b, keep, 4);
  for (auto* v : {&lj.a, &lj.b})
    for (Index& n : *v)
      if (n >= 0) n = g2l[n];
  lj.ea = pick(gj.ea, keep, 1), lj.eb = pick(gj.eb, keep, 1);
  for (auto* v : {&lj.ea, &lj.eb})
    for (Index& e : *v) e = e2l[e];
  lj.area0 = pick(gj.area0, keep, 1);
  lj.param = pick(gj.param, keep, 1);
  lj.params = gj.params, lj.quadrature = gj.quadrature;
  lj.lean = pick(gj.lean, keep, 4), lj.full = pick(gj.full, keep, 4), lj.state = pick(gj.state, keep, 4);
  lj.status = pick(gj.status, keep, 1);
  lj.released = pick(gj.released, keep, 1);
  lj.offset = pick(gj.offset, keep, 16);
  DSPDEM_CHECK(gj.failed.empty() && gj.released_energy == 0, "internal: make_subdomain on a model already run");
  m.joint_owned.resize(keep.size());
  for (std::size_t l = 0; l < keep.size(); ++l)
    m.joint_owned[l] = owner[gj.a[4 * static_cast<std::size_t>(keep[l])]] == r;
  m.joint_report = g.joint_report;
  if (g.contact.enabled()) {
    contact::ContactSystem::ShareMap map;
    map.node_global = sd.node_global, map.elem_global = sd.elem_global, map.elem_owner = sd.elem_owner;
    map.own_nodes = m.owned_nodes, map.joint_owned = m.joint_owned, map.rank = r;
    m.contact.take_share(g.contact, map);
  }

  // Boundary conditions and initial velocities of the nodes here (ghosts too: they are
  // overwritten each step, but a constrained ghost must not drift meanwhile).
  auto dof = [&](Index gdof) { return g2l[gdof / 3] < 0 ? -1 : 3 * g2l[gdof / 3] + gdof % 3; };
  for (const Constraint& c : g.constraints)
    if (const Index d = dof(c.dof); d >= 0) m.constraints.push_back({d, c.value, c.ramp});
  for (const NodalLoad& l : g.loads)
    if (const Index d = dof(l.dof); d >= 0) m.loads.push_back({d, l.value, l.ramp});
  m.v0.resize(3 * sd.node_global.size());
  for (std::size_t l = 0; l < sd.node_global.size(); ++l)
    for (int d = 0; d < 3; ++d) m.v0[3 * l + d] = g.v0[3 * static_cast<std::size_t>(sd.node_global[l]) + d];
  // Monitors over the own nodes only: each node is counted once over the processes.
  for (const MonitorSet& gs : g.monitors) {
    MonitorSet ls;
    ls.cfg = gs.cfg;
    auto own = [&](const std::vector<Index>& nodes, std::vector<Index>& out) {
      for (Index n : nodes)
        if (g2l[n] >= 0 && g2l[n] < m.owned_nodes) out.push_back(g2l[n]);
    };
    own(gs.nodes, ls.nodes);
    own(gs.nodes2, ls.nodes2);
    if (!gs.joint_in.empty()) {  // each joint counted by the process that owns it
      ls.joint_in.resize(keep.size());
      for (std::size_t l = 0; l < keep.size(); ++l) ls.joint_in[l] = gs.joint_in[keep[l]] && m.joint_owned[l];
    }
    if (!gs.dof_in_group.empty()) {
      ls.dof_in_group.assign(3 * sd.node_global.size(), 0);
      for (Index l = 0; l < m.owned_nodes; ++l)
        for (int d = 0; d < 3; ++d) ls.dof_in_group[3 * l + d] = gs.dof_in_group[3 * sd.node_global[l] + d];
    }
    m.monitors.push_back(std::move(ls));
  }
  return sd;
}

}  // namespace dspdem::par
