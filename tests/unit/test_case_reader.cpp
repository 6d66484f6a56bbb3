// Case-file validation: every error names the file, the line and the key.
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>

#include "core/error.hpp"
#include "io/case_config.hpp"

using namespace dspdem;

namespace {
namespace fs = std::filesystem;

const char* kGood = R"([case]
name = "t"
[mesh]
file = "box.msh"
[materials.rock]
density = 2500.0
E = 30.0e9
nu = 0.2
[[bodies]]
name = "b"
groups = ["all"]
material = "rock"
[time]
end = 1.0e-3
)";

std::string write_case(const std::string& text) {
  static int n = 0;
  const fs::path dir = fs::temp_directory_path() / "dspdem_case_reader";
  fs::create_directories(dir);
  // The process id in the name: ctest runs every test as its own process, side by side with -j,
  // and each process counts from 0 (two tests writing case0.toml at once read each other's).
  const fs::path p = dir / ("case" + std::to_string(getpid()) + "_" + std::to_string(n++) + ".toml");
  std::ofstream(p) << text;
  return p.string();
}

std::string replace(std::string s, const std::string& from, const std::string& to) {
  const auto p = s.find(from);
  EXPECT_NE(p, std::string::npos) << from;
  return s.replace(p, from.size(), to);
}

// Expects read_case to throw with every fragment in the message.
void expect_error(const std::string& text, const std::vector<std::string>& fragments,
                  const std::vector<std::string>& overrides = {}) {
  const std::string path = write_case(text);
  try {
    read_case(path, overrides);
    ADD_FAILURE() << "no error for:\n" << text;
  } catch (const Error& e) {
    const std::string msg = e.what();
    for (const auto& f : fragments) EXPECT_NE(msg.find(f), std::string::npos) << "'" << f << "' not in: " << msg;
    EXPECT_NE(msg.find(path), std::string::npos) << "file not named: " << msg;
  }
}
}  // namespace

TEST(CaseReader, GoodCaseResolvesDefaults) {
  const CaseConfig c = read_case(write_case(kGood));
  EXPECT_EQ(c.name, "t");
  EXPECT_DOUBLE_EQ(c.materials[0].E, 30e9);
  EXPECT_DOUBLE_EQ(c.safety, 0.9);
  EXPECT_DOUBLE_EQ(c.dt, 0.0);  // automatic
  EXPECT_DOUBLE_EQ(c.frame_interval, 1e-3 / 20);
  EXPECT_NE(c.resolved_toml.find("safety = 0.9"), std::string::npos);
}

TEST(CaseReader, SyntaxErrorHasLine) { expect_error(replace(kGood, "nu = 0.2", "nu = = 0.2"), {":8:", "syntax"}); }
TEST(CaseReader, UnknownKey) {
  expect_error(replace(kGood, "nu = 0.2", "nu = 0.2\nYoung = 3"), {":9:", "Young", "materials.rock"});
}
TEST(CaseReader, UnknownSection) { expect_error(std::string(kGood) + "[solver]\nx = 1\n", {":15:", "solver"}); }
TEST(CaseReader, NonPositiveE) { expect_error(replace(kGood, "E = 30.0e9", "E = 0.0"), {":7:", "'E'", "range"}); }
TEST(CaseReader, NuTooLarge) { expect_error(replace(kGood, "nu = 0.2", "nu = 0.5"), {":8:", "'nu'", "(-1, 0.5)"}); }
TEST(CaseReader, NuTooSmall) { expect_error(replace(kGood, "nu = 0.2", "nu = -1.0"), {":8:", "'nu'"}); }
TEST(CaseReader, NegativeDensity) {
  expect_error(replace(kGood, "density = 2500.0", "density = -1.0"), {":6:", "'density'"});
}
TEST(CaseReader, NonPositiveDt) { expect_error(std::string(kGood) + "dt = 0.0\n", {":15:", "'dt'", "> 0"}); }
TEST(CaseReader, WrongType) { expect_error(replace(kGood, "E = 30.0e9", "E = \"stiff\""), {":7:", "'E'", "number"}); }
TEST(CaseReader, MissingRequired) { expect_error(replace(kGood, "E = 30.0e9\n", ""), {"missing", "'E'"}); }
TEST(CaseReader, UnknownMaterial) {
  expect_error(replace(kGood, "material = \"rock\"", "material = \"granite\""), {":12:", "granite"});
}
TEST(CaseReader, BadChoice) {
  expect_error(std::string(kGood) + "[[monitors]]\nname = \"m\"\ntype = \"stress\"\n", {":17:", "'type'", "reaction"});
}
TEST(CaseReader, OverrideIsValidated) {
  expect_error(kGood, {"--set", "'nu'"}, {"materials.rock.nu=0.7"});
  const CaseConfig c = read_case(write_case(kGood), {"time.end=2e-3", "case.name=renamed"});
  EXPECT_DOUBLE_EQ(c.t_end, 2e-3);
  EXPECT_EQ(c.name, "renamed");
  // A value TOML cannot read as a number is a bare word, a string: a string key takes it, a
  // number key says what TOML made of it.
  EXPECT_EQ(read_case(write_case(kGood), {"case.name=007"}).name, "007");
  EXPECT_EQ(read_case(write_case(kGood), {"case.description=1."}).description, "1.");
  expect_error(kGood, {"'end' must be a number; 1e400 is not a number TOML reads", "could not be interpreted"},
               {"time.end=1e400"});
  expect_error(kGood, {"'end' must be a number, got the string \"soon\""}, {"time.end=soon"});
}
TEST(CaseReader, JointParametersComeTogetherAndStayConsistent) {
  expect_error(replace(kGood, "nu = 0.2", "nu = 0.2\ntensile_strength = 3.0e6"), {"joint parameters come together"});
  const std::string joint =
      "nu = 0.2\ntensile_strength = 3.0e6\nfracture_energy_I = 10.0\ncohesion = 1.0e6\n"
      "friction_angle = 45.0\nfracture_energy_II = 100.0";
  // c = 1 MPa < f_t tan(45 deg) = 3 MPa: no shear strength left at the tension cut-off.
  expect_error(replace(kGood, "nu = 0.2", joint), {":11:", "cohesion", "eq. 5"});
}

