// Generators: volumes against the analytic ones (tighter on a finer mesh), named groups
// present, no inverted elements, default element counts near the paper's, packing without
// overlaps and reproducible, and parameter errors that name the key.
#include <fcntl.h>
#include <gtest/gtest.h>
#include <sys/file.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <functional>
#include <iterator>
#include <sstream>

#include "core/error.hpp"
#include "io/case_config.hpp"
#include "meshing/generator.hpp"
#include "meshing/quality.hpp"

using namespace dspdem;
namespace fs = std::filesystem;

namespace {
// One folder per process: ctest runs this file's tests side by side (ctest -j2).
fs::path test_dir() { return fs::temp_directory_path() / ("dspdem_meshing_test_" + std::to_string(::getpid())); }

// Removed when the process ends, so the per-process folders do not pile up in /tmp.
class RemoveTestDir : public ::testing::Environment {
  void TearDown() override { fs::remove_all(test_dir()); }
};
const auto* const remove_test_dir = ::testing::AddGlobalTestEnvironment(new RemoveTestDir);

meshing::Params params(const std::string& gen, const std::vector<std::string>& sets = {}) {
  const fs::path dir = test_dir();
  fs::create_directories(dir);
  const fs::path f = dir / (gen + ".toml");
  std::ofstream(f)
      << "[mesh]\ngenerator = \"" << gen
      << "\"\n[materials.m]\ndensity = 1.0\nE = 1.0\nnu = 0.2\n[[bodies]]\nname = \"b\"\ngroups = [\"x\"]\n"
         "material = \"m\"\n[time]\nend = 1.0\n";
  std::vector<std::string> ov;
  for (const auto& s : sets) ov.push_back("mesh." + gen + "." + s);
  const CaseConfig c = read_case(f.string(), ov);
  return {c.mesh_generator, c.mesh_num, c.mesh_str};
}

double group_volume(const Mesh& m, const std::string& name) {
  const Group* g = m.find_group(name);
  EXPECT_NE(g, nullptr) << name;
  if (!g) return 0;
  double v = 0;
  for (std::size_t b = 0; b < m.blocks.size(); ++b) {
    const auto& blk = m.blocks[b];
    for (Index e : g->elements[b]) {
      const Index* c = &blk.conn[static_cast<std::size_t>(e) * blk.npe()];
      auto P = [&](int i) { return node_pos(m.x, c[i]); };
      if (blk.type == CellType::Tet4) {
        v += tet4_volume(P(0), P(1), P(2), P(3));
      } else {  // 6-tet split of the hex (exact for planar faces)
        const int t[6][4] = {{0, 1, 2, 6}, {0, 2, 3, 6}, {0, 3, 7, 6}, {0, 7, 4, 6}, {0, 4, 5, 6}, {0, 5, 1, 6}};
        for (const auto& q : t) v += tet4_volume(P(q[0]), P(q[1]), P(q[2]), P(q[3]));
      }
    }
  }
  return v;
}

void expect_groups(const Mesh& m, const std::vector<std::string>& names) {
  for (const auto& n : names) {
    const Group* g = m.find_group(n);
    ASSERT_NE(g, nullptr) << "missing group " << n << " (have " << m.group_names() << ")";
    EXPECT_FALSE(g->nodes.empty()) << n;
  }
}

Index count(const Mesh& m, const std::string& group) {
  Index n = 0;
  for (const auto& e : m.find_group(group)->elements) n += static_cast<Index>(e.size());
  return n;
}

// Mean edge length of the tetrahedra (first block) whose centroid passes `where`, each edge
// estimated from the volume (the cube root of a regular tet's volume is 0.49 x its edge).
double mean_edge(const Mesh& m, const std::function<bool(const Vec3&)>& where) {
  double sum = 0;
  int n = 0;
  const auto& blk = m.blocks.at(0);
  for (Index e = 0; e < blk.size(); ++e) {
    const Index* c = &blk.conn[static_cast<std::size_t>(e) * 4];
    const Vec3 a = node_pos(m.x, c[0]), b = node_pos(m.x, c[1]), d = node_pos(m.x, c[2]), f = node_pos(m.x, c[3]);
    if (where(0.25 * (a + b + d + f))) sum += std::cbrt(tet4_volume(a, b, d, f)) / 0.49, ++n;
  }
  EXPECT_GT(n, 0) << "no element where asked";
  return n > 0 ? sum / n : 0.0;
}

void expect_error(const meshing::Params& p, const std::string& fragment) {
  try {
    meshing::generate(p);
    ADD_FAILURE() << "no error, expected " << fragment;
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find(fragment), std::string::npos) << e.what();
  }
}
}  // namespace

