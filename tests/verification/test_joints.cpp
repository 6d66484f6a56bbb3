// Joints in a model: forces from the law through the kernel, energy, objectivity,
// compliance against the penalty, a bar broken dynamically, stability.
#include <gtest/gtest.h>

#include "core/error.hpp"
#include "joint/fragments.hpp"
#include "joint/joint_forces.hpp"
#include "support/run_helpers.hpp"

using namespace dspdem;
using namespace dspdem::testsupport;

namespace {
// Two hexahedra side by side along x with one quadrilateral joint between them.
Model two_blocks(Real penalty = 100) {
  CaseConfig c = simple_case(30e9, 0.2, 2400);
  make_fracturable(c, 3e6, 100, 10e6, 30, 1000, penalty);
  return build_model(c, box_mesh(CellType::Hex8, 2, 1, 1, Vec3(0.2, 0.1, 0.1)));
}

// Positions with element B moved rigidly by `shift` and the whole pair rotated by Q.
std::vector<Real> place(const Model& m, const Vec3& shift, const Mat3& Q) {
  std::vector<Real> x = m.fem.x0;
  const auto& blk = m.mesh.blocks[1];
  const Index eb = m.joints.eb[0] - m.mesh.blocks[0].size();
  for (int i = 0; i < 8; ++i) {
    const Index n = blk.conn[8 * static_cast<std::size_t>(eb) + i];
    for (int d = 0; d < 3; ++d) x[3 * n + d] += shift(d);
  }
  for (Index n = 0; n < m.fem.n_nodes; ++n) {
    const Vec3 p = Q * node_pos(x, n);
    for (int d = 0; d < 3; ++d) x[3 * n + d] = p(d);
  }
  return x;
}

// Total joint force on side B.
Vec3 force_on_b(Model& m, const std::vector<Real>& x, std::vector<Real>& slots) {
  std::vector<Real> f(x.size(), 0.0);
  joint::add_joint_forces(m.joints, x.data(), f.data(), slots);
  Vec3 F = Vec3::Zero();
  for (int k = 0; k < 4; ++k) F += node_pos(f, m.joints.b[k]);
  return F;
}
}  // namespace

TEST(Joints, InsertionBetweenTwoHexes) {
  const Model m = two_blocks();
  ASSERT_EQ(m.joints.size(), 1);
  EXPECT_EQ(m.joints.npf[0], 4);
  EXPECT_EQ(m.fem.n_nodes, 16);  // 12 nodes before: the 4 shared ones are duplicated
  EXPECT_NEAR(m.joints.area0[0], 0.01, 1e-12);
}

TEST(Joints, UniformOpeningGivesTheLawAndGfTimesArea) {
  // Quasi-static opening of the joint by moving block B; the traction (force / area) must
  // be the law's, in any orientation of the pair; fracture energy = G_fI A within 1 %.
  for (const Mat3& Q : {Mat3(Mat3::Identity()), Mat3(Eigen::AngleAxis<Real>(1.3, Vec3(1, -2, 0.5).normalized()))}) {
    Model m = two_blocks();
    const joint::CohesiveParams p = m.joints.params[0];
    const Real w_ft = p.ft / p.kn, w_GI = 2 * p.GfI / p.ft, A = 0.01;
    std::vector<Real> slots;
    Real worst = 0;
    const int n = 4000;
    for (int i = 1; i <= n; ++i) {
      const Real d = 1.2 * (w_ft + w_GI) * i / n;
      const Vec3 F = force_on_b(m, place(m, Vec3(d, 0, 0), Q), slots);
      const Real law = d <= w_ft ? p.kn * d : std::max<Real>(0, p.ft * (1 - (d - w_ft) / w_GI));
      // force on B is -traction * area along the (rotated) x axis
      worst = std::max(worst, (F + law * A * (Q * Vec3(1, 0, 0))).norm() / (p.ft * A));
    }
    EXPECT_LT(worst, 1e-8);
    const joint::JointTotals t = joint::joint_totals(m.joints);
    EXPECT_EQ(t.broken, 1);
    EXPECT_NEAR(t.fracture_I / (p.GfI * A), 1.0, 0.01);
    EXPECT_NEAR(t.fracture_II, 0.0, 1e-9);
  }
}

TEST(Joints, RigidRotationNeitherOpensNorShears) {
  Model m = two_blocks();
  std::vector<Real> slots;
  const Vec3 F =
      force_on_b(m, place(m, Vec3::Zero(), Mat3(Eigen::AngleAxis<Real>(2.0, Vec3(0.3, 1, 0.2).normalized()))), slots);
  EXPECT_LT(F.norm(), 1e-6);  // N, against forces of order f_t A = 3e4 N
  EXPECT_EQ(m.joints.status[0], joint::JointStatus::Intact);
}

