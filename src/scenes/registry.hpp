// Benchmark scenes by name. A scene owns its analysis, study variants and report text in
// src/scenes/<name>/; adding one is its folder plus one line in registry.cpp.
#pragma once
#include <functional>
#include <string>
#include <vector>

#include "io/case_config.hpp"
#include "report/report_args.hpp"

namespace dspdem::scenes {

struct Scene {
  std::string name;       ///< [case] scene = "<name>"
  std::string generator;  ///< mesh generator whose cases are this scene by default ("" none)
  std::string title;      ///< one line for listings
  std::function<int(const CaseConfig&, const report::ReportArgs&)> report;
  std::string case_file;                ///< its shipped case, relative to the source tree
  std::vector<std::string> quick_args;  ///< `dspdem report` arguments for a CI-sized run (figures --quick)
  bool speed_sweep = false;             ///< its report takes --speeds, --study-speeds and --realisations
};

const std::vector<Scene>& all();

/// The scene of a case: its [case] scene key, else the scene of its mesh generator. Throws
/// Error naming the case file and listing the known scenes when there is none.
const Scene& of_case(const CaseConfig& c);

}  // namespace dspdem::scenes