TEST(Generators, BrazilianDisc) {
  const Mesh m = meshing::generate(params("brazilian_disc"));  // generate() refuses inverted elements
  expect_groups(m, {"disc", "plate_top", "plate_bottom", "plate_top_load", "plate_bottom_load"});
  // Paper: 12335 tetrahedra; documented default within 10 %.
  EXPECT_NEAR(count(m, "disc") / 12335.0, 1.0, 0.10);
  const double D = 0.1427, L = 0.0713, exact = M_PI * D * D / 4 * L;
  // The polygonal boundary loses area ~ (h / R)^2: 1 % at the default size, 0.3 % at half.
  const double err = std::abs(group_volume(m, "disc") / exact - 1);
  EXPECT_LT(err, 0.01);
  const Mesh fine = meshing::generate(params("brazilian_disc", {"size=0.0038", "plate_size=0.02"}));
  const double err_fine = std::abs(group_volume(fine, "disc") / exact - 1);
  EXPECT_LT(err_fine, 0.003);
  EXPECT_LT(err_fine, err);
  EXPECT_NEAR(group_volume(m, "plate_top"), 0.06 * 0.02 * L, 1e-9);
}

// Area of the element faces lying on the plane x = 0 (every tet face counted once per
// element, so an interior face counts twice).
static double area_on_mid_plane(const Mesh& m) {
  double a = 0;
  for (const auto& blk : m.blocks) {
    if (blk.type != CellType::Tet4) continue;
    for (Index e = 0; e < blk.size(); ++e) {
      const Index* c = &blk.conn[static_cast<std::size_t>(e) * 4];
      for (int skip = 0; skip < 4; ++skip) {
        std::vector<Vec3> f;
        for (int i = 0; i < 4; ++i)
          if (i != skip) f.push_back(node_pos(m.x, c[i]));
        if (std::abs(f[0](0)) < 1e-12 && std::abs(f[1](0)) < 1e-12 && std::abs(f[2](0)) < 1e-12)
          a += 0.5 * (f[1] - f[0]).cross(f[2] - f[0]).norm();
      }
    }
  }
  return a;
}

