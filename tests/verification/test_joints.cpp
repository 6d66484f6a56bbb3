// Joints in a model: forces from the law through the kernel, energy, objectivity,
// compliance against the penalty, a bar broken dynamically, stability.
#include <fmt/format.h>
#include <gtest/gtest.h>
#include <omp.h>

#include <Eigen/Dense>
#include <cmath>
#include <functional>
#include <limits>
#include <map>
#include <tuple>

#include "core/error.hpp"
#include "joint/fragments.hpp"
#include "joint/joint_compliance.hpp"
#include "joint/joint_forces.hpp"
#include "joint/ties.hpp"
#include "support/run_helpers.hpp"
#include "support/scene.hpp"
#include "time/extrinsic.hpp"

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

// Whether joint j lies on the plane x_axis = at (its first three side-A points do; a face
// has at least three).
bool joint_on_plane(const Model& m, Index j, int axis, Real at) {
  const joint::JointSet& js = m.joints;
  for (int k = 0; k < 3; ++k) {
    const Index n = js.a[4 * static_cast<std::size_t>(j) + k];
    if (std::abs(m.fem.x0[3 * static_cast<std::size_t>(n) + axis] - at) > 1e-12) return false;
  }
  return true;
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

TEST(Joints, ABrokenFacesFrictionResistsASlipTurnedAcrossAndTurnsWithTheFace) {
  // Broken in shear along y under 2 MPa, the face then slides along z by 5 cap / k_s. Its
  // friction is a vector on the face's frame: it turns towards the new slip as
  // tanh(k_s z / cap) (test_cohesive_law.cpp has the law alone), so the force on B ends
  // against z at cap A tanh(5), and what is left against y is cap A / cosh(5), 0.0135 of the
  // cap (a friction that did not turn would leave all of it; one that forgot y, none).
  // Tolerances: the slide in n steps is first order in the step, so the error of the force
  // along y is checked to halve (0.4-0.6) from n = 4000 to 8000 (steps of 1/800 and 1/1600 of
  // cap / k_s) and to be within 0.5 % at 4000 (0.27 % when written); along z 2e-3, as the law
  // alone's. Then the pair turns rigidly by 2 rad at once: the force turns with it, and the
  // state does not change (no slip, nothing dissipated): 1e-9, rounding.
  Model m = two_blocks();
  const joint::CohesiveParams p = m.joints.params[0];
  const Real A = 0.01, sigma = -2e6, dn = sigma / p.kn, cap = -sigma * p.tan_phi, l = cap / p.ks;
  const Real fs = p.c - sigma * p.tan_phi, df = fs / p.ks + 2 * p.GfII / fs, y = 1.3 * df;
  std::vector<Real> slots;
  auto slide = [&](Model& mm, int n) {
    for (int i = 1; i <= 4000; ++i) force_on_b(mm, place(mm, Vec3(dn, y * i / 4000, 0), Mat3::Identity()), slots);
    EXPECT_EQ(mm.joints.status[0], joint::JointStatus::Broken);
    Vec3 F;
    for (int i = 1; i <= n; ++i) F = force_on_b(mm, place(mm, Vec3(dn, y, 5 * l * i / n), Mat3::Identity()), slots);
    return F;
  };
  const Vec3 F = slide(m, 4000);
  Model fine = two_blocks();
  const Real fy = -1.0 / std::cosh(5.0);
  const Real e4000 = F(1) / (cap * A) - fy, e8000 = slide(fine, 8000)(1) / (cap * A) - fy;
  RecordProperty("force_y_relative_error", fmt::format("{:.3e} at 4000 steps, {:.3e} at 8000", e4000 / fy, e8000 / fy));
  EXPECT_LT(std::abs(e4000 / fy), 5e-3);
  EXPECT_NEAR(e8000 / e4000, 0.5, 0.1);
  EXPECT_NEAR(-F(2) / (cap * A * std::tanh(5.0)), 1.0, 2e-3);
  EXPECT_NEAR(F(0) / (-sigma * A), 1.0, 1e-6);
  const joint::JointTotals before = joint::joint_totals(m.joints);
  const Mat3 Q(Eigen::AngleAxis<Real>(2.0, Vec3(0.3, 1, 0.2).normalized()));
  const Vec3 G = force_on_b(m, place(m, Vec3(dn, y, 5 * l), Q), slots);
  EXPECT_LT((G - Q * F).norm() / (cap * A), 1e-9);
  EXPECT_NEAR(joint::joint_totals(m.joints).fracture_II, before.fracture_II, 1e-12 * before.fracture_II);
}

TEST(Joints, AFacesFrameAndItsExtrinsicOffsetTurnWithTheFace) {
  // The face's frame (FaceFrame) is what a broken point's friction and an extrinsic joint's
  // offset are kept on. Turned rigidly, about any axis (so about its normal too), a
  // triangle's and a quadrilateral's frame turn with them: the slip plus the offset has the
  // same components on the turned frame, to rounding. (A slip offset kept on global axes, as
  // before session 104, changes its components by its size times the turn about the normal.)
  const Mat3 Q(Eigen::AngleAxis<Real>(2.0, Vec3(0.3, 1, 0.2).normalized()));
  for (int npf : {3, 4}) {
    Vec3 xm[4] = {Vec3(0, 0, 0), Vec3(0.1, 0.01, 0), Vec3(0.11, 0.09, 0.002), Vec3(-0.01, 0.1, 0)};
    const Real o[4] = {1e-7, 3e-6, -2e-6, 0};  // opening, slip on the frame (u, v), unused
    const Vec3 jump(2e-6, -1e-6, 5e-7);        // the face's own jump
    auto components = [&](const Vec3* y, const Vec3& jmp) {
      Vec3 n = npf == 3 ? Vec3((y[1] - y[0]).cross(y[2] - y[0])) : Vec3((y[2] - y[0]).cross(y[3] - y[1]));
      n.normalize();
      const joint::FaceFrame f(joint::FaceFrame::line(npf, y), n);
      Real dn = jmp.dot(n);
      Vec3 sv = jmp - dn * n;
      joint::apply_offset(o, f, dn, sv);
      const joint::Slip sl = f.slip(sv, sv.norm());
      return Vec3(dn, sl.u, sl.v);
    };
    const Vec3 before = components(xm, jump);
    Vec3 ym[4];
    for (int k = 0; k < 4; ++k) ym[k] = Q * xm[k] + Vec3(1, 2, 3);
    const Vec3 after = components(ym, Q * jump);
    EXPECT_LT((after - before).norm(), 1e-12 * before.norm()) << npf << " nodes";
  }
}

TEST(Joints, TheTextsShearSofteningKeepsTheFrictionThroughTheKernel) {
  // joint_law = "paper_residual" (src/joint/residual_law.hpp) on the same two blocks, under
  // 20 MPa of compression: halfway through the softening the face carries the friction and
  // half the cohesion (the printed law: half of the whole strength), and it breaks with G_fII
  // and the friction's work dissipated, sliding on the friction after. Tolerances as above.
  CaseConfig c = simple_case(30e9, 0.2, 2400);
  make_fracturable(c, 3e6, 100, 10e6, 30, 1000, 100);
  c.joint_materials[0].residual = true;
  Model m = build_model(c, box_mesh(CellType::Hex8, 2, 1, 1, Vec3(0.2, 0.1, 0.1)));
  const joint::CohesiveParams p = m.joints.params[0];
  ASSERT_EQ(p.law, joint::JointLaw::PaperResidual);
  const Real A = 0.01, sigma = -20e6, dn = sigma / p.kn, mu = -sigma * p.tan_phi;
  const Real fs = p.c + mu, w_GII = 2 * p.GfII / p.c;
  std::vector<Real> slots;
  // Halfway: plastic slip w_GII / 2, so ds = w_GII / 2 + (f_s - h w_GII / 2) / k_s.
  const Real half = 0.5 * w_GII + (fs - 0.5 * p.c) / p.ks;
  Vec3 F;
  const int n = 4000;
  for (int i = 1; i <= n; ++i) F = force_on_b(m, place(m, Vec3(dn, half * i / n, 0), Mat3::Identity()), slots);
  EXPECT_EQ(m.joints.status[0], joint::JointStatus::Softening);
  EXPECT_NEAR(-F(1) / ((mu + 0.5 * p.c) * A), 1.0, 1e-6);
  const Real end = 1.3 * (w_GII + fs / p.ks);
  for (int i = 1; i <= n; ++i)
    F = force_on_b(m, place(m, Vec3(dn, half + (end - half) * i / n, 0), Mat3::Identity()), slots);
  EXPECT_EQ(m.joints.status[0], joint::JointStatus::Broken);
  EXPECT_NEAR(F(0) / (-sigma * A), 1.0, 1e-6);
  EXPECT_NEAR(-F(1) / (mu * A), 1.0, 1e-6);
  const joint::JointTotals t = joint::joint_totals(m.joints);
  // G_fII A and the friction over all the plastic slip: end less the elastic slip mu / k_s.
  EXPECT_NEAR(t.fracture_II / (p.GfII * A + mu * A * (end - mu / p.ks)), 1.0, 0.01);
}

TEST(Joints, TheBooksAreTheWorkOfTheForcesAppliedAcrossAForcedBreak) {
  // The face between two hexahedra opens unevenly while it slips: the opening grows from
  // 0.75 (y = 0) to 1.5 (y = 0.1 m) times w_ft + w_GI, the slip to 2/3 of c / k_s, so the
  // points nearer y = 0.1 break in opening and fail the others, which still carry their
  // elastic shear (a forced break). The sides move by -+ half the jump about a fixed middle
  // surface, so the normal and the slip direction stay put and the law's trapezoid of its
  // tractions is the nodal forces' trapezoid over each increment. The books (stored plus
  // dissipated) must then equal the work the nodal forces absorbed, to rounding (1e-10:
  // 400 increments of terms exact to 1e-16 relative). Booked from the zeroed shear instead,
  // the increment after the break misses half its shear work: 7e-6 of the total with the
  // paper's law, 5e-9 with the coupled one (its secant shear is lower by then).
  for (const bool coupled : {false, true}) {
    CaseConfig c = simple_case(30e9, 0.2, 2400);
    make_fracturable(c, 3e6, 100, 10e6, 30, 1000, 100);
    c.joint_materials[0].coupled = coupled;
    Model m = build_model(c, box_mesh(CellType::Hex8, 2, 1, 1, Vec3(0.2, 0.1, 0.1)));
    ASSERT_EQ(m.joints.size(), 1);
    const joint::CohesiveParams p = m.joints.params[0];
    const Real w = p.ft / p.kn + 2 * p.GfI / p.ft, w_fs = p.c / p.ks;
    std::vector<Real> slots, x = m.fem.x0, f_old(x.size(), 0.0);
    Real absorbed = 0;
    bool forced = false;
    const int n = 400;
    for (int i = 1; i <= n; ++i) {
      const Real D = 1.5 * w * i / n, slip = 0.5 * w_fs * i / (0.75 * n);
      std::vector<Real> xn = m.fem.x0;
      for (int k = 0; k < 4; ++k)
        for (const auto& [node, sign] : {std::pair{m.joints.a[k], -0.5}, std::pair{m.joints.b[k], 0.5}}) {
          const Real y = m.fem.x0[3 * node + 1];
          xn[3 * node] += sign * D * (0.5 + 0.5 * y / 0.1);
          xn[3 * node + 1] += sign * slip;
        }
      std::vector<Real> f(x.size(), 0.0);
      joint::add_joint_forces(m.joints, xn.data(), f.data(), slots);
      for (std::size_t k = 0; k < x.size(); ++k) absorbed -= 0.5 * (f_old[k] + f[k]) * (xn[k] - x[k]);
      if (m.joints.status[0] == joint::JointStatus::Broken && !forced) {
        // The break happened in this increment: the two points at the larger y (2 x 2 Gauss)
        // opened through, the other two were forced.
        int opened = 0;
        for (int g = 0; g < 4; ++g) opened += m.joints.point_state(g).dn_max >= w;
        EXPECT_EQ(opened, 2) << "coupled " << coupled;
        forced = true;
      }
      x = xn, f_old = f;
    }
    ASSERT_TRUE(forced) << "coupled " << coupled;
    const joint::JointTotals t = joint::joint_totals(m.joints);
    const Real books = t.elastic + t.fracture_I + t.fracture_II;
    RecordProperty(coupled ? "coupled_books_over_work_minus_1" : "paper_books_over_work_minus_1",
                   sci(books / absorbed - 1));
    EXPECT_NEAR(books / absorbed, 1.0, 1e-10) << "coupled " << coupled;
  }
}

namespace {
// A 384-tet block, 0.1 m wide, under 1 MPa of uniaxial tension (rollers on three faces),
// relaxed to its static state; joints on every interior face when `joints`.
struct RelaxedBlock {
  Model m;
  std::vector<Real> x;
  Real dt;
};

RelaxedBlock relaxed_block(bool joints, Real penalty, joint::Quadrature rule = joint::Quadrature::Gauss,
                           bool closed = false, Real dt = 0) {
  const Real E = 30e9, F = 1e4;  // 1 MPa on 0.01 m^2: well below f_t
  CaseConfig c = simple_case(E, 0.2, 2400, Kinematics::SmallStrain);
  if (joints) make_fracturable(c, 3e6, 100, 10e6, 30, 1000, penalty);
  for (auto& jm : c.joint_materials) jm.nodal_quadrature = rule == joint::Quadrature::Nodal;
  c.boundaries.push_back(fixed("xmin", "x"));
  c.boundaries.push_back(fixed("ymin", "y"));
  c.boundaries.push_back(fixed("zmin", "z"));
  BoundaryConfig load;
  load.type = BoundaryConfig::Type::Force, load.group = "xmax", load.value = Vec3(F, 0, 0);
  c.boundaries.push_back(load);
  RelaxedBlock b{build_model(c, box_mesh(CellType::Tet4, 4, 4, 4, Vec3(0.1, 0.1, 0.1))), {}, 0};
  if (closed) b.m.joints.closed.assign(b.m.joints.size(), 1);
  const Real L = 0.1, w1 = M_PI / 2 * std::sqrt(E / 2400) / L;  // first axial mode
  b.m.fem.node_alpha.assign(b.m.fem.n_nodes, 2 * w1);
  b.dt = dt > 0 ? dt : critical_dt(b.m);
  Integrator it(b.m, 0.9 * b.dt);
  while (it.time() < 40 / w1) it.step();
  b.x = it.x();
  if (joints) {
    // 1 MPa against f_t = 3 MPa: no joint may have left the elastic branch.
    Index soft = 0;
    for (auto st : b.m.joints.status) soft += st != joint::JointStatus::Intact;
    EXPECT_EQ(soft, 0) << "penalty " << penalty;
  }
  return b;
}

// Static stiffness of the block. Returns {stiffness, critical dt, the joints' added
// compliance as dspdem estimates and prints it}.
std::tuple<Real, Real, Real> block_stiffness(bool joints, Real penalty) {
  const RelaxedBlock b = relaxed_block(joints, penalty);
  Real u = 0;
  const Group& g = *b.m.mesh.find_group("xmax");
  for (Index n : g.nodes) u += b.x[3 * n] - b.m.fem.x0[3 * n];
  u /= static_cast<Real>(g.nodes.size());
  std::vector<Real> E(b.m.fem.n_elements, 30e9), vol(b.m.fem.n_elements, 0.0);
  for (const auto& blk : b.m.fem.blocks)
    for (Index e = 0; e < blk.size(); ++e) vol[blk.elem[e]] = blk.vol[e];
  return {1e4 / u, b.dt, joint::added_compliance(b.m.joints, E, vol)};
}

// Normal traction at every joint point against the exact sigma n_x^2 of the uniform field
// (sigma = 1 MPa along x): {RMS, largest} deviation over sigma.
std::pair<Real, Real> traction_scatter(const RelaxedBlock& b) {
  const joint::JointSet& js = b.m.joints;
  Real sum2 = 0, worst = 0;
  Index count = 0;
  for (Index j = 0; j < js.size(); ++j) {
    const Index* a = &js.a[4 * static_cast<std::size_t>(j)];
    const Vec3 p0 = node_pos(b.m.fem.x0, a[0]);
    const Vec3 n = (node_pos(b.m.fem.x0, a[1]) - p0).cross(node_pos(b.m.fem.x0, a[2]) - p0).normalized();
    const Vec3 mid = (p0 + node_pos(b.m.fem.x0, a[1]) + node_pos(b.m.fem.x0, a[2])) / 3;
    if ((mid.array() < 0.025 - 1e-9).any() || (mid.array() > 0.075 + 1e-9).any()) continue;  // away from the faces
    const Real exact = 1e6 * n(0) * n(0);
    for (int g = 0; g < js.npf[j]; ++g) {
      const Real d = (js.point_state(4 * static_cast<std::size_t>(j) + g).sn - exact) / 1e6;
      sum2 += d * d, worst = std::max(worst, std::abs(d)), ++count;
    }
  }
  return {std::sqrt(sum2 / static_cast<Real>(count)), worst};
}
}  // namespace

TEST(Joints, AddedComplianceWithTheDefaultPenalty) {
  // Joints on every face of a 384-tet block: the static stiffness with the default penalty
  // (100) is within 2 % of the block without joints (measured: 1.5 %). The table (penalty,
  // dt, error) is recorded for the speed-against-error report. The compliance the run
  // prints (isotropic-orientation estimate, joint_compliance.hpp) must match the measured
  // one, k0/k - 1, within 20 % where the measurement is good (p 10 and 50: measured 1.62/p
  // and 1.55/p, estimate 1.75/p). This block's faces are not isotropic (a structured split
  // of cubes), and the estimate is what a user reads to choose the penalty: right in size,
  // not to the percent. At p 100 and 200 the measured p x C falls to 1.44 and 1.21, the
  // trend of an offset of about 0.2 % in the relaxed static solution, so not asserted there.
  const auto [k0, dt0, c0] = block_stiffness(false, 0);
  EXPECT_EQ(c0, 0.0);
  for (Real p : {10.0, 50.0, 100.0, 200.0}) {
    const auto [k, dt, est] = block_stiffness(true, p);
    const Real err = 1 - k / k0, added = k0 / k - 1;
    RecordProperty(fmt::format("penalty_{:g}", p),
                   fmt::format("dt/dt_elements={:.3f} stiffness_error={:.4f} added_compliance={:.4f} estimate={:.4f}",
                               dt / dt0, err, added, est));
    if (p == 100.0) {
      EXPECT_LT(std::abs(err), 0.02) << "stiffness error " << err;
    }
    EXPECT_GT(err, 0.0);  // joints only ever add compliance
    if (p <= 50) {
      EXPECT_NEAR(est / added, 1.0, 0.2) << "penalty " << p << ": measured " << added << ", estimate " << est;
    }
  }
}

namespace {
// The far end (x max) pulled along x at 0.01 m/s after a 20 us ramp, free across: slow, stress
// waves of 0.1 MPa, far below f_t.
BoundaryConfig slow_pull() {
  BoundaryConfig pull;
  pull.type = BoundaryConfig::Type::Velocity, pull.group = "xmax", pull.value = Vec3(0.01, 0, 0);
  pull.dof[1] = pull.dof[2] = false;
  pull.ramp = 2e-5;
  return pull;
}

// Hex bar of n cells along x, fixed at x = 0 and pulled at x = L until it breaks.
// Returns fracture energy / (G_fI x broken area), and the broken area.
std::pair<Real, Real> break_bar(int n, joint::Quadrature rule, bool mode_i = false) {
  const Real GfI = 100;
  CaseConfig c = simple_case(30e9, 0.2, 2400, Kinematics::SmallStrain);
  make_fracturable(c, 3e6, GfI, 10e6, 30, 1000);
  c.joint_materials[0].nodal_quadrature = rule == joint::Quadrature::Nodal;
  c.joint_materials[0].mode_i = mode_i;
  c.boundaries.push_back(fixed("xmin"));
  c.boundaries.push_back(slow_pull());
  Model m = build_model(c, box_mesh(CellType::Hex8, n, 1, 1, Vec3(0.1, 0.02, 0.02)));
  Integrator it(m, 0.9 * critical_dt(m));
  while (it.energy().broken_joints == 0 && it.time() < 0.05) it.step();
  const Energy e = it.energy();
  ::testing::Test::RecordProperty(
      fmt::format("cells_{}_{}{}_breakdown", n, rule == joint::Quadrature::Nodal ? "nodal" : "gauss",
                  mode_i ? "_mode_I" : ""),
      fmt::format("I={:.5g} II={:.5g} area={:.5g} t={:.4g}", e.fracture_I, e.fracture_II, e.crack_area, it.time()));
  EXPECT_EQ(e.broken_joints, 1);
  return {(e.fracture_I + e.fracture_II) / (GfI * e.crack_area), e.crack_area};
}
}  // namespace

TEST(Joints, BarBreaksDissipatingGfTimesAreaForAnyResolution) {
  // Tolerance 2 % (the issue's): the elastic ramp of the law adds f_t^2 / (2 k_n) per area
  // (0.2 % here) and joints that reach f_t without breaking dissipate nothing.
  // Both joint quadratures.
  for (joint::Quadrature rule : {joint::Quadrature::Gauss, joint::Quadrature::Nodal})
    for (int n : {4, 8}) {
      const auto [ratio, area] = break_bar(n, rule);
      const char* name = rule == joint::Quadrature::Nodal ? "nodal" : "gauss";
      RecordProperty(fmt::format("cells_{}_{}", n, name), fmt::format("{:.5f}", ratio));
      EXPECT_NEAR(area, 0.02 * 0.02, 1e-12) << n << " " << name;
      EXPECT_NEAR(ratio, 1.0, 0.02) << n << " cells, " << name;
    }
  // The same with joint_law = "mode_I" (the impact beam's quadrilateral joints): the bar
  // opens in pure mode I, so the law must dissipate G_fI x area alike.
  for (int n : {4, 8}) {
    const auto [ratio, area] = break_bar(n, joint::Quadrature::Gauss, true);
    RecordProperty(fmt::format("cells_{}_mode_I", n), fmt::format("{:.5f}", ratio));
    EXPECT_NEAR(area, 0.02 * 0.02, 1e-12) << n;
    EXPECT_NEAR(ratio, 1.0, 0.02) << n << " cells, mode_I";
  }
}

TEST(Joints, NodalQuadratureRemovesTractionOscillations) {
  // Schellekens & de Borst (1993, IJNME 36:43): Gauss-integrated interface elements with a
  // stiff penalty show spurious oscillating tractions, Newton-Cotes (nodal) integration does
  // not. In a uniform 1 MPa tension every joint must carry sigma n_x^2; joints within a
  // quarter width of a face are left out (the point loads and rollers disturb the field
  // there). Measured: Gauss 1.5 % RMS, 6.8 % worst; nodal 0.36 % and 1.05 %. Limits: nodal
  // within 1 % RMS and 3 % worst (its scatter is the joints' own compliance, ~1.5 % of the
  // strain), and at most half the Gauss scatter, so the difference itself is checked.
  const auto [g_rms, g_max] = traction_scatter(relaxed_block(true, 100, joint::Quadrature::Gauss));
  const auto [n_rms, n_max] = traction_scatter(relaxed_block(true, 100, joint::Quadrature::Nodal));
  RecordProperty("gauss", fmt::format("rms={:.4f} max={:.4f}", g_rms, g_max));
  RecordProperty("nodal", fmt::format("rms={:.4f} max={:.4f}", n_rms, n_max));
  EXPECT_LT(n_rms, 0.01);
  EXPECT_LT(n_max, 0.03);
  EXPECT_LT(n_rms, 0.5 * g_rms);
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

TEST(Joints, FaceQuadratureWeightsAndShapeValues) {
  // Both rules, both faces: weights are fractions of the face area (sum 1), the shape values
  // at every point sum to 1, and a field linear over the face integrates exactly (its mean
  // is the mean of its nodal values). Nodal puts each point on its node (N = identity).
  // The price of nodal: it is exact only to degree 1 on triangles, where the 3-point Gauss
  // rule is exact to degree 2 (mean of lambda_1^2 over a triangle: 1/6; nodal gives 1/3).
  for (int npf : {3, 4}) {
    for (joint::Quadrature rule : {joint::Quadrature::Gauss, joint::Quadrature::Nodal}) {
      double N[4][4], w[4];
      const int ng = joint::face_quadrature(npf, rule, N, w);
      ASSERT_EQ(ng, npf);
      double wsum = 0, mean = 0;
      const double f[4] = {1.0, -2.0, 3.5, 0.5};  // nodal values of a field (linear on the face)
      for (int g = 0; g < ng; ++g) {
        wsum += w[g];
        double nsum = 0, fg = 0;
        for (int k = 0; k < npf; ++k) nsum += N[g][k], fg += N[g][k] * f[k];
        EXPECT_NEAR(nsum, 1.0, 1e-14) << npf << " " << g;
        mean += w[g] * fg;
        if (rule == joint::Quadrature::Nodal) {
          for (int k = 0; k < npf; ++k) EXPECT_EQ(N[g][k], g == k ? 1.0 : 0.0);
        }
      }
      EXPECT_NEAR(wsum, 1.0, 1e-14);
      double exact = 0;
      for (int k = 0; k < npf; ++k) exact += f[k] / npf;  // exact mean of the interpolated field
      EXPECT_NEAR(mean, exact, 1e-14) << npf;
      if (npf == 3) {
        double q = 0;
        for (int g = 0; g < ng; ++g) q += w[g] * N[g][0] * N[g][0];
        EXPECT_NEAR(q, rule == joint::Quadrature::Gauss ? 1.0 / 6.0 : 1.0 / 3.0, 1e-14);
      }
    }
  }
}

namespace {
// A fracturable body (joints: f_t 3 MPa, cohesion 10 MPa) with a second material `name`, at
// first the same, as its zone material, for the joint-zone tests to change.
CaseConfig case_with_a_zone_material(const char* name, Kinematics kin = Kinematics::Corotational) {
  CaseConfig c = simple_case(30e9, 0.2, 2400, kin);
  Material zone = c.materials[0];
  zone.name = name;
  c.materials.push_back(zone);
  make_fracturable(c, 3e6, 100, 10e6, 30, 1000);
  c.bodies[0].zone_material = name;
  return c;
}

// The zone material "strong": joint cohesion 99 MPa.
CaseConfig case_with_a_strong_zone_material() {
  CaseConfig c = case_with_a_zone_material("strong");
  c.joint_materials[1].c = 99e6;
  return c;
}
}  // namespace

TEST(Joints, ZoneGroupsTakeTheZoneMaterialsJointParameters) {
  // Three hexes along x; the last two form the zone "end" with a stronger joint material:
  // the joint inside the zone takes its cohesion, the one across the zone's edge the body's.
  CaseConfig c = case_with_a_strong_zone_material();
  c.bodies[0].zone_groups = {"end"};
  Mesh mesh = box_mesh(CellType::Hex8, 3, 1, 1, Vec3(0.3, 0.1, 0.1));
  Group end;
  end.name = "end";
  end.dim = 3;
  end.elements.resize(2);
  end.elements[1] = {1, 2};
  mesh.groups.push_back(end);
  const Model m = build_model(c, mesh);
  ASSERT_EQ(m.joints.size(), 2);
  EXPECT_EQ(m.zone_joints, std::vector<Index>{1}) << "one joint inside the zone, counted for the run's log";
  const Index nt = m.mesh.blocks[0].size();
  for (Index j = 0; j < 2; ++j) {
    const Index a = std::min(m.joints.ea[j], m.joints.eb[j]) - nt, b = std::max(m.joints.ea[j], m.joints.eb[j]) - nt;
    const Real coh = m.joints.params[m.joints.param[j]].c;
    if (a == 0 && b == 1)
      EXPECT_EQ(coh, 10e6) << "a joint across the zone's edge keeps the body's material";
    else
      EXPECT_EQ(coh, 99e6) << "joint " << a << "-" << b << " inside the zone";
  }
  c.bodies[0].zone_groups = {"nothing"};
  EXPECT_THROW(build_model(c, mesh), Error);
}

TEST(Joints, AZoneBoxTakesTheElementsWhoseCentroidsLieInIt) {
  // The same three hexes (centroids at x = 0.05, 0.15, 0.25), no group: a box over x > 0.1
  // holds the last two, so only the joint between them takes the zone's cohesion.
  CaseConfig c = case_with_a_strong_zone_material();
  c.bodies[0].zone_box.emplace(Vec3(0.1, -1, -1), Vec3(1, 1, 1));
  const Mesh mesh = box_mesh(CellType::Hex8, 3, 1, 1, Vec3(0.3, 0.1, 0.1));
  const auto cohesions = [&] {
    const Model m = build_model(c, mesh);
    const Index nt = m.mesh.blocks[0].size();
    std::map<std::pair<Index, Index>, Real> out;
    for (Index j = 0; j < m.joints.size(); ++j)
      out[{std::min(m.joints.ea[j], m.joints.eb[j]) - nt, std::max(m.joints.ea[j], m.joints.eb[j]) - nt}] =
          m.joints.params[m.joints.param[j]].c;
    return out;
  };
  const std::pair<Index, Index> edge(0, 1), inside(1, 2);
  auto coh = cohesions();
  ASSERT_EQ(coh.size(), 2u);
  EXPECT_EQ(coh.at(edge), 10e6) << "a joint across the box's edge keeps the body's material";
  EXPECT_EQ(coh.at(inside), 99e6) << "the joint inside the box";
  EXPECT_EQ(build_model(c, mesh).zone_joints, std::vector<Index>{1});
  // A box over the middle element alone holds no joint of its own: both keep the body's, and
  // the count the run warns on is 0.
  c.bodies[0].zone_box.emplace(Vec3(0.1, -1, -1), Vec3(0.2, 1, 1));
  coh = cohesions();
  EXPECT_EQ(coh.at(edge), 10e6);
  EXPECT_EQ(coh.at(inside), 10e6);
  EXPECT_EQ(build_model(c, mesh).zone_joints, std::vector<Index>{0});
  // The box's faces belong to it: a lower face through the middle element's centroid (as the
  // builder computes it, so equal to the last bit) takes that element in.
  const Real x1 = element_centroid(mesh, mesh.blocks[1], 1).x();
  c.bodies[0].zone_box.emplace(Vec3(x1, -1, -1), Vec3(1, 1, 1));
  coh = cohesions();
  EXPECT_EQ(coh.at(inside), 99e6) << "a centroid on the box's face lies in the box";
  c.bodies[0].zone_box.emplace(Vec3(std::nextafter(x1, 1.0), -1, -1), Vec3(1, 1, 1));
  coh = cohesions();
  EXPECT_EQ(coh.at(inside), 10e6) << "a face one bit above the centroid leaves it out";
  // A box that holds no centroid is an error naming the body, not a zone that silently is not there.
  c.bodies[0].zone_box.emplace(Vec3(0.31, -1, -1), Vec3(1, 1, 1));
  try {
    build_model(c, mesh);
    ADD_FAILURE() << "an empty zone box was accepted";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("holds no element centroid"), std::string::npos) << e.what();
  }
}

TEST(Joints, JointMonitorsFindTheCrackWhereTheBarIsWeak) {
  // A hex bar (6 x 2 x 2 cells, 120 x 40 x 40 mm) with joints on every face, pulled slowly
  // along x; the joints between the cells at x = 60-100 mm (a zone box) take f_t = 1 MPa
  // against the body's 3 MPa, so the bar must break across the plane x = 80 mm, the only
  // cross-section in the zone. The broken_joints and crack_area monitors over a box round
  // that plane must then read its 4 faces and its whole cross-section, 1.6e-3 m^2 (to the
  // rounding of 4 face areas), those over the rest of the bar nothing, and those without a
  // box the run's totals at every row.
  CaseConfig c = case_with_a_zone_material("weak", Kinematics::SmallStrain);
  c.joint_materials[1].ft = 1e6;
  c.bodies[0].zone_box.emplace(Vec3(0.06, -1, -1), Vec3(0.10, 1, 1));
  c.boundaries.push_back(fixed("xmin"));
  c.boundaries.push_back(slow_pull());
  auto monitor = [](const char* name, MonitorConfig::Type type, Real x0, Real x1) {
    MonitorConfig mc;
    mc.name = name, mc.type = type;
    if (x1 > x0) mc.box.emplace(Vec3(x0, -1, -1), Vec3(x1, 1, 1));
    return mc;
  };
  using T = MonitorConfig::Type;
  c.monitors = {monitor("plane", T::BrokenJoints, 0.075, 0.085), monitor("plane_area", T::CrackArea, 0.075, 0.085),
                monitor("below", T::BrokenJoints, -1, 0.075),    monitor("above", T::BrokenJoints, 0.085, 1),
                monitor("all", T::BrokenJoints, 0, 0),           monitor("all_area", T::CrackArea, 0, 0)};
  Model m = build_model(c, box_mesh(CellType::Hex8, 6, 2, 2, Vec3(0.12, 0.04, 0.04)));
  Integrator it(m, 0.9 * critical_dt(m));
  auto read = [&](int k) { return it.monitor(m.monitors[static_cast<std::size_t>(k)]); };
  int rows = 0;
  while (read(0) < 4 && it.time() < 0.05) {
    for (int s = 0; s < 20; ++s) it.step();
    const Energy e = it.energy();
    ASSERT_EQ(read(4), static_cast<Real>(e.broken_joints)) << "t = " << it.time();
    ASSERT_EQ(read(5), e.crack_area) << "t = " << it.time();
    ++rows;
  }
  RecordProperty("broken_at", fmt::format("{:.4g} s after {} rows", it.time(), rows));
  EXPECT_EQ(read(0), 4.0) << "the weak plane's four faces";
  EXPECT_NEAR(read(1), 0.04 * 0.04, 1e-15) << "its whole cross-section";
  EXPECT_EQ(read(2), 0.0) << "no joint below the plane";
  EXPECT_EQ(read(3), 0.0) << "no joint above the plane";
  EXPECT_EQ(read(4), 4.0);
  // A box that holds no joint is an error naming the monitor; so is a joint monitor on a
  // model without joints.
  c.monitors = {monitor("nowhere", T::BrokenJoints, 0.2, 0.3)};
  const Mesh mesh = box_mesh(CellType::Hex8, 6, 2, 2, Vec3(0.12, 0.04, 0.04));
  try {
    build_model(c, mesh);
    ADD_FAILURE() << "a joint monitor over no joint was accepted";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("monitor 'nowhere'"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("holds no joint"), std::string::npos) << e.what();
  }
  c.bodies[0].fracture = BodyConfig::Fracture::None;
  c.bodies[0].zone_box.reset(), c.bodies[0].zone_material.clear();
  c.monitors = {monitor("any", T::CrackArea, 0, 0)};
  try {
    build_model(c, mesh);
    ADD_FAILURE() << "a joint monitor on a model without joints was accepted";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("the model has none"), std::string::npos) << e.what();
  }
}

