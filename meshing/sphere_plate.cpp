// Rock sphere above a plate (paper section 2.5).
#include <fmt/format.h>
#include <gmsh.h>

#include <Eigen/Geometry>
#include <cmath>
#include <cstdint>
#include <limits>
#include <random>
#include <vector>

#include "core/log.hpp"
#include "meshing/generator.hpp"

namespace dspdem::meshing {

namespace {
// The k-th of a fixed sequence of rotations, uniform over all rotations (Shoemake's
// quaternion from three uniform numbers). mt19937_64's output is fixed by the standard and
// the doubles are made from its bits here, so every platform draws the same numbers (the
// axis and angle may still differ in the last bits of sin and cos between libm versions).
Eigen::AngleAxisd orientation(int k) {
  std::mt19937_64 g(static_cast<std::uint64_t>(k));
  const auto u = [&g] { return static_cast<double>(g() >> 11) * 0x1.0p-53; };
  const double u1 = u(), u2 = u(), u3 = u(), two_pi = 2 * 3.14159265358979323846;
  const double a = std::sqrt(1 - u1), b = std::sqrt(u1);
  const Eigen::Quaterniond q(b * std::cos(two_pi * u3), a * std::sin(two_pi * u2), a * std::cos(two_pi * u2),
                             b * std::sin(two_pi * u3));
  return Eigen::AngleAxisd(q.normalized());
}

// Element size hc at the sphere's lowest point (0, -D/2, 0), where it meets the plate, growing
// linearly to the sphere's size at contact_distance from it. A turned sphere (orientation > 0)
// is refined at the same place: the turn is about the centre. Why: the Hertz contact's radius
// is 6.5 mm at 2.5 m/s and 10 mm at 7.5 m/s, under one of the case's 16.8 mm elements, so the
// crushing under it is the mesh's as much as the rock's.
void refine_at_contact(const Params& p, const std::vector<int>& sphere, double hc, double h) {
  const double D = p["diameter"], reach = p["contact_distance"];
  if (reach <= 0) param_error(p, "contact_distance", "must be > 0 when contact_size is set");
  if (hc >= h) {
    // With target_elements the size is rescaled, and may come out finer than contact_size.
    if (p["target_elements"] > 0) {
      log::warn(
          "mesh.sphere_plate: contact_size {:.4g} m is not finer than the size {:.4g} m that target_elements "
          "gives: no refinement at the contact",
          hc, h);
      return;
    }
    param_error(p, "contact_size", "not smaller than size: it refines the mesh at the contact");
  }
  gmsh::model::mesh::field::add("MathEval", 1);
  gmsh::model::mesh::field::setString(1, "F", fmt::format("Sqrt(x^2 + (y + {:.12f})^2 + z^2)", D / 2));
  set_graded_size(1, hc, h, reach, sphere);
}

// The sphere cut by the plane cap_height above its lowest point into two volumes meshed as
// one (their common face conforming): {cap, above}. Why: a case can then leave the cap
// without joints (fracture_groups = ["sphere_above"]), a contact that cannot crush, to see
// what the crushing under it does to the rest of the sphere (REFERENCE.md of the scene).
std::vector<int> cut_cap(const Params& p, int sphere) {
  namespace occ = gmsh::model::occ;
  const double D = p["diameter"], hcap = p["cap_height"];
  if (hcap >= D) param_error(p, "cap_height", "not below the sphere's diameter");
  const int box = occ::addBox(-D, -D, -D, 2 * D, D / 2 + hcap, 2 * D);  // y < -D/2 + cap_height
  gmsh::vectorpair out;
  std::vector<gmsh::vectorpair> from;
  occ::fragment({{3, sphere}}, {{3, box}}, out, from);
  // from[0]: the sphere's pieces; from[1]: the box's. The cap is in both; what is only the
  // box's lies outside the sphere and goes.
  int cap = -1, above = -1;
  for (auto [dim, t] : from[0]) {
    bool in_box = false;
    for (auto [d2, t2] : from[1]) in_box = in_box || t2 == t;
    (in_box ? cap : above) = t;
  }
  if (from[0].size() != 2 || cap < 0 || above < 0) param_error(p, "cap_height", "did not cut the sphere in two (gmsh)");
  for (auto [dim, t] : from[1])
    if (t != cap) occ::remove({{3, t}}, true);
  return {cap, above};
}
}  // namespace

void build_sphere_plate(const Params& p) {
  namespace occ = gmsh::model::occ;
  const double D = p["diameter"], h = p["size"], gap = p["gap"];
  const double pw = p["plate_width"], pt = p["plate_thickness"], ph = p["plate_size"];
  if (h > 0.25 * D) param_error(p, "size", "larger than a quarter of the diameter: the sphere cannot be meshed");
  if (pw < D) param_error(p, "plate_width", "narrower than the sphere");
  check_tet_count(p, "size", M_PI / 6 * D * D * D, h);
  if (p["plate"] != 0) check_tet_count(p, "plate_size", pw * pw * p["plate_thickness"], ph);
  const double ytop = -D / 2 - gap;
  // The plate is meshed only when asked for: the paper's plate is rigid, a [[walls]] plane.
  const bool meshed_plate = p["plate"] != 0;
  const int sphere = occ::addSphere(0, 0, 0, D / 2);
  // Another realisation of the mesh at the same size: the sphere (its poles and seam) turned
  // before meshing. gmsh then meshes it differently (4332, 4284, 4435 tetrahedra at the
  // case's size for orientations 0, 1, 2), and other elements meet the plate first.
  // Fracture at an impact is chaotic; a few realisations tell a pattern from one mesh's chance.
  if (const int k = static_cast<int>(p["orientation"]); k > 0) {
    const Eigen::AngleAxisd r = orientation(k);
    occ::rotate({{3, sphere}}, 0, 0, 0, r.axis().x(), r.axis().y(), r.axis().z(), r.angle());
  }
  // The cap is cut after the turn, so it is always at the lowest point, where the plate is.
  const std::vector<int> pieces = p["cap_height"] > 0 ? cut_cap(p, sphere) : std::vector<int>{sphere};
  const int plate = meshed_plate ? occ::addBox(-pw / 2, ytop - pt, -pw / 2, pw, pt, pw) : -1;
  occ::synchronize();
  set_volume_size(pieces, h);
  if (const double hc = p["contact_size"]; hc > 0) refine_at_contact(p, pieces, hc, h);
  if (meshed_plate) set_volume_size({plate}, ph);
  gmsh::model::mesh::generate(3);
  add_group(3, pieces, "sphere");
  if (pieces.size() == 2) {
    add_group(3, {pieces[0]}, "sphere_cap");
    add_group(3, {pieces[1]}, "sphere_above");
  }
  if (!meshed_plate) return;
  add_group(3, {plate}, "plate");
  add_group(2, entities_in_box(2, -pw / 2, ytop, -pw / 2, pw / 2, ytop, pw / 2), "plate_top");
  add_group(2, entities_in_box(2, -pw / 2, ytop - pt, -pw / 2, pw / 2, ytop - pt, pw / 2), "plate_bottom");
}

// Parameters of [mesh.sphere_plate], declared beside the generator that uses them (the case reader
// validates them, `dspdem keys` documents them).
// clang-format off
const std::vector<schema::Key>& sphere_plate_keys() {
  using T = schema::Type;
  constexpr double inf = std::numeric_limits<double>::infinity();
  static const std::vector<schema::Key> k = {
    {"mesh.sphere_plate", "diameter", T::Real, "0.2", 0, inf, true, false, "m", nullptr, "Sphere diameter [S]."},
    {"mesh.sphere_plate", "target_elements", T::Int, "0", 0, 1e8, false, false, "", nullptr, "Element count wanted in the sphere: when > 0 the size is rescaled (a few gmsh runs) until the count is within 3 %."},
    {"mesh.sphere_plate", "size", T::Real, "0.0168", 0, inf, true, false, "m", nullptr, "Element size in the sphere; the default gives about the paper's 4539 tetrahedra."},
    {"mesh.sphere_plate", "orientation", T::Int, "0", 0, 1e6, false, false, "", nullptr, "0: the sphere as gmsh builds it; k > 0: the sphere turned before meshing by the k-th of a fixed sequence of rotations, uniform over all rotations: another realisation of the mesh at the same size (gmsh meshes it differently; element counts within a few %), for a pattern's spread (`dspdem report --realisations`)."},
    {"mesh.sphere_plate", "contact_size", T::Real, "0", 0, inf, false, false, "m", nullptr, "> 0: element size at the sphere's lowest point, where it meets the plate, growing linearly to size at contact_distance from it (the Hertz contact's radius is 6.5 mm at 2.5 m/s and 10 mm at 7.5 m/s on the paper's sphere); 0: size everywhere."},
    {"mesh.sphere_plate", "contact_distance", T::Real, "0.05", 0, inf, false, false, "m", nullptr, "Distance from the lowest point over which contact_size grows to size."},
    {"mesh.sphere_plate", "cap_height", T::Real, "0", 0, inf, false, false, "m", nullptr, "> 0: the sphere is cut by a plane this far above its lowest point into the volume groups sphere_cap (below) and sphere_above, both also in sphere, meshed as one (conforming). For a study of the contact: fracture = \"groups\" with fracture_groups = [\"sphere_above\"] leaves the cap without joints, so it cannot crush. 0: no cut (the mesh is not the same with a cut)."},
    {"mesh.sphere_plate", "gap", T::Real, "0.0", 0, inf, false, false, "m", nullptr, "Gap between the sphere and the plate."},
    {"mesh.sphere_plate", "plate", T::Int, "1", 0, 1, false, false, "", nullptr, "1: mesh the steel plate under the sphere (groups plate, plate_top, plate_bottom); 0: the sphere alone (strike a rigid [[walls]] plane, as the paper's plate)."},
    {"mesh.sphere_plate", "plate_width", T::Real, "0.3", 0, inf, true, false, "m", nullptr, "Plate side (square, in x and z)."},
    {"mesh.sphere_plate", "plate_thickness", T::Real, "0.02", 0, inf, true, false, "m", nullptr, "Plate thickness."},
    {"mesh.sphere_plate", "plate_size", T::Real, "0.03", 0, inf, true, false, "m", nullptr, "Element size in the plate."},
  };
  return k;
}
// clang-format on

}  // namespace dspdem::meshing