TEST(Generators, BrazilianDiscSplitPlaneAndBand) {
  const double D = 0.1427, L = 0.0713, R = D / 2, w = 0.03;
  // split_plane: the loaded diametral plane is made of element faces, each met from both
  // sides, so they cover exactly 2 D L (its edges are the straight generator lines).
  const Mesh split = meshing::generate(params("brazilian_disc", {"split_plane=1", "plates=0"}));
  EXPECT_NEAR(area_on_mid_plane(split) / (2 * D * L), 1.0, 1e-9);
  const Mesh plain = meshing::generate(params("brazilian_disc", {"plates=0"}));
  EXPECT_LT(area_on_mid_plane(plain), 0.2 * D * L);
  expect_groups(plain, {"disc", "disc_top_line", "disc_bottom_line"});
  // band_width: the slab |x| < w/2 is its own volume group; its volume is the circular
  // slab's (the faceted boundary loses ~1 %, as for the whole disc).
  const Mesh band = meshing::generate(params("brazilian_disc", {"band_width=0.03", "plates=0"}));
  expect_groups(band, {"disc", "disc_band", "disc_side", "disc_top_line", "disc_bottom_line"});
  const double slab = 2 * ((w / 2) * std::sqrt(R * R - w * w / 4) + R * R * std::asin(w / (2 * R))) * L;
  EXPECT_NEAR(group_volume(band, "disc_band") / slab, 1.0, 0.01);
  EXPECT_NEAR((group_volume(band, "disc_band") + group_volume(band, "disc_side")) / group_volume(band, "disc"), 1.0,
              1e-12);
  EXPECT_EQ(count(band, "disc_band") + count(band, "disc_side"), count(band, "disc"));
  // cap_height: the two circular segments within c of the loaded lines are disc_caps; each
  // has area R^2 acos(1 - c/R) - (R - c) sqrt(2 R c - c^2).
  const double c = 0.02;
  const Mesh caps = meshing::generate(params("brazilian_disc", {"cap_height=0.02", "plates=0"}));
  expect_groups(caps, {"disc", "disc_core", "disc_caps", "disc_top_line", "disc_bottom_line"});
  const double segment = R * R * std::acos(1 - c / R) - (R - c) * std::sqrt(2 * R * c - c * c);
  EXPECT_NEAR(group_volume(caps, "disc_caps") / (2 * segment * L), 1.0, 0.02);
  EXPECT_EQ(count(caps, "disc_core") + count(caps, "disc_caps"), count(caps, "disc"));
  // load_size: elements at the loaded lines are about load_size, those at the centre about
  // size (the cube root of a regular tet's volume is 0.49 x its edge).
  const Mesh graded = meshing::generate(params("brazilian_disc", {"load_size=0.0025", "plates=0"}));
  EXPECT_LT(mean_edge(graded, [&](const Vec3& g) { return std::hypot(g(0), g(1) - R) < 0.005; }), 1.6 * 0.0025);
  EXPECT_GT(mean_edge(graded, [&](const Vec3& g) { return std::hypot(g(0), g(1)) < 0.015; }), 0.7 * 0.0076);
}

TEST(Generators, FirstAndCachedRunsGetTheSameMesh) {
  // A cold cache generates and writes the mesh, a warm one reads it: both runs must see the
  // same coordinates, bit for bit (the file has fewer digits than gmsh's memory), or the
  // same case gives a different result the second time.
  const fs::path dir = fs::temp_directory_path() / "dspdem_mesh_cache_test";
  fs::remove_all(dir);
  const auto p = params("brazilian_disc", {"size=0.03", "plate_size=0.03"});
  // What writers killed mid-write left (NAME.PID.tmp.msh, no longer locked): removed by the
  // next run that meshes here; a file a writer holds locked (a parallel job meshing now, on
  // this host or another) is kept.
  fs::create_directories(dir);
  const fs::path dead = dir / "x-0123.msh.4242.tmp.msh", live = dir / "x-0456.msh.4343.tmp.msh";
  std::ofstream(dead) << "half a mesh";
  std::ofstream(live) << "half a mesh";
  const int held = ::open(live.c_str(), O_RDWR | O_CLOEXEC);
  ASSERT_GE(held, 0);
  ASSERT_EQ(::flock(held, LOCK_EX | LOCK_NB), 0);
  bool cached = true;
  const Mesh first = meshing::load_or_generate(p, dir.string(), &cached);
  EXPECT_FALSE(cached);
  EXPECT_FALSE(fs::exists(dead));
  EXPECT_TRUE(fs::exists(live));
  ::close(held);
  const Mesh second = meshing::load_or_generate(p, dir.string(), &cached);
  EXPECT_TRUE(cached);
  ASSERT_EQ(first.x.size(), second.x.size());
  EXPECT_TRUE(first.x == second.x);
  ASSERT_EQ(first.blocks.size(), second.blocks.size());
  for (std::size_t b = 0; b < first.blocks.size(); ++b) EXPECT_TRUE(first.blocks[b].conn == second.blocks[b].conn);
  fs::remove_all(dir);
}