TEST(Joints, AZoneBoxTakesOnlyItsOwnBodysElementsAcrossBlocks) {
  // Two bodies apart in one mesh: tetrahedra "t" over x in [0, 0.2] (block 0) and three hexes
  // "h" over x in [0.3, 0.6] (block 1, centroids 0.35, 0.45, 0.55). "t"'s box spans the whole
  // mesh, yet "h"'s joints keep the body's cohesion: a box only takes its own body's elements.
  // "h"'s own box over x >= 0.4 gives its last joint alone the zone's, found through block 1's
  // offset.
  CaseConfig c = case_with_a_strong_zone_material();
  Mesh mesh;
  add_part(mesh, box_mesh(CellType::Tet4, 2, 1, 1, Vec3(0.2, 0.1, 0.1)), "t", Vec3::Zero(), Vec3::Zero());
  add_part(mesh, box_mesh(CellType::Hex8, 3, 1, 1, Vec3(0.3, 0.1, 0.1)), "h", Vec3::Zero(), Vec3(0.3, 0, 0));
  c.bodies[0].name = "t", c.bodies[0].groups = {"t"};
  c.bodies[0].zone_box.emplace(Vec3(-1, -1, -1), Vec3(1, 1, 1));
  BodyConfig h = c.bodies[0];
  h.name = "h", h.groups = {"h"}, h.zone_box.reset(), h.zone_material.clear();
  c.bodies.push_back(h);
  const auto check = [&](Real last_hex_joint, const char* what) {
    const Model m = build_model(c, mesh);
    const Index nt = m.mesh.blocks[0].size();
    Index tet_joints = 0, hex_joints = 0;
    for (Index j = 0; j < m.joints.size(); ++j) {
      const Index a = std::min(m.joints.ea[j], m.joints.eb[j]), b = std::max(m.joints.ea[j], m.joints.eb[j]);
      const Real coh = m.joints.params[m.joints.param[j]].c;
      if (b < nt) {
        ++tet_joints;
        EXPECT_EQ(coh, 99e6) << what << ": tet joint " << a << "-" << b << " lies in t's box";
      } else {
        ASSERT_GE(a, nt) << "no joint joins the two bodies";
        ++hex_joints;
        EXPECT_EQ(coh, b - nt == 2 ? last_hex_joint : 10e6) << what << ": hex joint " << a - nt << "-" << b - nt;
      }
    }
    EXPECT_GT(tet_joints, 0);
    EXPECT_EQ(hex_joints, 2);
    // The run's log counts each body's own: all of t's joints, and h's last when h has its box.
    const Index h_zone = last_hex_joint == 99e6 ? 1 : 0;
    EXPECT_EQ(m.zone_joints, (std::vector<Index>{tet_joints, h_zone})) << what;
  };
  check(10e6, "h without a zone");
  c.bodies[1].zone_material = "strong";
  c.bodies[1].zone_box.emplace(Vec3(0.4, -1, -1), Vec3(1, 1, 1));
  EXPECT_NO_THROW(check(99e6, "h's box over x >= 0.4")) << "h's box must find h's hexes in block 1";
}

