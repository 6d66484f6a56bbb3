// Contact between bodies and with walls (README M3): conservation in impacts,
// smooth hand-over between feature pairs, friction on an incline, resting stacks (the
// Hertz contact time of a meshed sphere is in test_hertz.cpp). Tolerances are stated per
// test.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <functional>

#include "contact/narrow_phase.hpp"
#include "core/error.hpp"
#include "joint/fragments.hpp"
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

namespace {
// Runs two cubes (hex8, 2x2x2) rotated by Qa and Qb towards each other along x at 1 m/s
// each and returns the force history on cube A (from its momentum change per step).
struct Impact {
  std::vector<Vec3> force;
  Real e0 = 0, e_end = 0, balance = 0;
  bool finite = true;
};

Impact impact(const Mat3& Qa, const Mat3& Qb, Real reach) {
  Mesh mesh;
  const Mesh c1 = cube(CellType::Hex8, 2, 0.1);
  const Vec3 cc(0.05, 0.05, 0.05);
  add_part(mesh, c1, "b0", cc, Vec3(-reach, 0, 0), Qa);
  add_part(mesh, c1, "b1", cc, Vec3(reach, 0, 0), Qb);
  CaseConfig c = contact_case();
  c.initial = {initial("b0", Vec3(1, 0, 0)), initial("b1", Vec3(-1, 0, 0))};
  Model m = build_model(c, mesh);
  Integrator it(m, 0.9 * critical_dt(m));
  Impact out;
  out.e0 = it.energy().kinetic;
  const Group* a = m.mesh.find_group("b0");
  auto momentum_a = [&]() {
    Vec3 p = Vec3::Zero();
    for (Index n : a->nodes) p += m.fem.mass[n] * node_pos(it.v(), n);
    return p;
  };
  Vec3 p0 = momentum_a();
  while (it.time() < 0.02) {
    it.step();
    const Vec3 p1 = momentum_a();
    out.force.push_back((p1 - p0) / it.dt());
    p0 = p1;
    for (Real v : it.v()) out.finite = out.finite && std::isfinite(v);
  }
  const Energy e = it.energy();
  out.e_end = mechanical(e);
  out.balance = e.balance_error();
  return out;
}
}  // namespace

TEST(Contact, CornerAndCrossedEdgeImpactsAreBoundedAndSymmetric) {
  // Corner to corner: both cubes turned so a body diagonal lies on the x axis. Crossed
  // edges: A turned 45 deg about z (a z edge leads), B 45 deg about y (a y edge leads).
  // Both configurations are symmetric about the x axis, so the force on A must be along -x:
  // sideways components below 1e-6 of the peak (round-off level; a contact counted on one
  // side only would tilt it). Bounded: the force rises over several steps, no step-to-step
  // change above half the peak (a spike from a contact appearing at full depth would).
  // Energy: kinetic + strain + contact energy within 2 % of the initial kinetic energy.
  const Mat3 diag = Mat3(Eigen::AngleAxis<Real>(std::atan(std::sqrt(0.5)), Vec3::UnitY())) *
                    Mat3(Eigen::AngleAxis<Real>(M_PI / 4, Vec3::UnitZ()));
  const Mat3 flip = Mat3(Eigen::AngleAxis<Real>(M_PI, Vec3::UnitZ()));
  struct Config {
    const char* name;
    Mat3 qa, qb;
    Real reach;
  };
  const Config configs[] = {
      {"corner", diag, flip * diag, 0.5 * std::sqrt(3.0) * 0.1 + 0.002},
      {"edge", Mat3(Eigen::AngleAxis<Real>(M_PI / 4, Vec3::UnitZ())),
       Mat3(Eigen::AngleAxis<Real>(M_PI / 4, Vec3::UnitY())), 0.5 * std::sqrt(2.0) * 0.1 + 0.002}};
  for (const Config& cf : configs) {
    SCOPED_TRACE(cf.name);
    const Impact r = impact(cf.qa, cf.qb, cf.reach);
    ASSERT_TRUE(r.finite);
    Real peak = 0, side = 0, jump = 0;
    for (std::size_t i = 0; i < r.force.size(); ++i) {
      peak = std::max(peak, std::abs(r.force[i](0)));
      side = std::max(side, r.force[i].tail<2>().norm());
      if (i > 0) jump = std::max(jump, (r.force[i] - r.force[i - 1]).norm());
    }
    RecordProperty(std::string(cf.name) + "_peak_force", sci(peak));
    RecordProperty(std::string(cf.name) + "_side_over_peak", sci(side / peak));
    RecordProperty(std::string(cf.name) + "_max_jump_over_peak", sci(jump / peak));
    RecordProperty(std::string(cf.name) + "_energy_ratio", sci(r.e_end / r.e0));
    EXPECT_GT(peak, 0) << "they must have touched";
    EXPECT_LT(side, 1e-6 * peak);
    EXPECT_LT(jump, 0.5 * peak);
    EXPECT_NEAR(r.e_end / r.e0, 1.0, 0.02);
    EXPECT_LT(r.balance, 0.02);
  }
}

namespace {
// The tip of a tetrahedron over the top face of a 0.1 m hex cube, moved rigidly along x at a
// fixed height: its skeleton vertex 0.2 R deeper than first touch over the face (R the two
// contact radii). place(xs) puts the tip's vertex at x = xs; forces(dt) evaluates the
// contacts once (their history advancing over dt) and returns the force on the tip.
struct TipOverCube {
  Mesh mesh;
  Model m;
  Real R = 0, top = -INFINITY, xmax = -INFINITY;
  Vec3 tip0;
  const Group* g = nullptr;
  std::vector<Real> x, v, f;
  Real U = 0;  ///< stored contact energy after the last forces()

  explicit TipOverCube(Real mu) : mesh(two_parts()), m(build_model(contact_case(mu), mesh)) {
    const Index e_tip = 0, e_cube = m.mesh.blocks[0].size();  // tets first, then hexes
    R = m.contact.radius(e_tip) + m.contact.radius(e_cube);
    const contact::Poly cube_sk = m.contact.skeleton_poly(e_cube, m.fem.x0.data());
    for (int k = 0; k < 8; ++k) top = std::max(top, cube_sk.v[k](2)), xmax = std::max(xmax, cube_sk.v[k](0));
    tip0 = m.contact.skeleton_poly(e_tip, m.fem.x0.data()).v[0];
    g = m.mesh.find_group("tip");
    x = m.fem.x0, v.assign(x.size(), 0.0);
  }
  static Mesh two_parts() {
    Mesh mesh;
    add_part(mesh, cube(CellType::Hex8, 1, 0.1), "cube", Vec3(0.05, 0.05, 0.05), Vec3::Zero());
    add_part(mesh, tip_tet(0.03, 0.05), "tip", Vec3::Zero(), Vec3::Zero());
    return mesh;
  }
  void place(Real xs, Real height = 0.8) {  // the tip's skeleton `height` R above the cube's
    x = m.fem.x0;
    const Vec3 shift(xs - tip0(0), -tip0(1), top + height * R - tip0(2));
    for (Index n : g->nodes)
      for (int d = 0; d < 3; ++d) x[3 * n + d] += shift(d);
  }
  Vec3 forces(Real dt) {
    f.assign(x.size(), 0.0);
    m.contact.add_forces(m.mesh, m.joints, x.data(), v.data(), dt, f.data());
    U = m.contact.totals().elastic;
    Vec3 F = Vec3::Zero();
    for (Index n : g->nodes) F += node_pos(f, n);
    return F;
  }
};
}  // namespace