TEST(Generators, SpherePlate) {
  const Mesh m = meshing::generate(params("sphere_plate"));
  expect_groups(m, {"sphere", "plate", "plate_top", "plate_bottom"});
  EXPECT_NEAR(count(m, "sphere") / 4539.0, 1.0, 0.10);  // paper: 4539
  const double exact = 4.0 / 3.0 * M_PI * 0.1 * 0.1 * 0.1;
  const double err = std::abs(group_volume(m, "sphere") / exact - 1);
  EXPECT_LT(err, 0.03);  // facetted sphere at h/R = 0.17
  const Mesh fine = meshing::generate(params("sphere_plate", {"size=0.0084"}));
  const double err_fine = std::abs(group_volume(fine, "sphere") / exact - 1);
  EXPECT_LT(err_fine, 0.01);
  EXPECT_LT(err_fine, err);
  // plate = 0 (the shipped case: a rigid [[walls]] plane instead): the sphere alone, still
  // about the paper's count (gmsh meshes it a little differently without the plate beside it).
  const Mesh alone = meshing::generate(params("sphere_plate", {"plate=0"}));
  EXPECT_EQ(alone.find_group("plate"), nullptr);
  EXPECT_EQ(alone.n_elements(), count(alone, "sphere"));
  EXPECT_NEAR(count(alone, "sphere") / 4539.0, 1.0, 0.10);
}

TEST(Generators, SphereOrientationIsAnotherMeshOfTheSameSphere) {
  // orientation = k > 0 turns the sphere before meshing: the same sphere (every node on or
  // inside it, the volume as exact as the unturned mesh's), meshed differently, and the same
  // k gives the same mesh every time (the sequence of rotations is fixed).
  const Mesh m0 = meshing::generate(params("sphere_plate", {"plate=0"}));
  const Mesh m1 = meshing::generate(params("sphere_plate", {"plate=0", "orientation=1"}));
  const Mesh again = meshing::generate(params("sphere_plate", {"plate=0", "orientation=1"}));
  EXPECT_TRUE(m1.x == again.x);
  EXPECT_FALSE(m1.x == m0.x);
  const double R = 0.1, exact = 4.0 / 3.0 * M_PI * R * R * R;
  double rmax = 0;
  for (std::size_t i = 0; i < m1.x.size(); i += 3)
    rmax = std::max(rmax, std::sqrt(m1.x[i] * m1.x[i] + m1.x[i + 1] * m1.x[i + 1] + m1.x[i + 2] * m1.x[i + 2]));
  EXPECT_NEAR(rmax, R, 1e-9 * R);
  EXPECT_LT(std::abs(group_volume(m1, "sphere") / exact - 1), 0.03);  // as SpherePlate's bound at this size
  EXPECT_NEAR(count(m1, "sphere") / static_cast<double>(count(m0, "sphere")), 1.0, 0.05);
}