// Extrinsic insertion's closed joints (joint/ties.hpp): the copies of a node are tied into one
// point while every face around it is closed.
TEST(Joints, ClosedJointsTieEachNodesCopiesIntoOneGroup) {
  CaseConfig c = simple_case(30e9, 0.2, 2400);
  make_fracturable(c, 3e6, 100, 10e6, 30, 1000);
  Model m = build_model(c, box_mesh(CellType::Tet4, 4, 4, 4, Vec3(0.1, 0.1, 0.1)));
  joint::JointSet& js = m.joints;
  js.closed.assign(js.size(), 1);
  const joint::Ties t = joint::build_ties(js, m.fem.n_nodes);
  // One group per node of the mesh before insertion: its copies, ascending.
  const auto& copies = m.joint_report.copies;
  Index split = 0;
  for (const auto& cp : copies) {
    if (cp.size() < 2) continue;
    ++split;
    const Index g = t.group[cp.front()];
    ASSERT_GE(g, 0);
    std::vector<Index> want = cp, got(t.node.begin() + t.ptr[g], t.node.begin() + t.ptr[g + 1]);
    std::sort(want.begin(), want.end());
    EXPECT_EQ(got, want);
  }
  EXPECT_EQ(t.groups(), split);
  EXPECT_EQ(split, 125);  // the 5 x 5 x 5 nodes of the box

  // One open face frees no node (the closed faces around it still join its copies); all the
  // faces of the plane x = 0.05 open split each of its 25 nodes in two.
  auto on_plane = [&](Index j) { return joint_on_plane(m, j, 0, 0.05); };
  Index first = -1, plane = 0;
  for (Index j = 0; j < js.size(); ++j)
    if (on_plane(j)) first = first < 0 ? j : first, ++plane;
  ASSERT_EQ(plane, 4 * 4 * 2);  // two triangles per cell face
  js.closed[first] = 0;
  EXPECT_EQ(joint::build_ties(js, m.fem.n_nodes).groups(), 125);
  for (Index j = 0; j < js.size(); ++j)
    if (on_plane(j)) js.closed[j] = 0;
  EXPECT_EQ(joint::build_ties(js, m.fem.n_nodes).groups(), 125 + 25);
}

