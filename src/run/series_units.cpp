#include "run/series_units.hpp"

#include <array>
#include <string_view>

namespace dspdem {

const char* monitor_unit(MonitorConfig::Type t) {
  switch (t) {
    case MonitorConfig::Type::Reaction:
      return "N";
    case MonitorConfig::Type::Displacement:
    case MonitorConfig::Type::DisplacementDifference:
    case MonitorConfig::Type::MaxDisplacement:
      return "m";
    case MonitorConfig::Type::Velocity:
      return "m/s";
    case MonitorConfig::Type::Momentum:
      return "kg m/s";
  }
  return "";
}

std::string series_unit(const CaseConfig& c, const std::string& column) {
  struct Fixed {
    std::string_view name, unit;
  };
  static constexpr std::array<Fixed, 20> fixed = {{{"time", "s"},
                                                   {"step", "count"},
                                                   {"kinetic", "J"},
                                                   {"internal", "J"},
                                                   {"external_work", "J"},
                                                   {"damping", "J"},
                                                   {"joint_elastic", "J"},
                                                   {"fracture_I", "J"},
                                                   {"fracture_II", "J"},
                                                   {"broken_joints", "count"},
                                                   {"crack_area", "m^2"},
                                                   {"contact_elastic", "J"},
                                                   {"friction", "J"},
                                                   {"contact_damping", "J"},
                                                   {"contacts", "count"},
                                                   {"born_split_energy", "J"},
                                                   {"born_unseen_energy", "J"},
                                                   {"born_wall_energy", "J"},
                                                   {"kick", "J"},
                                                   {"balance_error", "1"}}};
  for (const auto& f : fixed)
    if (column == f.name) return std::string(f.unit);
  for (const auto& m : c.monitors)
    if (column == m.name) return monitor_unit(m.type);
  // A wall's force, and a free wall's centre and velocity: <name>_fx ... <name>_vz.
  struct Suffix {
    std::string_view suffix, unit;
  };
  static constexpr std::array<Suffix, 9> walls = {{{"_fx", "N"},
                                                   {"_fy", "N"},
                                                   {"_fz", "N"},
                                                   {"_x", "m"},
                                                   {"_y", "m"},
                                                   {"_z", "m"},
                                                   {"_vx", "m/s"},
                                                   {"_vy", "m/s"},
                                                   {"_vz", "m/s"}}};
  for (const auto& w : c.walls)
    for (const auto& s : walls)
      if (column == w.wall.name + std::string(s.suffix)) return std::string(s.unit);
  return "";
}

std::string series_axis_title(const CaseConfig& c, const std::string& column) {
  const std::string u = series_unit(c, column);
  return u.empty() || u == "count" ? column : column + " [" + u + "]";
}

}  // namespace dspdem