TEST(Generators, SphereRefinedAtTheContact) {
  // contact_size: the elements within r = 8 mm of the lowest point are smaller than the
  // uniform mesh's there, and near what the size field asks: contact_size growing linearly
  // to size over contact_distance, taken at the mean distance of a half-ball's points, 3 r / 4.
  // The 1.6 is the bound used for the disc's load_size above: elements reaching into the ball
  // from outside it are counted, and gmsh's elements in a steep gradient come out larger than
  // the field. A mesh that ignored the field would read the uniform mesh's 18 mm, 3x the
  // bound. The centre keeps size, and the sphere is the same sphere.
  const double hc = 0.004, reach = 0.04, h = 0.0168, r = 0.008;
  const auto near_pole = [&](const Vec3& g) { return (g - Vec3(0, -0.1, 0)).norm() < r; };
  const Mesh uniform = meshing::generate(params("sphere_plate", {"plate=0"}));
  const Mesh m = meshing::generate(params("sphere_plate", {"plate=0", "contact_size=0.004", "contact_distance=0.04"}));
  const double asked = hc + (h - hc) * 0.75 * r / reach;
  const double got = mean_edge(m, near_pole);
  EXPECT_LT(got, 1.6 * asked);
  EXPECT_LT(got, 0.6 * mean_edge(uniform, near_pole));
  EXPECT_GT(mean_edge(m, [](const Vec3& g) { return g.norm() < 0.03; }), 0.7 * h);
  const double exact = 4.0 / 3.0 * M_PI * 0.1 * 0.1 * 0.1;
  EXPECT_LT(std::abs(group_volume(m, "sphere") / exact - 1), 0.03);
  // The turned sphere is refined at the same place: where it meets the plate.
  const Mesh turned = meshing::generate(
      params("sphere_plate", {"plate=0", "contact_size=0.004", "contact_distance=0.04", "orientation=2"}));
  // Measured: uniform 18.2 mm, refined 8.1, turned 6.2; asked 5.9.
  EXPECT_LT(mean_edge(turned, near_pole), 1.6 * asked);
  // A meshed plate keeps its own size under the contact (the field is restricted to the
  // sphere): its elements within 15 mm of the point below the contact are about plate_size.
  const Mesh plate = meshing::generate(params("sphere_plate", {"contact_size=0.004", "contact_distance=0.04"}));
  const double ph = 0.03;
  EXPECT_GT(mean_edge(plate, [](const Vec3& g) { return g(1) < -0.1 && (g - Vec3(0, -0.11, 0)).norm() < 0.015; }),
            0.7 * ph);
}

TEST(Generators, SphereCapIsTheSphereBelowAPlane) {
  // cap_height = c: the elements of sphere_cap lie below the plane c above the lowest point
  // (their centroids; their nodes on or below it), those of sphere_above above it, the two
  // make up the group sphere, and the cut is meshed as one: the cap's faces on the plane are
  // the faces of elements above (shared nodes, so the mesh is one piece). The cap's volume is
  // the spherical cap's, pi c^2 (3 R - c) / 3, to the faceting error: facets lose volume in
  // proportion to the curved area, so the cap's relative error is the whole sphere's times
  // the ratio of their area-to-volume ratios (3.6 here), with a margin of 1.5 (measured: the
  // sphere 0.9-1.0 %, the cap 3.2-3.3 %). The cut is made after the turn: a turned sphere's
  // cap is at its lowest point too.
  const double R = 0.1, c = 0.02, y_cut = -R + c;
  for (const char* turn : {"orientation=0", "orientation=2"}) {
    SCOPED_TRACE(turn);
    const Mesh m = meshing::generate(params("sphere_plate", {"plate=0", "cap_height=0.02", turn}));
    expect_groups(m, {"sphere", "sphere_cap", "sphere_above"});
    EXPECT_EQ(count(m, "sphere_cap") + count(m, "sphere_above"), count(m, "sphere"));
    EXPECT_EQ(count(m, "sphere"), m.n_elements());
    const double cap_exact = M_PI * c * c * (3 * R - c) / 3, ball = 4.0 / 3.0 * M_PI * R * R * R;
    const double err_ball = std::abs(group_volume(m, "sphere") / ball - 1);
    const double err_cap = std::abs(group_volume(m, "sphere_cap") / cap_exact - 1);
    EXPECT_LT(err_ball, 0.03);  // SpherePlate's bound
    const double area_ratio = (2 * M_PI * R * c / cap_exact) / (3 / R);
    EXPECT_LT(err_cap, 1.5 * area_ratio * err_ball);
    auto extreme_y = [&](const std::string& g, bool top) {
      double y = top ? -1e9 : 1e9;
      for (Index n : m.find_group(g)->nodes) y = top ? std::max(y, m.x[3 * n + 1]) : std::min(y, m.x[3 * n + 1]);
      return y;
    };
    EXPECT_LE(extreme_y("sphere_cap", true), y_cut + 1e-9);
    EXPECT_GE(extreme_y("sphere_above", false), y_cut - 1e-9);
    // Conforming: nodes on the plane belong to both groups.
    const auto& a = m.find_group("sphere_cap")->nodes;
    const auto& b = m.find_group("sphere_above")->nodes;
    std::vector<Index> shared;
    std::set_intersection(a.begin(), a.end(), b.begin(), b.end(), std::back_inserter(shared));
    EXPECT_GT(shared.size(), 10u);
    for (Index n : shared) EXPECT_NEAR(m.x[3 * n + 1], y_cut, 1e-9);
  }
  expect_error(params("sphere_plate", {"plate=0", "cap_height=0.2"}), "mesh.sphere_plate.cap_height");
}

