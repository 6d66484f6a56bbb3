#include "io/case_schema.hpp"

#include <fmt/format.h>

#include <limits>

namespace dspdem::schema {

namespace {
constexpr double inf = std::numeric_limits<double>::infinity();
using T = Type;
}  // namespace

const std::vector<const char*>& sections() {
  static const std::vector<const char*> s = {"case",    "mesh",    "physics", "materials.<name>", "bodies[]",
                                             "boundary[]", "initial[]", "time", "output", "monitors[]", "checks"};
  return s;
}

// clang-format off
const std::vector<Key>& keys() {
  static const std::vector<Key> k = {
    {"case", "name", T::String, "auto", 0, 0, false, false, "", nullptr, "Case name used in outputs; defaults to the file name without extension."},
    {"case", "description", T::String, "\"\"", 0, 0, false, false, "", nullptr, "Free text: what the case checks, sources of its numbers and choices made."},
    {"mesh", "file", T::String, nullptr, 0, 0, false, false, "", nullptr, "Mesh file (.msh v2/v4, or a .geo script that gmsh meshes in 3D), relative to the case file."},
    {"physics", "gravity", T::Vec3, "[0.0, 0.0, 0.0]", -inf, inf, false, false, "m/s^2", nullptr, "Gravitational acceleration applied to every node."},
    {"materials.<name>", "density", T::Real, nullptr, 0, inf, true, false, "kg/m^3", nullptr, "Mass density."},
    {"materials.<name>", "E", T::Real, nullptr, 0, inf, true, false, "Pa", nullptr, "Young's modulus."},
    {"materials.<name>", "nu", T::Real, nullptr, -1, 0.5, true, true, "", nullptr, "Poisson's ratio."},
    {"materials.<name>", "damping_alpha", T::Real, "0.0", 0, inf, false, false, "1/s", nullptr, "Mass-proportional Rayleigh coefficient (C = alpha M + beta K)."},
    {"materials.<name>", "damping_beta", T::Real, "0.0", 0, inf, false, false, "s", nullptr, "Stiffness-proportional Rayleigh coefficient."},
    {"materials.<name>", "damping_ratio", T::Real, "0.0", 0, 1, false, true, "", nullptr, "Damping ratio xi reached at damping_frequency; adds alpha = 2 xi w (mode mass) or beta = 2 xi / w (mode stiffness)."},
    {"materials.<name>", "damping_frequency", T::Real, "auto", 0, inf, true, false, "Hz", nullptr, "Frequency at which damping_ratio holds; required when damping_ratio > 0."},
    {"materials.<name>", "damping_mode", T::String, "\"mass\"", 0, 0, false, false, "", "mass|stiffness", "How damping_ratio is realised: mass-proportional (all modes decay at the same rate) or stiffness-proportional (ratio grows with frequency)."},
    {"bodies[]", "name", T::String, nullptr, 0, 0, false, false, "", nullptr, "Body name (unique)."},
    {"bodies[]", "groups", T::StringList, nullptr, 0, 0, false, false, "", nullptr, "Physical volume groups of the mesh that make up the body."},
    {"bodies[]", "material", T::String, nullptr, 0, 0, false, false, "", nullptr, "Name of a [materials.<name>] table."},
    {"bodies[]", "kinematics", T::String, "\"corotational\"", 0, 0, false, false, "", "corotational|small_strain", "Strain measure: corotational (objective, for large rotations) or small_strain (cheaper, small rotations only)."},
    {"boundary[]", "group", T::String, nullptr, 0, 0, false, false, "", nullptr, "Physical group (any dimension) whose nodes the condition acts on."},
    {"boundary[]", "type", T::String, nullptr, 0, 0, false, false, "", "fixed|velocity|force", "fixed: zero velocity; velocity: prescribed velocity; force: total force spread over the group (by area on surfaces, equally on nodes otherwise)."},
    {"boundary[]", "dofs", T::String, "\"xyz\"", 0, 0, false, false, "", nullptr, "Which components are constrained or loaded: any of x, y, z."},
    {"boundary[]", "value", T::Vec3, "[0.0, 0.0, 0.0]", -inf, inf, false, false, "m/s or N", nullptr, "Velocity (type velocity) or total force (type force); only the listed dofs are used."},
    {"boundary[]", "ramp", T::Real, "0.0", 0, inf, false, false, "s", nullptr, "Linear ramp from zero to value over this time (0 = applied at once)."},
    {"initial[]", "group", T::String, nullptr, 0, 0, false, false, "", nullptr, "Physical group whose nodes get the initial velocity."},
    {"initial[]", "velocity", T::Vec3, "[0.0, 0.0, 0.0]", -inf, inf, false, false, "m/s", nullptr, "Initial translational velocity."},
    {"initial[]", "angular_velocity", T::Vec3, "[0.0, 0.0, 0.0]", -inf, inf, false, false, "rad/s", nullptr, "Initial rigid spin about center: v += w x (x - center)."},
    {"initial[]", "center", T::Vec3, "[0.0, 0.0, 0.0]", -inf, inf, false, false, "m", nullptr, "Centre of the initial spin."},
    {"time", "end", T::Real, nullptr, 0, inf, true, false, "s", nullptr, "Simulated end time."},
    {"time", "dt", T::Real, "auto", 0, inf, true, false, "s", nullptr, "Fixed time step; when absent, safety x the critical step."},
    {"time", "safety", T::Real, "0.9", 0, 1, true, false, "", nullptr, "Fraction of the critical step used when dt is absent."},
    {"time", "allow_unstable", T::Bool, "false", 0, 0, false, false, "", nullptr, "Accept a fixed dt above the critical step (for stability studies; the run's checks still stop a blow-up)."},
    {"time", "max_steps", T::Int, "0", 0, inf, false, false, "", nullptr, "Stop after this many steps (0 = no limit)."},
    {"output", "frame_interval", T::Real, "auto", 0, inf, true, false, "s", nullptr, "Simulated time between VTU frames; default end/20."},
    {"output", "series_interval", T::Real, "auto", 0, inf, true, false, "s", nullptr, "Simulated time between rows of series.csv; default frame_interval/10."},
    {"output", "fields", T::StringList, "[\"displacement\", \"velocity\", \"stress\", \"von_mises\", \"max_principal\", \"body\", \"material\"]", 0, 0, false, false, "", "displacement|velocity|stress|von_mises|max_principal|body|material", "Fields written to each frame."},
    {"output", "compress", T::Bool, "true", 0, 0, false, false, "", nullptr, "zlib-compress the VTU data arrays."},
    {"monitors[]", "name", T::String, nullptr, 0, 0, false, false, "", nullptr, "Column name in series.csv (unique)."},
    {"monitors[]", "type", T::String, nullptr, 0, 0, false, false, "", "reaction|displacement|displacement_difference|max_displacement|velocity", "reaction: sum of support reactions on the group's constrained dofs [N]; displacement/velocity: mean over the group [m, m/s]; displacement_difference: mean of group2 minus mean of group [m]; max_displacement: largest over the group [m]."},
    {"monitors[]", "group", T::String, "auto", 0, 0, false, false, "", nullptr, "Physical group (default: all nodes, for max_displacement only)."},
    {"monitors[]", "group2", T::String, "auto", 0, 0, false, false, "", nullptr, "Second group for displacement_difference."},
    {"monitors[]", "component", T::String, "\"magnitude\"", 0, 0, false, false, "", "x|y|z|magnitude", "Component recorded."},
    {"checks", "energy_blowup_factor", T::Real, "10.0", 1, inf, true, false, "", nullptr, "Stop when kinetic + internal energy exceeds this factor times (initial energy + work done on the body + a floor)."},
  };
  return k;
}
// clang-format on

const char* type_name(Type t) {
  switch (t) {
    case Type::Real: return "number";
    case Type::Int: return "integer";
    case Type::Bool: return "boolean";
    case Type::String: return "string";
    case Type::Vec3: return "[x, y, z]";
    case Type::StringList: return "list of strings";
  }
  return "?";
}

std::string range_text(const Key& k) {
  if (k.type != Type::Real && k.type != Type::Int) return k.choices ? std::string(k.choices) : "";
  const bool has_lo = k.lo > -inf, has_hi = k.hi < inf;
  if (has_lo && has_hi)
    return fmt::format("{}{}, {}{}", k.lo_open ? "(" : "[", k.lo, k.hi, k.hi_open ? ")" : "]");
  if (has_lo) return fmt::format("{} {}", k.lo_open ? ">" : ">=", k.lo);
  if (has_hi) return fmt::format("{} {}", k.hi_open ? "<" : "<=", k.hi);
  return "";
}

}  // namespace dspdem::schema