TEST(Contact, VertexSlidingOverAFaceOntoAnEdgeAndOffIsSmoothAndConservative) {
  // The tip of a tetrahedron is moved rigidly at a fixed height across the top face of a
  // hex cube, over its edge and off. Over the face the tip-face pair (VF) carries the
  // force; past the edge the tip-edge pair (VE) takes over, then nothing. Smooth: the
  // overlap changes at most as fast as the tip moves, so between samples ds apart the
  // force may change by at most k ds (k the pair stiffness), plus k delta ds / d for the
  // turning of the edge normal past the edge (delta/d = 0.25 here): we allow 2 k ds. A
  // feature counted twice or missed at the hand-over would jump by k x overlap = 125 k ds. Conservative: the work done
  // along the path plus the change of contact energy is zero to 1e-3 of the initial contact energy.
  TipOverCube s(0.0);
  const Real ds = 1e-5, R = s.R;
  const Real x_start = s.xmax - 0.02, x_end = s.xmax + 1.5 * R;
  s.place(x_start);
  Vec3 F_prev = s.forces(0.0);
  const Real U0 = s.U;
  const Real kn = F_prev(2) / (0.2 * R);
  Real work = 0, max_jump = 0;
  for (Real xs = x_start + ds; xs <= x_end; xs += ds) {
    s.place(xs);
    const Vec3 F = s.forces(0.0);
    work += 0.5 * (F + F_prev)(0) * ds;  // the path is along x
    max_jump = std::max(max_jump, (F - F_prev).norm());
    F_prev = F;
  }
  const Real U = s.U;
  RecordProperty("max_jump_over_k_ds", sci(max_jump / (kn * ds)));
  RecordProperty("energy_error", sci((work + U - U0) / U0));
  EXPECT_GT(U0, 0);
  EXPECT_EQ(U, 0) << "the tip must have left the cube";
  EXPECT_LT(max_jump, 2 * kn * ds);
  EXPECT_NEAR((work + U - U0) / U0, 0.0, 1e-3);
}

// After the first build a pair comes into reach with at most one step's approach of
// overlap: the candidates are rebuilt once anything has moved half the skin. So a pair
// first found overlapping more was overlapped where no contact was computed (an element
// that had no free face until a joint of it failed, reached through its exposed edge by a
// foreign piece: a contact born with 208 J, 0.74 mm deep, in the sphere at 7.5 m/s 2.27 ms
// after contact, the ledger off by 1.4). Such a pair must start from the overlap it has: no
// energy, no push; it pushes only by what it closes beyond the least overlap it has had
// since. The joint's failure is not staged here: the tip is first far above the cube (no
// pair), then set down 0.8 R above the cube's skeleton (0.2 R of overlap) in one move, a
// move no run makes, which finds the pair overlapping as that failure does. Slid along the
// face past half the skin (a rebuild) it keeps its offset; lifted to 0.9 R and set down to
// 0.8 R again, it must push as a tip pressed 0.1 R in: half the force and a quarter of the
// energy of a tip that starts 0.8 R above at the first build (an overlap of the set-up,
// which pushes).
TEST(Contact, APairFirstFoundOverlappingAfterTheFirstBuildStartsFromItsOverlap) {
  TipOverCube ref(0.0);
  const Real xs = ref.xmax - 0.05;  // over the middle of the top face: a vertex-face pair
  ref.place(xs);
  const Real F_ref = ref.forces(0.0)(2), U_ref = ref.U;
  ASSERT_GT(F_ref, 0);
  TipOverCube s(0.0);
  s.place(xs, 20.0);
  EXPECT_EQ(s.forces(0.0).norm(), 0);
  s.place(xs, 0.8);
  EXPECT_EQ(s.forces(0.0).norm(), 0) << "a pair first found overlapping pushed";
  EXPECT_EQ(s.U, 0);
  // Recorded: one pair, its overlap 0.2 of the radii, the energy the tip pressed in so at
  // the first build stores (the same touch and law).
  const contact::ContactTotals t = s.m.contact.totals();
  EXPECT_EQ(t.born.unseen.pairs, 1);  // no joint between the tip and the cube
  EXPECT_NEAR(t.born.unseen.max_ratio, 0.2, 1e-9);
  EXPECT_NEAR(t.born.unseen.energy, U_ref, 1e-9 * U_ref);
  EXPECT_EQ(t.born.split.pairs, 0);
  // Moved along the face by more than half the skin: the candidates are rebuilt, and the
  // pair keeps its offset through the rebuild.
  const Index builds = s.m.contact.totals().rebuilds;
  s.place(xs + 0.02, 0.8);
  EXPECT_EQ(s.forces(0.0).norm(), 0) << "the offset was lost at a rebuild";
  EXPECT_GT(s.m.contact.totals().rebuilds, builds);
  EXPECT_EQ(s.m.contact.totals().born.unseen.pairs, 1) << "a pair kept through a rebuild was counted again";
  s.place(xs, 0.9);
  EXPECT_EQ(s.forces(0.0).norm(), 0);
  s.place(xs, 0.8);
  const Vec3 F = s.forces(0.0);
  EXPECT_NEAR(F(2), 0.5 * F_ref, 1e-9 * F_ref);
  EXPECT_NEAR(s.U, 0.25 * U_ref, 1e-9 * U_ref);
}

TEST(Contact, VertexSlidingWithFrictionOntoAnEdgeKeepsTheLedger) {
  // The tip of the last test slides with friction (mu = 0.5) over the cube's face, onto its
  // edge and off, moved at 1 m/s (dx = 1e-6 m per step of 1e-6 s), so its tangential spring
  // is loaded to mu fn / kt. Over the face the tip-face pair holds the spring; past the edge
  // the tip-edge pair takes over with a spring of its own that starts at zero, and the
  // energy the old spring held (a fifth of the contact's) leaves the contact without work.
  // The ledger must book it as dissipated: the work of the contact forces on the tip plus
  // the change of stored energy plus the dissipation is zero to 1e-3 of the largest stored
  // energy. The trapezoidal rule's error is half the force's jump at the hand-over (kt |xi|)
  // times dx, 3.2e-4 of it here. Measured: -3.5e-4; without the booking -0.20.
  TipOverCube s(0.5);
  const Real ds = 1e-6, dt = 1e-6;
  for (Index n : s.g->nodes) s.v[3 * n] = ds / dt;
  const Real x_end = s.xmax + 1.5 * s.R;
  Real U_max = 0;
  s.place(s.xmax - 0.02);
  Real F_prev = s.forces(dt)(0);
  const Real U0 = s.U, D0 = s.m.contact.totals().friction;
  Real work = 0;
  for (Real xs = s.xmax - 0.02 + ds; xs <= x_end; xs += ds) {
    s.place(xs);
    const Real F = s.forces(dt)(0);
    work += 0.5 * (F + F_prev) * ds;
    U_max = std::max(U_max, s.U);
    F_prev = F;
  }
  const Real U = s.U;
  const Real dissipated = s.m.contact.totals().friction - D0;
  RecordProperty("dissipated_over_max_energy", sci(dissipated / U_max));
  RecordProperty("ledger_error", sci((work + U - U0 + dissipated) / U_max));
  EXPECT_EQ(U, 0) << "the tip must have left the cube";
  EXPECT_GT(dissipated, U_max);  // it slid all the way: friction did work (measured 14 U_max)
  EXPECT_NEAR((work + U - U0 + dissipated) / U_max, 0.0, 1e-3);
}

namespace {
// Two one-element hex cubes, "under" at the origin and "over" above it, both turned by Q;
// over's skeleton set `gap` contact radii R above under's. x0 holds that placement.
struct StackedCubes {
  Model m;
  Real R = 0;
  const Group* over = nullptr;
  std::vector<Real> x0;
};
StackedCubes stacked_cubes(Real side_over, Real mu, Real gap, const Mat3& Q = Mat3::Identity()) {
  Mesh mesh;
  add_part(mesh, cube(CellType::Hex8, 1, 0.1), "under", Vec3(0.05, 0.05, 0.05), Vec3::Zero(), Q);
  add_part(mesh, cube(CellType::Hex8, 1, side_over), "over", Vec3::Constant(side_over / 2), Vec3(0, 0, 0.2), Q);
  StackedCubes s{build_model(contact_case(mu), mesh), 0, nullptr, {}};
  const Index e_under = 0, e_over = 1;
  s.R = s.m.contact.radius(e_under) + s.m.contact.radius(e_over);
  const contact::Poly su = s.m.contact.skeleton_poly(e_under, s.m.fem.x0.data());
  const contact::Poly so = s.m.contact.skeleton_poly(e_over, s.m.fem.x0.data());
  Real top = -INFINITY, bottom = INFINITY;
  for (int k = 0; k < 8; ++k) top = std::max(top, su.v[k](2)), bottom = std::min(bottom, so.v[k](2));
  s.over = s.m.mesh.find_group("over");
  s.x0 = s.m.fem.x0;
  for (Index n : s.over->nodes) s.x0[3 * n + 2] -= bottom - (top + gap * s.R);
  return s;
}
}  // namespace