TEST(Generators, ElementCountTarget) {
  // target_elements rescales the size until the count is within 3 % (the documented bound).
  const Mesh m = meshing::generate(params("sphere_plate", {"target_elements=8000"}));
  EXPECT_NEAR(count(m, "sphere") / 8000.0, 1.0, 0.03);
}

TEST(Generators, ContactSizeNotFinerThanATargetedSizeWarnsAndMeshesUniformly) {
  // With target_elements the size is rescaled (from 16.8 mm to about 14 mm for 8000
  // elements), and a contact_size that is then not finer is skipped with a warning naming
  // the key, not refused: the sphere study's contact row cannot know the rescaled size. The
  // count keeps the target's 3 %. (A contact_size between the two sizes, 16.5 mm, switches
  // the refinement on and off between the rescaling's gmsh runs; the count then missed by
  // 4.0 %, which the rescaling's own warning says.)
  testing::internal::CaptureStderr();
  const Mesh m = meshing::generate(
      params("sphere_plate", {"plate=0", "target_elements=8000", "contact_size=0.03", "contact_distance=0.04"}));
  const std::string err = testing::internal::GetCapturedStderr();
  EXPECT_NE(err.find("contact_size"), std::string::npos) << err;
  EXPECT_NE(err.find("no refinement at the contact"), std::string::npos) << err;
  EXPECT_NEAR(count(m, "sphere") / 8000.0, 1.0, 0.03);
}

TEST(Generators, MurrayBeamHexahedra) {
  const Mesh m = meshing::generate(params("murray_beam", {"cylinders=1"}));
  expect_groups(
      m, {"beam", "impactor_left", "impactor_right", "support_left", "support_right", "midspan_bottom", "beam_bottom",
          "beam_top", "beam_span", "overhang_left", "overhang_right", "impact_line_left", "support_line_right"});
  EXPECT_EQ(count(m, "beam"), 4080);  // paper: 4080 hexahedra
  EXPECT_EQ(m.find_group("beam")->elements[1].size(), 4080u) << "beam must be hexahedra";
  EXPECT_NEAR(group_volume(m, "beam") / (1.524 * 0.1143 * 0.1), 1.0, 1e-12);  // a box: exact
  const double cyl = M_PI * 0.016 * 0.016 * 0.1;
  EXPECT_NEAR(group_volume(m, "impactor_left") / cyl, 1.0, 0.03);
  const Mesh fine = meshing::generate(params("murray_beam", {"cylinders=1", "cylinder_size=0.003"}));
  EXPECT_NEAR(group_volume(fine, "impactor_left") / cyl, 1.0, 0.01);
  // The mid-span bottom line is a mesh line across the width: nz + 1 nodes.
  EXPECT_EQ(m.find_group("midspan_bottom")->nodes.size(), 11u);
  // The span between the supports and the overhangs partition the beam.
  EXPECT_EQ(count(m, "beam_span") + count(m, "overhang_left") + count(m, "overhang_right"), 4080);
  EXPECT_EQ(m.find_group("impact_line_left")->nodes.size(), 11u);
  // Without cylinders (the default: analytic cylinder walls strike the beam) only the beam is meshed.
  const Mesh b = meshing::generate(params("murray_beam"));
  EXPECT_EQ(b.n_elements(), 4080);
  EXPECT_EQ(b.find_group("impactor_left"), nullptr);
}