// Extrinsic insertion's step at a state (joint/joint_dt.hpp): a closed joint has no spring
// and the copies it ties are one point, so the step starts at the elements' and falls as
// joints open, to the every-joint-open step when all are.
TEST(Joints, TheStepAtAStateCountsOpenJointsAtTheirPointsMasses) {
  // Two equal hexahedra and their one quadrilateral joint, worked out by hand: closed, each
  // pair of copies on the face is one point and no spring acts, dt = 2 / w_e; open, each
  // copy (mass rho V / 8) carries a quarter of the face's spring k A:
  // dt = 2 / sqrt(w_e^2 + 2 (k A / 4) / (rho V / 8)).
  {
    Model m = two_blocks();
    std::vector<Real> pe;
    element_stable_step(m.fem, m.materials, &pe);
    ASSERT_EQ(pe.size(), 2u);
    ASSERT_NEAR(pe[0], pe[1], 1e-12 * pe[0]);  // equal cubes, to rounding
    const Real we = 2.0 / std::min(pe[0], pe[1]);
    const Real k = joint::max_stiffness(m.joints.params[m.joints.param[0]]);
    const Real A = 0.1 * 0.1, V = 0.1 * 0.1 * 0.1, rho = 2400;
    m.joints.closed.assign(1, 1);
    const joint::Ties closed = joint::build_ties(m.joints, m.fem.n_nodes);
    ASSERT_EQ(closed.groups(), 4);
    const StableStep sc = stable_step(m, pe, &closed);
    EXPECT_DOUBLE_EQ(sc.dt, std::min(pe[0], pe[1]));  // 2 / sqrt((2 / dt)^2): dt to rounding
    EXPECT_EQ(sc.limiter, "element");
    m.joints.closed.assign(1, 0);
    const joint::Ties open = joint::build_ties(m.joints, m.fem.n_nodes);
    ASSERT_EQ(open.groups(), 0);
    const StableStep so = stable_step(m, pe, &open);
    EXPECT_NEAR(so.dt, 2.0 / std::sqrt(we * we + 2 * (k * A / 4) / (rho * V / 8)), 1e-12 * so.dt);
    EXPECT_EQ(so.limiter, "joint");
    EXPECT_EQ(so.dt, stable_step(m).dt);  // every joint open: the step of a run without insertion
  }
  // A tet block: the step only falls as faces open. One open face frees no node (its copies
  // stay tied round it through closed faces), so no spring stretches and the step is the
  // elements'; a plane of open faces splits its nodes, and its springs act on half-points; a
  // second plane lowers it no further than every joint open.
  CaseConfig c = simple_case(30e9, 0.2, 2400);
  make_fracturable(c, 3e6, 100, 10e6, 30, 1000);
  Model m = build_model(c, box_mesh(CellType::Tet4, 4, 4, 4, Vec3(0.1, 0.1, 0.1)));
  ASSERT_FALSE(m.contact.enabled());
  joint::JointSet& js = m.joints;
  std::vector<Real> pe;
  const StableStep elements = element_stable_step(m.fem, m.materials, &pe);
  const Real all_open = stable_step(m).dt;
  auto step_now = [&]() {
    const joint::Ties t = joint::build_ties(js, m.fem.n_nodes);
    return stable_step(m, pe, &t);
  };
  js.closed.assign(js.size(), 1);
  EXPECT_DOUBLE_EQ(step_now().dt, elements.dt);
  Index first = -1;
  for (Index j = 0; j < js.size() && first < 0; ++j)
    if (joint_on_plane(m, j, 0, 0.05)) first = j;
  ASSERT_GE(first, 0);
  js.closed[first] = 0;
  EXPECT_DOUBLE_EQ(step_now().dt, elements.dt);
  for (Index j = 0; j < js.size(); ++j)
    if (joint_on_plane(m, j, 0, 0.05)) js.closed[j] = 0;
  const StableStep one_plane = step_now();
  EXPECT_LT(one_plane.dt, elements.dt);
  EXPECT_EQ(one_plane.limiter, "joint");
  for (Index j = 0; j < js.size(); ++j)
    if (joint_on_plane(m, j, 1, 0.05)) js.closed[j] = 0;
  const StableStep two_planes = step_now();
  EXPECT_LE(two_planes.dt, one_plane.dt);
  EXPECT_GT(two_planes.dt, all_open);
  std::fill(js.closed.begin(), js.closed.end(), 0);
  EXPECT_EQ(step_now().dt, all_open);
}