TEST(Contact, CornersSlidingApartWithFrictionKeepTheLedger) {
  // A 0.1 m cube (one hex8) rests face on face on another, its skeleton 0.8 R above, corners
  // over corners, and slides along (1, 0.5, 0) at 1 m/s in x (1e-6 m per step of 1e-6 s) by
  // 1.5 R in x. At each aligned corner several feature pairs see one contact and share it by
  // weight (weigh in narrow_phase.cpp); as the corners part the shares move while the
  // tangential springs are loaded to mu fn / kt. A share is not a force: a loaded spring's
  // energy must not follow it. The ledger (work of the contact forces on the top cube plus
  // the change of stored energy plus the dissipation) is zero to 1e-3 of the largest stored
  // energy. What is left is the normal springs' energy, which follows the shares (4.5e-4
  // here without friction; not carried, narrow_phase.cpp). Measured 3.5e-4; with the
  // springs' history not carried at constant energy (before PairHistory::carry) 5.3e-3: the
  // cluster shares' leak of the sphere impact at friction 2.0
  // (src/scenes/sphere_impact/REFERENCE.md). (Along x alone the edges stay in line and the
  // leak is 1.1e-3 against 2.0e-4.)
  StackedCubes st = stacked_cubes(0.1, 0.5, 0.8);
  Model& m = st.m;
  const Real R = st.R;
  const Group* g = st.over;
  const std::vector<Real>& x0 = st.x0;
  const Real ds = 1e-6, dt = 1e-6, dy = 0.5;  // dy: the slide's y per x
  std::vector<Real> x = x0, v(x.size(), 0.0), f;
  for (Index n : g->nodes) v[3 * n] = ds / dt, v[3 * n + 1] = dy * ds / dt;
  auto forces = [&] {
    f.assign(x.size(), 0.0);
    m.contact.add_forces(m.mesh, m.joints, x.data(), v.data(), dt, f.data());
    Real F = 0;
    for (Index n : g->nodes) F += f[3 * n] + dy * f[3 * n + 1];
    return F;
  };
  Real F_prev = forces();
  const Real U0 = m.contact.totals().elastic, D0 = m.contact.totals().friction;
  const Index touches0 = m.contact.totals().contacts;
  Real work = 0, U_max = U0;
  const int steps = static_cast<int>(1.5 * R / ds);
  for (int i = 1; i <= steps; ++i) {
    for (Index n : g->nodes) x[3 * n] = x0[3 * n] + i * ds, x[3 * n + 1] = x0[3 * n + 1] + dy * i * ds;
    const Real F = forces();
    work += 0.5 * (F + F_prev) * ds;
    U_max = std::max(U_max, m.contact.totals().elastic);
    F_prev = F;
  }
  const Real U = m.contact.totals().elastic, dissipated = m.contact.totals().friction - D0;
  RecordProperty("dissipated_over_max_energy", sci(dissipated / U_max));
  RecordProperty("ledger_error", sci((work + U - U0 + dissipated) / U_max));
  RecordProperty("touches_at_start", static_cast<int>(touches0));
  EXPECT_GT(U0, 0);
  EXPECT_GT(touches0, 4) << "each corner must be seen through several feature pairs (a cluster)";
  EXPECT_GT(dissipated, U_max);  // it slid: friction did work
  EXPECT_NEAR((work + U - U0 + dissipated) / U_max, 0.0, 1e-3);
}

namespace {
// Two cubes turned 45 deg about x meet ridge on ridge: a 0.1 m cube's top edge under a
// 0.05 m cube's bottom edge, crossed at their middles with the skeletons 0.5 R apart. The
// small cube is moved rigidly by `place(u)` (a turn angle about the vertical through the
// crossing and a shift along y) over u from 0 to 1 in `steps`; returns the work of the
// contact forces on it plus the change of contact energy, over the initial energy, and
// the largest step of its vertical force over its start.
struct PathCheck {
  Real energy_error, max_jump, energy_ratio;
};

PathCheck ridge_over_ridge(const std::function<std::pair<Real, Real>(Real)>& place, int steps) {
  StackedCubes st = stacked_cubes(0.05, 0.0, 0.5, Mat3(Eigen::AngleAxis<Real>(M_PI / 4, Vec3::UnitX())));
  Model& m = st.m;
  const Group* g = st.over;
  const std::vector<Real>& x0 = st.x0;
  std::vector<Real> x = x0, v(x.size(), 0.0), f;
  auto move = [&](Real u) {
    const auto [angle, shift] = place(u);
    const Mat3 Q = Mat3(Eigen::AngleAxis<Real>(angle, Vec3::UnitZ()));
    for (Index n : g->nodes) {
      const Vec3 p = Q * node_pos(x0, n) + Vec3(0, shift, 0);
      for (int d = 0; d < 3; ++d) x[3 * n + d] = p(d);
    }
  };
  auto forces = [&](Real& U) {
    f.assign(x.size(), 0.0);
    m.contact.add_forces(m.mesh, m.joints, x.data(), v.data(), 0.0, f.data());
    U = m.contact.totals().elastic;
  };
  auto vertical = [&](const std::vector<Real>& fv) {
    Real z = 0;
    for (Index n : g->nodes) z += fv[3 * n + 2];
    return z;
  };
  Real U0 = 0, U = 0, work = 0, max_jump = 0;
  move(0);
  forces(U0);
  std::vector<Real> f_prev = f, x_prev = x;
  const Real fz0 = vertical(f);
  for (int i = 1; i <= steps; ++i) {
    move(static_cast<Real>(i) / steps);
    forces(U);
    for (Index n : g->nodes)
      for (int d = 0; d < 3; ++d) work += 0.5 * (f[3 * n + d] + f_prev[3 * n + d]) * (x[3 * n + d] - x_prev[3 * n + d]);
    max_jump = std::max(max_jump, std::abs(vertical(f) - vertical(f_prev)));
    f_prev = f, x_prev = x;
  }
  if (!(fz0 > 0)) return {INFINITY, INFINITY, 0};  // they must touch
  return {(work + U - U0) / U0, max_jump / fz0, U / U0};
}

// Conservative: the forces' work plus the change of energy within 1e-3 of the initial energy
// (the trapezoidal rule's error is orders below). Smooth: no step of the vertical force above
// 1 % of its start.
void expect_smooth_and_conservative(const PathCheck& r) {
  ::testing::Test::RecordProperty("energy_error", sci(r.energy_error));
  ::testing::Test::RecordProperty("max_jump_over_start_force", sci(r.max_jump));
  ::testing::Test::RecordProperty("energy_end_over_start", sci(r.energy_ratio));
  EXPECT_NEAR(r.energy_error, 0.0, 1e-3);
  EXPECT_LT(r.max_jump, 0.01);
}
}  // namespace

TEST(Contact, NearlyParallelEdgesTurnedThroughTheBlendAreSmoothAndConservative) {
  // The small cube is turned about the vertical through the crossing from 0.03 to 0.12 rad:
  // nearly parallel, its edge's two end points carry the contact (vertex-edge pairs); past
  // 0.1 rad the crossing does (one edge-edge pair, which stores 45 % less than the two end
  // points' pairs at 0.05 rad and 28 % less at 0.1 rad); between 0.05 and 0.1 rad the two
  // are blended (narrow_phase.hpp). Conservative: the work of the forces along the turn plus
  // the change of contact energy is zero to 1e-3 of the initial energy (measured 2e-7, the
  // trapezoidal rule's error); without the blend's couple it was -0.31, and with the pairs
  // switched at 0.05 rad (no blend) -0.43. Smooth: no step of the vertical force above 1 %
  // of its start (measured 0.12 %, the turn's own change; the switch made one of 43 %).
  const PathCheck r = ridge_over_ridge([](Real u) { return std::pair<Real, Real>(0.03 + 0.09 * u, 0); }, 900);
  expect_smooth_and_conservative(r);
}