TEST(CaseReader, JointQuadratureIsAChoice) {
  EXPECT_FALSE(read_case(write_case(kGood)).joint_materials[0].nodal_quadrature);  // the paper's Gauss
  EXPECT_TRUE(
      read_case(write_case(kGood), {"materials.rock.joint_quadrature=\"nodal\""}).joint_materials[0].nodal_quadrature);
  expect_error(replace(kGood, "nu = 0.2", "nu = 0.2\njoint_quadrature = \"lobatto\""),
               {":9:", "'joint_quadrature'", "gauss|nodal"});
}

TEST(CaseReader, RereadKeepsItsOverridesAndAddsMore) {
  // A study variant is its base read again with the base's overrides and then its own; its
  // resolved text (written as case.resolved.toml) must carry both, later ones winning.
  const CaseConfig base = read_case(write_case(kGood), {"materials.rock.joint_penalty=30", "time.end=2e-3"});
  const CaseConfig v = reread_with(base, {"materials.rock.joint_quadrature=\"nodal\"", "time.end=5e-4"});
  EXPECT_EQ(v.joint_materials[0].penalty, 30.0);
  EXPECT_TRUE(v.joint_materials[0].nodal_quadrature);
  EXPECT_EQ(v.t_end, 5e-4);
  EXPECT_EQ(base.t_end, 2e-3);
  EXPECT_EQ(v.overrides.size(), 4u);
  EXPECT_NE(v.resolved_toml.find("nodal"), std::string::npos);
  EXPECT_EQ(base.resolved_toml.find("nodal"), std::string::npos);
}

TEST(CaseReader, MissingFile) { EXPECT_THROW(read_case("/nonexistent/case.toml"), Error); }

TEST(CaseReader, OverrideReplacesAWholeArrayElement) {
  // --set walls.0={...} swaps one element of an array of tables for another (a study row
  // that puts flat plates where the case has jaws must drop the jaw's radius, which a box
  // refuses); an index further than one past the end is refused with the array's size.
  const std::string walls = std::string(kGood) +
                            "[contact]\nenabled = true\n[[walls]]\nname = \"j\"\ntype = \"jaw\"\n"
                            "point = [0.0, -0.5, 0.0]\nnormal = [0.0, 1.0, 0.0]\nradius = 1.5\n";
  const std::string path = write_case(walls);
  const CaseConfig c =
      read_case(path, {"walls.0={name = \"p\", type = \"box\", point = [0.0, 1.1, 0.0], half_size = [0.1, 0.1, 0.1]}"});
  ASSERT_EQ(c.walls.size(), 1u);
  EXPECT_EQ(c.walls[0].wall.name, "p");
  EXPECT_EQ(c.walls[0].wall.type, contact::Wall::Type::Box);
  EXPECT_DOUBLE_EQ(c.walls[0].wall.centre(1), 1.1);
  expect_error(walls, {"--set 'walls.2=", "(size 1"}, {"walls.2={name = \"q\"}"});
  // One past the end appends (AWholeElementOnePastTheEndIsAppended); an incomplete element is
  // then checked like any wall of the file, and the error says it came from --set.
  expect_error(walls, {"(--set)", "'type'"}, {"walls.1={name = \"q\"}"});
}

