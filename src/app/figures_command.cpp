#include "app/figures_command.hpp"

#include <fmt/format.h>

#include <filesystem>
#include <fstream>

#include "core/error.hpp"
#include "core/log.hpp"
#include "core/timer.hpp"
#include "io/case_config.hpp"
#include "report/site.hpp"
#include "run/process_pool.hpp"
#include "scenes/registry.hpp"

namespace dspdem {

namespace fs = std::filesystem;

namespace {
struct Item {
  std::string scene, case_file;
  std::vector<std::string> quick_args;
};

// A scene's shipped case: under the working folder, else under the source tree dspdem was
// built from.
std::string find_case(const scenes::Scene& s) {
  for (const fs::path& root : {fs::current_path(), fs::path(DSPDEM_SOURCE_DIR)})
    if (fs::exists(root / s.case_file)) return (root / s.case_file).string();
  fail("figures: the case of scene '{}' ({}) is neither under {} nor under {}; give the case files", s.name,
       s.case_file, fs::current_path().string(), DSPDEM_SOURCE_DIR);
}

std::string last_line(const std::string& path) {
  std::ifstream f(path);
  std::string line, last;
  while (std::getline(f, line))
    if (!line.empty()) last = line;
  return last;
}
}  // namespace

int figures_command(const FiguresArgs& a) {
  DSPDEM_CHECK(!a.resume || a.from_runs.empty(),
               "figures: --resume and --from-runs: --from-runs runs nothing; --resume keeps or continues the runs "
               "in --out and runs the rest");
  Timer total;
  std::vector<Item> items;
  if (a.cases.empty()) {
    for (const auto& s : scenes::all())  // --from-runs runs nothing: no case needed
      items.push_back({s.name, a.from_runs.empty() ? find_case(s) : s.case_file, s.quick_args});
  } else {
    for (const auto& f : a.cases) {
      const scenes::Scene& s = scenes::of_case(read_case(f));
      for (const auto& it : items)
        DSPDEM_CHECK(it.scene != s.name, "figures: {} and {} are both the scene '{}'; give one case per scene",
                     it.case_file, f, s.name);
      items.push_back({s.name, f, s.quick_args});
    }
  }
  fs::create_directories(a.out);
  report::SiteInfo info;
  info.set = a.quick   ? "quick (CI-sized meshes and runs, no studies: the figures show the method, not the "
                         "converged numbers)"
             : a.study ? "full (the shipped cases as they are, each with its speed-against-error study)"
                       : "full (the shipped cases as they are, without the studies)";
  info.made_by = "dspdem figures" + std::string(a.quick ? " --quick" : "") + (a.study ? "" : " --no-study") +
                 (a.resume ? " --resume" : "") +
                 (a.checkpoint_wall.empty() ? "" : " --checkpoint-wall " + a.checkpoint_wall) +
                 (a.from_runs.empty() ? "" : " --from-runs " + a.from_runs) + " --out " + a.out;
  for (const auto& c : a.cases) info.made_by += " " + c;

  std::vector<std::string> dirs;
  int code = 0;
  for (const auto& it : items) {
    if (!a.from_runs.empty()) {
      dirs.push_back((fs::path(a.from_runs) / it.scene).string());
      continue;
    }
    // Each report is its own process: a scene that fails cannot take the others down, and
    // its log stays beside the site.
    const std::string dir = (fs::path(a.out) / it.scene).string();
    const std::string log = (fs::path(a.out) / "logs" / (it.scene + ".log")).string();
    std::vector<std::string> args;
    if (a.threads > 0) args.insert(args.end(), {"-t", std::to_string(a.threads)});
    args.insert(args.end(), {"report", it.case_file, "--out", dir});
    if (a.quick) args.insert(args.end(), it.quick_args.begin(), it.quick_args.end());
    if (!a.quick && a.study) args.push_back("--study");  // the speed-against-error tables
    if (a.resume) args.push_back("--resume");
    if (!a.checkpoint_wall.empty()) args.insert(args.end(), {"--checkpoint-wall", a.checkpoint_wall});
    log::info("figures: {} ({}{})", it.scene, it.case_file, a.quick ? ", quick" : "");
    Timer t;
    int rc = 0;
    try {
      // With --resume the log goes on after the stopped report's messages.
      if (a.resume && fs::exists(log))
        std::ofstream(log, std::ios::app) << "\n--- dspdem figures --resume: the report again ---\n\n";
      rc = run_processes({Job{args, log, a.resume}}, 1).front();
    } catch (const Interrupted& e) {
      throw Interrupted(fmt::format("{} (the report of {}); the same command with --resume keeps the runs that "
                                    "finished and continues the stopped one",
                                    e.what(), it.scene),
                        e.step, e.time);
    }
    if (rc != 0) {
      info.failed.emplace_back(it.scene, fmt::format("exit {}: {} (log: logs/{}.log)", rc, last_line(log), it.scene));
      log::warn("figures: the report of {} failed with exit {}; its log: {}", it.scene, rc, log);
      if (code == 0) code = rc > 0 ? rc : 4;
      continue;
    }
    log::info("figures: {} done in {:.1f} s", it.scene, t.seconds());
    dirs.push_back(dir);
  }
  info.wall_s = total.seconds();
  const report::SiteWritten site = report::write_site(dirs, a.out, info);
  log::info("figures: {} ({} scenes, {} failed, {:.1f} s)", site.index, dirs.size(), site.failed, total.seconds());
  // A scene listed as failed fails the command, also when only its headline was missing
  // (--from-runs over an incomplete folder).
  return code != 0 ? code : site.failed > 0 ? 2 : 0;
}

}  // namespace dspdem
