#include "io/model_builder.hpp"

#include <algorithm>
#include <cmath>
#include <map>
#include <set>

#include "core/error.hpp"
#include "core/log.hpp"

namespace dspdem {

namespace {
const Group& need_group(const Mesh& mesh, const std::string& name, const std::string& where) {
  const Group* g = mesh.find_group(name);
  if (!g)
    fail("{}: group '{}' is not a physical group of mesh '{}' (groups: {})", where, name, mesh.source,
         mesh.group_names());
  if (g->nodes.empty()) fail("{}: group '{}' of mesh '{}' has no nodes", where, name, mesh.source);
  return *g;
}

// Nodal weights that spread a total force over a group: by tributary area on surface
// groups (a uniform traction), equally over nodes otherwise.
std::vector<std::pair<Index, Real>> load_weights(const Mesh& mesh, const Group& g) {
  std::map<Index, Real> w;
  Real total = 0;
  auto add_face = [&](const Index* c, int n) {
    Vec3 area = Vec3::Zero();
    const Vec3 p0 = node_pos(mesh.x, c[0]);
    for (int i = 1; i + 1 < n; ++i) area += 0.5 * (node_pos(mesh.x, c[i]) - p0).cross(node_pos(mesh.x, c[i + 1]) - p0);
    const Real a = area.norm();
    for (int i = 0; i < n; ++i) w[c[i]] += a / n;
    total += a;
  };
  for (std::size_t i = 0; i < g.tri.size(); i += 3) add_face(&g.tri[i], 3);
  for (std::size_t i = 0; i < g.quad.size(); i += 4) add_face(&g.quad[i], 4);
  std::vector<std::pair<Index, Real>> out;
  if (total > 0) {
    for (auto [n, a] : w) out.emplace_back(n, a / total);
  } else {
    for (Index n : g.nodes) out.emplace_back(n, 1.0 / static_cast<Real>(g.nodes.size()));
  }
  return out;
}
}  // namespace

namespace {
// One rigid motion per body with kinematics = "rigid" (per part when the body is split into
// its connected components). A node may be shared with a deformable body (the two are then
// bonded there) but not with another rigid body, and no boundary condition may hold it: a
// rigid body moves freely (hold one with a fixed [[walls]] instead).
void build_rigid_bodies(const CaseConfig& c, Model& m) {
  std::map<Index, std::set<Index>> nodes_of;
  for (const auto& b : m.fem.blocks)
    if (b.kin == Kinematics::Rigid)
      for (Index e = 0; e < b.size(); ++e)
        for (int i = 0; i < b.npe(); ++i)
          nodes_of[m.fem.elem_body[b.elem[e]]].insert(b.conn[static_cast<std::size_t>(e) * b.npe() + i]);
  if (nodes_of.empty()) return;
  std::vector<Index> owner(m.fem.n_nodes, -1);
  for (const auto& [bi, ns] : nodes_of)
    for (Index n : ns) {
      if (owner[n] >= 0)
        fail("{}: rigid bodies '{}' and '{}' share node {}: give them separate meshes", c.path, m.body_names[owner[n]],
             m.body_names[bi], m.mesh.node_tag[n]);
      owner[n] = bi;
    }
  for (const auto& bc : c.boundaries) {
    if (bc.type == BoundaryConfig::Type::Force) continue;
    for (Index n : need_group(m.mesh, bc.group, bc.where).nodes)
      if (owner[n] >= 0)
        fail(
            "{}: [[boundary]] on group '{}' holds node {} of rigid body '{}'; a rigid body moves freely (hold it with "
            "a fixed [[walls]], or make it deformable)",
            bc.where, bc.group, m.mesh.node_tag[n], m.body_names[owner[n]]);
  }
  for (const auto& [bi, ns] : nodes_of) {
    m.rigid.push_back(
        make_rigid_body(m.body_names[bi], std::vector<Index>(ns.begin(), ns.end()), m.fem.x0, m.fem.mass, m.v0));
    rigid_set_velocities(m.rigid.back(), m.fem.x0.data(), m.v0.data());
  }
}
}  // namespace

Model build_model(const CaseConfig& c, Mesh mesh) {
  Model m;
  m.mesh = std::move(mesh);
  m.materials = c.materials;
  m.gravity = c.gravity;
  const Mesh& me = m.mesh;

  // Element -> body and material.
  const Index ne = me.n_elements();
  std::vector<Index> body(ne, -1), material(ne, -1);
  std::vector<Kinematics> body_kin;
  std::vector<Index> block_offset;
  {
    Index off = 0;
    for (const auto& b : me.blocks) block_offset.push_back(off), off += b.size();
  }
  for (std::size_t bi = 0; bi < c.bodies.size(); ++bi) {
    const BodyConfig& bc = c.bodies[bi];
    m.body_names.push_back(bc.name);
    body_kin.push_back(bc.kinematics);
    Index mat = 0;
    for (std::size_t k = 0; k < c.materials.size(); ++k)
      if (c.materials[k].name == bc.material) mat = static_cast<Index>(k);
    for (const auto& gname : bc.groups) {
      const Group* g = me.find_group(gname);
      const std::string where = fmt::format("{}: [[bodies]] '{}'", c.path, bc.name);
      if (!g)
        fail("{}: group '{}' is not a physical group of mesh '{}' (groups: {})", where, gname, me.source,
             me.group_names());
      if (g->dim != 3)
        fail("{}: group '{}' has dimension {}; bodies are made of volume (3D) groups", where, gname, g->dim);
      for (std::size_t b = 0; b < g->elements.size(); ++b)
        for (Index e : g->elements[b]) {
          const Index gid = block_offset[b] + e;
          if (body[gid] >= 0 && body[gid] != static_cast<Index>(bi))
            fail("{}: element {} is in body '{}' and in body '{}'", where, me.blocks[b].tag[e],
                 c.bodies[body[gid]].name, bc.name);
          body[gid] = static_cast<Index>(bi);
          material[gid] = mat;
        }
    }
  }
  Index orphans = 0;
  std::size_t first_orphan = 0;
  for (std::size_t b = 0; b < me.blocks.size(); ++b)
    for (Index e = 0; e < me.blocks[b].size(); ++e)
      if (body[block_offset[b] + e] < 0 && orphans++ == 0) first_orphan = me.blocks[b].tag[e];
  if (orphans > 0)
    fail(
        "{}: {} element(s) of mesh '{}' belong to no body (first: element {}); list their volume groups in [[bodies]] "
        "groups",
        c.path, orphans, me.source, first_orphan);

  const std::vector<Index> cfg_body = body;  // before splitting into components
  // Split bodies into connected components where asked (e.g. one body per particle).
  for (std::size_t bi = 0; bi < c.bodies.size(); ++bi) {
    if (!c.bodies[bi].split_components) continue;
    std::vector<Index> parent(me.n_nodes());
    for (Index n = 0; n < me.n_nodes(); ++n) parent[n] = n;
    auto find = [&](Index a) {
      while (parent[a] != a) a = parent[a] = parent[parent[a]];
      return a;
    };
    auto each_element = [&](auto&& fn) {
      for (std::size_t b = 0; b < me.blocks.size(); ++b)
        for (Index e = 0; e < me.blocks[b].size(); ++e)
          if (body[block_offset[b] + e] == static_cast<Index>(bi)) fn(me.blocks[b], block_offset[b] + e, e);
    };
    each_element([&](const ElementBlock& blk, Index, Index e) {
      const Index* cn = &blk.conn[static_cast<std::size_t>(e) * blk.npe()];
      for (int i = 1; i < blk.npe(); ++i) parent[find(cn[i])] = find(cn[0]);
    });
    std::map<Index, Index> component_body;  // root node -> body id, numbered in element order
    Index k = 0;
    each_element([&](const ElementBlock& blk, Index gid, Index e) {
      const Index root = find(blk.conn[static_cast<std::size_t>(e) * blk.npe()]);
      auto [it, inserted] = component_body.try_emplace(root, -1);
      if (inserted) {
        if (k == 0) {
          it->second = static_cast<Index>(bi);  // the first component keeps the body's slot
          m.body_names[bi] = c.bodies[bi].name + "#0";
        } else {
          it->second = static_cast<Index>(m.body_names.size());
          m.body_names.push_back(c.bodies[bi].name + "#" + std::to_string(k));
          body_kin.push_back(c.bodies[bi].kinematics);
        }
        ++k;
      }
      body[gid] = it->second;
    });
  }

  // Force conditions are spread over the original mesh (its surface faces are exact); after
  // joint insertion each node's share is split equally among its copies.
  std::vector<std::vector<std::pair<Index, Real>>> force_weights(c.boundaries.size());
  for (std::size_t i = 0; i < c.boundaries.size(); ++i)
    if (c.boundaries[i].type == BoundaryConfig::Type::Force)
      force_weights[i] = load_weights(me, need_group(me, c.boundaries[i].group, c.boundaries[i].where));

  // Calls fn(element) for every element of the named volume groups of body bi; a name that is
  // not a volume group, or a group reaching into another body, is an error naming the key.
  auto for_body_groups = [&](std::size_t bi, const std::vector<std::string>& names, const char* key, auto&& fn) {
    const std::string where = fmt::format("{}: [[bodies]] '{}' {}", c.path, c.bodies[bi].name, key);
    for (const auto& gname : names) {
      const Group* g = me.find_group(gname);
      if (!g || g->dim != 3)
        fail("{}: '{}' is not a volume group of mesh '{}' (groups: {})", where, gname, me.source, me.group_names());
      for (std::size_t b = 0; b < g->elements.size(); ++b)
        for (Index e : g->elements[b]) {
          const Index gid = block_offset[b] + e;
          if (cfg_body[gid] != static_cast<Index>(bi))
            fail("{}: group '{}' holds element {} of another body", where, gname, me.blocks[b].tag[e]);
          fn(gid);
        }
    }
  };
  // Cohesive joints on the faces of fracturable bodies (node duplication).
  {
    joint::InsertionInput in;
    in.fracturable.assign(ne, 0);
    in.body = cfg_body;
    bool any = false;
    for (std::size_t bi = 0; bi < c.bodies.size(); ++bi) {
      const BodyConfig& bc = c.bodies[bi];
      if (bc.fracture == BodyConfig::Fracture::None) continue;
      any = true;
      if (bc.fracture == BodyConfig::Fracture::All) {
        for (Index g = 0; g < ne; ++g)
          if (cfg_body[g] == static_cast<Index>(bi)) in.fracturable[g] = 1;
        continue;
      }
      for_body_groups(bi, bc.fracture_groups, "fracture_groups", [&](Index gid) { in.fracturable[gid] = 1; });
    }
    // Joint zones: elements whose joints (with another element of the same zone) take the
    // zone material's joint parameters; from volume groups, or by centroid from a box.
    std::vector<Index> zone(ne, -1);
    for (std::size_t bi = 0; bi < c.bodies.size(); ++bi) {
      const BodyConfig& bc = c.bodies[bi];
      if (bc.zone_groups.empty() && !bc.zone_box) continue;
      Index zm = 0;
      while (c.materials[zm].name != bc.zone_material) ++zm;  // checked by the case reader
      for_body_groups(bi, bc.zone_groups, "zone_groups", [&](Index gid) { zone[gid] = zm; });
      if (!bc.zone_box) continue;
      Index in_box = 0;
      const auto& box = *bc.zone_box;
      for (std::size_t b = 0; b < me.blocks.size(); ++b) {
        for (Index e = 0; e < me.blocks[b].size(); ++e) {
          const Index gid = block_offset[b] + e;
          if (cfg_body[gid] != static_cast<Index>(bi)) continue;
          const Vec3 centroid = element_centroid(me, me.blocks[b], e);
          if (box.contains(centroid)) zone[gid] = zm, ++in_box;
        }
      }
      DSPDEM_CHECK(in_box > 0,
                   "{}: [[bodies]] '{}': the zone box from zone_box_min [{:g}, {:g}, {:g}] to zone_box_max [{:g}, "
                   "{:g}, {:g}] holds no element centroid of the body",
                   c.path, bc.name, box.min().x(), box.min().y(), box.min().z(), box.max().x(), box.max().y(),
                   box.max().z());
    }
    if (any) {
      m.joints = joint::insert_joints(m.mesh, in, &m.joint_report);
      // Loads on surfaces whose faces are element faces are spread again by area over the
      // copies that own those faces; otherwise each node's share is split among its copies.
      for (std::size_t bi = 0; bi < c.boundaries.size(); ++bi) {
        auto& fw = force_weights[bi];
        if (fw.empty()) continue;
        const Group& g = need_group(me, c.boundaries[bi].group, c.boundaries[bi].where);
        const auto& um = m.joint_report.unmatched_face_groups;
        if ((!g.tri.empty() || !g.quad.empty()) && std::find(um.begin(), um.end(), g.name) == um.end()) {
          fw = load_weights(me, g);
          continue;
        }
        std::vector<std::pair<Index, Real>> split;
        for (auto [n, w] : fw) {
          const auto& cp = m.joint_report.copies[n];
          for (Index k : cp) split.emplace_back(k, w / static_cast<Real>(cp.size()));
        }
        fw = std::move(split);
      }
      // Penalty stiffness from the two elements' heights over the face.
      std::vector<Real> vol(ne);
      for (std::size_t b = 0; b < me.blocks.size(); ++b)
        for (Index e = 0; e < me.blocks[b].size(); ++e) vol[block_offset[b] + e] = element_volume(me, me.blocks[b], e);
      auto height = [&](Index g, Real area) {
        const bool tet = me.blocks[0].size() > g;  // block 0 holds the tets
        return (tet ? 3.0 : 1.0) * vol[g] / area;
      };
      joint::JointSet& js = m.joints;
      js.param.resize(js.size());
      m.zone_joints.assign(c.bodies.size(), 0);
      for (Index j = 0; j < js.size(); ++j) {
        const Index mat = material[js.ea[j]];
        const Index za = zone[js.ea[j]];
        const bool in_zone = za >= 0 && zone[js.eb[j]] == za;
        if (in_zone) ++m.zone_joints[cfg_body[js.ea[j]]];
        const JointMaterial& jm = c.joint_materials[in_zone ? za : mat];
        const Real h = 0.5 * (height(js.ea[j], js.area0[j]) + height(js.eb[j], js.area0[j]));
        joint::CohesiveParams p;
        p.kn = jm.kn > 0 ? jm.kn : jm.penalty * c.materials[mat].E / h;
        p.ks = jm.ks > 0 ? jm.ks : p.kn;
        p.ft = jm.ft, p.GfI = jm.GfI, p.c = jm.c, p.GfII = jm.GfII;
        p.tan_phi = std::tan(jm.phi_deg * M_PI / 180.0);
        p.law = jm.coupled    ? joint::JointLaw::Coupled
                : jm.mode_i   ? joint::JointLaw::ModeI
                : jm.residual ? joint::JointLaw::PaperResidual
                              : joint::JointLaw::Paper;
        p.energy_mixed_mode = jm.energy_mixed_mode;
        js.param[j] = static_cast<Index>(js.params.size());
        js.params.push_back(p);
        js.quadrature.push_back(jm.nodal_quadrature ? joint::Quadrature::Nodal : joint::Quadrature::Gauss);
      }
      // Extrinsic bodies: their joints start closed (joint/ties.hpp), with room for the
      // offsets their laws start from when they open.
      if (std::any_of(c.bodies.begin(), c.bodies.end(), [](const BodyConfig& b) { return b.extrinsic; })) {
        js.closed.assign(js.size(), 0);
        js.offset.assign(16 * static_cast<std::size_t>(js.size()), 0.0);
        for (Index j = 0; j < js.size(); ++j) js.closed[j] = c.bodies[cfg_body[js.ea[j]]].extrinsic;
      }
    }
  }

  m.fem = build_fem_model(me, m.materials, material, body, body_kin);

  if (c.contact.enabled) {
    std::vector<Real> elem_E(ne);
    for (Index e = 0; e < ne; ++e) elem_E[e] = c.materials[material[e]].E;
    std::vector<contact::Wall> walls;
    for (const auto& wc : c.walls) walls.push_back(wc.wall);
    m.contact.setup(me, m.joints, material, c.contact_materials, elem_E, m.fem.mass, walls, c.contact.settings);
    if (!m.contact.setup_error().empty())
      fail("{}: contact: {}; lower contact_radius or contact_radius_fraction of its material", c.path,
           m.contact.setup_error());
  }

  // Constraints: the last condition on a dof wins; say so when two disagree (a velocity over a
  // fixed edge's nodes changes the run, and nothing else would tell).
  std::map<Index, Constraint> cons;
  std::map<Index, std::size_t> set_by;                              // dof -> the [[boundary]] that set it
  std::map<std::pair<std::size_t, std::size_t>, Index> overridden;  // (earlier, later) -> dofs
  for (std::size_t bi = 0; bi < c.boundaries.size(); ++bi) {
    const BoundaryConfig& bc = c.boundaries[bi];
    const Group& g = need_group(me, bc.group, bc.where);
    if (bc.type == BoundaryConfig::Type::Force) {
      for (auto [n, w] : force_weights[bi])
        for (int d = 0; d < 3; ++d)
          if (bc.dof[d] && bc.value(d) != 0) m.loads.push_back({3 * n + d, w * bc.value(d), bc.ramp});
      continue;
    }
    const bool fixed = bc.type == BoundaryConfig::Type::Fixed;
    for (Index n : g.nodes)
      for (int d = 0; d < 3; ++d) {
        if (!bc.dof[d]) continue;
        const Constraint now{3 * n + d, fixed ? 0.0 : bc.value(d), fixed ? 0.0 : bc.ramp};
        // A ramp scales the value: two zero values are the same condition whatever their ramps.
        if (const auto it = cons.find(now.dof);
            it != cons.end() && (it->second.value != now.value || (now.value != 0 && it->second.ramp != now.ramp)))
          ++overridden[{set_by[now.dof], bi}];
        cons[now.dof] = now, set_by[now.dof] = bi;
      }
  }
  for (auto& [dof, con] : cons) m.constraints.push_back(con);
  for (const auto& [pair, count] : overridden)
    log::warn(
        "{}: sets {} node component(s) that {} also sets, to another velocity or ramp; the later condition "
        "holds there",
        c.boundaries[pair.second].where, count, c.boundaries[pair.first].where);

  m.v0.assign(3 * static_cast<std::size_t>(me.n_nodes()), 0.0);
  for (const auto& ic : c.initial) {
    const Group& g = need_group(me, ic.group, ic.where);
    for (Index n : g.nodes) {
      const Vec3 v = ic.velocity + ic.angular_velocity.cross(node_pos(me.x, n) - ic.center);
      for (int d = 0; d < 3; ++d) m.v0[3 * n + d] = v(d);
    }
  }
  build_rigid_bodies(c, m);
  for (const auto& mc : c.monitors) {
    MonitorSet ms;
    ms.cfg = mc;
    if (!mc.group.empty())
      ms.nodes = need_group(me, mc.group, mc.where).nodes;
    else if (!mc.counts_joints())
      for (Index n = 0; n < me.n_nodes(); ++n) ms.nodes.push_back(n);
    if (!mc.group2.empty()) ms.nodes2 = need_group(me, mc.group2, mc.where).nodes;
    if (mc.counts_joints()) {
      const joint::JointSet& js = m.joints;
      ms.joint_in.assign(js.size(), 0);
      Index in = 0;
      for (Index j = 0; j < js.size(); ++j) {
        Vec3 centroid = Vec3::Zero();
        for (int k = 0; k < js.npf[j]; ++k) centroid += node_pos(me.x, js.a[4 * static_cast<std::size_t>(j) + k]);
        centroid /= js.npf[j];
        if (!mc.box || mc.box->contains(centroid)) ms.joint_in[j] = 1, ++in;
      }
      // A count over no joints is zero whatever happens: a mistake, not a measurement.
      if (in == 0 && js.size() == 0)
        fail("{}: monitor '{}' counts broken joints, but the model has none (no body with fracture)", mc.where,
             mc.name);
      if (in == 0)
        fail(
            "{}: monitor '{}': the box from box_min [{:g}, {:g}, {:g}] to box_max [{:g}, {:g}, {:g}] holds no joint's "
            "face centroid (of {} joints)",
            mc.where, mc.name, mc.box->min().x(), mc.box->min().y(), mc.box->min().z(), mc.box->max().x(),
            mc.box->max().y(), mc.box->max().z(), js.size());
    }
    if (mc.type == MonitorConfig::Type::Reaction) {
      ms.dof_in_group.assign(3 * static_cast<std::size_t>(me.n_nodes()), 0);
      bool any = false;
      for (Index n : ms.nodes)
        for (int d = 0; d < 3; ++d)
          if (cons.count(3 * n + d)) ms.dof_in_group[3 * n + d] = 1, any = true;
      if (!any)
        fail("{}: reaction monitor '{}': group '{}' has no fixed or velocity-driven dofs", mc.where, mc.name, mc.group);
    }
    m.monitors.push_back(std::move(ms));
  }
  return m;
}

}  // namespace dspdem