namespace {
// The top eigenvalue of M^-1 K of a model at a state of extrinsic insertion, assembled: K by
// central differences of the element and joint forces about the reference state (small
// enough that no joint leaves its elastic branch, so K is the linear stiffness), then both
// K and the lumped M restricted to the state's points (a node's tied copies move as one:
// K_t = T^T K T, M_t = T^T M T). A closed joint's springs join copies of one point and drop
// out by themselves. Returns the true stable step 2 / w_max of central differences.
Real assembled_stable_step(const Model& m, const joint::Ties& t) {
  const Index n = m.fem.n_nodes, ndof = 3 * n;
  FemModel fem = m.fem;
  std::vector<Real> x = fem.x0, v(ndof, 0.0);
  auto forces = [&](std::vector<Real>& out) {
    internal_forces(fem, x.data(), v.data(), out.data());
    joint::JointSet js = m.joints;  // a fresh history each time: K is the elastic branch's
    std::fill(js.closed.begin(), js.closed.end(), 0);
    joint::add_joint_forces_reference(js, x.data(), out.data());
  };
  // Point of each node: its tie group, or a point of its own.
  std::vector<Index> point(n);
  Index np = t.groups();
  for (Index i = 0; i < n; ++i) point[i] = t.group[i] >= 0 ? t.group[i] : np++;
  Eigen::MatrixXd K = Eigen::MatrixXd::Zero(3 * np, 3 * np);
  Eigen::VectorXd M = Eigen::VectorXd::Zero(3 * np);
  const Real h = 1e-10;  // [m]: joints stay elastic below f_t / k_n, 3.5e-8 m or more here
  std::vector<Real> fp(ndof), fm(ndof);
  for (Index i = 0; i < n; ++i)
    for (int d = 0; d < 3; ++d) M[3 * point[i] + d] += fem.mass[i];
  // A point's column: every copy of it moved together.
  std::vector<std::vector<Index>> copies(np);
  for (Index i = 0; i < n; ++i) copies[point[i]].push_back(i);
  for (Index p = 0; p < np; ++p)
    for (int d = 0; d < 3; ++d) {
      for (Index i : copies[p]) x[3 * i + d] = fem.x0[3 * i + d] + h;
      forces(fp);
      for (Index i : copies[p]) x[3 * i + d] = fem.x0[3 * i + d] - h;
      forces(fm);
      for (Index i : copies[p]) x[3 * i + d] = fem.x0[3 * i + d];
      for (Index r = 0; r < n; ++r)
        for (int e = 0; e < 3; ++e) K(3 * point[r] + e, 3 * p + d) -= (fp[3 * r + e] - fm[3 * r + e]) / (2 * h);
    }
  const Eigen::MatrixXd S = 0.5 * (K + K.transpose());
  const Eigen::VectorXd s = M.cwiseSqrt().cwiseInverse();
  const Eigen::MatrixXd A = s.asDiagonal() * S * s.asDiagonal();
  const Real w2 = Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd>(A, Eigen::EigenvaluesOnly).eigenvalues().maxCoeff();
  return 2.0 / std::sqrt(w2);
}
}  // namespace

