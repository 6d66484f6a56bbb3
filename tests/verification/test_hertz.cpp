// Hertz impact (Johnson, Contact Mechanics, 1985, sec. 11.4): a meshed elastic sphere hits
// a rigid plane (a contact wall) and rebounds. The contact duration must match the
// quasi-static Hertz estimate t_c = 2.87 (m^2 / (R E*^2 v))^(1/5), E* = E / (1 - nu^2),
// within 10 %; peak force and rebound coefficient are reported.
//
// Parameters: R = 0.05 m, E = 1e7 Pa, nu = 0.3, rho = 1000 kg/m^3, v = 0.5 m/s, so
//   t_c = 7.07 ms = 7 x the longitudinal transit time 2R/c = 1 ms (c = sqrt(E/rho)):
//     the impact is quasi-static, as Hertz assumes (v/c = 0.005);
//   delta_max = 1.2 mm, a = sqrt(R delta_max) = 7.7 mm = 0.155 R: small contact, small strain.
// Mesh: linear tetrahedra graded from a/4 (1.9 mm, 8 elements across the contact
// diameter) at the contact pole by 0.05 per unit distance up to R/8 (6.25 mm): 27.9k
// elements. The step (1.56 us, 5.2k steps) is set by the contact springs of the smallest
// surface elements, about half the element limit.
//
// Why 10 % holds: the contact time goes as (contact stiffness)^(-2/5), so it forgives
// stiffness errors. Linear tetrahedra are too stiff and shorten the contact; with this
// grading and all sizes scaled by s (penalty 10) t_c / Hertz was
//   s = 1.25: 14k elements, 0.935;  s = 1: 28k, 0.947;  s = 0.79: 55k, 0.954,
// converging about as h^1.5 towards ~0.97; the remaining ~3 % we attribute to Hertz's
// half-space idealisation of a finite sphere at a/R = 0.155 (not separated further).
// Refining only within 2a of the pole (R/5 elsewhere, 2.7k elements) gave 0.875: the far
// field carries a good part of the approach. The penalty overlap adds little compliance:
// penalty 10 -> 4 lengthened t_c by 0.5 %. So the measured 0.947 has a margin of about
// 5 %. The peak force is 8 % above Hertz's, consistent with the same stiffness excess
// (F_max ~ stiffness^(2/5)).
#include <gmsh.h>
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "mesh/gmsh_reader.hpp"
#include "support/run_helpers.hpp"

using namespace dspdem;
using namespace dspdem::testsupport;

namespace {

// Sphere of radius R centred at the origin; element size h_pole at the south pole
// (0, 0, -R), growing by `grad` per unit distance from it up to h_far. One volume group
// "all".
Mesh sphere_mesh(Real R, Real h_pole, Real grad, Real h_far) {
  GmshSession session;
  gmsh::model::add("hertz_sphere");
  gmsh::option::setNumber("General.NumThreads", 1);  // deterministic mesh
  gmsh::option::setNumber("Mesh.Algorithm3D", 1);    // Delaunay
  gmsh::option::setNumber("Mesh.MeshSizeFromPoints", 0);
  gmsh::option::setNumber("Mesh.MeshSizeFromCurvature", 0);
  gmsh::option::setNumber("Mesh.MeshSizeExtendFromBoundary", 0);
  const int s = gmsh::model::occ::addSphere(0, 0, 0, R);
  gmsh::model::occ::synchronize();
  const int f = gmsh::model::mesh::field::add("MathEval");
  gmsh::model::mesh::field::setString(
      f, "F",
      fmt::format("Min({:.17g}, {:.17g} + {:.17g} * Sqrt(x*x + y*y + (z + {:.17g})^2))", h_far, h_pole, grad, R));
  gmsh::model::mesh::field::setAsBackgroundMesh(f);
  gmsh::model::mesh::generate(3);
  const int g = gmsh::model::addPhysicalGroup(3, {s});
  gmsh::model::setPhysicalName(3, g, "all");
  return mesh_from_gmsh_model("hertz sphere");
}

}  // namespace