TEST(Contact, CrossingInTheBlendSlidingOffAnEdgesEndIsSmoothAndConservative) {
  // The small cube, turned 0.07 rad (in the blend: edge-edge weight 0.24), is shifted 2 mm
  // sideways, so that the two edges' crossing runs from the middle of its edge over its end
  // (at 1.57 mm) and 0.43 mm past it. On the way the end vertex's vertex-edge pair takes the
  // contact back from the edge-edge pair where the crossing reaches the vertex. Bounds as
  // for the turn (measured -2e-8 and 0.014 %). With the vertex's test along > 1e-3 not
  // scaled by sin^2 the hand-over came where the crossing was still 0.2 of the edge from
  // the vertex: -3.7e-3 and a step of 15 %. Not covered: 0.5 mm farther, an edge-edge pair
  // of the far end vertex's other edge appears at full weight where that vertex's own pair
  // was faded to 0.76 (a step of 6.7 %; above 0.1 rad, where the vertex's pair is dropped,
  // the step is the whole pair's, as before the blend).
  const PathCheck r = ridge_over_ridge([](Real u) { return std::pair<Real, Real>(0.07, -0.002 * u); }, 2000);
  expect_smooth_and_conservative(r);
}

namespace {
// A cube (hex8, 2x2x2, side 0.1 m) resting on the rigid plane z = 0 under gravity tilted
// by theta about y (the same as a plane inclined by theta). Returns the down-slope
// position and velocity of its centre at times t1 and t2.
struct Slide {
  Real x1, x2, v1, v2, t1, t2;
};

Slide incline(Real theta_deg, Real mu, Real t1, Real t2) {
  Mesh mesh;
  add_part(mesh, cube(CellType::Hex8, 2, 0.1), "block", Vec3(0.05, 0.05, 0.05), Vec3(0, 0, 0.05));
  CaseConfig c = contact_case(mu);
  // Damping of the block's own vibration (stiffness-proportional: no drag on rigid motion)
  // and of the contact bounce. Undamped, the block rocks on its penalty springs, its rear
  // edge lifts in part of each period and clamped (never pulling) contact forces then
  // carry more than the springs: friction averaged 0.49 N instead of 0.5 N and the block
  // slid 25 % faster than a rigid one (the acceleration is a small difference).
  c.materials[0].beta = 1e-4;
  c.contact_materials[0].damping_ratio = 0.3;
  WallConfig w;
  w.wall.name = "slope";
  w.wall.type = contact::Wall::Type::Plane;
  w.wall.centre = Vec3::Zero();
  w.wall.normal0 = Vec3::UnitZ();
  c.walls.push_back(w);
  const Real th = theta_deg * M_PI / 180;
  c.gravity = 9.81 * Vec3(std::sin(th), 0, -std::cos(th));
  Model m = build_model(c, mesh);
  Integrator it(m, 0.9 * critical_dt(m));
  Slide s{};
  while (it.time() < t1) it.step();
  s.t1 = it.time(), s.x1 = group_mean(m, it.x(), "block")(0), s.v1 = group_mean(m, it.v(), "block")(0);
  while (it.time() < t2) it.step();
  s.t2 = it.time(), s.x2 = group_mean(m, it.x(), "block")(0), s.v2 = group_mean(m, it.v(), "block")(0);
  return s;
}
}  // namespace

TEST(Contact, BlockOnAnInclineSticksBelowTheFrictionAngleAndSlidesAbove) {
  // mu = 0.5: friction angle 26.57 deg. Two degrees below it the block must stay: after
  // the first touch has settled (0.05 s) it moves less than 1e-3 of its size in the next
  // 0.1 s (the tangential springs deflect elastically, by microns). Two degrees above it
  // slides with a = g (sin theta - mu cos theta): the mean acceleration between 0.05 s and
  // 0.15 s within 2 %.
  const Real mu = 0.5, phi = std::atan(mu) * 180 / M_PI;
  const Slide stay = incline(phi - 2, mu, 0.05, 0.15);
  RecordProperty("creep_below_over_size", sci(std::abs(stay.x2 - stay.x1) / 0.1));
  EXPECT_LT(std::abs(stay.x2 - stay.x1), 1e-4);
  const Real th = (phi + 2) * M_PI / 180;
  const Slide go = incline(phi + 2, mu, 0.05, 0.15);
  const Real a = (go.v2 - go.v1) / (go.t2 - go.t1), a_ref = 9.81 * (std::sin(th) - mu * std::cos(th));
  RecordProperty("slide_acceleration_ratio", sci(a / a_ref));
  EXPECT_NEAR(a / a_ref, 1.0, 0.02);
}

TEST(Contact, StackOfFiveCubesStaysAtRestOnTheFloor) {
  // Five 0.1 m cubes (one hex8 each, faces aligned: every contact is corner on corner,
  // the tie case of the narrow phase) stacked on the rigid floor under gravity, 100 000
  // steps (5 s). The weight settles into the contacts (damped); after that no cube may
  // drift by more than 1e-3 of the cube size, sideways (no spurious tangential force from
  // the tie handling) or vertically (no creep). The floor carries the weight to 1 %.
  Mesh mesh;
  const Real a = 0.1;
  for (int k = 0; k < 5; ++k)
    add_part(mesh, cube(CellType::Hex8, 1, a), fmt::format("c{}", k), Vec3(0.05, 0.05, 0.05),
             Vec3(0, 0, a * (k + 0.5)));
  CaseConfig c = contact_case(0.5);
  c.materials[0].beta = 1e-4;  // the cubes' own ringing (see the incline test)
  c.contact_materials[0].damping_ratio = 0.3;
  WallConfig w;
  w.wall.name = "floor";
  w.wall.type = contact::Wall::Type::Plane;
  c.walls.push_back(w);
  c.gravity = Vec3(0, 0, -9.81);
  Model m = build_model(c, mesh);
  Integrator it(m, 0.9 * critical_dt(m));
  std::vector<Vec3> settled(5);
  for (long s = 1; s <= 100000; ++s) {
    it.step();
    if (s == 20000)
      for (int k = 0; k < 5; ++k) settled[k] = group_mean(m, it.x(), fmt::format("c{}", k));
  }
  Real drift = 0, side = 0;
  for (int k = 0; k < 5; ++k) {
    const Vec3 p = group_mean(m, it.x(), fmt::format("c{}", k));
    drift = std::max(drift, (p - settled[k]).norm());
    side = std::max(side, p.head<2>().norm());
  }
  const Vec3 floor_force = m.contact.walls()[0].force;
  const Real weight = 5 * kRho * a * a * a * 9.81;
  RecordProperty("simulated_time_s", sci(it.time()));
  RecordProperty("drift_after_settling_over_size", sci(drift / a));
  RecordProperty("sideways_over_size", sci(side / a));
  RecordProperty("floor_force_over_weight", sci(-floor_force(2) / weight));
  EXPECT_LT(drift, 1e-3 * a);
  EXPECT_LT(side, 1e-3 * a);
  EXPECT_NEAR(-floor_force(2) / weight, 1.0, 0.01) << "the floor carries the stack's weight";
}