// The estimate of the step at a state against the true step of the assembled system: the
// estimate is a bound (Gershgorin on M^-1 K with each element's eigenvalue bound), so it may
// never exceed the true step, at any state; and the run's floor, the every-joint-open
// estimate, stays below the true step of every state too (the tied state is the open one
// constrained). A tet block of 2 x 2 x 2 cells (48 tetrahedra, 192 copies) is small enough
// for a dense eigenvalue solve.
TEST(Joints, TheStepAtAStateNeverExceedsTheAssembledSystemsStep) {
  CaseConfig c = simple_case(30e9, 0.2, 2400);
  make_fracturable(c, 3e6, 100, 10e6, 30, 1000);
  Model m = build_model(c, box_mesh(CellType::Tet4, 2, 2, 2, Vec3(0.1, 0.1, 0.1)));
  joint::JointSet& js = m.joints;
  std::vector<Real> pe;
  element_stable_step(m.fem, m.materials, &pe);
  const Real floor = stable_step(m).dt;
  struct State {
    const char* name;
    std::function<bool(Index)> open;
  };
  const std::vector<State> states = {
      {"all closed", [](Index) { return false; }},
      {"the plane x = 0.05 open", [&](Index j) { return joint_on_plane(m, j, 0, 0.05); }},
      {"the planes x = 0.05 and y = 0.05 open",
       [&](Index j) { return joint_on_plane(m, j, 0, 0.05) || joint_on_plane(m, j, 1, 0.05); }},
      {"all open", [](Index) { return true; }},
  };
  js.closed.assign(js.size(), 1);
  for (const State& st : states) {
    for (Index j = 0; j < js.size(); ++j) js.closed[j] = st.open(j) ? 0 : 1;
    const joint::Ties t = joint::build_ties(js, m.fem.n_nodes);
    const Real estimate = stable_step(m, pe, &t).dt, exact = assembled_stable_step(m, t);
    RecordProperty(std::string(st.name), fmt::format("estimate {:.4g} s, assembled {:.4g} s", estimate, exact));
    std::printf("%s: estimate %.4g s, assembled %.4g s (ratio %.3f), floor %.4g s\n", st.name, estimate, exact,
                estimate / exact, floor);
    // Rounding: the assembled eigenvalue is good to about 1e-6 (differences over h).
    EXPECT_LE(estimate, exact * (1 + 1e-6)) << st.name;
    EXPECT_LE(floor, exact * (1 + 1e-6)) << st.name;
    // Nor needlessly small: within a factor 2 (measured 0.745-0.91 over these states). A step
    // that leaves out the open faces' springs would fail the first check; one that counted
    // every face's spring while few are open (the old estimate) would fail this one.
    EXPECT_GE(estimate, 0.5 * exact) << st.name;
  }
}

TEST(Joints, ClosedJointsAddNoCompliance) {
  // The block of AddedComplianceWithTheDefaultPenalty relaxed under 1 MPa: with its joints
  // closed it is the block without joints, every node's displacement the same to 1e-9 of
  // the largest with the same step: the two runs may
  // differ only in the order nodal forces are added (per element copy, then per tied group),
  // rounding of 1e-16 per step, against the 1.5 % the open joints' penalty adds.
  const RelaxedBlock plain = relaxed_block(false, 0);
  // The same step: the elements' (the closed joints act on nothing; a run's step falls
  // below it only as they open).
  const RelaxedBlock tied = relaxed_block(true, 100, joint::Quadrature::Gauss, true, plain.dt);
  // Each copy's displacement against its node's in the block without joints.
  Real worst = 0, largest = 0;
  const auto& copies = tied.m.joint_report.copies;
  for (std::size_t n = 0; n < copies.size(); ++n)
    for (int d = 0; d < 3; ++d) {
      const Real u = plain.x[3 * n + d] - plain.m.fem.x0[3 * n + d];
      largest = std::max(largest, std::abs(u));
      for (Index k : copies[n]) worst = std::max(worst, std::abs(tied.x[3 * k + d] - tied.m.fem.x0[3 * k + d] - u));
    }
  EXPECT_GT(largest, 1e-7);  // the block is loaded: 1 MPa over 30 GPa on 0.1 m is 3.3e-6 m
  EXPECT_LE(worst, 1e-9 * largest);
  // Every copy of a group at the same place, to the bit.
  const joint::Ties t = joint::build_ties(tied.m.joints, tied.m.fem.n_nodes);
  ASSERT_EQ(t.groups(), 125);
  for (Index g = 0; g < t.groups(); ++g)
    for (Index q = t.ptr[g] + 1; q < t.ptr[g + 1]; ++q)
      for (int d = 0; d < 3; ++d)
        ASSERT_EQ(tied.x[3 * t.node[q] + d], tied.x[3 * t.node[t.ptr[g]] + d]) << "group " << g;
}

// A free block with all its joints closed moves as the block without joints: tumbling and
// breathing (an initial velocity that spins and stretches it), falling under its weight and
// damped by its mass. No dof is loaded or supported, so the step moves each tied group once,
// at its first copy, and copies that motion (Integrator::step), where a supported block
// (ClosedJointsAddNoCompliance) takes the per-copy passes. Tolerance: the two runs differ in
// the order nodal forces are added (per copy, then per group) and the weight and damping
// sums (per group mass), rounding of 1e-16 per step over 2000 steps; 1e-9 of the motion.
TEST(Joints, AFreeTiedBlockMovesAsTheBlockWithoutJoints) {
  auto build = [](bool joints) {
    CaseConfig c = simple_case(30e9, 0.2, 2400);
    if (joints) make_fracturable(c, 3e6, 100, 10e6, 30, 1000);
    Model m = build_model(c, box_mesh(CellType::Tet4, 3, 3, 3, Vec3(0.1, 0.1, 0.1)));
    if (joints) m.joints.closed.assign(m.joints.size(), 1);
    m.gravity = Vec3(0, -9.81, 0);
    m.fem.node_alpha.assign(m.fem.n_nodes, 200.0);
    for (Index i = 0; i < m.fem.n_nodes; ++i) {
      const Vec3 r = Vec3(m.fem.x0[3 * i], m.fem.x0[3 * i + 1], m.fem.x0[3 * i + 2]) - Vec3(0.05, 0.05, 0.05);
      const Vec3 v = Vec3(1, 2, 3) + Vec3(30, -20, 10).cross(r) + Vec3(20 * r(0), -10 * r(1), 5 * r(2));
      for (int d = 0; d < 3; ++d) m.v0[3 * i + d] = v(d);
    }
    return m;
  };
  Model plain = build(false), tied = build(true);
  const Real dt = 0.9 * critical_dt(plain);
  Integrator ip(plain, dt), itd(tied, dt);
  ASSERT_EQ(itd.ties().groups(), 64);  // the 4 x 4 x 4 nodes of the box
  for (int n = 0; n < 2000; ++n) ip.step(), itd.step();
  Real worst = 0, largest = 0;
  const auto& copies = tied.joint_report.copies;
  for (std::size_t n = 0; n < copies.size(); ++n)
    for (int d = 0; d < 3; ++d) {
      const Real u = ip.x()[3 * n + d] - plain.fem.x0[3 * n + d];
      largest = std::max(largest, std::abs(u));
      for (Index k : copies[n]) {
        worst = std::max(worst, std::abs(itd.x()[3 * k + d] - tied.fem.x0[3 * k + d] - u));
        EXPECT_EQ(itd.v()[3 * k + d], itd.v()[3 * copies[n].front() + d]) << "node " << n;
        EXPECT_EQ(itd.x()[3 * k + d], itd.x()[3 * copies[n].front() + d]) << "node " << n;
      }
    }
  EXPECT_GT(largest, 1e-4);  // it moved: 2000 steps at about 1 m/s
  EXPECT_LE(worst, 1e-9 * largest);
  const Energy ep = ip.energy(), et = itd.energy();
  EXPECT_GT(ep.damping, 1e-3 * ep.largest());  // the damping is at work
  for (auto [a, b] : {std::pair{ep.kinetic, et.kinetic}, std::pair{ep.internal, et.internal},
                      std::pair{ep.damping, et.damping}, std::pair{ep.external_work, et.external_work}})
    EXPECT_NEAR(b, a, 1e-9 * ep.largest());
  // The ledger's own error (the lagged damping's, 1e-3 here) is the block's, not the ties'.
  EXPECT_NEAR(et.balance_error(), ep.balance_error(), 1e-9);
}

