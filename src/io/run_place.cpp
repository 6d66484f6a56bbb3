#include "io/run_place.hpp"

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <optional>
#include <regex>
#include <set>
#include <sstream>

#include "core/error.hpp"
#include "core/folder_lock.hpp"
#include "io/staging.hpp"

namespace dspdem {

namespace fs = std::filesystem;

namespace {
constexpr const char* kDerivedFrom = "derived_from";

std::string recorded_run(const fs::path& place) {
  std::ostringstream was;
  was << std::ifstream(place / kDerivedFrom).rdbuf();
  return was.str();
}

// A lock file: its holder removes it as it lets go, and one removed under its holder would let a
// second writer in.
bool is_lock_file(const fs::path& entry) {
  return entry.filename() == report_lock_file || entry.filename() == render_lock_file;
}

// Everything in the place but its record and the locks, then the record: a removal that stops
// partway leaves a place still known as a report's.
void empty_place(const fs::path& place) {
  for (const auto& entry : fs::directory_iterator(place))
    if (entry.path().filename() != kDerivedFrom && !is_lock_file(entry.path())) fs::remove_all(entry.path());
  fs::remove(place / kDerivedFrom);
}

// Files in the place other than the lock of the render drawing into it now.
bool holds_files(const fs::path& place) {
  std::error_code e;
  for (const auto& entry : fs::directory_iterator(place, e))
    if (entry.path().filename() != render_lock_file) return true;
  return false;
}
// An entry that marks its folder as a run's: finished, failed, stopped, or running or killed.
bool marks_a_run(const fs::directory_entry& entry) {
  const std::string name = entry.path().filename().string();
  std::error_code e;
  if (entry.is_directory(e))
    return name == failed_folder || name == interrupted_folder || is_staging_folder(entry.path().string());
  return name == "summary.json" || name == "run.pvd";
}
// An entry that marks its folder as a report's: written, or being written (its lock).
bool marks_a_report(const fs::directory_entry& entry) {
  const std::string name = entry.path().filename().string();
  return name == "report.md" || name == report_lock_file;
}

// Whether an entry at the folder's top level is one that `marks` it.
bool holds(const std::string& dir, bool (*marks)(const fs::directory_entry&)) {
  std::error_code e;
  for (const auto& entry : fs::directory_iterator(dir, e))
    if (marks(entry)) return true;
  return false;
}

// A render drawing into the folder of `entry`, its lock file, now.
bool marks_a_render_drawing(const fs::directory_entry& entry) {
  return entry.path().filename() == render_lock_file &&
         FolderLock::held(entry.path().parent_path().string(), render_lock_file);
}

// A run, a report or a render drawing now anywhere below the place's top level (made inside a
// place a report or a render filled): emptying the place would take it too. (A render drawing
// into the place itself holds its lock for its own emptying, or is refused by the lock.)
std::optional<fs::path> kept_below(const fs::path& place) {
  std::error_code e;
  for (auto it = fs::recursive_directory_iterator(place, e); !e && it != fs::recursive_directory_iterator();
       it.increment(e))
    if (marks_a_run(*it) || marks_a_report(*it) || (it.depth() > 0 && marks_a_render_drawing(*it)))
      return it->path().parent_path();
  return std::nullopt;
}

// The first entry under a run's images/ that `dspdem render` does not write there: a folder
// per view (stress, fragments, cracks) of frame_NNNN.png, the view's animations beside it
// (<view>.ogv, .mp4, .gif, the <view>.seq folder of links an encoding stages and the log of one
// that failed), plots/*.png, and PNGs a report drew of the run beside them.
// Anything else is someone's own, which a replaced run's images going with its frames must
// not take.
std::optional<fs::path> not_drawn(const fs::path& images) {
  static const std::set<std::string> folders = {"stress", "fragments", "cracks", "plots"};
  static const std::set<std::string> animations = {".ogv", ".mp4", ".gif"};
  std::error_code e;
  for (auto it = fs::recursive_directory_iterator(images, e); !e && it != fs::recursive_directory_iterator();
       it.increment(e)) {
    const fs::path& p = it->path();
    const bool dir = it->is_directory(e) && !it->is_symlink(e);
    // At the top also a report's own images of the run (the packing's heap_front.png) and the
    // log ffmpeg leaves beside an animation it could not encode (fragments.mp4.log).
    const std::string ext = p.extension().string(), inner = p.stem().extension().string();
    const bool ok = it.depth() == 0 ? (dir ? folders.count(p.filename().string()) > 0 || ext == ".seq"
                                           : animations.count(ext) > 0 || ext == ".png" ||
                                                 (ext == ".log" && animations.count(inner)))
                                    : it.depth() == 1 && !dir && ext == ".png";
    if (!ok) return p;
  }
  if (e) return images;  // unreadable: not known to be drawn
  return std::nullopt;
}
}  // namespace

bool holds_a_run(const std::string& dir) { return holds(dir, marks_a_run); }

bool holds_a_report(const std::string& dir) { return holds(dir, marks_a_report); }

std::optional<std::string> derived_from(const std::string& dir) {
  if (!fs::exists(fs::path(dir) / kDerivedFrom)) return std::nullopt;
  return recorded_run(dir);
}

void check_derived_place(const std::string& place, const std::string& run_dir) {
  std::error_code differ;
  if (fs::equivalent(place, run_dir, differ)) return;
  const fs::path p = fs::weakly_canonical(place), r = fs::weakly_canonical(run_dir);
  const auto [in_p, in_r] = std::mismatch(p.begin(), p.end(), r.begin(), r.end());
  DSPDEM_CHECK(in_p != p.end(), "the run in {} lies inside {}, where what is derived from it would be written", run_dir,
               place);
  DSPDEM_CHECK(!holds_a_run(place),
               "{} holds a run of its own (a summary.json, run.pvd, failed_run/, interrupted_run/ or a run's staging "
               "folder), where what is derived from the run in {} would be written; give --out a folder without "
               "one",
               place, run_dir);
  DSPDEM_CHECK(!holds_a_report(place),
               "{} holds a report (report.md, or {} while one is written), where what is derived from the run in {} "
               "would be written; give --out a folder without one",
               place, report_lock_file, run_dir);
  if (const auto below = kept_below(place))
    fail(
        "{} holds a run, a report or a render drawing now below it, in {}, which emptying it for the run in {} would "
        "take too; give --out a folder without one",
        place, below->string(), run_dir);
  // Inside a place filled from another run: a render of a third run into that place would empty
  // it, this one with it. Inside another run's images/: a run made there again removes them.
  // (Elsewhere inside another run's folder nothing removes it, and derived_from says whose it is.)
  fs::path below = p;
  for (fs::path up = p.parent_path(); !up.empty() && up != r; below = up, up = up.parent_path()) {
    if (fs::is_directory(up)) {
      DSPDEM_CHECK(below.filename() != "images" || !holds_a_run(up.string()),
                   "{} lies inside {}, the images of the run in {}, which a run made there again removes; give --out "
                   "a folder outside it",
                   place, below.string(), up.string());
      const auto from = derived_from(up.string());
      DSPDEM_CHECK(!from || *from == r.string(),
                   "{} lies inside {}, which a render or a report filled from the run in {}, where what is derived "
                   "from the run in {} would be written; give --out a folder outside it",
                   place, up.string(), from.value_or(""), run_dir);
    }
    if (up == up.root_path()) break;
  }
  if (fs::exists(place) && holds_files(place))
    DSPDEM_CHECK(fs::exists(fs::path(place) / kDerivedFrom),
                 "{} holds files that no report or render derived from a run (no {} there); give --out another "
                 "folder",
                 place, kDerivedFrom);
}

void prepare_derived_place(const std::string& place, const std::string& run_dir) {
  check_derived_place(place, run_dir);
  std::error_code differ;
  if (fs::equivalent(place, run_dir, differ)) return;
  const std::string from = fs::weakly_canonical(run_dir).string();
  if (fs::exists(fs::path(place) / kDerivedFrom) && recorded_run(place) != from) empty_place(place);
  fs::create_directories(place);
  std::ofstream mark(fs::path(place) / kDerivedFrom);
  mark << from;
  DSPDEM_CHECK(mark.flush().good(), "cannot write '{}/{}'", place, kDerivedFrom);
}

void take_derived_place(const std::string& place, const std::string& run_dir) {
  check_derived_place(place, run_dir);
  std::error_code differ;
  if (fs::equivalent(place, run_dir, differ)) return;
  const FolderLock drawing(place, render_lock_file, "a render");
  prepare_derived_place(place, run_dir);
}

void clear_derived_place(const std::string& place) {
  if (!fs::exists(fs::path(place) / kDerivedFrom) || holds_a_run(place) || holds_a_report(place)) return;
  if (const auto below = kept_below(place)) {
    // A run or a report below stays, and the place with it; a render drawing below ends soon,
    // and the run would otherwise go on beside what was derived from another run.
    DSPDEM_CHECK(!FolderLock::held(below->string(), render_lock_file),
                 "{}: a render is drawing into {} now, in a folder filled from another run that this run would "
                 "empty; wait for it to end",
                 place, below->string());
    return;
  }
  // Not under a render drawing there now: refused by its lock (Error) rather than emptied under it.
  const FolderLock drawing(place, render_lock_file, "a render");
  empty_place(place);
}

void check_run_frames(const std::string& run_dir) {
  const fs::path frames = fs::path(run_dir) / "frames";
  std::error_code ec;
  if (!fs::is_directory(frames, ec)) return;
  // frame_0012.vtu, joints_0012.pvtu, frame_0012_3.vtu (process 3's piece).
  static const std::regex written(R"((frame|joints)_[0-9]{4,}(_[0-9]+)?\.p?vtu)");
  for (const auto& e : fs::directory_iterator(frames, ec)) {
    const std::string name = e.path().filename().string();
    DSPDEM_CHECK(e.is_regular_file() && std::regex_match(name, written),
                 "{}: '{}' is not a run's frame, and a run replaces frames/ whole as it ends: move it out, or give "
                 "--out another folder",
                 frames.string(), name);
  }
  DSPDEM_CHECK(!ec, "cannot read '{}': {}", frames.string(), ec.message());
}

ReplacedImages remove_replaced_images(const std::string& run_dir) {
  // Under the folder's render lock, so that no render starts drawing between the look and the
  // removal; refused means a render is drawing into the folder now. Without flock there is no
  // lock to take, and the run's end has nothing to warn of.
  std::optional<FolderLock> drawing;
  try {
    drawing.emplace(run_dir, render_lock_file, "a render", FolderLock::NoFlock::quiet);
  } catch (const FolderBusy&) {
    return {ReplacedImages::Fate::render_drawing, {}};
  }
  const fs::path images = fs::path(run_dir) / "images";
  std::error_code ec;
  if (!fs::is_directory(images, ec)) return {};
  if (const auto inside = kept_below(images)) return {ReplacedImages::Fate::holds_inside, inside->string()};
  if (const auto other = not_drawn(images)) return {ReplacedImages::Fate::not_drawn, other->string()};
  fs::remove_all(images, ec);
  DSPDEM_CHECK(!ec, "cannot remove '{}': {}", images.string(), ec.message());
  return {ReplacedImages::Fate::removed, {}};
}

}  // namespace dspdem