TEST(Joints, ShearUnderCompressionThroughTheKernel) {
  Model m = two_blocks();
  const joint::CohesiveParams p = m.joints.params[0];
  const Real A = 0.01, sigma = -2e6, dn = sigma / p.kn;
  const Real fs = p.c - sigma * p.tan_phi, df = fs / p.ks + 2 * p.GfII / fs;
  std::vector<Real> slots;
  Vec3 F;
  for (int i = 1; i <= 4000; ++i)
    F = force_on_b(m, place(m, Vec3(dn, 1.3 * df * i / 4000, 0), Mat3::Identity()), slots);
  EXPECT_EQ(m.joints.status[0], joint::JointStatus::Broken);
  EXPECT_NEAR(F(0) / (-sigma * A), 1.0, 1e-6);               // compression still carried
  EXPECT_NEAR(-F(1) / (-sigma * p.tan_phi * A), 1.0, 1e-6);  // residual friction
  const joint::JointTotals t = joint::joint_totals(m.joints);
  // Mode II dissipation: G_fII A up to failure, plus friction over the slip after it.
  const Real slip_after = 1.3 * df - df;
  EXPECT_NEAR(t.fracture_II / (p.GfII * A + fs * fs / (2 * p.ks) * A + -sigma * p.tan_phi * A * slip_after), 1.0, 0.01);
}

namespace {
// Static stiffness of a block under uniaxial tension (rollers on three faces), by dynamic
// relaxation. Returns {stiffness, critical dt}.
std::pair<Real, Real> block_stiffness(bool joints, Real penalty) {
  const Real E = 30e9, F = 1e4;  // 1 MPa on 0.01 m^2: well below f_t
  CaseConfig c = simple_case(E, 0.2, 2400, Kinematics::SmallStrain);
  if (joints) make_fracturable(c, 3e6, 100, 10e6, 30, 1000, penalty);
  c.boundaries.push_back(fixed("xmin", "x"));
  c.boundaries.push_back(fixed("ymin", "y"));
  c.boundaries.push_back(fixed("zmin", "z"));
  BoundaryConfig load;
  load.type = BoundaryConfig::Type::Force, load.group = "xmax", load.value = Vec3(F, 0, 0);
  c.boundaries.push_back(load);
  Model m = build_model(c, box_mesh(CellType::Tet4, 4, 4, 4, Vec3(0.1, 0.1, 0.1)));
  const Real L = 0.1, w1 = M_PI / 2 * std::sqrt(E / 2400) / L;  // first axial mode
  m.fem.node_alpha.assign(m.fem.n_nodes, 2 * w1);
  const Real dt = critical_dt(m);
  Integrator it(m, 0.9 * dt);
  while (it.time() < 40 / w1) it.step();
  Real u = 0;
  const Group& g = *m.mesh.find_group("xmax");
  for (Index n : g.nodes) u += it.x()[3 * n] - m.fem.x0[3 * n];
  u /= static_cast<Real>(g.nodes.size());
  if (joints) {
    // 1 MPa against f_t = 3 MPa: no joint may have left the elastic branch.
    Index soft = 0;
    for (auto st : m.joints.status) soft += st != joint::JointStatus::Intact;
    EXPECT_EQ(soft, 0) << "penalty " << penalty;
  }
  return {F / u, dt};
}
}  // namespace

TEST(Joints, AddedComplianceWithTheDefaultPenalty) {
  // Joints on every face of a 384-tet block: the static stiffness with the default penalty
  // (100) is within 2 % of the block without joints (measured: 1.5 %). The table (penalty,
  // dt, error) is recorded for the speed-against-error report.
  const auto [k0, dt0] = block_stiffness(false, 0);
  for (Real p : {10.0, 50.0, 100.0, 200.0}) {
    const auto [k, dt] = block_stiffness(true, p);
    const Real err = 1 - k / k0;
    RecordProperty(fmt::format("penalty_{:g}", p),
                   fmt::format("dt/dt_elements={:.3f} stiffness_error={:.4f}", dt / dt0, err));
    if (p == 100.0) {
      EXPECT_LT(std::abs(err), 0.02) << "stiffness error " << err;
    }
    EXPECT_GT(err, 0.0);  // joints only ever add compliance
  }
}

