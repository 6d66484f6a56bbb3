#include "report/run_place.hpp"

#include <filesystem>
#include <fstream>
#include <sstream>

#include "core/error.hpp"
#include "io/staging.hpp"

namespace dspdem::report {

namespace fs = std::filesystem;

namespace {
constexpr const char* kDerivedFrom = "derived_from";
}

bool holds_a_run(const std::string& dir) {
  for (const char* f : {"summary.json", "run.pvd", failed_folder, interrupted_folder})
    if (fs::exists(fs::path(dir) / f)) return true;
  std::error_code e;
  for (const auto& entry : fs::directory_iterator(dir, e))
    if (entry.is_directory(e) && is_staging_folder(entry.path().string())) return true;
  return false;
}

void prepare_derived_place(const std::string& place, const std::string& run_dir) {
  std::error_code differ;
  if (fs::equivalent(place, run_dir, differ)) return;
  DSPDEM_CHECK(!holds_a_run(place),
               "{} holds a run of its own, where the report would write what it derives from the run in {}; give "
               "--out a folder without one",
               place, run_dir);
  const std::string from = fs::weakly_canonical(run_dir).string();
  const fs::path mark = fs::path(place) / kDerivedFrom;
  if (fs::exists(place) && !fs::is_empty(place)) {
    // Only a folder a report filled is ever emptied.
    DSPDEM_CHECK(fs::exists(mark),
                 "{} holds files that no report derived from a run (no {} there); give --out another folder", place,
                 kDerivedFrom);
    std::ostringstream was;
    was << std::ifstream(mark).rdbuf();
    if (was.str() != from) fs::remove_all(place);  // another run's: its images would show as this one's
  }
  fs::create_directories(place);
  std::ofstream(mark) << from;
}

}  // namespace dspdem::report