TEST(Generators, GalvezBeam) {
  const Mesh m = meshing::generate(params("galvez_beam", {"size=0.015", "notch_size=0.006"}));
  expect_groups(m, {"beam", "support_left", "support_right", "load_inner", "load_outer", "cmod_left", "cmod_right"});
  const double exact = 0.675 * 0.15 * 0.05 - 0.002 * 0.075 * 0.05;  // prism: exact
  EXPECT_NEAR(group_volume(m, "beam") / exact, 1.0, 1e-10);
  // CMOD edges sit on the two faces of the notch mouth.
  for (Index n : m.find_group("cmod_left")->nodes) EXPECT_NEAR(m.x[3 * n], -0.001, 1e-9);
  for (Index n : m.find_group("cmod_right")->nodes) EXPECT_NEAR(m.x[3 * n], 0.001, 1e-9);
}

namespace {
// Separating-axis test for two tetrahedra: true if they overlap (interiors intersect).
bool tets_overlap(const Vec3* a, const Vec3* b) {
  std::vector<Vec3> axes;
  auto faces = [&](const Vec3* t) {
    for (int i = 0; i < 4; ++i) axes.push_back((t[(i + 1) % 4] - t[i]).cross(t[(i + 2) % 4] - t[i]));
  };
  faces(a), faces(b);
  const int e[6][2] = {{0, 1}, {0, 2}, {0, 3}, {1, 2}, {1, 3}, {2, 3}};
  for (const auto& ea : e)
    for (const auto& eb : e) axes.push_back((a[ea[1]] - a[ea[0]]).cross(b[eb[1]] - b[eb[0]]));
  for (const Vec3& ax : axes) {
    if (ax.squaredNorm() < 1e-24) continue;
    double amin = 1e300, amax = -1e300, bmin = 1e300, bmax = -1e300;
    for (int i = 0; i < 4; ++i) {
      amin = std::min(amin, a[i].dot(ax)), amax = std::max(amax, a[i].dot(ax));
      bmin = std::min(bmin, b[i].dot(ax)), bmax = std::max(bmax, b[i].dot(ax));
    }
    if (amax <= bmin || bmax <= amin) return false;
  }
  return true;
}

std::string slurp(const std::string& p) {
  std::ifstream f(p, std::ios::binary);
  std::stringstream s;
  s << f.rdbuf();
  return s.str();
}
}  // namespace

TEST(Generators, PackingNoOverlapAndReproducible) {
  const fs::path dir = test_dir();
  const std::string a = (dir / "pack_a.msh").string(), b = (dir / "pack_b.msh").string(),
                    c = (dir / "pack_c.msh").string();
  const Mesh m = meshing::generate(params("packing"), a);
  expect_groups(m, {"container", "particles"});
  const Group& pg = *m.find_group("particles");
  EXPECT_EQ(pg.elements[0].size(), 5346u);  // paper: 5346 particles
  // No two particles overlap (separating axis test on every pair whose bounding spheres meet).
  std::vector<std::array<Vec3, 4>> tets;
  for (Index e : pg.elements[0]) {
    std::array<Vec3, 4> t;
    for (int i = 0; i < 4; ++i) t[i] = node_pos(m.x, m.blocks[0].conn[4 * e + i]);
    EXPECT_GT(tet4_volume(t[0], t[1], t[2], t[3]), 0);
    tets.push_back(t);
  }
  long overlaps = 0, checked = 0;
  for (std::size_t i = 0; i < tets.size(); ++i)
    for (std::size_t j = i + 1; j < tets.size(); ++j) {
      const Vec3 ci = (tets[i][0] + tets[i][1] + tets[i][2] + tets[i][3]) / 4;
      const Vec3 cj = (tets[j][0] + tets[j][1] + tets[j][2] + tets[j][3]) / 4;
      if ((ci - cj).norm() > 2 * (0.6124 + 0.1) * 0.7 * 1.01) continue;
      ++checked;
      overlaps += tets_overlap(tets[i].data(), tets[j].data());
    }
  EXPECT_EQ(overlaps, 0);
  EXPECT_GT(checked, 1000);  // the test did look at neighbours
  // Inside the container footprint.
  for (const auto& t : tets)
    for (const Vec3& p : t) {
      EXPECT_TRUE(p(0) > 0 && p(0) < 16.0 && p(1) > 0 && p(2) > 0 && p(2) < 13.8) << p.transpose();
    }
  meshing::generate(params("packing"), b);
  meshing::generate(params("packing", {"seed=2"}), c);
  EXPECT_EQ(slurp(a), slurp(b)) << "same seed, different bytes";
  EXPECT_NE(slurp(a), slurp(c)) << "different seed, same bytes";
}

