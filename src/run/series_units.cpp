#include "run/series_units.hpp"

#include <array>
#include <string_view>

#include "core/error.hpp"

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
    case MonitorConfig::Type::BrokenJoints:
      return "count";
    case MonitorConfig::Type::CrackArea:
      return "m^2";
  }
  return "";
}

const std::array<SeriesColumn, 11> kSeriesColumns = {{{"time", "s"},
                                                      {"step", "count"},
                                                      {"kinetic", "J"},
                                                      {"internal", "J"},
                                                      {"external_work", "J"},
                                                      {"damping", "J"},
                                                      {"joint_elastic", "J"},
                                                      {"fracture_I", "J"},
                                                      {"fracture_II", "J"},
                                                      {"broken_joints", "count"},
                                                      {"crack_area", "m^2"}}};
const std::array<SeriesColumn, 7> kSeriesContactColumns = {{{"contact_elastic", "J"},
                                                            {"friction", "J"},
                                                            {"contact_damping", "J"},
                                                            {"contacts", "count"},
                                                            {"born_split_energy", "J"},
                                                            {"born_unseen_energy", "J"},
                                                            {"born_wall_energy", "J"}}};
const std::array<SeriesColumn, 2> kSeriesLastColumns = {{{"kick", "J"}, {"balance_error", "1"}}};
const std::array<SeriesColumn, 3> kWallForceColumns = {{{"_fx", "N"}, {"_fy", "N"}, {"_fz", "N"}}};
const std::array<SeriesColumn, 6> kFreeWallColumns = {
    {{"_x", "m"}, {"_y", "m"}, {"_z", "m"}, {"_vx", "m/s"}, {"_vy", "m/s"}, {"_vz", "m/s"}}};

namespace {
// The unit of a column the run writes of its own or for a wall; "" for any other name.
std::string own_or_wall_unit(const CaseConfig& c, const std::string& column) {
  auto in = [&](const auto& table) -> std::string {
    for (const auto& f : table)
      if (column == f.name) return std::string(f.unit);
    return {};
  };
  for (std::string u : {in(kSeriesColumns), in(kSeriesContactColumns), in(kSeriesLastColumns)})
    if (!u.empty()) return u;
  for (const auto& w : c.walls) {
    for (const auto& s : kWallForceColumns)
      if (column == w.wall.name + std::string(s.name)) return std::string(s.unit);
    if (w.wall.free)
      for (const auto& s : kFreeWallColumns)
        if (column == w.wall.name + std::string(s.name)) return std::string(s.unit);
  }
  return "";
}
}  // namespace

std::string series_unit(const CaseConfig& c, const std::string& column) {
  if (std::string u = own_or_wall_unit(c, column); !u.empty()) return u;
  for (const auto& m : c.monitors)
    if (column == m.name) return monitor_unit(m.type);
  return "";
}

void check_monitor_columns(const CaseConfig& c) {
  // A monitor named as one of those columns (broken_joints, plate_fy) would make series.csv
  // hold the name twice, and whatever reads it by name would take the first.
  for (const auto& m : c.monitors)
    if (!own_or_wall_unit(c, m.name).empty())
      fail("{}: [[monitors]] name '{}' is already a column of series.csv (the run's own or a wall's): choose another",
           m.where, m.name);
}

std::string series_axis_title(const CaseConfig& c, const std::string& column) {
  const std::string u = series_unit(c, column);
  return u.empty() || u == "count" ? column : column + " [" + u + "]";
}

}  // namespace dspdem
