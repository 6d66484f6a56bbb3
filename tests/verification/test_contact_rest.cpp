// Contacts that come to rest (issue 21), with the case file's default contact settings
// (read from a case file, so a change of default is tested here): a block sliding down
// inclines a little steeper than its friction angle accelerates at g (sin - mu cos), on a
// plane and over a meshed slab, a block put on a floor comes to rest and carries its
// weight, and the energy ledger closes.
//
// The block is deformable, 2 x 2 x 2 hexahedra of 0.1 m (over the meshed slab: 48
// tetrahedra), E = 1e7 Pa, rho = 1000 kg/m^3, with
// stiffness-proportional body damping beta = 3e-5 s: 4.7 % of critical at 500 Hz, the
// block's first axial mode (c / 2L = 100 m/s / 0.2 m), the order of a rock's or concrete's
// material damping. Without body damping nothing damps the block's own modes: the contacts
// set it ringing, it touches in part of every period only, and slides 4-33 % too fast
// whatever the contact damping (measured up to 0.3 of critical; cases/README.md).
#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <fstream>

#include "contact/restitution.hpp"
#include "io/case_config.hpp"
#include "support/run_helpers.hpp"
#include "support/scene.hpp"

using namespace dspdem;
using namespace dspdem::testsupport;

namespace {
namespace fs = std::filesystem;
constexpr Real kE = 1e7, kNu = 0.25, kRho = 1000, kSide = 0.1, kG = 9.81, kBeta = 3e-5;

/// The contact settings of a case file that gives only the friction coefficient.
contact::ContactMaterial default_contact(Real mu) {
  // One file per process and test: ctest runs the tests of this file side by side.
  const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
  const fs::path p = fs::temp_directory_path() / fmt::format("dspdem_contact_rest_{}_{}.toml", getpid(), info->name());
  std::ofstream(p) << "[case]\nname = \"t\"\n[mesh]\nfile = \"box.msh\"\n[materials.rock]\ndensity = 1000.0\n"
                   << "E = 1.0e7\nnu = 0.25\nfriction = " << mu << "\n[[bodies]]\nname = \"b\"\ngroups = [\"all\"]\n"
                   << "material = \"rock\"\n[contact]\nenabled = true\n[time]\nend = 1.0\n";
  const contact::ContactMaterial cm = read_case(p.string()).contact_materials.at(0);
  fs::remove(p);
  return cm;
}

struct Slide {
  Real accel_ratio;           ///< mean acceleration along the slope / g (sin - mu cos)
  Real ledger;                ///< largest balance error over the run
  Real force_min, force_max;  ///< floor force / weight over the window
  Real kinetic;               ///< at the end [J]
  Real travel;                ///< mean displacement of the block's nodes along x at the end [m]
};

/// What the block slides on: the plane wall z = 0, or a fixed tetrahedral slab whose top is
/// z = 0 (a body of its own, 1.2 m x 0.4 m in cells of 50 mm, each of six tetrahedra), so
/// that the block's contacts pass from element to element and from face to edge.
enum class Floor { Plane, MeshedSlab };

/// The block on the floor under gravity tilted by theta (the slope's frame), starting
/// `lift` above it, at rest or sliding at v0 along x; mean acceleration along x over [t1, t2].
Slide run(Real theta_deg, Real mu, Real t1, Real t2, Real lift, Floor floor = Floor::Plane, Real v0 = 0,
          CellType block = CellType::Hex8) {
  Mesh mesh;
  add_part(mesh, cube(block, 2, kSide), "block", Vec3::Constant(kSide / 2), Vec3(0, 0, kSide / 2 + lift));
  CaseConfig c = simple_case(kE, kNu, kRho, Kinematics::Corotational);
  c.contact.enabled = true;
  c.contact_materials = {default_contact(mu)};
  c.materials[0].beta = kBeta;
  if (floor == Floor::Plane) {
    WallConfig w;
    w.wall.name = "slope";
    w.wall.type = contact::Wall::Type::Plane;
    c.walls.push_back(w);
  } else {
    add_part(mesh, box_mesh(CellType::Tet4, 24, 8, 1, Vec3(1.2, 0.4, 0.05)), "slab", Vec3(0.6, 0.2, 0.025),
             Vec3(0.533, 0.013, -0.025));
    c.boundaries.push_back(fixed("slab"));
  }
  const Real th = theta_deg * M_PI / 180;
  c.gravity = kG * Vec3(std::sin(th), 0, -std::cos(th));
  InitialConfig ic;
  ic.group = "block";
  ic.velocity = Vec3(v0, 0, 0);
  c.initial = {ic};
  Model m = build_model(c, mesh);
  Integrator it(m, 0.9 * critical_dt(m));
  const Group* g = m.mesh.find_group("block");
  auto mean_vx = [&] {
    Real s = 0;
    for (Index n : g->nodes) s += it.v()[3 * n];
    return s / static_cast<Real>(g->nodes.size());
  };
  const Real weight = kRho * std::pow(kSide, 3) * kG * std::cos(th);
  Slide out{0, 0, 1e30, -1e30, 0, 0};
  Real v1 = 0, tt1 = 0;
  bool started = false;
  while (it.time() < t2) {
    it.step();
    // Sampled every 10 steps after the first millisecond (before it every term is near 0).
    if (it.steps() % 10 == 0 && it.time() > 1e-3) out.ledger = std::max(out.ledger, it.energy().balance_error());
    if (!started && it.time() >= t1) started = true, v1 = mean_vx(), tt1 = it.time();
    if (started && floor == Floor::Plane) {
      const Real fz = -m.contact.walls()[0].force(2) / weight;
      out.force_min = std::min(out.force_min, fz), out.force_max = std::max(out.force_max, fz);
    }
  }
  const Real a = (mean_vx() - v1) / (it.time() - tt1), a_ref = kG * (std::sin(th) - mu * std::cos(th));
  out.accel_ratio = a_ref != 0 ? a / a_ref : a;
  out.kinetic = it.energy().kinetic;
  for (Index n : g->nodes) out.travel += (it.x()[3 * n] - m.fem.x0[3 * n]) / static_cast<Real>(g->nodes.size());
  return out;
}
}  // namespace

