#include "fem/fem_model.hpp"

#include <algorithm>

#include "core/chunked_sum.hpp"
#include "core/error.hpp"
#include "fem/hex8.hpp"
#include "fem/tet4.hpp"

namespace dspdem {

FemModel build_fem_model(const Mesh& mesh, const std::vector<Material>& materials, const std::vector<Index>& material,
                         const std::vector<Index>& body, const std::vector<Kinematics>& body_kin) {
  FemModel m;
  m.n_nodes = mesh.n_nodes();
  m.n_elements = mesh.n_elements();
  m.x0 = mesh.x;
  m.mass.assign(m.n_nodes, 0.0);
  m.node_alpha.assign(m.n_nodes, 0.0);
  m.elem_material = material;
  m.elem_body = body;
  DSPDEM_CHECK(static_cast<Index>(material.size()) == m.n_elements && static_cast<Index>(body.size()) == m.n_elements,
               "internal: element assignment has the wrong size");
  std::vector<Real> alpha_mass(m.n_nodes, 0.0);  // sum of alpha * mass, for a mass-weighted nodal alpha

  Index gid = 0;
  std::size_t slot = 0;
  for (const auto& mblk : mesh.blocks) {
    const int npe = mblk.npe();
    for (Kinematics kin : {Kinematics::Corotational, Kinematics::SmallStrain, Kinematics::Rigid}) {
      FemBlock fb;
      fb.type = mblk.type;
      fb.kin = kin;
      fb.slot0 = slot;
      for (Index e = 0; e < mblk.size(); ++e) {
        const Index g = gid + e;
        if (body_kin[body[g]] != kin) continue;
        const Material& mat = materials[material[g]];
        const LinearElastic el = LinearElastic::from_E_nu(mat.E, mat.nu);
        const Index* c = &mblk.conn[static_cast<std::size_t>(e) * npe];
        fb.elem.push_back(g);
        fb.conn.insert(fb.conn.end(), c, c + npe);
        fb.lambda.push_back(el.lambda);
        fb.mu.push_back(el.mu);
        fb.beta.push_back(mat.beta);
        fb.damped = fb.damped || mat.beta > 0;
        if (mblk.type == CellType::Tet4) {
          tet4::Coords X;
          for (int i = 0; i < 4; ++i) X.col(i) = node_pos(mesh.x, c[i]);
          tet4::Grad b;
          Real v;
          tet4::gradients(X, b, v);
          fb.grad.insert(fb.grad.end(), b.data(), b.data() + 12);
          fb.vol.push_back(v);
          for (int i = 0; i < 4; ++i) {
            m.mass[c[i]] += mat.density * v / 4.0;
            alpha_mass[c[i]] += mat.alpha * mat.density * v / 4.0;
          }
        } else {
          hex8::Coords X;
          for (int i = 0; i < 8; ++i) X.col(i) = node_pos(mesh.x, c[i]);
          const hex8::Reference r = hex8::setup(X, el);
          fb.grad.insert(fb.grad.end(), r.b.data(), r.b.data() + 24);
          fb.vol.push_back(r.volume);
          fb.gamma.insert(fb.gamma.end(), r.gamma.data(), r.gamma.data() + 32);
          fb.khg.insert(fb.khg.end(), r.k_hg.data(), r.k_hg.data() + 144);
          for (int i = 0; i < 8; ++i) {
            const Real mi = mat.density * r.volume * r.mass_fraction(i);
            m.mass[c[i]] += mi;
            alpha_mass[c[i]] += mat.alpha * mi;
          }
        }
      }
      slot += static_cast<std::size_t>(fb.size()) * npe * 3;
      m.any_stiffness_damping = m.any_stiffness_damping || fb.damped;
      if (fb.size() > 0) m.blocks.push_back(std::move(fb));
    }
    for (Index e = 0; e < mblk.size(); ++e) m.elem_tag.push_back(mblk.tag[e]);
    gid += mblk.size();
  }
  for (Index n = 0; n < m.n_nodes; ++n) {
    DSPDEM_CHECK(m.mass[n] > 0, "mesh '{}': node {} has no mass (not attached to any element)", mesh.source,
                 mesh.node_tag[n]);
    m.node_alpha[n] = alpha_mass[n] / m.mass[n];
  }

  // CSR gather lists in element order: fixed summation order per node.
  m.node_ptr.assign(m.n_nodes + 1, 0);
  for (const auto& b : m.blocks)
    for (Index c : b.conn) ++m.node_ptr[c + 1];
  for (Index n = 0; n < m.n_nodes; ++n) m.node_ptr[n + 1] += m.node_ptr[n];
  m.node_slot.resize(m.node_ptr.back());
  std::vector<Index> fill(m.node_ptr.begin(), m.node_ptr.end() - 1);
  for (const auto& b : m.blocks) {
    const int npe = b.npe();
    for (Index e = 0; e < b.size(); ++e)
      for (int i = 0; i < npe; ++i)
        m.node_slot[fill[b.conn[static_cast<std::size_t>(e) * npe + i]]++] =
            static_cast<Index>(b.slot0 + (static_cast<std::size_t>(e) * npe + i) * 3);
  }
  m.slots.assign(slot, 0.0);
  m.elem_energy.assign(m.n_elements, 0.0);
  m.elem_dpower.assign(m.n_elements, 0.0);
  return m;
}

ForceStatus internal_forces(FemModel& m, const Real* x, const Real* v, Real* f, Real* stress) {
  const ForceStatus st = element_forces(m, x, v, stress, {});
  gather_forces(m, f);
  return st;
}

ForceStatus element_forces(FemModel& m, const Real* x, const Real* v, Real* stress, ElementPass pass) {
  ForceStatus st;
  for (const auto& b : m.blocks) {
    if (b.kin == Kinematics::Rigid) {  // no strain: its slots stay zero, its stress is zero
      if (stress)
        for (Index g : b.elem)
          if (pass.takes(g))
            std::fill(stress + 6 * static_cast<std::size_t>(g), stress + 6 * (g + std::size_t{1}), 0.0);
      continue;
    }
    const ForceStatus s =
        b.type == CellType::Tet4 ? tet4_forces(m, b, x, v, stress, pass) : hex8_forces(m, b, x, v, stress, pass);
    if (s.inverted_element >= 0 && (st.inverted_element < 0 || s.min_detF < st.min_detF)) st = s;
  }
  return st;
}

void gather_forces(const FemModel& m, Real* f) {
  const Index n = m.n_nodes;
  const Index* ptr = m.node_ptr.data();
  const Index* sl = m.node_slot.data();
  const Real* s = m.slots.data();
#pragma omp parallel for schedule(static) if (n > 2048)
  for (Index i = 0; i < n; ++i) {
    Real fx = 0, fy = 0, fz = 0;
    for (Index k = ptr[i]; k < ptr[i + 1]; ++k) {
      const Real* p = s + sl[k];
      fx += p[0], fy += p[1], fz += p[2];
    }
    f[3 * i] = fx, f[3 * i + 1] = fy, f[3 * i + 2] = fz;
  }
}

Real deterministic_sum(const std::vector<Real>& a) {
  return chunked_sums<1>(
      a.size(),
      [&](std::size_t b, std::size_t e) {
        Real s = 0;
        for (std::size_t i = b; i < e; ++i) s += a[i];
        return std::array<Real, 1>{s};
      },
      4096)[0];
}

}  // namespace dspdem
