// The unit of each series.csv column, for the axes of the plots drawn from it. The columns
// are written by run_case's series writer: the ledger, the counts, each wall's force (and a
// free wall's motion), each monitor.
#pragma once
#include <array>
#include <string>
#include <string_view>

#include "io/case_config.hpp"
#include "time/monitor.hpp"

namespace dspdem {

/// A series.csv column of the run's own (not a wall's or a monitor's) and its unit.
struct SeriesColumn {
  std::string_view name, unit;
};

/// The run's own columns, in their order in series.csv: the first always, the second with
/// contact (born_*_energy: the spring energy of pairs first found overlapping after the first
/// build, so far; contact/contact_system.hpp, BornTotals), the last always; the walls' and
/// the monitors' columns follow.
extern const std::array<SeriesColumn, 11> kSeriesColumns;
extern const std::array<SeriesColumn, 7> kSeriesContactColumns;
extern const std::array<SeriesColumn, 2> kSeriesLastColumns;
/// Each wall's force, <name>_fx ...; a free wall's centre and velocity after them.
extern const std::array<SeriesColumn, 3> kWallForceColumns;
extern const std::array<SeriesColumn, 6> kFreeWallColumns;

/// SI unit of what a monitor of this type records ("kg m/s" for momentum).
const char* monitor_unit(MonitorConfig::Type t);

/// The unit of series.csv's column `column` of case `c`: "J", "N", "m", "s", ...; "1" for the
/// dimensionless (balance_error), "count" for counts, "" for a column the case does not write
/// (a fixed wall's motion included).
std::string series_unit(const CaseConfig& c, const std::string& column);

/// Fails, naming the monitor, when a monitor's name is one of the run's own columns or a
/// wall's: series.csv's names must be unique.
void check_monitor_columns(const CaseConfig& c);

/// An axis title: the column with its unit in brackets where it has one ("tip_uy [m]").
std::string series_axis_title(const CaseConfig& c, const std::string& column);

}  // namespace dspdem
