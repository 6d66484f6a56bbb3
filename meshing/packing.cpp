// Tetrahedral particles above and inside an open-top box (paper section 2.1). The box is
// meshed by gmsh from five wall slabs when asked for (container = 1; the shipped case takes
// the box as five rigid [[walls]] boxes instead); the particles are single tet4 elements
// added as a discrete gmsh entity, each one its own connected component.
//
// Placement: a lattice of cubic cells of side s = 2 R_max (1 + 1 %), where R_max bounds
// the distance from a particle's centroid to its vertices (regular tet: 0.6124 a, plus the
// vertex jitter), so particles in different cells cannot overlap whatever their
// orientation. Cells fill the box footprint layer by layer from the floor up to
// fill_height. Random numbers come from a 64-bit Mersenne twister with explicit
// conversions, so a seed gives the same bytes on any platform.
#include <fmt/format.h>
#include <gmsh.h>

#include <cmath>
#include <limits>
#include <random>

#include "core/types.hpp"
#include "meshing/generator.hpp"

namespace dspdem::meshing {

namespace {
double uniform(std::mt19937_64& g) { return static_cast<double>(g() >> 11) * 0x1.0p-53; }

Mat3 random_rotation(std::mt19937_64& g) {
  // Shoemake (1992): uniform unit quaternion from three uniforms.
  const double u1 = uniform(g), u2 = uniform(g), u3 = uniform(g);
  const double a = std::sqrt(1 - u1), b = std::sqrt(u1);
  const Eigen::Quaternion<Real> q(b * std::cos(2 * M_PI * u3), a * std::sin(2 * M_PI * u2), a * std::cos(2 * M_PI * u2),
                                  b * std::sin(2 * M_PI * u3));
  return q.normalized().toRotationMatrix();
}
}  // namespace

void build_packing(const Params& p) {
  namespace occ = gmsh::model::occ;
  const double lx = p["box_x"], ly = p["box_height"], lz = p["box_z"], t = p["wall_thickness"];
  const double amin = p["size_min"], amax = p["size_max"], irr = p["irregularity"], top = p["fill_height"];
  const long n = static_cast<long>(p["count"]);
  if (amin > amax) param_error(p, "size_min", "larger than size_max");
  check_count(p, "count", static_cast<double>(n) * std::pow(8.0, p["refine"]), "count x 8^refine tetrahedra");
  if (p["container"] != 0)
    check_tet_count(p, "wall_size", t * ((lx + 2 * t) * (lz + 2 * t) + 2 * ly * (lz + 2 * t) + 2 * lx * ly),
                    p["wall_size"]);
  const double rmax = (0.6124 + irr) * amax;
  const double s = 2.02 * rmax;
  const long nx = static_cast<long>(std::floor(lx / s)), nz = static_cast<long>(std::floor(lz / s));
  const long ny = static_cast<long>(std::floor(top / s));
  const long capacity = nx * ny * nz;
  if (nx < 1 || nz < 1)
    param_error(p, "size_max", fmt::format("a particle cell ({:.3g} m) does not fit in the box", s));
  if (n > capacity)
    param_error(p, "count",
                fmt::format("only {} particles with size_max = {:g} m fit in the box footprint up to "
                            "fill_height = {:g} m ({} x {} per layer, {} layers)",
                            capacity, amax, top, nx, nz, ny));

  // Container: floor and four walls, non-overlapping slabs fragmented into one conformal body.
  std::vector<int> container;
  if (p["container"] != 0) {
    gmsh::vectorpair walls = {
        {3, occ::addBox(-t, -t, -t, lx + 2 * t, t, lz + 2 * t)},  // floor
        {3, occ::addBox(-t, 0, -t, t, ly, lz + 2 * t)},           // x = 0 wall
        {3, occ::addBox(lx, 0, -t, t, ly, lz + 2 * t)},           // x = lx wall
        {3, occ::addBox(0, 0, -t, lx, ly, t)},                    // z = 0 wall
        {3, occ::addBox(0, 0, lz, lx, ly, t)},                    // z = lz wall
    };
    gmsh::vectorpair out;
    std::vector<gmsh::vectorpair> map;
    occ::fragment({walls.front()}, gmsh::vectorpair(walls.begin() + 1, walls.end()), out, map);
    occ::synchronize();
    for (auto [d, tag] : out) container.push_back(tag);
    set_volume_size(container, p["wall_size"]);
    gmsh::model::mesh::generate(3);
  }

  std::size_t next_node = 0;
  {
    std::vector<std::size_t> tags;
    std::vector<double> c, pc;
    gmsh::model::mesh::getNodes(tags, c, pc, -1, -1, false, false);
    for (auto tg : tags) next_node = std::max(next_node, tg);
  }
  std::mt19937_64 rng(static_cast<std::uint64_t>(p["seed"]));
  // Regular tetrahedron of unit edge, centroid at the origin, positively oriented.
  const Vec3 ref[4] = {Vec3(1, 1, 1), Vec3(1, -1, -1), Vec3(-1, 1, -1), Vec3(-1, -1, 1)};
  const double unit = 1.0 / std::sqrt(8.0);
  std::vector<std::size_t> node_tags, conn;
  std::vector<double> coords;
  const double ox = 0.5 * (lx - nx * s), oz = 0.5 * (lz - nz * s);
  for (long k = 0; k < n; ++k) {
    const long layer = k / (nx * nz), in_layer = k % (nx * nz);
    const Vec3 centre(ox + (in_layer % nx + 0.5) * s, (layer + 0.5) * s, oz + (in_layer / nx + 0.5) * s);
    const double a = amin + (amax - amin) * uniform(rng);
    const Mat3 R = random_rotation(rng);
    Vec3 v[4];
    for (int i = 0; i < 4; ++i) {
      // Jitter inside a ball of radius irr * a (rejection sampling keeps it isotropic).
      Vec3 j;
      do j = Vec3(2 * uniform(rng) - 1, 2 * uniform(rng) - 1, 2 * uniform(rng) - 1);
      while (j.squaredNorm() > 1.0);
      v[i] = centre + R * (a * unit * ref[i] + irr * a * j);
    }
    if ((v[1] - v[0]).cross(v[2] - v[0]).dot(v[3] - v[0]) < 0) std::swap(v[2], v[3]);
    for (int i = 0; i < 4; ++i) {
      node_tags.push_back(++next_node);
      conn.push_back(next_node);
      coords.insert(coords.end(), {v[i](0), v[i](1), v[i](2)});
    }
  }
  const int ent = gmsh::model::addDiscreteEntity(3);
  gmsh::model::mesh::addNodes(3, ent, node_tags, coords);
  gmsh::model::mesh::addElementsByType(ent, 4, {}, conn);
  // Meshed particles: gmsh's uniform refinement splits every tetrahedron into 8 (at its edge
  // midpoints), so each particle becomes a small meshed polyhedron of 8^refine elements with
  // its shape kept. It refines a meshed container too.
  for (long i = 0; i < static_cast<long>(p["refine"]); ++i) gmsh::model::mesh::refine();
  if (!container.empty()) add_group(3, container, "container");
  add_group(3, {ent}, "particles");
}

// Parameters of [mesh.packing], declared beside the generator that uses them (the case reader
// validates them, `dspdem keys` documents them).
// clang-format off
const std::vector<schema::Key>& packing_keys() {
  using T = schema::Type;
  constexpr double inf = std::numeric_limits<double>::infinity();
  static const std::vector<schema::Key> k = {
    {"mesh.packing", "box_x", T::Real, "16.0", 0, inf, true, false, "m", nullptr, "Inner box size along x [S]."},
    {"mesh.packing", "box_z", T::Real, "13.8", 0, inf, true, false, "m", nullptr, "Inner box size along z [S]."},
    {"mesh.packing", "box_height", T::Real, "15.2", 0, inf, true, false, "m", nullptr, "Inner box height along y (gravity along -y) [S]; which of the paper's three sizes is the height is [NF]."},
    {"mesh.packing", "container", T::Int, "1", 0, 1, false, false, "", nullptr, "1: mesh the box's five wall slabs as the group `container`; 0: particles only (the box is given as [[walls]])."},
    {"mesh.packing", "wall_thickness", T::Real, "0.5", 0, inf, true, false, "m", nullptr, "Thickness of the five wall slabs."},
    {"mesh.packing", "wall_size", T::Real, "2.0", 0, inf, true, false, "m", nullptr, "Element size in the walls."},
    {"mesh.packing", "count", T::Int, "5346", 1, 10000000, false, false, "", nullptr, "Number of particles [S]."},
    {"mesh.packing", "size_min", T::Real, "0.4", 0, inf, true, false, "m", nullptr, "Smallest particle edge length. Sizes are [NF]: chosen so 5346 particles start in a 30 m column over the box."},
    {"mesh.packing", "size_max", T::Real, "0.7", 0, inf, true, false, "m", nullptr, "Largest particle edge length (sizes uniform in [size_min, size_max])."},
    {"mesh.packing", "irregularity", T::Real, "0.1", 0, 0.25, false, false, "", nullptr, "Vertex jitter as a fraction of the edge length (0 = regular tetrahedra)."},
    {"mesh.packing", "fill_height", T::Real, "30.0", 0, inf, true, false, "m", nullptr, "Top of the region, above the floor, where particles are placed."},
    {"mesh.packing", "refine", T::Int, "0", 0, 2, false, false, "", nullptr, "Particles as small meshed polyhedra: gmsh's uniform refinements of each particle, each splitting every tetrahedron into 8 (0: one tet4 per particle, the paper's; 1: 8 elements; 2: 64)."},
    {"mesh.packing", "seed", T::Int, "1", 0, 4294967295.0, false, false, "", nullptr, "Random seed: the same seed gives the same mesh."},
  };
  return k;
}
// clang-format on

}  // namespace dspdem::meshing
