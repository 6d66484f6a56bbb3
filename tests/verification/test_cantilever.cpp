// Static tip deflection of a cantilever by dynamic relaxation, against Timoshenko beam
// theory: delta = P L^3 / (3 E I) + P L / (k G A), k = 5/6 (rectangle, nu = 0). nu = 0 so
// that the fully clamped end imposes no lateral (Poisson) restraint that beam theory lacks.
// Mass-proportional damping at twice the first bending frequency damps every mode at the
// rate of critical damping of mode 1. Tolerance 3 % (the issue's).
#include <gtest/gtest.h>

#include "support/run_helpers.hpp"

using namespace dspdem;
using namespace dspdem::testsupport;

namespace {
struct Result {
  Real deflection, reference;
};

Result cantilever(CellType type, int nx, int ny, int nz, Real L, Real H) {
  const Real E = 30e9, rho = 2400, P = 1e3;
  CaseConfig c = simple_case(E, 0.0, rho, Kinematics::SmallStrain);
  const Real I = H * H * H * H / 12, A = H * H, G = E / 2;
  const Real w1 = 3.516 * std::sqrt(E * I / (rho * A * L * L * L * L));
  c.materials[0].alpha = 2 * w1;
  c.boundaries.push_back(fixed("xmin"));
  BoundaryConfig load;
  load.type = BoundaryConfig::Type::Force;
  load.group = "xmax";
  load.value = Vec3(0, -P, 0);
  load.ramp = 2.0 / w1;
  c.boundaries.push_back(load);
  Model m = build_model(c, box_mesh(type, nx, ny, nz, Vec3(L, H, H)));
  Integrator it(m, 0.9 * critical_dt(m));
  const Group& tip = *m.mesh.find_group("xmax");
  while (it.time() < load.ramp + 12.0 / w1) it.step();
  Real uy = 0;
  for (Index n : tip.nodes) uy += it.x()[3 * n + 1] - m.fem.x0[3 * n + 1];
  uy /= static_cast<Real>(tip.nodes.size());
  return {-uy, P * L * L * L / (3 * E * I) + P * L / (5.0 / 6.0 * G * A)};
}
}  // namespace

TEST(Cantilever, Hex8_20x2x2) {
  // Two elements through the depth: one-point integration with incompatible-mode
  // stabilisation does not lock.
  const Result r = cantilever(CellType::Hex8, 20, 2, 2, 1.0, 0.1);
  RecordProperty("deflection_over_theory", fmt::format("{:.5f}", r.deflection / r.reference));
  EXPECT_NEAR(r.deflection / r.reference, 1.0, 0.03) << "tip " << r.deflection << " vs " << r.reference;
}

TEST(Cantilever, Tet4_60x12x12) {
  // Linear tets are stiff in bending; L/H = 5, 60 x 12 x 12 cells x 6 tets = 51840: measured 2.3 % low
  // (30x6x6: 8.7 %, 60x6x6: 6.1 %, 30x12x12: 5.2 % low; hex8 20x2x2: 0.16 % low).
  const Result r = cantilever(CellType::Tet4, 60, 12, 12, 0.5, 0.1);
  RecordProperty("deflection_over_theory", fmt::format("{:.5f}", r.deflection / r.reference));
  EXPECT_NEAR(r.deflection / r.reference, 1.0, 0.03) << "tip " << r.deflection << " vs " << r.reference;
}