namespace {
// The bar of break_bar with extrinsic joints (penalty 1: it acts only once a face opens):
// {fracture energy / (G_fI x broken area), broken area, largest ledger error, opened joints,
// the step over the intrinsic bar's (penalty 100)}.
// The hex bar of break_bar (G_fI 100, nodal joints), fixed at x = 0 and pulled slowly at
// x = L; extrinsic: its joints start closed.
Model pulled_bar(int n, bool mode_i, bool extrinsic, Real penalty) {
  CaseConfig c = simple_case(30e9, 0.2, 2400, Kinematics::SmallStrain);
  make_fracturable(c, 3e6, 100, 10e6, 30, 1000, penalty);
  c.joint_materials[0].nodal_quadrature = true;
  c.joint_materials[0].mode_i = mode_i;
  c.bodies[0].extrinsic = extrinsic;
  c.boundaries.push_back(fixed("xmin"));
  c.boundaries.push_back(slow_pull());
  return build_model(c, box_mesh(CellType::Hex8, n, 1, 1, Vec3(0.1, 0.02, 0.02)));
}

struct ExtrinsicBar {
  Real ratio, area, balance, dt_ratio;
  Index opened, broken;
};
ExtrinsicBar break_bar_extrinsic(int n, bool mode_i, Real penalty) {
  const Real GfI = 100;
  auto bar = [&](bool extrinsic) { return pulled_bar(n, mode_i, extrinsic, extrinsic ? penalty : 100); };
  const Real dt_intrinsic = critical_dt(bar(false));
  Model m = bar(true);
  EXPECT_EQ(std::count(m.joints.closed.begin(), m.joints.closed.end(), 1), n - 1);
  const Real dt = critical_dt(m);
  Integrator it(m, 0.9 * dt);
  ExtrinsicInsertion ins(1, joint::FaceStress::Larger);
  Real balance = 0;
  while (it.energy().broken_joints == 0 && it.time() < 0.05) {
    it.step();
    ins.check(m, it);
    balance = std::max(balance, std::abs(it.energy().balance()) / (GfI * 0.02 * 0.02));
  }
  const Energy e = it.energy();
  return {(e.fracture_I + e.fracture_II) / (GfI * e.crack_area),
          e.crack_area,
          balance,
          dt / dt_intrinsic,
          ins.opened(),
          e.broken_joints};
}

// A 0.1 m tet block (8x8x8 cells, 3072 tets, some 6000 joints: the parallel paths run),
// its coupled nodal joints (f_t 3 MPa, G_fI 10, penalty 1) closed until their faces reach
// the strength. Supports and loads are the caller's.
CaseConfig extrinsic_tet_block() {
  CaseConfig c = simple_case(30e9, 0.2, 2400, Kinematics::SmallStrain);
  make_fracturable(c, 3e6, 10, 6e6, 30, 100, 1);
  c.joint_materials[0].nodal_quadrature = true;
  c.joint_materials[0].coupled = true;
  c.bodies[0].extrinsic = true;
  return c;
}
Mesh extrinsic_tet_block_mesh() { return box_mesh(CellType::Tet4, 8, 8, 8, Vec3(0.1, 0.1, 0.1), 0.2); }
// The block fixed at x = 0 and its face x = 0.1 m moved at velocity v.
Model pulled_extrinsic_tet_block(const Vec3& v) {
  CaseConfig c = extrinsic_tet_block();
  c.boundaries.push_back(fixed("xmin"));
  BoundaryConfig pull;
  pull.type = BoundaryConfig::Type::Velocity, pull.group = "xmax", pull.value = v;
  c.boundaries.push_back(pull);
  return build_model(c, extrinsic_tet_block_mesh());
}
}  // namespace

TEST(Joints, BarWithExtrinsicJointsBreaksDissipatingGfTimesArea) {
  // The bar pulled slowly, its faces closed until the traction reaches f_t. As the stress is
  // uniform, several faces reach it within a few steps and open; one softens and breaks, the
  // others close again. The broken one dissipates G_fI x area (its law starts on its softening
  // branch, whose area is G_fI). A face that opened and closed again gives back the elastic
  // energy of the branch its law skipped, f_t^2 / (2 k_n) per area, which no work paid for:
  // the known cost of starting the law at its elastic limit, small where the penalty k_n = p
  // E / h is stiff against the face's f_t^2 / G_fI. With p = 10 on this coarse bar (h = 25 or
  // 12.5 mm) it is 0.4 % or 0.2 % of G_fI per face, so the total stays within 2 % (the
  // intrinsic bar's tolerance); with p = 1 it is 3.75 % or 1.9 % per face, and the deficit
  // must be what that bound says. The ledger closes within 1 % of G_fI x area through the
  // insertions (they make no energy in it), and the step is near sqrt(100 / 10) = 3.2 times the
  // intrinsic bar's (penalty 100), where the joints set the step.
  const Real ft = 3e6, E = 30e9, GfI = 100;
  for (bool mode_i : {true, false})
    for (int n : {4, 8})
      for (Real p : {10.0, 1.0}) {
        const ExtrinsicBar b = break_bar_extrinsic(n, mode_i, p);
        const std::string what = fmt::format("{} cells, {}, penalty {:g}", n, mode_i ? "mode I" : "paper law", p);
        RecordProperty(fmt::format("cells_{}_{}_p{:g}", n, mode_i ? "mode_I" : "paper", p),
                       fmt::format("ratio={:.5f} opened={} balance={:.2e} dt_ratio={:.2f}", b.ratio, b.opened,
                                   b.balance, b.dt_ratio));
        EXPECT_EQ(b.broken, 1) << what;
        EXPECT_NEAR(b.area, 0.02 * 0.02, 1e-12) << what;
        EXPECT_LT(b.balance, 0.01) << what;
        const Real e0 = ft * ft * (0.1 / n) / (2 * p * E) / GfI;  // per reclosed face, over G_fI
        EXPECT_GT(b.ratio, 1.0 - static_cast<Real>(b.opened - 1) * e0 - 0.02) << what;
        EXPECT_LT(b.ratio, 1.02) << what;
        if (p == 10.0) {
          EXPECT_NEAR(b.ratio, 1.0, 0.02) << what;
          EXPECT_GT(b.dt_ratio, 2.5) << what;
        }
      }
}

TEST(Joints, ExtrinsicInsertionIsTheSameOnOneAndTwoThreads) {
  // A tet block (3072 tets, some 6000 closed joints: the parallel paths run) pulled apart
  // fast enough that faces open, soften and break within a few hundred steps: positions,
  // the joints opened and the ledger the same to the bit on 1 and 2 threads, with the crack
  // front cut (the default) and tied.
  for (InsertionFront front : {InsertionFront::Cut, InsertionFront::Tied}) {
    auto run = [front](int threads) {
      omp_set_num_threads(threads);
      Model m = pulled_extrinsic_tet_block(Vec3(2.0, 0.3, 0));
      Integrator it(m, 0.9 * critical_dt(m));
      ExtrinsicInsertion ins(1, joint::FaceStress::Larger, front);
      for (int s = 0; s < 400; ++s) {
        it.step();
        ins.check(m, it);
      }
      return std::make_tuple(it.x(), ins.opened(), it.energy().broken_joints, it.energy().balance());
    };
    const auto [x1, opened1, broken1, bal1] = run(1);
    const auto [x2, opened2, broken2, bal2] = run(2);
    EXPECT_GT(opened1, 100);
    EXPECT_GT(broken1, 0);
    EXPECT_EQ(opened1, opened2);
    EXPECT_EQ(broken1, broken2);
    EXPECT_EQ(bal1, bal2);
    ASSERT_EQ(x1.size(), x2.size());
    for (std::size_t k = 0; k < x1.size(); ++k) ASSERT_EQ(x1[k], x2[k]) << "dof " << k;
  }
}

TEST(Joints, AFreeExtrinsicBlockIsTheSameOnOneAndTwoThreadsAndOnEitherPath) {
  // The block of ExtrinsicInsertionIsTheSameOnOneAndTwoThreads unsupported, torn apart by
  // its initial velocity (a stretch along x, 100 1/s), mass-damped and falling: no dof is
  // loaded or supported, so its step moves each tied group once (Integrator::step), in
  // passes of several chunks of groups and of nodes (729 groups, 12288 copies). The same
  // to the bit on 1 and 2 threads, and as the per-copy path, which a zero load on one copy
  // forces: both add each copy's damping and weight, then sum a group's copies in copy order.
  auto run = [](int threads, bool zero_load) {
    omp_set_num_threads(threads);
    CaseConfig c = extrinsic_tet_block();
    Model m = build_model(c, extrinsic_tet_block_mesh());
    m.gravity = Vec3(0, -9.81, 0);
    m.fem.node_alpha.assign(m.fem.n_nodes, 100.0);
    for (Index i = 0; i < m.fem.n_nodes; ++i) m.v0[3 * i] = 100 * (m.fem.x0[3 * i] - 0.05);
    for (const auto& cp : m.joint_report.copies)  // on a copy of a node with several
      if (zero_load && cp.size() > 1) {
        m.loads.push_back({3 * cp.back() + 1, 0.0, 0.0});
        break;
      }
    Integrator it(m, 0.9 * critical_dt(m));
    ExtrinsicInsertion ins(1, joint::FaceStress::Larger);
    const Index groups0 = it.ties().groups();
    for (int s = 0; s < 400; ++s) {
      it.step();
      ins.check(m, it);
    }
    return std::make_tuple(it.x(), it.v(), ins.opened(), groups0, it.ties().groups());
  };
  const auto [x1, v1, opened1, g0, g1] = run(1, false);
  EXPECT_EQ(g0, 729);
  EXPECT_GT(opened1, 100);
  EXPECT_NE(g1, g0);  // groups split or came apart: the passes ran over changing groups
  for (auto [threads, zero_load] : {std::pair{2, false}, std::pair{1, true}, std::pair{2, true}}) {
    const auto [x, v, opened, unused0, groups] = run(threads, zero_load);
    EXPECT_EQ(opened, opened1) << threads << " thread(s), zero load " << zero_load;
    EXPECT_EQ(groups, g1);
    ASSERT_EQ(x.size(), x1.size());
    for (std::size_t k = 0; k < x1.size(); ++k) {
      ASSERT_EQ(x[k], x1[k]) << "dof " << k << ", " << threads << " thread(s), zero load " << zero_load;
      ASSERT_EQ(v[k], v1[k]) << "dof " << k << ", " << threads << " thread(s), zero load " << zero_load;
    }
  }
}