TEST(CaseReader, JointMonitorsTakeABoxNotAGroup) {
  // broken_joints and crack_area count joints where they lie: a box, both corners, the lower
  // below the upper; a group or a component would be silently meaningless, so they are errors,
  // and a box on a node monitor too.
  const std::string m = std::string(kGood) + "[[monitors]]\nname = \"low\"\ntype = \"broken_joints\"\n";
  const CaseConfig all = read_case(write_case(m));
  ASSERT_EQ(all.monitors.size(), 1u);
  EXPECT_EQ(all.monitors[0].type, MonitorConfig::Type::BrokenJoints);
  EXPECT_FALSE(all.monitors[0].box.has_value()) << "no box: every joint";
  const std::string lo = "monitors.0.box_min=[-1.0, -1.0, -1.0]", hi = "monitors.0.box_max=[1.0, 0.5, 1.0]";
  const CaseConfig boxed = read_case(write_case(m), {lo, hi});
  ASSERT_TRUE(boxed.monitors[0].box.has_value());
  EXPECT_EQ(boxed.monitors[0].box->max(), Vec3(1.0, 0.5, 1.0));
  expect_error(m, {"'low'", "box_min and box_max come together"}, {lo});
  expect_error(m, {"'low'", "box_max must lie above box_min", "(y is -2"}, {lo, "monitors.0.box_max=[1.0, -2.0, 1.0]"});
  expect_error(m, {"'low'", "takes no group"}, {"monitors.0.group=\"caps\""});
  expect_error(m, {"'low'", "takes no component"}, {"monitors.0.component=\"y\""});
  expect_error(replace(m, "broken_joints", "crack_area"), {"crack_area monitor", "takes no group"},
               {"monitors.0.group=\"caps\""});
  expect_error(replace(m, "\"broken_joints\"", "\"reaction\"\ngroup = \"caps\""),
               {"'low'", "box_min is for broken_joints and crack_area monitors, not reaction"}, {lo, hi});
}

TEST(CaseReader, JointZonesNeedBothKeysAndJointParameters) {
  const std::string joint =
      "nu = 0.2\ntensile_strength = 3.0e6\nfracture_energy_I = 10.0\ncohesion = 4.0e6\n"
      "friction_angle = 45.0\nfracture_energy_II = 100.0";
  const std::string base =
      replace(replace(kGood, "nu = 0.2", joint), "material = \"rock\"", "material = \"rock\"\nfracture = \"all\"");
  expect_error(base, {"zone_groups and zone_material come together"}, {"bodies.0.zone_groups=[\"caps\"]"});
  expect_error(base, {"'steel'"}, {"bodies.0.zone_groups=[\"caps\"]", "bodies.0.zone_material=\"steel\""});
  const CaseConfig c =
      read_case(write_case(base), {"bodies.0.zone_groups=[\"caps\"]", "bodies.0.zone_material=\"rock\""});
  EXPECT_EQ(c.bodies[0].zone_material, "rock");
  EXPECT_FALSE(c.bodies[0].zone_box.has_value());
  // The box: both corners, the lower below the upper on every axis, and a material.
  const std::string lo = "bodies.0.zone_box_min=[-1.0, -1.0, -1.0]", hi = "bodies.0.zone_box_max=[1.0, 0.5, 1.0]";
  expect_error(base, {"zone_box_min and zone_box_max come together"}, {lo, "bodies.0.zone_material=\"rock\""});
  expect_error(base, {"zone_box_min and zone_box_max come together"}, {hi, "bodies.0.zone_material=\"rock\""});
  expect_error(base, {"has a joint zone but no joints"},
               {lo, hi, "bodies.0.zone_material=\"rock\"", "bodies.0.fracture=\"none\""});
  expect_error(base, {"needs zone_material"}, {lo, hi});
  expect_error(base, {"zone_box_max must lie above zone_box_min", "(y is -2"},
               {lo, "bodies.0.zone_box_max=[1.0, -2.0, 1.0]", "bodies.0.zone_material=\"rock\""});
  expect_error(base, {"zone_material needs zone_groups or a zone box"}, {"bodies.0.zone_material=\"rock\""});
  const CaseConfig b = read_case(write_case(base), {lo, hi, "bodies.0.zone_material=\"rock\""});
  ASSERT_TRUE(b.bodies[0].zone_box.has_value());
  EXPECT_EQ(b.bodies[0].zone_box->min(), Vec3(-1.0, -1.0, -1.0));
  EXPECT_EQ(b.bodies[0].zone_box->max(), Vec3(1.0, 0.5, 1.0));
  EXPECT_TRUE(b.bodies[0].zone_groups.empty());
}