namespace {
// Hex bar of n cells along x, fixed at x = 0 and pulled at x = L until it breaks.
// Returns fracture energy / (G_fI x broken area), and the broken area.
std::pair<Real, Real> break_bar(int n) {
  const Real GfI = 100;
  CaseConfig c = simple_case(30e9, 0.2, 2400, Kinematics::SmallStrain);
  make_fracturable(c, 3e6, GfI, 10e6, 30, 1000);
  c.boundaries.push_back(fixed("xmin"));
  BoundaryConfig pull;
  pull.type = BoundaryConfig::Type::Velocity, pull.group = "xmax",
  pull.value = Vec3(0.01, 0, 0);  // slow: stress waves of 0.1 MPa, far below f_t
  pull.dof[1] = pull.dof[2] = false;
  pull.ramp = 2e-5;
  c.boundaries.push_back(pull);
  Model m = build_model(c, box_mesh(CellType::Hex8, n, 1, 1, Vec3(0.1, 0.02, 0.02)));
  Integrator it(m, 0.9 * critical_dt(m));
  while (it.energy().broken_joints == 0 && it.time() < 0.05) it.step();
  const Energy e = it.energy();
  ::testing::Test::RecordProperty(
      fmt::format("cells_{}_breakdown", n),
      fmt::format("I={:.5g} II={:.5g} area={:.5g} t={:.4g}", e.fracture_I, e.fracture_II, e.crack_area, it.time()));
  EXPECT_EQ(e.broken_joints, 1);
  return {(e.fracture_I + e.fracture_II) / (GfI * e.crack_area), e.crack_area};
}
}  // namespace

TEST(Joints, BarBreaksDissipatingGfTimesAreaForAnyResolution) {
  // Tolerance 2 % (the issue's): the elastic ramp of the law adds f_t^2 / (2 k_n) per area
  // (0.2 % here) and joints that reach f_t without breaking dissipate nothing.
  for (int n : {4, 8}) {
    const auto [ratio, area] = break_bar(n);
    RecordProperty(fmt::format("cells_{}", n), fmt::format("{:.5f}", ratio));
    EXPECT_NEAR(area, 0.02 * 0.02, 1e-12) << n;
    EXPECT_NEAR(ratio, 1.0, 0.02) << n << " cells";
  }
}

TEST(Joints, StableAtPointNineCaughtAtTwice) {
  auto run = [](Real factor, long* done) -> std::string {
    CaseConfig c = simple_case(30e9, 0.2, 2400);
    make_fracturable(c, 3e6, 100, 10e6, 30, 1000);
    c.boundaries.push_back(fixed("xmin"));
    Model m = build_model(c, box_mesh(CellType::Tet4, 4, 2, 2, Vec3(0.2, 0.05, 0.05)));
    for (Index k = 0; k < m.fem.n_nodes; ++k) m.v0[3 * k + 1] = 0.5 * m.fem.x0[3 * k];
    Integrator it(m, factor * critical_dt(m));
    try {
      for (*done = 0; *done < 20000; ++*done) {
        it.step();
        if (*done % 100 == 0) it.check_energy(10.0);
      }
    } catch (const NumericalError& e) {
      return e.what();
    }
    return "";
  };
  long done = 0;
  EXPECT_EQ(run(0.9, &done), "");
  EXPECT_EQ(done, 20000);
  const std::string msg = run(2.0, &done);
  ASSERT_FALSE(msg.empty()) << "a run at 2x the critical step with joints was not stopped";
  EXPECT_NE(msg.find("step"), std::string::npos) << msg;
  EXPECT_NE(msg.find("element"), std::string::npos) << msg;
}

TEST(Joints, NodesSplitWithoutAJointAreCounted) {
  // Two tets of one fracturable body that share only an edge: inserting joints splits the
  // edge's nodes although no joint ties them; the report must say so.
  Mesh m;
  m.source = "two tets on an edge";
  const Real p[6][3] = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}, {0, -1, 0}, {0, 0, -1}};
  for (int i = 0; i < 6; ++i) {
    m.x.insert(m.x.end(), {p[i][0], p[i][1], p[i][2]});
    m.node_tag.push_back(i + 1);
  }
  ElementBlock tets{CellType::Tet4, {0, 1, 2, 3, 0, 1, 4, 5}, {1, 2}};
  m.blocks.push_back(tets);
  m.blocks.push_back(ElementBlock{CellType::Hex8, {}, {}});
  check_element_volumes(m);
  joint::InsertionInput in;
  in.fracturable = {1, 1};
  in.body = {0, 0};
  joint::InsertionReport rep;
  const joint::JointSet js = joint::insert_joints(m, in, &rep);
  EXPECT_EQ(js.size(), 0);
  EXPECT_EQ(rep.split_without_joint, 2);
  EXPECT_EQ(m.n_nodes(), 8);
}