TEST(Contact, AtTheFullContactStepACubeBouncingOnTheFloorStaysStable) {
  // contact.step_fraction = 1: the contact springs' stability limit itself bounds the step
  // (the default is half of it, for impacts). A 0.1 m hex8 cube released touching the floor
  // under gravity, undamped, bounces on its contact springs for 20 000 steps at 0.9 of the
  // step. The step is the contact's (its springs are 80 times stiffer than the cube's own)
  // and twice the default's. Stable: the cube stays on the floor and its bounce does not
  // grow (the deepest point of the last 5000 steps within 1 % of the first 5000's; measured
  // 0.995). The limit assumes four contact springs per node and these nodes have one each,
  // so this is a margin of about two below the true limit: at 3x the default's step the
  // bounce grows by 54 %. Many springs per node under slow loading are the disc's stress
  // check (test_disc_field: tets against plates at 1, ledger 1.3e-8). Recorded, not
  // bounded: the ledger of this undamped bounce reads 8.1 % at the whole limit and 2.4 % at
  // half (velocity Verlet's energy error grows as (w dt)^2), which is why impacts keep half.
  Mesh mesh;
  const Real a = 0.1;
  add_part(mesh, cube(CellType::Hex8, 1, a), "cube", Vec3(0.05, 0.05, 0.05), Vec3(0, 0, 0.5 * a));
  CaseConfig c = contact_case(0.5);
  WallConfig w;
  w.wall.name = "floor";
  w.wall.type = contact::Wall::Type::Plane;
  c.walls.push_back(w);
  c.gravity = Vec3(0, 0, -9.81);
  auto bounce = [&](Real fraction, Real& early, Real& late, Real& balance) {
    c.contact.settings.step_fraction = fraction;
    Model m = build_model(c, mesh);
    Integrator it(m, 0.9 * critical_dt(m));
    early = late = INFINITY, balance = 0;
    for (long s = 1; s <= 20000; ++s) {
      it.step();
      balance = std::max(balance, it.energy().balance_error());
      Real low = INFINITY;
      for (Index n = 0; n < m.fem.n_nodes; ++n) low = std::min(low, it.x()[3 * n + 2]);
      if (s <= 5000) early = std::min(early, low);
      if (s > 15000) late = std::min(late, low);
    }
    return m.contact.radius(0);
  };
  c.contact.settings.step_fraction = 1.0;
  const Model full = build_model(c, mesh);
  c.contact.settings.step_fraction = 0.5;
  const Model half = build_model(c, mesh);
  EXPECT_EQ(stable_step(full).limiter, "contact");
  EXPECT_NEAR(full.contact.stable_dt() / half.contact.stable_dt(), 2.0, 1e-12);
  Real early, late, balance, early_h, late_h, balance_h;
  const Real r = bounce(1.0, early, late, balance);
  bounce(0.5, early_h, late_h, balance_h);
  RecordProperty("dt_over_default", sci(critical_dt(full) / critical_dt(half)));
  RecordProperty("deepest_late_over_early", sci(late / early));
  RecordProperty("balance_error_full", sci(balance));
  RecordProperty("balance_error_half", sci(balance_h));
  ASSERT_LT(early, 0) << "the cube must press into the floor";
  EXPECT_LT(late, 0) << "the cube left the floor";
  EXPECT_LT(late / early, 1.01);
  EXPECT_GT(late, -r);
}

TEST(Contact, BrokenPiecesCollideAndComeToRest) {
  // A column of four 0.1 m hex8 cubes tied by weak cohesive joints spins about x (its long
  // axis is z) and falls on a rigid floor: the spin tears the joints at once, and the
  // pieces fall, hit the floor and each other. Contacts between the new fragments must
  // start as joints fail (the candidate list is refreshed). Checks: more than one
  // fragment; after 1.5 s kinetic energy below 1e-3 of its peak (they came to rest, with
  // contact damping 0.3 and friction 0.5); no node below the floor by more than the
  // contact radius (corners of a spheropolyhedron are rounded by r, so a corner node may
  // dip below the floor by less than r; more would mean a piece fell through); energy
  // ledger balanced to 3 %: nearly all the energy is dissipated in some twenty damped
  // impacts of stiff contact springs integrated at w dt ~ 1, and viscous work is booked
  // trapezoidally, which leaves an O((w dt)^2) residue per impact (measured: 1.0 %). Broken joints between separate
  // pieces are released (contact alone acts): kept, their penalty threw pieces that came back turned (KE 27 -> 149 J).
  CaseConfig c = contact_case(0.5);
  make_fracturable(c, 10.0, 1e-3, 100.0, 30, 1e-2);
  c.contact_materials[0].damping_ratio = 0.3;
  c.materials[0].beta = 1e-4;
  WallConfig w;
  w.wall.name = "floor";
  w.wall.type = contact::Wall::Type::Plane;
  c.walls.push_back(w);
  c.gravity = Vec3(0, 0, -9.81);
  InitialConfig spin;
  spin.group = "all";
  spin.angular_velocity = Vec3(20, 0, 0);
  spin.center = Vec3(0.05, 0.05, 0.4);
  c.initial = {spin};
  Mesh mesh = box_mesh(CellType::Hex8, 1, 1, 4, Vec3(0.1, 0.1, 0.4));
  for (std::size_t i = 2; i < mesh.x.size(); i += 3) mesh.x[i] += 0.2;  // start 0.2 m above the floor
  Model m = build_model(c, mesh);
  ASSERT_EQ(m.joints.size(), 3);
  Integrator it(m, 0.9 * critical_dt(m));
  Real peak = 0;
  while (it.time() < 1.5) {
    it.step();
    if (it.steps() % 100 == 0) peak = std::max(peak, it.energy().kinetic);
  }
  std::vector<Real> emass(m.fem.n_elements, 1.0);
  const joint::Fragments fr = joint::find_fragments(m.mesh, m.joints, emass);
  Real lowest = INFINITY;
  for (Index n = 0; n < m.fem.n_nodes; ++n) lowest = std::min(lowest, it.x()[3 * n + 2]);
  const Energy e = it.energy();
  RecordProperty("fragments", static_cast<int>(fr.count));
  RecordProperty("broken_joints", static_cast<int>(e.broken_joints));
  RecordProperty("final_over_peak_kinetic", sci(e.kinetic / peak));
  RecordProperty("lowest_node_z", sci(lowest));
  RecordProperty("balance_error", sci(e.balance_error()));
  EXPECT_GT(fr.count, 1);
  EXPECT_LT(e.kinetic, 1e-3 * peak);
  EXPECT_GT(lowest, -m.contact.radius(0));
  EXPECT_LT(e.balance_error(), 0.03);
}

TEST(Contact, SplittingKeepsTheEnergyLedger) {
  // A distorted tet block (3x3x3 cells, 162 tets, weak joints everywhere) torn apart fast: as joints
  // fail, elements that met only at an edge or a vertex of the crack land in different
  // pieces and become contact candidates with their skeletons already overlapping. That
  // overlap is not an impact: it must not push (before the fix, the Brazilian disc's
  // balance error jumped from 1e-5 to 0.33 during its split). Undamped, frictionless:
  // the ledger must balance to 1e-3 of its largest term through the whole fragmentation
  // (measured 2.7e-4; with the birth overlaps pushing, 2.0e-3).
  CaseConfig c = contact_case(0.0);
  make_fracturable(c, 1e5, 1.0, 1e6, 30, 10.0);
  BoundaryConfig l = fixed("xmin", "x");
  BoundaryConfig r = fixed("xmax", "x");
  r.type = BoundaryConfig::Type::Velocity;
  r.value = Vec3(2.0, 0, 0);
  c.boundaries = {l, r};
  Model m = build_model(c, box_mesh(CellType::Tet4, 3, 3, 3, Vec3(0.1, 0.1, 0.1), 0.25));
  Integrator it(m, 0.9 * critical_dt(m));
  Real worst = 0;
  while (it.time() < 0.01) {
    it.step();
    if (it.steps() % 50 == 0) worst = std::max(worst, it.energy().balance_error());
  }
  std::vector<Real> emass(m.fem.n_elements, 1.0);
  const joint::Fragments fr = joint::find_fragments(m.mesh, m.joints, emass);
  RecordProperty("fragments", static_cast<int>(fr.count));
  RecordProperty("broken_joints", static_cast<int>(it.energy().broken_joints));
  RecordProperty("worst_balance_error", sci(worst));
  EXPECT_GT(fr.count, 1);
  EXPECT_LT(worst, 1e-3);
}