TEST(CaseReader, CylinderWallsNeedRadiusAndLengthAndMayBeFree) {
  const std::string walls = std::string(kGood) +
                            "[contact]\nenabled = true\n[[walls]]\nname = \"roller\"\ntype = \"cylinder\"\n"
                            "point = [0.0, 0.0, 0.1]\naxis = [0.0, 2.0, 0.0]\n";
  expect_error(walls, {"'roller'", "cylinder", "radius and length"});
  expect_error(walls + "radius = 0.016\n", {"radius and length"});
  const CaseConfig c = read_case(write_case(walls + "radius = 0.016\nlength = 0.1\nfree = true\ndensity = 7800.0\n"));
  const contact::Wall& w = c.walls[0].wall;
  EXPECT_EQ(w.type, contact::Wall::Type::Cylinder);
  EXPECT_DOUBLE_EQ(w.half_length, 0.05);
  EXPECT_TRUE(w.axis0.isApprox(Vec3::UnitY()));
  const Real m = 7800 * M_PI * 0.016 * 0.016 * 0.1;
  EXPECT_NEAR(w.mass, m, 1e-12 * m);
  EXPECT_NEAR(w.inertia_body(1, 1), 0.5 * m * 0.016 * 0.016, 1e-12 * m);                   // about the axis
  EXPECT_NEAR(w.inertia_body(0, 0), m * (3 * 0.016 * 0.016 + 0.1 * 0.1) / 12, 1e-12 * m);  // across it
  // A mass instead of the density: the same body; both, or neither, or a fixed wall with a mass, are refused.
  const CaseConfig cm = read_case(
      write_case(walls + "radius = 0.016\nlength = 0.1\nfree = true\nmass = " + fmt::format("{:.17g}", m) + "\n"));
  EXPECT_NEAR(cm.walls[0].wall.mass, m, 1e-12 * m);
  EXPECT_NEAR(cm.walls[0].wall.inertia_body(1, 1), w.inertia_body(1, 1), 1e-12 * m);
  expect_error(walls + "radius = 0.016\nlength = 0.1\nfree = true\n", {"'roller'", "density or its mass"});
  expect_error(walls + "radius = 0.016\nlength = 0.1\nfree = true\nmass = 2.0\ndensity = 7800.0\n",
               {"density or its mass"});
  expect_error(walls + "radius = 0.016\nlength = 0.1\nmass = 2.0\n", {"'mass'", "free walls only"});
  // length is for cylinders only
  expect_error(
      std::string(kGood) + "[contact]\nenabled = true\n[[walls]]\nname = \"p\"\ntype = \"plane\"\nlength = 1.0\n",
      {"'length'", "cylinders only"});
}

TEST(CaseReader, RigidBodiesDoNotFracture) {
  const CaseConfig c = read_case(write_case(kGood), {"bodies.0.kinematics=\"rigid\""});
  EXPECT_EQ(c.bodies[0].kinematics, Kinematics::Rigid);
  expect_error(kGood, {"rigid and cannot fracture"}, {"bodies.0.kinematics=\"rigid\"", "bodies.0.fracture=\"all\""});
  expect_error(kGood, {"'kinematics'"}, {"bodies.0.kinematics=\"stiff\""});
}

