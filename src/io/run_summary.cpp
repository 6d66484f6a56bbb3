#include "io/run_summary.hpp"

#include <cmath>
#include <fstream>
#include <nlohmann/json.hpp>

#include "core/error.hpp"
#include "io/staging.hpp"

namespace dspdem {

namespace {
using nlohmann::json;

// Non-finite numbers (a failed run's energy) are written as null and read back as NaN.
json num(double v) { return std::isfinite(v) ? json(v) : json(nullptr); }

template <class T>
void get(const json& j, const char* key, T& out, const std::string& path) {
  const auto it = j.find(key);
  if (it == j.end()) fail("'{}': no key '{}'", path, key);
  try {
    if constexpr (std::is_floating_point_v<T>) {
      out = it->is_null() ? std::nan("") : it->get<T>();
    } else {
      out = it->get<T>();
    }
  } catch (const json::exception& e) {
    fail("'{}': key '{}': {}", path, key, e.what());
  }
}
}  // namespace

void write_run_summary(const std::string& path, const RunSummary& s) {
  nlohmann::ordered_json e = {{"kinetic", num(s.energy.kinetic)},
                              {"internal", num(s.energy.internal)},
                              {"external_work", num(s.energy.external_work)},
                              {"damping", num(s.energy.damping)},
                              {"initial", num(s.energy.initial)},
                              {"joint_elastic", num(s.energy.joint_elastic)},
                              {"fracture_I", num(s.energy.fracture_I)},
                              {"fracture_II", num(s.energy.fracture_II)},
                              {"contact_elastic", num(s.energy.contact_elastic)},
                              {"friction", num(s.energy.friction)},
                              {"contact_damping", num(s.energy.contact_damping)},
                              {"kick", num(s.energy.kick)},
                              {"balance_error", num(s.energy.balance_error)}};
  json masses = json::array();
  for (double m : s.largest_fragment_masses) masses.push_back(num(m));
  // ordered_json keeps the keys in this order: the file reads top-down like the run log.
  nlohmann::ordered_json j;
  j["case"] = s.case_name;
  j["case_file"] = s.case_file;
  j["status"] = s.status;
  j["message"] = s.message;
  j["build"] = s.build;
  j["steps"] = s.steps;
  j["dt"] = num(s.dt);
  j["dt_start"] = num(s.dt_start);
  j["dt_critical"] = num(s.dt_critical);
  j["dt_limiter"] = s.dt_limiter;
  j["dt_limiting_element"] = s.dt_limiting_element;
  j["t_end"] = num(s.t_end);
  j["wall_s"] = num(s.wall_s);
  j["threads"] = s.threads;
  j["processes"] = s.processes;
  j["nodes"] = s.nodes;
  j["elements"] = s.elements;
  j["frames"] = s.frames;
  j["joints"] = s.joints;
  j["joint_added_compliance"] = num(s.joint_added_compliance);
  j["broken_joints"] = s.broken_joints;
  j["crack_area"] = num(s.crack_area);
  if (!s.monitor_joints.empty()) {
    json mj = json::object();
    for (const auto& [name, n] : s.monitor_joints) mj[name] = n;
    j["monitor_joints"] = mj;
  }
  j["fragments"] = s.fragments;
  j["total_mass"] = num(s.total_mass);
  j["largest_fragment_masses"] = masses;
  j["element_steps_per_s"] = num(s.element_steps_per_s);
  j["energy"] = e;
  if (s.born_split.pairs >= 0) {
    auto born = [](const BornOverlapSummary& b) {
      return nlohmann::ordered_json{{"pairs", b.pairs}, {"energy", num(b.energy)}, {"max_ratio", num(b.max_ratio)}};
    };
    j["contacts_born_overlapping"] = {
        {"split", born(s.born_split)}, {"unseen", born(s.born_unseen)}, {"wall", born(s.born_wall)}};
  }
  write_file_atomic(path, j.dump(2) + "\n");
}

RunSummary read_run_summary(const std::string& path) {
  std::ifstream f(path);
  if (!f) fail("cannot read '{}' (not the output folder of a finished run?)", path);
  json j;
  try {
    j = json::parse(f);
  } catch (const json::exception& e) {
    fail("'{}' is not valid JSON: {}", path, e.what());
  }
  if (!j.is_object()) fail("'{}' does not hold a JSON object", path);
  RunSummary s;
  get(j, "case", s.case_name, path);
  get(j, "case_file", s.case_file, path);
  get(j, "status", s.status, path);
  get(j, "message", s.message, path);
  if (j.contains("build")) get(j, "build", s.build, path);  // not in older run folders
  get(j, "steps", s.steps, path);
  get(j, "dt", s.dt, path);
  s.dt_start = s.dt;
  if (j.contains("dt_start")) get(j, "dt_start", s.dt_start, path);  // not in older run folders
  get(j, "dt_critical", s.dt_critical, path);
  get(j, "dt_limiter", s.dt_limiter, path);
  get(j, "dt_limiting_element", s.dt_limiting_element, path);
  get(j, "t_end", s.t_end, path);
  get(j, "wall_s", s.wall_s, path);
  get(j, "threads", s.threads, path);
  if (j.contains("processes")) get(j, "processes", s.processes, path);  // not in older run folders
  get(j, "nodes", s.nodes, path);
  get(j, "elements", s.elements, path);
  get(j, "frames", s.frames, path);
  get(j, "joints", s.joints, path);
  get(j, "joint_added_compliance", s.joint_added_compliance, path);
  get(j, "broken_joints", s.broken_joints, path);
  get(j, "crack_area", s.crack_area, path);
  if (const auto mj = j.find("monitor_joints"); mj != j.end()) {  // only with joint monitors, and not in older folders
    if (!mj->is_object()) fail("'{}': 'monitor_joints' must be an object (monitor name: joints)", path);
    for (const auto& [name, n] : mj->items()) {
      if (!n.is_number_integer()) fail("'{}': monitor_joints '{}' must be an integer", path, name);
      s.monitor_joints.emplace_back(name, n.get<long>());
    }
  }
  get(j, "fragments", s.fragments, path);
  get(j, "total_mass", s.total_mass, path);
  get(j, "element_steps_per_s", s.element_steps_per_s, path);
  const auto m = j.find("largest_fragment_masses");
  if (m == j.end() || !m->is_array()) fail("'{}': no list 'largest_fragment_masses'", path);
  for (const auto& v : *m) s.largest_fragment_masses.push_back(v.is_null() ? std::nan("") : v.get<double>());
  const auto ej = j.find("energy");
  if (ej == j.end() || !ej->is_object()) fail("'{}': no object 'energy'", path);
  EnergySummary& e = s.energy;
  get(*ej, "kinetic", e.kinetic, path);
  get(*ej, "internal", e.internal, path);
  get(*ej, "external_work", e.external_work, path);
  get(*ej, "damping", e.damping, path);
  get(*ej, "initial", e.initial, path);
  get(*ej, "joint_elastic", e.joint_elastic, path);
  get(*ej, "fracture_I", e.fracture_I, path);
  get(*ej, "fracture_II", e.fracture_II, path);
  get(*ej, "contact_elastic", e.contact_elastic, path);
  get(*ej, "friction", e.friction, path);
  get(*ej, "contact_damping", e.contact_damping, path);
  if (ej->contains("kick")) get(*ej, "kick", e.kick, path);  // not in folders written before it
  get(*ej, "balance_error", e.balance_error, path);
  // Not in runs without contact, nor in run folders written before it was recorded.
  if (const auto bj = j.find("contacts_born_overlapping"); bj != j.end()) {
    for (auto [key, b] :
         {std::pair{"split", &s.born_split}, std::pair{"unseen", &s.born_unseen}, std::pair{"wall", &s.born_wall}}) {
      const auto o = bj->find(key);
      if (o == bj->end() || !o->is_object()) fail("'{}': no object 'contacts_born_overlapping.{}'", path, key);
      get(*o, "pairs", b->pairs, path);
      get(*o, "energy", b->energy, path);
      get(*o, "max_ratio", b->max_ratio, path);
    }
  }
  return s;
}

}  // namespace dspdem
