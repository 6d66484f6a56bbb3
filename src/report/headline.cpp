#include "report/headline.hpp"

#include <fmt/format.h>

#include <filesystem>
#include <nlohmann/json.hpp>

#include "core/error.hpp"
#include "core/file.hpp"

namespace dspdem::report {

HeadlineRow balance_row(double balance_max, const std::string& test, const std::string& quantity) {
  return {quantity, "-", fmt::format("{:.1e} of the largest term", balance_max), agrees(balance_max < 0.01), test};
}

std::string headline_json(const Headline& h) {
  nlohmann::ordered_json j;
  j["scene"] = h.scene;
  j["title"] = h.title;
  j["summary"] = h.summary;
  j["rows"] = nlohmann::json::array();
  for (const auto& r : h.rows)
    j["rows"].push_back(
        {{"quantity", r.quantity}, {"paper", r.paper}, {"dspdem", r.dspdem}, {"agrees", r.agrees}, {"test", r.test}});
  j["images"] = nlohmann::json::array();
  for (const auto& [caption, path] : h.images) j["images"].push_back({{"caption", caption}, {"path", path}});
  j["animation"] = h.animation;
  j["wall_s"] = h.wall_s;
  return j.dump(2) + "\n";
}

Headline read_headline(const std::string& path) {
  if (!std::filesystem::exists(path))
    fail("cannot read '{}': no such file (a report written by this version of dspdem has one)", path);
  const std::string text = read_file(path, "headline");
  Headline h;
  try {
    const auto j = nlohmann::json::parse(text);
    h.scene = j.at("scene").get<std::string>();
    h.title = j.at("title").get<std::string>();
    h.summary = j.at("summary").get<std::string>();
    for (const auto& r : j.at("rows"))
      h.rows.push_back({r.at("quantity").get<std::string>(), r.at("paper").get<std::string>(),
                        r.at("dspdem").get<std::string>(), r.at("agrees").get<std::string>(),
                        r.value("test", std::string())});
    for (const auto& i : j.at("images")) h.images.emplace_back(i.at("caption"), i.at("path"));
    h.animation = j.at("animation").get<std::string>();
    h.wall_s = j.at("wall_s").get<double>();
  } catch (const nlohmann::json::exception& e) {
    fail("'{}': not a dspdem headline ({})", path, e.what());
  }
  return h;
}

}  // namespace dspdem::report