// A curved jaw (concave cylinder of radius R about the z axis through the origin, arc
// +-30 deg about +y): a tet skeleton whose top vertex is pushed past the cylinder touches
// it at that vertex only, with the gap R - rho and the normal towards the axis; outside
// the arc nothing touches.
TEST(Contact, JawTouchesTheVertexPastItsCylinder) {
  const Real R = 0.1, cos30 = std::cos(M_PI / 6);
  contact::Poly A;
  A.topo = &contact::topology(contact::Shape::Tet);
  A.v[0] = Vec3(0.01, 0.098, 0.0), A.v[1] = Vec3(0.0, 0.09, 0.0), A.v[2] = Vec3(0.02, 0.09, 0.0),
  A.v[3] = Vec3(0.01, 0.09, 0.01);
  std::vector<contact::Touch> t;
  contact::find_jaw_touches(A, 0.003, Vec3::Zero(), Vec3::UnitZ(), Vec3::UnitY(), R, cos30, t);
  ASSERT_EQ(t.size(), 1u);
  const Real rho = std::hypot(0.01, 0.098);
  EXPECT_EQ(t[0].fa, 0);
  EXPECT_NEAR(t[0].d, R - rho, 1e-15);
  EXPECT_LT((t[0].n + Vec3(0.01, 0.098, 0).normalized()).norm(), 1e-14);
  EXPECT_NEAR((t[0].pa - t[0].pb).dot(t[0].n), t[0].d, 1e-15);
  EXPECT_NEAR(t[0].pb.head<2>().norm(), R, 1e-15);
  // The same tet turned to 60 deg from +y: beyond the arc.
  const Mat3 Q = Eigen::AngleAxis<Real>(M_PI / 3, Vec3::UnitZ()).toRotationMatrix();
  for (int k = 0; k < 4; ++k) A.v[k] = Q * A.v[k];
  t.clear();
  contact::find_jaw_touches(A, 0.003, Vec3::Zero(), Vec3::UnitZ(), Vec3::UnitY(), R, cos30, t);
  EXPECT_TRUE(t.empty());
}

TEST(Contact, CylinderWallTouchesAVertexAndAFaceAcrossIt) {
  // A cylinder wall is its axis segment dilated by its radius (a spherocylinder). A tet
  // vertex 12 mm from the axis of a 10 mm cylinder (skeleton radius 3 mm): one touch, gap
  // 12 mm, normal radial from the axis. A hex face (skeleton radius 3 mm) 11 mm under a long
  // cylinder lying across it: the face's two edges that cross the axis carry it
  // (edge-edge), normal = the face's.
  const Real R = 0.01;
  contact::Poly axis;
  axis.topo = &contact::topology(contact::Shape::Segment);
  axis.v[0] = Vec3(0, 0, -0.1), axis.v[1] = Vec3(0, 0, 0.1);
  contact::Poly A;
  A.topo = &contact::topology(contact::Shape::Tet);
  A.v[0] = Vec3(0.012, 0, 0.0), A.v[1] = Vec3(0.03, -0.01, -0.01), A.v[2] = Vec3(0.03, 0.01, -0.01),
  A.v[3] = Vec3(0.03, 0.0, 0.01);
  std::vector<contact::Touch> t;
  contact::find_touches(A, 0.003, axis, R, t);
  ASSERT_EQ(t.size(), 1u);
  EXPECT_EQ(t[0].kind, contact::Feature::VE);
  EXPECT_NEAR(t[0].d, 0.012, 1e-15);
  EXPECT_LT((t[0].n - Vec3::UnitX()).norm(), 1e-14);
  EXPECT_LT(t[0].pb.head<2>().norm(), 1e-15);  // on the axis
  // A 20 mm cube whose top face z = -0.011 lies 11 mm below an axis along x.
  const Mesh h = cube(CellType::Hex8, 1, 0.02);
  contact::Poly B;
  B.topo = &contact::topology(contact::Shape::Hex);
  for (int k = 0; k < 8; ++k) B.v[k] = node_pos(h.x, h.blocks[1].conn[k]) + Vec3(-0.01, -0.01, -0.031);
  axis.v[0] = Vec3(-0.1, 0, 0), axis.v[1] = Vec3(0.1, 0, 0);
  t.clear();
  contact::find_touches(B, 0.003, axis, R, t);
  ASSERT_EQ(t.size(), 2u);
  for (const auto& c : t) {
    EXPECT_EQ(c.kind, contact::Feature::EE);
    EXPECT_NEAR(c.d, 0.011, 1e-15);
    EXPECT_LT((c.n + Vec3::UnitZ()).norm(), 1e-14);
    EXPECT_NEAR(std::abs(c.pa(0)), 0.01, 1e-15);  // at the face's two edges across the axis
  }
}

TEST(Contact, FreeCylinderStrikingAFreeBlockConservesMomentum) {
  // A free steel-density cylinder (radius 16 mm, as the paper's impactors) strikes a free
  // elastic 0.1 m block (2x2x2 hex8, no supports, no gravity) at 5 m/s, off-centre and
  // tilted so that it also spins. No other force acts: linear momentum of block + cylinder
  // is conserved to round-off (1e-10 of sum m|v|), since every contact force acts equally
  // and oppositely on the two.
  Mesh mesh;
  add_part(mesh, cube(CellType::Hex8, 2, 0.1), "b", Vec3(0.05, 0.05, 0.05), Vec3::Zero());
  CaseConfig c = contact_case();
  WallConfig w;
  w.wall.name = "cyl";
  w.wall.type = contact::Wall::Type::Cylinder;
  w.wall.radius = 0.016, w.wall.half_length = 0.1;
  w.wall.axis0 = Vec3(1, 0.2, 0).normalized();
  w.wall.centre = Vec3(0.01, 0.02, 0.05 + 0.016 + 0.001);
  w.wall.free = true;
  const Real rho = 7800, R = w.wall.radius, L = 2 * w.wall.half_length;
  w.wall.mass = rho * M_PI * R * R * L;
  const Mat3 aa = w.wall.axis0 * w.wall.axis0.transpose();
  w.wall.inertia_body =
      w.wall.mass * (3 * R * R + L * L) / 12 * (Mat3::Identity() - aa) + 0.5 * w.wall.mass * R * R * aa;
  w.wall.velocity = w.wall.velocity_target = Vec3(0, 0, -5);
  c.walls.push_back(w);
  Model m = build_model(c, mesh);
  Integrator it(m, 0.9 * critical_dt(m));
  const auto total = [&]() -> Vec3 {
    return momentum(m, it) + m.contact.walls()[0].mass * m.contact.walls()[0].velocity;
  };
  const Vec3 p0 = total();
  const Real scale = m.contact.walls()[0].mass * 5;
  Real worst = 0;
  Index touched = 0;
  while (it.time() < 0.02) {
    it.step();
    worst = std::max(worst, (total() - p0).norm() / scale);
    touched = std::max(touched, m.contact.totals().contacts);
  }
  RecordProperty("worst_momentum_error", sci(worst));
  EXPECT_GT(touched, 0) << "the cylinder never reached the block";
  EXPECT_LT(momentum(m, it)(2), -0.1 * scale) << "the block did not take momentum";
  EXPECT_GT(m.contact.walls()[0].velocity(2), -4.0) << "the cylinder was not slowed";
  RecordProperty("steps", std::to_string(it.steps()));
  EXPECT_LT(worst, 1e-10);
}