// The default is a damped contact: restitution 0.8 (cases/README.md says why not lower).
TEST(ContactRest, TheDefaultContactIsDampedToRestitutionPointEight) {
  EXPECT_NEAR(default_contact(0.5).damping_ratio, contact::damping_for_restitution(0.8), 1e-12);
  EXPECT_GT(default_contact(0.5).damping_ratio, 0.07);
}

// Three (mu, angle above the friction angle) pairs within 3 degrees: the block accelerates
// within 2 % of g (sin - mu cos) over 0.05-0.15 s (measured 0.25-0.52 %), the floor carries
// its weight within 15 % at every step, and the ledger closes within 0.5 % (measured 0.7-1.6e-3).
TEST(ContactRest, BlockSlidesDownInclinesAtCoulombAcceleration) {
  for (auto [mu, above] : {std::pair{0.3, 1.0}, {0.5, 2.0}, {0.7, 3.0}}) {
    SCOPED_TRACE(fmt::format("mu {} angle {} deg above the friction angle", mu, above));
    const Real theta = std::atan(mu) * 180 / M_PI + above;
    const Slide s = run(theta, mu, 0.05, 0.15, 0.0);
    RecordProperty(fmt::format("accel_ratio_mu{}", mu), sci(s.accel_ratio));
    RecordProperty(fmt::format("ledger_mu{}", mu), sci(s.ledger));
    EXPECT_NEAR(s.accel_ratio, 1.0, 0.02);
    EXPECT_LT(s.ledger, 5e-3);
    EXPECT_GT(s.force_min, 0.85);
    EXPECT_LT(s.force_max, 1.15);
  }
}

// Put on a floor (touching, at rest) the block settles: after 0.3 s the floor force equals
// its weight within 0.1 % and its kinetic energy is below 1e-12 of m g L (measured 3e-22);
// the ledger closes within 0.5 % (measured 1.9e-4).
TEST(ContactRest, BlockPutOnAFloorComesToRest) {
  const Slide s = run(0.0, 0.5, 0.3, 0.5, 0.0);
  RecordProperty("ledger", sci(s.ledger));
  RecordProperty("kinetic", sci(s.kinetic));
  EXPECT_NEAR(s.force_min, 1.0, 1e-3);
  EXPECT_NEAR(s.force_max, 1.0, 1e-3);
  EXPECT_LT(s.kinetic, 1e-12 * kRho * std::pow(kSide, 4) * kG);
  EXPECT_LT(s.ledger, 5e-3);
}