TEST(Hertz, SphereOnRigidPlaneContactTime) {
  const Real E = 1e7, nu = 0.3, rho = 1000, R = 0.05, v0 = 0.5;
  const Real Es = E / (1 - nu * nu);  // rigid plane
  // Contact radius of the analytic sphere, for the mesh size.
  const Real m_sphere = 4.0 / 3.0 * std::numbers::pi * R * R * R * rho;
  const Real a = std::sqrt(R * std::pow(15 * m_sphere * v0 * v0 / (16 * Es * std::sqrt(R)), 0.4));
  Mesh mesh = sphere_mesh(R, a / 4, 0.05, R / 8);

  CaseConfig c = simple_case(E, nu, rho);
  c.contact.enabled = true;
  contact::ContactMaterial cm;  // default penalty 10, no damping
  cm.friction = 0;
  c.contact_materials = {cm};
  // The plane just below the lowest node: the contact surface (skeleton dilated by r)
  // lies on or inside the element faces, so nothing touches at t = 0.
  Real zmin = INFINITY;
  for (Index n = 0; n < mesh.n_nodes(); ++n) zmin = std::min(zmin, node_pos(mesh.x, n)(2));
  WallConfig w;
  w.wall.type = contact::Wall::Type::Plane;
  w.wall.name = "floor";
  w.wall.centre = Vec3(0, 0, zmin - 1e-4 * R);
  w.wall.normal0 = Vec3(0, 0, 1);
  c.walls.push_back(w);
  InitialConfig ic;
  ic.group = "all";
  ic.velocity = Vec3(0, 0, -v0);
  c.initial = {ic};
  Model m = build_model(c, mesh);
  Integrator it(m, 0.9 * critical_dt(m));
  ASSERT_EQ(m.contact.walls()[0].force.norm(), 0.0) << "the sphere must start clear of the plane";

  // Hertz with the meshed sphere's mass (0.4 % below the analytic one).
  Real mass = 0;
  for (Index n = 0; n < m.fem.n_nodes; ++n) mass += m.fem.mass[n];
  const Real tc_h = 2.87 * std::pow(mass * mass / (R * Es * Es * v0), 0.2);
  const Real dmax = std::pow(15 * mass * v0 * v0 / (16 * Es * std::sqrt(R)), 0.4);
  const Real fmax_h = 4.0 / 3.0 * Es * std::sqrt(R) * std::pow(dmax, 1.5);
  auto vz_com = [&] {
    Real p = 0;
    for (Index n = 0; n < m.fem.n_nodes; ++n) p += m.fem.mass[n] * node_pos(it.v(), n)(2);
    return p / mass;
  };

  // Contact: from the middle of the step in which the wall force appears to the middle of
  // the step in which it vanishes. Run until it has been zero for 0.2 t_c.
  Real t_on = -1, t_off = -1, fmax = 0;
  int intervals = 0;
  bool touching = false;
  while (it.time() < 3 * tc_h) {
    it.step();
    const Real F = -m.contact.walls()[0].force(2);  // the sphere pushes the wall down
    if (F != 0) {
      if (!touching) ++intervals;
      if (t_on < 0) t_on = it.time() - 0.5 * it.dt();
      t_off = it.time() + 0.5 * it.dt();
      fmax = std::max(fmax, F);
    } else if (t_on >= 0 && it.time() > t_off + 0.2 * tc_h) {
      break;
    }
    touching = F != 0;
  }
  ASSERT_GT(t_on, 0) << "no contact";
  const Real tc = t_off - t_on, vz = vz_com();
  RecordProperty("elements", std::to_string(m.fem.n_elements));
  RecordProperty("dt", sci(it.dt()));
  RecordProperty("steps", std::to_string(it.steps()));
  RecordProperty("tc_measured", sci(tc));
  RecordProperty("tc_hertz", sci(tc_h));
  RecordProperty("tc_ratio", sci(tc / tc_h));
  RecordProperty("fmax_measured", sci(fmax));
  RecordProperty("fmax_hertz", sci(fmax_h));
  RecordProperty("fmax_ratio", sci(fmax / fmax_h));
  RecordProperty("rebound_coefficient", sci(vz / v0));
  RecordProperty("contact_intervals", std::to_string(intervals));
  EXPECT_NEAR(tc / tc_h, 1.0, 0.10);
  // Rebound: the centre of mass moves up again. Undamped and frictionless, and the
  // impact is quasi-static, so little energy stays in vibrations: e > 0.9 (measured 0.9996).
  EXPECT_GT(vz, 0.0) << "no rebound";
  EXPECT_GT(vz / v0, 0.9);
}