TEST(Contact, FreeCylinderRollsDownAnInclineWithoutSlipping) {
  // A free solid cylinder (radius 16 mm, axis along y) on the top face of a fixed elastic
  // block, with gravity tilted by 10 deg (the same as an incline of 10 deg) and friction
  // 0.5 (rolling needs tan(10 deg) / 3 = 0.06). A solid cylinder rolling without slipping
  // accelerates at 2/3 g sin(theta): the fitted acceleration of its centre over 0.1-0.4 s
  // within 2 % (the tolerance), and its spin matches v / R within 2 %.
  const Real theta = 10 * M_PI / 180, g = 9.81, R = 0.016;
  Mesh mesh = box_mesh(CellType::Hex8, 8, 2, 1, Vec3(0.4, 0.1, 0.05));
  CaseConfig c = simple_case(1e9, 0.25, 2500);
  c.contact.enabled = true;
  contact::ContactMaterial cm;
  cm.friction = 0.5;
  cm.damping_ratio = 0.2;  // the contact's own bounce dies out; rolling does not dissipate
  c.contact_materials = {cm};
  c.boundaries.push_back(fixed("zmin"));
  WallConfig w;
  w.wall.name = "roller";
  w.wall.type = contact::Wall::Type::Cylinder;
  w.wall.radius = R, w.wall.half_length = 0.03;
  w.wall.axis0 = Vec3::UnitY();
  w.wall.centre = Vec3(0.05, 0.05, 0.05 + R);
  w.wall.free = true;
  const Real L = 2 * w.wall.half_length;
  w.wall.mass = 2500 * M_PI * R * R * L;
  const Mat3 aa = w.wall.axis0 * w.wall.axis0.transpose();
  w.wall.inertia_body =
      w.wall.mass * (3 * R * R + L * L) / 12 * (Mat3::Identity() - aa) + 0.5 * w.wall.mass * R * R * aa;
  c.walls.push_back(w);
  c.gravity = g * Vec3(std::sin(theta), 0, -std::cos(theta));
  Model m = build_model(c, mesh);
  Integrator it(m, 0.9 * critical_dt(m));
  // Least-squares fit x = x0 + v0 t + a t^2 / 2 over the window.
  Eigen::Matrix3d AtA = Eigen::Matrix3d::Zero();
  Eigen::Vector3d Atb = Eigen::Vector3d::Zero();
  while (it.time() < 0.4) {
    it.step();
    if (it.time() < 0.1) continue;
    const Real t = it.time();
    const Eigen::Vector3d row(1, t, 0.5 * t * t);
    AtA += row * row.transpose(), Atb += row * m.contact.walls()[0].centre(0);
  }
  const Real a = AtA.ldlt().solve(Atb)(2), expected = 2.0 / 3.0 * g * std::sin(theta);
  const contact::Wall& cyl = m.contact.walls()[0];
  RecordProperty("acceleration_ratio", sci(a / expected));
  RecordProperty("spin_ratio", sci(cyl.omega(1) * R / cyl.velocity(0)));
  EXPECT_NEAR(a / expected, 1.0, 0.02);
  EXPECT_NEAR(cyl.omega(1) * R / cyl.velocity(0), 1.0, 0.02);
  EXPECT_LT(cyl.centre(0), 0.38) << "rolled off the block";
}

TEST(Fragments, DescribedLargestFirstWithMassAndCentroid) {
  // A 3 x 1 x 1 hex bar with joints, the joint between the first two cells broken by hand:
  // two fragments, the first cell alone and the other two. With element masses 1, 2, 3 kg
  // (by x) the pair comes first (5 kg, centroid x = (2 x 0.15 + 3 x 0.25) / 5 = 0.21 m),
  // then the single cell (1 kg at x = 0.05 m); ids are the fragments' smallest element tag.
  CaseConfig c = contact_case(0.0);
  make_fracturable(c, 1e5, 1.0, 1e6, 30, 10.0);
  Model m = build_model(c, box_mesh(CellType::Hex8, 3, 1, 1, Vec3(0.3, 0.1, 0.1)));
  ASSERT_EQ(m.joints.size(), 2);
  ASSERT_EQ(m.mesh.n_elements(), 3);
  const auto& b = *std::find_if(m.mesh.blocks.begin(), m.mesh.blocks.end(), [](const auto& k) { return k.size() > 0; });
  auto cx = [&](Index e) {  // centroid x of element e (the hexahedra are the only block with elements)
    Real s = 0;
    for (int i = 0; i < b.npe(); ++i) s += m.fem.x0[3 * b.conn[static_cast<std::size_t>(e) * b.npe() + i]];
    return s / b.npe();
  };
  std::vector<Real> emass(3);
  Index first = 0;
  for (Index e = 0; e < 3; ++e) {
    emass[e] = cx(e) < 0.1 ? 1.0 : cx(e) < 0.2 ? 2.0 : 3.0;
    if (cx(e) < 0.1) first = e;
  }
  for (Index j = 0; j < m.joints.size(); ++j)
    if (m.joints.ea[j] == first || m.joints.eb[j] == first) m.joints.status[j] = joint::JointStatus::Broken;
  const joint::Fragments fr = joint::find_fragments(m.mesh, m.joints, emass);
  const auto info = joint::describe_fragments(m.mesh, fr, m.fem.x0.data(), emass);
  ASSERT_EQ(info.size(), 2u);
  EXPECT_DOUBLE_EQ(info[0].mass, 5.0);
  EXPECT_EQ(info[0].elements, 2);
  EXPECT_NEAR(info[0].centroid(0), 0.21, 1e-12);
  EXPECT_NEAR(info[0].centroid(1), 0.05, 1e-12);
  EXPECT_DOUBLE_EQ(info[1].mass, 1.0);
  EXPECT_EQ(info[1].id, static_cast<Index>(b.tag[first]));
  EXPECT_EQ(info[0].id, static_cast<Index>(std::min(b.tag[(first + 1) % 3], b.tag[(first + 2) % 3])));
  EXPECT_NEAR(info[1].centroid(0), 0.05, 1e-12);
}

TEST(Contact, HardCaseCylinderStrikesAHexEdgeOnAtAnAngle) {
  // Hard case (issue 17): a free steel cylinder (radius 16 mm) strikes the top edge of a free
  // 3x3x3 hex8 block with weak mode-I joints at 20 m/s, along the edge's bisector, its axis
  // turned 19 deg from the edge in the plane normal to the motion: the contact starts at a
  // point on an edge, the block breaks and the hex skeletons of its pieces meet each other.
  // No support, no gravity: linear momentum of block + cylinder is conserved to round-off
  // (every contact and joint force acts equally and oppositely; checked every step against
  // 1e-10 of m|v|), the energy balance stays within 1 % of the impact energy, nothing
  // becomes NaN, and no energy is created (kinetic at the end below the impact energy).
  CaseConfig c = contact_case(0.3);
  make_fracturable(c, 2e4, 1.0, 1e6, 30, 10.0, 30);
  for (auto& jm : c.joint_materials) jm.mode_i = true;
  const Vec3 dir = Vec3(0, -1, -1).normalized();
  WallConfig w;
  w.wall.name = "cyl";
  w.wall.type = contact::Wall::Type::Cylinder;
  w.wall.radius = 0.016, w.wall.half_length = 0.08;
  w.wall.axis0 = Vec3(1, 0.25, -0.25).normalized();  // normal to the motion, 19 deg off the edge
  w.wall.centre = Vec3(0.05, 0.1, 0.1) - (0.016 + 0.001) * dir;
  w.wall.free = true;
  const Real R = w.wall.radius, L = 2 * w.wall.half_length;
  w.wall.mass = 7800 * M_PI * R * R * L;
  const Mat3 aa = w.wall.axis0 * w.wall.axis0.transpose();
  w.wall.inertia_body =
      w.wall.mass * (3 * R * R + L * L) / 12 * (Mat3::Identity() - aa) + 0.5 * w.wall.mass * R * R * aa;
  w.wall.velocity = w.wall.velocity_target = 20 * dir;
  c.walls.push_back(w);
  Model m = build_model(c, box_mesh(CellType::Hex8, 3, 3, 3, Vec3(0.1, 0.1, 0.1)));
  Integrator it(m, 0.9 * critical_dt(m));
  const auto total = [&]() -> Vec3 {
    return momentum(m, it) + m.contact.walls()[0].mass * m.contact.walls()[0].velocity;
  };
  const Vec3 p0 = total();
  const Real scale = m.contact.walls()[0].mass * 20, e0 = it.energy().kinetic;
  Real worst_p = 0, worst_balance = 0;
  Index touched = 0;
  bool finite = true;
  while (it.time() < 0.01) {
    it.step();
    worst_p = std::max(worst_p, (total() - p0).norm() / scale);
    touched = std::max(touched, m.contact.totals().contacts);
    if (it.steps() % 20 == 0) {
      worst_balance = std::max(worst_balance, it.energy().balance_error());
      for (Real x : it.x()) finite &= std::isfinite(x);
    }
  }
  std::vector<Real> emass(m.fem.n_elements, 1.0);
  const joint::Fragments fr = joint::find_fragments(m.mesh, m.joints, emass);
  RecordProperty("worst_momentum_error", sci(worst_p));
  RecordProperty("worst_balance_error", sci(worst_balance));
  RecordProperty("fragments", static_cast<int>(fr.count));
  RecordProperty("steps", std::to_string(it.steps()));
  EXPECT_GT(touched, 0) << "the cylinder never reached the block";
  EXPECT_GT(fr.count, 1) << "the block did not break: not the hard case meant";
  EXPECT_TRUE(finite);
  EXPECT_LT(worst_p, 1e-10);
  EXPECT_LT(worst_balance, 0.01);
  EXPECT_LT(it.energy().kinetic, e0 * (1 + 1e-6));
}