TEST(CaseReader, ModeIJointsTakeNoShearParameters) {
  // joint_law = "mode_I" is a clear setting, not large shear numbers: it needs f_t, G_fI and
  // the friction angle of broken faces, and refuses a cohesion or a G_fII it would ignore.
  const std::string mode_i =
      "nu = 0.2\njoint_law = \"mode_I\"\ntensile_strength = 3.0e6\nfracture_energy_I = 10.0\nfriction_angle = 30.0";
  const CaseConfig c = read_case(write_case(replace(kGood, "nu = 0.2", mode_i)));
  EXPECT_TRUE(c.joint_materials[0].given);
  EXPECT_TRUE(c.joint_materials[0].mode_i);
  expect_error(replace(kGood, "nu = 0.2", mode_i + "\ncohesion = 20.0e6"), {":13:", "'cohesion'", "mode_I"});
  expect_error(replace(kGood, "nu = 0.2", "nu = 0.2\njoint_law = \"mode_I\"\ntensile_strength = 3.0e6"),
               {"come together", "friction_angle"});
}

TEST(CaseReader, TheMixedModeFormIsTheCoupledLawsOnly) {
  // mixed_mode chooses where the coupled law's mixed paths break; under another law it would
  // be ignored, so it is refused, naming the key's line and the law.
  const std::string coupled = "nu = 0.2\njoint_law = \"coupled\"\nmixed_mode = \"displacement\"";
  const CaseConfig c = read_case(write_case(replace(kGood, "nu = 0.2", coupled)));
  EXPECT_TRUE(c.joint_materials[0].coupled);
  EXPECT_FALSE(c.joint_materials[0].energy_mixed_mode);
  EXPECT_TRUE(read_case(write_case(kGood)).joint_materials[0].energy_mixed_mode);  // the default
  // The default, as a resolved case writes it for every material, is read under any law.
  EXPECT_NO_THROW(read_case(write_case(replace(kGood, "nu = 0.2", "nu = 0.2\nmixed_mode = \"energy\""))));
  expect_error(replace(kGood, "nu = 0.2", "nu = 0.2\nmixed_mode = \"displacement\""),
               {":9:", "mixed_mode", "coupled", "\"paper\""});
  expect_error(replace(kGood, "nu = 0.2", "nu = 0.2\njoint_law = \"coupled\"\nmixed_mode = \"energies\""),
               {"'mixed_mode'"});
}

TEST(CaseReader, ExtrinsicInsertionNeedsJoints) {
  // The good case's body has no joints: extrinsic insertion there is an error naming the key;
  // a wrong choice names it too; the check interval is read.
  expect_error(kGood, {"fracture_insertion", "no joints"}, {"bodies.0.fracture_insertion=\"extrinsic\""});
  expect_error(kGood, {"'fracture_insertion'"}, {"bodies.0.fracture_insertion=\"later\""});
  expect_error(kGood, {"'insertion_interval'"}, {"time.insertion_interval=0"});
  expect_error(kGood, {"'insertion_stress'"}, {"time.insertion_stress=\"median\""});
  const CaseConfig c = read_case(write_case(kGood), {"time.insertion_interval=5"});
  EXPECT_EQ(c.insertion_interval, 5);
  EXPECT_EQ(c.insertion_stress, joint::FaceStress::Larger);  // the default
  EXPECT_EQ(read_case(write_case(kGood), {"time.insertion_stress=\"mean\""}).insertion_stress, joint::FaceStress::Mean);
  EXPECT_FALSE(c.bodies[0].extrinsic);
}

// Defects the fuzz test (tests/robustness/test_fuzz_inputs.cpp) found, one input each.

TEST(CaseReader, AMissingSectionIsNotBlamedOnSet) {
  // Fuzz: with [time] gone, the error read "case.toml (--set): [time] is missing required key
  // 'end'", naming an override that was never given; and a default filled in (a box's
  // half_size) was placed the same way. Now: the file alone, or the table's line.
  const std::string no_time = replace(kGood, "[time]\nend = 1.0e-3\n", "");
  expect_error(no_time, {"[time]", "'end'"});
  try {
    read_case(write_case(no_time));
  } catch (const Error& e) {
    EXPECT_EQ(std::string(e.what()).find("--set"), std::string::npos) << e.what();
  }
  const std::string box = std::string(kGood) + "[contact]\nenabled = true\n[[walls]]\nname = \"w\"\ntype = \"box\"\n";
  expect_error(box, {":17:", "half_size"});
  // Values that do come from --set are still named so, bare words included.
  expect_error(kGood, {"(--set)", "'kinematics'"}, {"bodies.0.kinematics=stiff"});
  expect_error(kGood, {"(--set)", "'nu'"}, {"materials.rock.nu=0.7"});
}

