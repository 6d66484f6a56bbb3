// Contact between bodies and with walls (METHOD.md section 3): conservation in impacts,
// smooth hand-over between feature pairs, friction on an incline, resting stacks, and
// the Hertz contact time of a meshed sphere. Tolerances are stated per test.
#include <gtest/gtest.h>

#include <cmath>

#include "support/run_helpers.hpp"
#include "support/scene.hpp"

using namespace dspdem;
using namespace dspdem::testsupport;

namespace {
constexpr Real kE = 1e7, kNu = 0.25, kRho = 1000;

CaseConfig contact_case(Real mu = 0.0, Kinematics kin = Kinematics::Corotational) {
  CaseConfig c = simple_case(kE, kNu, kRho, kin);
  c.contact.enabled = true;
  contact::ContactMaterial cm;
  cm.friction = mu;
  c.contact_materials = {cm};
  return c;
}

InitialConfig initial(const std::string& group, const Vec3& v) {
  InitialConfig ic;
  ic.group = group;
  ic.velocity = v;
  return ic;
}

Vec3 momentum(const Model& m, const Integrator& it) {
  Vec3 p = Vec3::Zero();
  for (Index n = 0; n < m.fem.n_nodes; ++n) p += m.fem.mass[n] * node_pos(it.v(), n);
  return p;
}

Vec3 group_mean(const Model& m, const std::vector<Real>& a, const std::string& group) {
  const Group* g = m.mesh.find_group(group);
  Vec3 s = Vec3::Zero();
  for (Index n : g->nodes) s += node_pos(a, n);
  return s / static_cast<Real>(g->nodes.size());
}

Real mechanical(const Energy& e) { return e.kinetic + e.internal + e.contact_elastic; }
}  // namespace

TEST(Contact, TwoCubesHeadOnConserveMomentumAndEnergy) {
  // Two 0.1 m cubes (2x2x2 hex8) meet face to face at 2 x 1 m/s, undamped, frictionless.
  // Momentum: forces are equal, opposite and collinear, so it is conserved to round-off:
  // 1e-10 of sum m|v|. Energy: after separation, kinetic + strain energy (the cubes ring
  // after the impact, so kinetic energy alone is not conserved by the physics) within 1 %
  // of the initial kinetic energy; the penalty contact is conservative up to the time
  // discretisation.
  Mesh mesh;
  const Mesh c1 = cube(CellType::Hex8, 2, 0.1);
  const Vec3 cc(0.05, 0.05, 0.05);
  add_part(mesh, c1, "b0", cc, Vec3(-0.0525, 0, 0));
  add_part(mesh, c1, "b1", cc, Vec3(0.0525, 0, 0));
  CaseConfig c = contact_case();
  c.initial = {initial("b0", Vec3(1, 0, 0)), initial("b1", Vec3(-1, 0, 0))};
  Model m = build_model(c, mesh);
  const Real dt = 0.9 * critical_dt(m);
  Integrator it(m, dt);
  const Real e0 = it.energy().kinetic;
  Real scale = 0;
  for (Index n = 0; n < m.fem.n_nodes; ++n) scale += m.fem.mass[n] * node_pos(it.v(), n).norm();
  Real worst_p = 0;
  Index max_contacts = 0;
  while (it.time() < 0.01) {
    it.step();
    worst_p = std::max(worst_p, momentum(m, it).norm() / scale);
    max_contacts = std::max(max_contacts, m.contact.totals().contacts);
  }
  const Energy e = it.energy();
  const Real gap = group_mean(m, it.x(), "b1")(0) - group_mean(m, it.x(), "b0")(0);
  const Real separation_speed = group_mean(m, it.v(), "b1")(0) - group_mean(m, it.v(), "b0")(0);
  RecordProperty("momentum_error", sci(worst_p));
  RecordProperty("energy_ratio", sci(mechanical(e) / e0));
  RecordProperty("rebound_kinetic_ratio", sci(e.kinetic / e0));
  EXPECT_GT(max_contacts, 0);
  RecordProperty("separation_speed", sci(separation_speed));
  EXPECT_GT(gap, 0.1) << "the cubes must have bounced apart";
  EXPECT_GT(separation_speed, 0.5) << "and be moving apart";
  EXPECT_EQ(m.contact.totals().contacts, 0) << "separated at the end";
  EXPECT_LT(worst_p, 1e-10);
  EXPECT_NEAR(mechanical(e) / e0, 1.0, 0.01);
  EXPECT_LT(e.balance_error(), 0.01);
}
