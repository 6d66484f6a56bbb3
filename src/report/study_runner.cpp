#include "report/study_runner.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <filesystem>

#include "core/error.hpp"
#include "core/log.hpp"
#include "report/resume.hpp"

namespace dspdem::report {

namespace fs = std::filesystem;

std::vector<VariantOutcome> run_variants(const std::vector<Variant>& variants, const std::string& dir,
                                         const std::function<void(std::size_t, const std::string&)>& run) {
  std::vector<VariantOutcome> out(variants.size());
  for (std::size_t i = 0; i < variants.size(); ++i) {
    const Variant& v = variants[i];
    if (v.reuse) continue;
    log::info("study: {} ({})", v.name, v.knob);
    out[i].run_dir = (fs::path(dir) / "study" / v.name).string();
    try {
      run(i, out[i].run_dir);
    } catch (const Interrupted&) {
      throw;  // the user stopped the run: stop the study, rather than start the next variant
    } catch (const std::exception& e) {
      log::warn("study: {} failed: {}", v.name, e.what());
      out[i].error = e.what();
    }
  }
  return out;
}

CaseConfig run_variant_case(const CaseConfig& base, const Variant& v, const std::string& run_dir,
                            const RunPolicy& runs) {
  const CaseConfig c = reread_with(base, v.sets);
  run_or_resume(c, run_dir, runs);
  return c;
}

std::vector<std::string> extrinsic_overrides(const CaseConfig& base) {
  std::vector<std::string> sets;
  for (std::size_t i = 0; i < base.bodies.size(); ++i)
    if (base.bodies[i].fracture != BodyConfig::Fracture::None)
      sets.push_back(override_of(fmt::format("bodies.{}.fracture_insertion", i), std::string("extrinsic")));
  if (sets.empty()) return sets;
  sets.push_back(override_of("time.insertion_interval", 10.0));
  for (std::size_t i = 0; i < base.materials.size(); ++i)
    if (base.joint_materials[i].given)
      sets.push_back(override_of("materials." + base.materials[i].name + ".joint_penalty", 2.0));
  return sets;
}

std::vector<std::vector<std::string>> study_rows(const std::vector<Variant>& variants,
                                                 const std::vector<VariantOutcome>& out, std::size_t width,
                                                 const std::function<std::vector<std::string>(std::size_t)>& row) {
  std::vector<std::vector<std::string>> rows;
  for (std::size_t i = 0; i < variants.size(); ++i) {
    if (out[i].error.empty()) {
      rows.push_back(row(i));
      continue;
    }
    std::vector<std::string> failed(std::max<std::size_t>(width, 3));
    failed[0] = variants[i].name, failed[1] = variants[i].knob, failed[2] = "failed: " + out[i].error;
    rows.push_back(std::move(failed));
  }
  return rows;
}

}  // namespace dspdem::report