TEST(CaseReader, AVectorOutOfRangeSaysItsRange) {
  // Fuzz: "[[walls]] #1 key 'half_size' = -1 is out of range: must be  (m)" (no range).
  const std::string box = std::string(kGood) +
                          "[contact]\nenabled = true\n[[walls]]\nname = \"w\"\ntype = \"box\"\n"
                          "half_size = [-1.0, 1.0, 1.0]\n";
  expect_error(box, {":20:", "'half_size'", "must be >= 0 (m)"});
  expect_error(std::string(kGood) + "[render]\nbackground = [2.0, 0.0, 0.0]\n", {":16:", "'background'", "[0, 1]"});
}

TEST(CaseReader, AnIntegerTooLargeForADoubleIsNamedSo) {
  // Fuzz: E = 9223372036854775807 read "key 'E' must be a number, got an integer".
  expect_error(replace(kGood, "E = 30.0e9", "E = 9223372036854775807"),
               {":7:", "'E'", "too large an integer", "9.223e+18"});
}

// Contact damping is given as a restitution (default 0.8) or as a fraction of critical,
// never both; restitution 1 is an elastic contact.
TEST(CaseReader, ContactRestitutionOrDampingNotBoth) {
  expect_error(replace(kGood, "nu = 0.2", "nu = 0.2\ncontact_restitution = 0.6\ncontact_damping = 0.1"),
               {":10:", "contact_restitution", "contact_damping", "not both"});
  expect_error(replace(kGood, "nu = 0.2", "nu = 0.2\ncontact_restitution = 0.1"),
               {":9:", "contact_restitution", "range"});
  EXPECT_EQ(read_case(write_case(replace(kGood, "nu = 0.2", "nu = 0.2\ncontact_restitution = 1.0")))
                .contact_materials.at(0)
                .damping_ratio,
            0.0);
  EXPECT_EQ(read_case(write_case(replace(kGood, "nu = 0.2", "nu = 0.2\ncontact_damping = 0.3")))
                .contact_materials.at(0)
                .damping_ratio,
            0.3);
}

TEST(CaseReader, AWholeElementOnePastTheEndIsAppended) {
  // A study variant adds a condition (the Galvez beam's held second top line) by --set.
  const std::string text = std::string(kGood) + "[[boundary]]\ngroup = \"all\"\ntype = \"fixed\"\n";
  const CaseConfig c = read_case(write_case(text), {"boundary.1={group=\"all\", type=\"fixed\", dofs=\"y\"}"});
  ASSERT_EQ(c.boundaries.size(), 2u);
  EXPECT_TRUE(c.boundaries[0].dof[0]);
  EXPECT_FALSE(c.boundaries[1].dof[0]);
  EXPECT_TRUE(c.boundaries[1].dof[1]);
  // Further than one past the end, or not a table: refused, naming the override.
  for (const std::string bad : {"boundary.2={group=\"all\", type=\"fixed\"}", "boundary.1=3"}) {
    try {
      read_case(write_case(text), {bad});
      ADD_FAILURE() << "no error for --set " << bad;
    } catch (const Error& e) {
      EXPECT_NE(std::string(e.what()).find(bad), std::string::npos) << e.what();
    }
  }
}

TEST(CaseReader, NamesThatHeadSeriesColumnsAreRefusedWhenTheyWouldShiftThem) {
  // A probe's finding: a monitor named "a,b" ran, and series.csv then held one more name than
  // values in each row, which the render refused after the run.
  const std::string m = std::string(kGood) + "[[monitors]]\nname = \"low\"\ntype = \"broken_joints\"\n";
  for (const char* bad : {"\"a,b\"", "\"\"", "\"say \\\"hi\\\"\"", "\"two\\nlines\"", "\" padded\""})
    expect_error(replace(m, "\"low\"", bad), {":16:", "heads columns of series.csv"});
  const std::string w = std::string(kGood) +
                        "[contact]\nenabled = true\n[[walls]]\nname = \"w,1\"\ntype = \"plane\"\n"
                        "point = [0.0, 0.0, 0.0]\nnormal = [0.0, 1.0, 0.0]\n";
  expect_error(w, {"wall name 'w,1' heads columns of series.csv"});
  EXPECT_NO_THROW(read_case(write_case(replace(m, "\"low\"", "\"notch-left_2.a\""))));
}