TEST(Generators, ParameterErrorsNameTheKey) {
  expect_error(params("galvez_beam", {"notch_depth=0.2"}), "mesh.galvez_beam.notch_depth");
  expect_error(params("packing", {"count=100000"}), "mesh.packing.count");
  expect_error(params("sphere_plate", {"size=0.1"}), "mesh.sphere_plate.size");
  expect_error(params("sphere_plate", {"contact_size=0.02"}), "mesh.sphere_plate.contact_size");
  expect_error(params("sphere_plate", {"contact_size=0.005", "contact_distance=0"}),
               "mesh.sphere_plate.contact_distance");
  expect_error(params("brazilian_disc", {"size=0.05"}), "mesh.brazilian_disc.size");
  expect_error(params("brazilian_disc", {"band_width=0.2"}), "mesh.brazilian_disc.band_width");
  expect_error(params("murray_beam", {"span=2.0"}), "mesh.murray_beam.span");
  // Range errors are caught by the schema, with the key and the file line.
  EXPECT_THROW(params("sphere_plate", {"size=-0.01"}), Error);
}

TEST(Generators, AMeshPastAHundredMillionElementsIsRefusedBeforeGmshMeshesIt) {
  // gmsh went on filling the memory for minutes, then aborted. Each is refused at once, before
  // any meshing (a run of these would take hours): the key named, the count said.
  const char* more = "more than dspdem meshes (1e+08)";
  expect_error(params("brazilian_disc", {"size=1e-5"}), "mesh.brazilian_disc.size = 1e-05: about 4.6e+12 elements");
  expect_error(params("brazilian_disc", {"plate_size=1e-5"}), "mesh.brazilian_disc.plate_size");
  expect_error(params("sphere_plate", {"size=1e-4"}), more);
  expect_error(params("galvez_beam", {"size=1e-4"}), "mesh.galvez_beam.size");
  expect_error(params("galvez_beam", {"band_min_x=-0.05", "band_max_x=0.05", "band_size=1e-4"}),
               "mesh.galvez_beam.band_size");
  // A graded size: the disc's load_size at the loaded lines (growing as 1 / load_size).
  expect_error(params("brazilian_disc", {"load_size=1e-9", "plates=0"}),
               "mesh.brazilian_disc.load_size = 1e-09: about 2e+10 elements");
  expect_error(params("murray_beam", {"nx=100000", "ny=1000", "nz=1000"}), "nx x ny x nz hexahedra");
  expect_error(params("murray_beam", {"cylinders=1", "cylinder_size=1e-5"}), "mesh.murray_beam.cylinder_size");
  expect_error(params("packing", {"count=2000000", "refine=2", "size_max=0.41", "fill_height=3000"}),
               "count x 8^refine");
  expect_error(params("packing", {"wall_size=0.001"}), "mesh.packing.wall_size");
}

TEST(Quality, RegularTetHasGammaOne) {
  const Vec3 a(1, 1, 1), b(1, -1, -1), c(-1, 1, -1), d(-1, -1, 1);
  EXPECT_NEAR(meshing::tet_gamma(a, b, c, d), 1.0, 1e-12);
  EXPECT_LT(meshing::tet_gamma(a, b, c, Vec3(0.33, 0.33, -0.33)), 0.1);  // nearly flat
}
