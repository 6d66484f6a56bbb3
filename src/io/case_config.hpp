// A case, as read from its TOML file: every value resolved, validated and in SI units.
// The schema (keys, types, defaults, ranges, units, documentation) is in case_schema.cpp
// and is printed by `dspdem keys`; cases/README.md holds the same table.
#pragma once
#include <Eigen/Geometry>
#include <map>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "contact/contact_params.hpp"
#include "contact/walls.hpp"
#include "core/types.hpp"
#include "fem/fem_model.hpp"
#include "joint/onset.hpp"
#include "time/monitor.hpp"

namespace dspdem {

/// Joint (cohesive) parameters of a material; `given` when the material defines them.
struct JointMaterial {
  bool given = false;
  Real ft = 0, GfI = 0, c = 0, phi_deg = 0, GfII = 0;
  Real penalty = 100, kn = 0, ks = 0;  ///< kn, ks = 0: from the penalty factor
  bool nodal_quadrature = false;       ///< joint_quadrature = "nodal"
  bool coupled = false;                ///< joint_law = "coupled"
  bool mode_i = false;                 ///< joint_law = "mode_I": no shear failure
  bool residual = false;               ///< joint_law = "paper_residual": the cohesion softens, friction stays
  bool energy_mixed_mode = true;       ///< mixed_mode = "energy" (coupled law; the default)
};

/// [contact] and [[walls]].
struct ContactConfig {
  bool enabled = false;
  contact::ContactSettings settings;
};

struct WallConfig {
  contact::Wall wall;  ///< pose, motion and contact parameters (density -> mass for free boxes)
  Vec3 velocity = Vec3::Zero();
  std::string where;
};

struct BodyConfig {
  std::string name;
  enum class Fracture { None, All, Groups } fracture = Fracture::None;
  /// Intrinsic: every joint acts from the start (the paper's). Extrinsic: a joint stays closed
  /// (its two sides one material) until the traction on its face reaches the strength.
  bool extrinsic = false;
  std::vector<std::string> fracture_groups;
  std::vector<std::string> zone_groups;  ///< their joints take zone_material's joint parameters
  std::string zone_material;
  /// Elements whose centroid lies in the box from zone_box_min to zone_box_max (its faces
  /// included, as Eigen's contains()) join the zone too: a zone with no mesh surface along its
  /// edge. Absent unless both corners are given.
  std::optional<Eigen::AlignedBox<Real, 3>> zone_box;
  std::vector<std::string> groups;
  std::string material;
  Kinematics kinematics = Kinematics::Corotational;
  bool split_components = false;
};

struct BoundaryConfig {
  enum class Type { Fixed, Velocity, Force } type = Type::Fixed;
  std::string group;
  bool dof[3] = {true, true, true};
  Vec3 value = Vec3::Zero();
  Real ramp = 0;      ///< linear ramp time from zero [s]
  std::string where;  ///< file:line for messages
};

struct InitialConfig {
  std::string group;
  Vec3 velocity = Vec3::Zero();
  Vec3 angular_velocity = Vec3::Zero();
  Vec3 center = Vec3::Zero();
  std::string where;
};

/// [render]: how `dspdem render` draws a run.
struct RenderConfig {
  std::vector<std::string> views = {"stress", "fragments"};
  std::string field = "von_mises", camera = "iso", cut = "none", plot_reference;
  std::string fit = "diagonal";  ///< how the camera frames the first frame (render/views.hpp)
  Real magnify = 1;
  bool auto_min = true, auto_max = true;
  Real range_min = 0, range_max = 0;
  int width = 1280, height = 720, fps = 10;
  Vec3 background = Vec3::Ones();
  bool animation = true;
  bool edges = false;  ///< element edges over the stress and fragments views
  std::vector<std::string> plots;
};

/// A resolved case's first line: kResolvedFrom, the case file as it was given, kResolvedFromEnd.
inline constexpr std::string_view kResolvedFrom = "# Resolved from ", kResolvedFromEnd = " (every default filled in)";

struct CaseConfig {
  std::string path;  ///< the case file
  std::string dir;   ///< its directory (relative paths are resolved against it)
  std::string name, description;
  std::string scene;                            ///< [case] scene: empty = from the mesh generator
  std::string mesh_file;                        ///< absolute or relative to dir (empty when a generator is used)
  std::string mesh_generator;                   ///< generator name (empty when a file is used)
  std::map<std::string, double> mesh_num;       ///< its numeric parameters
  std::map<std::string, std::string> mesh_str;  ///< its text parameters
  bool mesh_cache = true;
  double mesh_time_limit = 600;  ///< [mesh] time_limit: seconds gmsh may take to read mesh_file
  Vec3 gravity = Vec3::Zero();
  std::vector<Material> materials;
  std::vector<JointMaterial> joint_materials;               ///< parallel to materials
  std::vector<contact::ContactMaterial> contact_materials;  ///< parallel to materials
  ContactConfig contact;
  std::vector<WallConfig> walls;
  std::vector<BodyConfig> bodies;
  std::vector<BoundaryConfig> boundaries;
  std::vector<InitialConfig> initial;
  std::vector<MonitorConfig> monitors;
  // time
  Real t_end = 0, dt = 0, safety = 0.9;
  bool allow_unstable = false;
  long max_steps = 0;
  long insertion_interval = 1;  ///< extrinsic insertion: steps between checks of the closed faces
  joint::FaceStress insertion_stress = joint::FaceStress::Larger;  ///< extrinsic insertion: the face traction's rule
  bool insertion_cut_front = true;  ///< extrinsic insertion: open the faces that tie an opened face's nodes
  std::string stop_series;          ///< empty: run to t_end
  Real stop_fraction = 0.3, stop_min_peak = 0, stop_delay = 0;
  Real stop_reach = 0;  ///< > 0: also stop once |stop_series| has reached this
  // output
  Real frame_interval = 0, series_interval = 0;
  std::vector<std::string> fields;
  bool compress = true;
  RenderConfig render;
  // checks
  Real energy_blowup_factor = 10;
  Real energy_balance_warn = 0.01;     ///< [checks]: time/balance_watch.hpp
  std::string resolved_toml;           ///< the case with every default filled in, under kResolvedFrom's line
  std::vector<std::string> overrides;  ///< the "section.key=value" strings it was read with
};

/// Reads and validates a case. `overrides` are "section.key=value" strings (values in TOML
/// syntax; bare words are taken as strings). Throws Error with file, line and key.
CaseConfig read_case(const std::string& path, const std::vector<std::string>& overrides = {});

/// A numeric parameter of the case's mesh generator ([mesh.<generator>] key, defaults
/// resolved); throws Error naming the case and the key when it has none.
Real mesh_param(const CaseConfig& c, const std::string& key);

/// One "section.key=value" override for read_case, numbers written to round-trip.
std::string override_of(const std::string& key, Real v);
std::string override_of(const std::string& key, const Vec3& v);
std::string override_of(const std::string& key, const std::string& v);  ///< a TOML string

/// `base` read again from its file with its own overrides and then `extra`: a variant whose
/// case.resolved.toml says what it ran (a copy edited in memory would carry base's text).
CaseConfig reread_with(const CaseConfig& base, const std::vector<std::string>& extra);

/// The schema as a Markdown table (for `dspdem keys` and cases/README.md).
std::string case_schema_markdown();

}  // namespace dspdem
