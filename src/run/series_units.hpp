// The unit of each series.csv column, for the axes of the plots drawn from it. The columns
// are written by run_case's series writer: the ledger, the counts, each wall's force (and a
// free wall's motion), each monitor.
#pragma once
#include <string>

#include "io/case_config.hpp"
#include "time/monitor.hpp"

namespace dspdem {

/// SI unit of what a monitor of this type records ("kg m/s" for momentum).
const char* monitor_unit(MonitorConfig::Type t);

/// The unit of series.csv's column `column` of case `c`: "J", "N", "m", "s", ...; "1" for the
/// dimensionless (balance_error), "count" for counts, "" for a column the case does not write.
std::string series_unit(const CaseConfig& c, const std::string& column);

/// An axis title: the column with its unit in brackets where it has one ("tip_uy [m]").
std::string series_axis_title(const CaseConfig& c, const std::string& column);

}  // namespace dspdem
