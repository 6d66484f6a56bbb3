// Where what is derived from a run goes when it is not the run's own folder: a report's place
// for a run it did not make (`report --from-run`), or `render RUN --out OUT`. The run's folder,
// which may be another report's, is only read. The place records the run it was filled from
// (derived_from), so that a place filled from another run is emptied rather than mixed, and only
// such a place; a run made into such a place empties it too (clear_derived_place).
#pragma once
#include <optional>
#include <string>

namespace dspdem {

/// The file a report holds locked while it writes into its folder (core/folder_lock.hpp).
inline constexpr const char* report_lock_file = ".report.lock";
/// The file a render holds locked while it draws into its folder (the run's, or --out).
inline constexpr const char* render_lock_file = ".render.lock";

/// Whether `dir` holds a run: finished (summary.json, run.pvd), failed or stopped (failed_run/,
/// interrupted_run/), or running or killed (a staging folder, io/staging.hpp).
bool holds_a_run(const std::string& dir);

/// Whether `dir` holds a report: its report.md, or the lock of one being written.
bool holds_a_report(const std::string& dir);

/// The run a report or a render filled `dir` from (its derived_from record), if any.
std::optional<std::string> derived_from(const std::string& dir);

/// Whether `place` may take what a report derives from the run in `run_dir`, changing nothing:
/// Error when the run given lies inside it, it lies inside another run's images/ (removed when
/// a run is made there again) or inside a place filled from another run (emptied with it when
/// a third run is drawn there), it holds another run (derived files beside it would read as its)
/// or a report, it holds a run, a report or a render drawing now anywhere below it, or it holds
/// files but no derived_from (no report or render filled it). The render's lock file is not
/// counted as a file.
void check_derived_place(const std::string& place, const std::string& run_dir);

/// check_derived_place, then makes `place` ready (for the render drawing there, which holds its
/// render lock; other callers take_derived_place): nothing to do when it is the run itself; a
/// place filled from another run is emptied first (its images would show as this run's); the
/// run is recorded in place/derived_from.
void prepare_derived_place(const std::string& place, const std::string& run_dir);

/// prepare_derived_place for a caller other than the render drawing into `place` (a report's
/// place for a run it did not make), under the place's render lock: Error, changing nothing,
/// when a render is drawing into it now.
void take_derived_place(const std::string& place, const std::string& run_dir);

/// A place a report or a render filled from a run (derived_from, no run or report in it or
/// below it) that a run is now to be made in: emptied, so that nothing derived from the other
/// run stays beside the new one; Error when a render is drawing into it or below it now.
void clear_derived_place(const std::string& place);

/// Error, naming the first such entry, when `run_dir`/frames holds anything a run does not
/// write there (frame_NNNN and joints_NNNN files, .vtu or .pvtu, and a distributed run's pieces
/// of them): a run's commit replaces frames/ whole, so a file or a folder put there by hand
/// (another run made inside it, too) went with it. Checked before the run starts.
void check_run_frames(const std::string& run_dir);

/// What became of the images/ of a run a new run replaced (remove_replaced_images).
struct ReplacedImages {
  enum class Fate {
    none,            ///< there were none
    removed,         ///< drawn from the frames replaced, they went with them
    render_drawing,  ///< kept: a render is drawing into the run's folder now
    holds_inside,    ///< kept: a run, a report or a render drawing now lies inside them
    not_drawn,       ///< kept: they hold a file a render does not write
  };
  Fate fate = Fate::none;
  std::string inside;  ///< for holds_inside: where that one lies; for not_drawn: the file
};

/// The images/ of a run in `run_dir` that a new run has just replaced: removed, under the
/// folder's render lock, as they were drawn from the frames it replaced; kept when a render is
/// drawing into the folder now (it may have drawn the new run's frames already) or when a run, a
/// report or a render drawing now lies inside them (made there by hand: removing them would take
/// that too), or when they hold a file a render does not write (<view>/ and plots/ of .png
/// files, the views' .ogv, .mp4 and .gif): a folder's images/ may be its owner's, not a render's.
ReplacedImages remove_replaced_images(const std::string& run_dir);

}  // namespace dspdem