TEST(Joints, InsertionKeepsTheTractionAndMakesNoEnergy) {
  // The bar of BarWithExtrinsicJointsBreaksDissipatingGfTimesArea (mode I, penalty 10, 4
  // cells): at the step a face opens, its joint starts with the face's normal traction, and
  // one step later (the face now free to open) the joint carries it still, within 1 % (one
  // step of loading at 0.01 m/s moves the traction by far less; a jump to the softened or
  // to zero traction would be 100 %). The opening itself changes no term of the ledger's
  // balance but the kick's (the law's skipped elastic energy is booked with an equal
  // negative dissipation).
  Model m = pulled_bar(4, true, true, 10);
  Integrator it(m, 0.9 * critical_dt(m));
  ExtrinsicInsertion ins(1, joint::FaceStress::Larger);
  Index j = -1;
  Real tn = 0;
  while (j < 0 && it.time() < 0.05) {
    it.step();
    const Energy before = it.energy();
    if (ins.check(m, it) == 0) continue;
    // The kick's term follows the forces, which the opened face changes at the same
    // positions: the next step's kick applies them (Energy::kick). Every other term holds.
    const Energy e = it.energy();
    EXPECT_NEAR(e.balance() + e.kick, before.balance() + before.kick, 1e-12 * e.largest());
    for (Index k = 0; k < m.joints.size() && j < 0; ++k)
      if (!m.joints.closed[k]) j = k;
    tn = m.joints.point_state(4 * static_cast<std::size_t>(j)).sn;
    EXPECT_NEAR(tn / 3e6, 1.0, 0.01);  // opened at f_t (within the step's increment)
  }
  ASSERT_GE(j, 0) << "no face opened";
  it.step();
  ins.check(m, it);
  for (int g = 0; g < 4; ++g)
    EXPECT_NEAR(m.joints.point_state(4 * static_cast<std::size_t>(j) + g).sn / tn, 1.0, 0.01) << "point " << g;
}

TEST(Joints, ACutFrontFreesEveryOpenedFaceWithoutAJumpOrEnergy) {
  // The tet block of ExtrinsicInsertionIsTheSameOnOneAndTwoThreads pulled along x, checked
  // until a check opens faces. Tied, some of those faces keep nodes tied across them (their
  // neighbours still closed), so they cannot open. Cut (time.insertion_front = "cut"): after
  // the same check no face opened by its onset has a node tied across it; the faces opened to
  // free them are below their onset, freed at one node at least, and start with the normal
  // and the shear traction they carried (the two elements' mean: no jump, to rounding; the
  // shear as a vector, at the joints' first update); the check changes
  // no term of the ledger's balance but the kick's (the skipped elastic energy is booked
  // against dissipation).
  // (The stresses read after the check are evaluated again from the same positions: the
  // elastic stresses depend on them only.)
  auto run = [](InsertionFront front, auto&& inspect) {
    Model m = pulled_extrinsic_tet_block(Vec3(0.5, 0, 0));
    Integrator it(m, 0.9 * critical_dt(m));
    ExtrinsicInsertion ins(1, joint::FaceStress::Larger, front);
    while (it.time() < 1e-3) {
      it.step();
      const std::vector<char> was = m.joints.closed;
      const Energy e0 = it.energy();
      if (ins.check(m, it) == 0) continue;
      // The kick's term follows the forces, which the opened faces change at the same
      // positions: the next step's kick applies them (Energy::kick). Every other term holds.
      const Energy e = it.energy();
      EXPECT_NEAR(e.balance() + e.kick, e0.balance() + e0.kick, 1e-12 * e.largest());
      inspect(m, it, ins, was);
      return;
    }
    FAIL() << "no face opened";
  };
  auto tied_across = [](const Model& m, const Integrator& it, Index j) {
    const auto& g = it.ties().group;
    int n = 0;
    for (int k = 0; k < m.joints.npf[j]; ++k) {
      const Index a = m.joints.a[4 * j + k], b = m.joints.b[4 * j + k];
      n += g[a] >= 0 && g[a] == g[b];
    }
    return n;
  };
  int tied_nodes = 0;
  run(InsertionFront::Tied, [&](Model& m, Integrator& it, const ExtrinsicInsertion&, const std::vector<char>& was) {
    for (Index j = 0; j < m.joints.size(); ++j)
      if (was[j] && !m.joints.closed[j]) tied_nodes += tied_across(m, it, j);
  });
  EXPECT_GT(tied_nodes, 0);
  run(InsertionFront::Cut, [&](Model& m, Integrator& it, const ExtrinsicInsertion& ins, const std::vector<char>& was) {
    std::vector<Real> stress;
    it.stresses(stress);
    const Real* x = it.x().data();
    const joint::JointSet& js = m.joints;
    // The joints' first update at these positions (on a copy): an opened face's own jump is
    // zero (its sides still coincide), so its points' slip is the offset alone, measured on the
    // frame the kernel builds from both sides' nodes.
    joint::JointSet probe = js;
    std::vector<Real> fprobe(it.x().size(), 0.0), slots;
    joint::add_joint_forces(probe, x, fprobe.data(), slots);
    Real ts_largest = 0;
    Index by_onset = 0, forced = 0;
    for (Index j = 0; j < js.size(); ++j) {
      if (!was[j] || js.closed[j]) continue;
      const Vec3 p0 = node_pos_ptr(x, js.a[4 * j]), p1 = node_pos_ptr(x, js.a[4 * j + 1]),
                 p2 = node_pos_ptr(x, js.a[4 * j + 2]);
      const Vec3 n = (p1 - p0).cross(p2 - p0).normalized();
      const Real* sa = &stress[6 * static_cast<std::size_t>(js.ea[j])];
      const Real* sb = &stress[6 * static_cast<std::size_t>(js.eb[j])];
      if (joint::face_onset(js.params[js.param[j]], sa, sb, n, joint::FaceStress::Larger).ratio >= 1) {
        ++by_onset;  // its own law: free to open at every node
        EXPECT_EQ(tied_across(m, it, j), 0) << "joint " << j;
        continue;
      }
      // Opened to free a front: below its onset, still on its elastic branch, at the mean
      // traction, and freed at one node at least.
      ++forced;
      EXPECT_LT(joint::face_onset(js.params[js.param[j]], sa, sb, n, joint::FaceStress::Mean).ratio, 1)
          << "joint " << j;
      EXPECT_LT(tied_across(m, it, j), js.npf[j]) << "joint " << j;
      EXPECT_NEAR(js.point_state(4 * static_cast<std::size_t>(j)).sn, joint::face_traction(sa, sb, n).tn, 1e-9 * 3e6)
          << "joint " << j;
      // And the shear traction it carried, as a vector: at its first update each point's law
      // gives k_s times the slip the kernel measures, which must be the mean traction's shear
      // part (a frame at insertion other than the kernel's would turn it; a sign slip would
      // reverse it). Tolerance: rounding of tractions of some MPa.
      const Vec3 t = joint::face_traction_vector(sa, sb, n), ts = t - t.dot(n) * n;
      ts_largest = std::max(ts_largest, ts.norm());
      Vec3 xm[3];
      for (int k = 0; k < 3; ++k) xm[k] = 0.5 * (node_pos_ptr(x, js.a[4 * j + k]) + node_pos_ptr(x, js.b[4 * j + k]));
      const joint::FaceFrame frame(joint::FaceFrame::line(3, xm), n);
      const Real ks = js.params[js.param[j]].ks;
      for (int g = 0; g < 3; ++g) {
        const joint::CohesiveState st = probe.point_state(4 * static_cast<std::size_t>(j) + g);
        EXPECT_EQ(st.status, joint::JointStatus::Intact) << "joint " << j;  // below its onset: elastic
        EXPECT_LT((ks * frame.vector(st.su, st.sv) - ts).norm(), 1e-9 * 3e6) << "joint " << j << ", point " << g;
        EXPECT_NEAR(st.ss, ts.norm(), 1e-9 * 3e6) << "joint " << j << ", point " << g;
      }
    }
    EXPECT_GT(ts_largest, 0.1 * 3e6);  // the faces opened carried shear worth testing
    EXPECT_GT(by_onset, 0);
    EXPECT_GT(forced, 0);
    EXPECT_EQ(forced, ins.forced());
    EXPECT_EQ(by_onset + forced, ins.opened());
  });
}