// A rigid block dropped 1 mm onto a floor with elastic contacts bounces back to where it
// started, so at the top of every bounce each term of the ledger is near 0 again. The
// balance error is then measured against the largest work done so far (Energy::peak_work):
// before that it read 0.92 there (at 0.45 of the critical step 1.97), 2e-7 J of rounding
// and impact error over terms of 2e-7 J. Measured now: at most 1.2e-2 (the contact
// springs' part of Velocity Verlet's kinetic energy during an impact, gone after it).
TEST(ContactRest, BouncingRigidBlockIsJudgedAgainstTheEnergyItExchanged) {
  Mesh mesh;
  add_part(mesh, cube(CellType::Hex8, 2, kSide), "block", Vec3::Constant(kSide / 2), Vec3(0, 0, kSide / 2 + 1e-3));
  CaseConfig c = simple_case(kE, kNu, kRho, Kinematics::Rigid);
  c.contact.enabled = true;
  contact::ContactMaterial cm;  // elastic, frictionless
  cm.friction = 0;
  c.contact_materials = {cm};
  WallConfig w;
  w.wall.name = "floor";
  w.wall.type = contact::Wall::Type::Plane;
  c.walls.push_back(w);
  c.gravity = Vec3(0, 0, -kG);
  Model m = build_model(c, mesh);
  Integrator it(m, 0.9 * critical_dt(m));
  Real worst = 0;
  int tops = 0;
  Real vz_prev = 0;
  while (it.time() < 0.5) {
    it.step();
    if (it.time() > 1e-3) worst = std::max(worst, it.energy().balance_error());
    const Real vz = it.v()[2];
    if (vz_prev > 0 && vz <= 0) ++tops;  // the top of a bounce
    vz_prev = vz;
  }
  RecordProperty("worst", sci(worst));
  EXPECT_GE(tops, 3) << "the block must bounce";
  EXPECT_LT(worst, 2e-2);
  EXPECT_LT(it.energy().balance_error(), 2e-3);
}

// The same slide over a meshed floor: a tetrahedral block, sliding at 1 m/s, over a fixed
// slab of tetrahedra in 50 mm cells, set off the block's grid by 17 mm along and 13 mm
// across the slope so that the block's vertices slide over the slab's faces and cross its
// edges and seams rather than run along them. Its contacts pass from element to element of the slab and between
// feature pairs (a vertex on a face, on an edge, ...) many times a cell; a tangential force
// that dropped there, or a floor that caught the block's vertices at the seams of its
// elements' rounded edges, would slow or speed the block against Coulomb. Over the run it
// travels more than four cells, and over 0.05-0.25 s it must accelerate as on the plane,
// within the plane test's 2 % (measured 0.2-1.0 %); the ledger closes within 0.5 % (measured
// 5.5e-4 to 7.3e-4).
TEST(ContactRest, BlockSlidingOverAMeshedSlabAcceleratesAsOnAPlane) {
  for (auto [mu, above] : {std::pair{0.3, 1.0}, {0.5, 2.0}, {0.7, 3.0}}) {
    SCOPED_TRACE(fmt::format("mu {} angle {} deg above the friction angle", mu, above));
    const Real theta = std::atan(mu) * 180 / M_PI + above;
    const Slide s = run(theta, mu, 0.05, 0.25, 0.0, Floor::MeshedSlab, 1.0, CellType::Tet4);
    RecordProperty(fmt::format("accel_ratio_mu{}", mu), sci(s.accel_ratio));
    RecordProperty(fmt::format("ledger_mu{}", mu), sci(s.ledger));
    RecordProperty(fmt::format("travel_mu{}", mu), sci(s.travel));
    EXPECT_GT(s.travel, 4 * 0.05);
    EXPECT_NEAR(s.accel_ratio, 1.0, 0.02);
    EXPECT_LT(s.ledger, 5e-3);
  }
}