TEST(RigidBody, TumblesFreelyAsOneRigidMotion) {
  // A meshed box (0.2 x 0.1 x 0.05 m, 4x2x2 hex8) with kinematics = "rigid", thrown at 1 m/s
  // and spun at (3, 5, 7) rad/s, off every principal axis, so it tumbles. No force acts. Its
  // nodes keep their distances (to 1e-12 of the size: one rigid motion), its momentum and
  // its angular momentum about the centre stay exact (to 1e-12: no torque, and the scheme
  // kicks the angular momentum, not the spin), its centre moves at 1 m/s, and its kinetic
  // energy, which the explicit rotation update does not conserve exactly, stays within
  // 0.1 % over 1 s (about 1.5 turns) at h = 1e-4 s (h |w| = 9e-4 rad per step).
  CaseConfig c = simple_case(1e9, 0.25, 2000, Kinematics::Rigid);
  InitialConfig ic = initial("all", Vec3(1, 0, 0));
  ic.angular_velocity = Vec3(3, 5, 7), ic.center = Vec3(0.1, 0.05, 0.025);
  c.initial = {ic};
  Model m = build_model(c, box_mesh(CellType::Hex8, 4, 2, 2, Vec3(0.2, 0.1, 0.05)));
  ASSERT_EQ(m.rigid.size(), 1u);
  Integrator it(m, 1e-4);
  const auto ang = [&]() -> Vec3 {  // angular momentum of the nodes about their centre of mass
    Vec3 cm = Vec3::Zero(), L = Vec3::Zero();
    Real M = 0;
    for (Index n = 0; n < m.fem.n_nodes; ++n) cm += m.fem.mass[n] * node_pos(it.x(), n), M += m.fem.mass[n];
    cm /= M;
    for (Index n = 0; n < m.fem.n_nodes; ++n)
      L += m.fem.mass[n] * (node_pos(it.x(), n) - cm).cross(node_pos(it.v(), n));
    return L;
  };
  const Vec3 p0 = momentum(m, it), L0 = ang(), c0 = m.rigid[0].centre;
  const Real e0 = it.energy().kinetic;
  std::vector<Real> d0;
  for (Index n = 1; n < m.fem.n_nodes; ++n) d0.push_back((node_pos(it.x(), n) - node_pos(it.x(), 0)).norm());
  Real worst_d = 0, worst_e = 0;
  while (it.time() < 1.0 - 1e-9) {
    it.step();
    if (it.steps() % 100) continue;
    for (Index n = 1; n < m.fem.n_nodes; ++n)
      worst_d = std::max(worst_d, std::abs((node_pos(it.x(), n) - node_pos(it.x(), 0)).norm() - d0[n - 1]));
    worst_e = std::max(worst_e, std::abs(it.energy().kinetic / e0 - 1));
  }
  RecordProperty("worst_distance_change", sci(worst_d));
  RecordProperty("worst_kinetic_change", sci(worst_e));
  RecordProperty("angular_momentum_change", sci((ang() - L0).norm() / L0.norm()));
  EXPECT_LT(worst_d, 1e-12 * 0.2);
  EXPECT_LT((momentum(m, it) - p0).norm(), 1e-12 * p0.norm());
  EXPECT_LT((ang() - L0).norm(), 1e-12 * L0.norm());
  EXPECT_NEAR((m.rigid[0].centre - c0)(0), it.time(), 1e-12);
  EXPECT_LT(worst_e, 1e-3);
}

TEST(RigidBody, MeshedImpactorStrikesAFreeBlockConservingMomentum) {
  // A rigid meshed cube (0.05 m, 2x2x2 hex8, steel density) strikes a free deformable cube
  // (0.1 m, 3x3x3 hex8) at 5 m/s, off-centre. No support, no gravity: the momentum of the
  // two is conserved to round-off (1e-10 of m|v|), the block takes momentum, the impactor
  // is slowed, and the energy balance closes within 1 % (contact, no damping).
  Mesh mesh;
  add_part(mesh, cube(CellType::Hex8, 3, 0.1), "block", Vec3(0.05, 0.05, 0.05), Vec3::Zero());
  add_part(mesh, cube(CellType::Hex8, 2, 0.05), "striker", Vec3(0.025, 0.025, 0.025), Vec3(0.01, 0.015, 0.077));
  CaseConfig c = contact_case();
  c.bodies[0].groups = {"block"};
  BodyConfig s = c.bodies[0];
  s.name = "striker", s.groups = {"striker"}, s.kinematics = Kinematics::Rigid;
  c.bodies.push_back(s);
  c.initial = {initial("striker", Vec3(0, 0, -5))};
  Model m = build_model(c, mesh);
  ASSERT_EQ(m.rigid.size(), 1u);
  Integrator it(m, 0.9 * critical_dt(m));
  const Vec3 p0 = momentum(m, it);
  const Real scale = p0.norm();
  Real worst_p = 0, worst_balance = 0;
  while (it.time() < 0.01) {
    it.step();
    worst_p = std::max(worst_p, (momentum(m, it) - p0).norm() / scale);
    if (it.steps() % 20 == 0) worst_balance = std::max(worst_balance, it.energy().balance_error());
  }
  Vec3 block = Vec3::Zero();
  for (Index n : m.mesh.find_group("block")->nodes) block += m.fem.mass[n] * node_pos(it.v(), n);
  RecordProperty("worst_momentum_error", sci(worst_p));
  RecordProperty("worst_balance_error", sci(worst_balance));
  EXPECT_LT(block(2), -0.1 * scale) << "the block did not take momentum";
  EXPECT_GT(m.rigid[0].velocity(2), -4.0) << "the striker was not slowed";
  EXPECT_LT(worst_p, 1e-10);
  EXPECT_LT(worst_balance, 0.01);
}

TEST(RigidBody, RestsOnAPlaneUnderGravity) {
  // A rigid meshed cube (0.1 m, 2x2x2 hex8, 2500 kg/m^3) dropped from 5 mm onto a plane wall
  // with damped contact: at rest after 0.5 s, the wall carries its weight M g (within 0.5 %),
  // and it has not turned.
  CaseConfig c = simple_case(1e8, 0.25, 2500, Kinematics::Rigid);
  c.contact.enabled = true;
  contact::ContactMaterial cm;
  cm.friction = 0.5, cm.damping_ratio = 0.5;
  c.contact_materials = {cm};
  c.gravity = Vec3(0, 0, -9.81);
  WallConfig w;
  w.wall.name = "floor";
  w.wall.type = contact::Wall::Type::Plane;
  c.walls.push_back(w);
  Mesh mesh = cube(CellType::Hex8, 2, 0.1);
  for (std::size_t i = 2; i < mesh.x.size(); i += 3) mesh.x[i] += 0.005;
  Model m = build_model(c, mesh);
  Integrator it(m, 0.9 * critical_dt(m));
  while (it.time() < 0.5) it.step();
  const Real Mg = m.rigid[0].mass * 9.81;
  RecordProperty("wall_force_over_weight", sci(m.contact.walls()[0].force(2) / Mg));
  EXPECT_NEAR(std::abs(m.contact.walls()[0].force(2)) / Mg, 1.0, 5e-3);
  EXPECT_LT(m.rigid[0].velocity.norm(), 1e-3);
  EXPECT_LT(std::abs(Eigen::AngleAxis<Real>(m.rigid[0].q).angle()), 1e-6);
}

TEST(RigidBody, RefusesABoundaryOnItsNodes) {
  CaseConfig c = simple_case(1e9, 0.25, 2000, Kinematics::Rigid);
  c.boundaries.push_back(fixed("xmin"));
  try {
    build_model(c, box_mesh(CellType::Hex8, 2, 1, 1, Vec3(0.2, 0.1, 0.1)));
    FAIL() << "a fixed boundary on a rigid body was accepted";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("rigid body 'body'"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("'xmin'"), std::string::npos) << e.what();
  }
}
