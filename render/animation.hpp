// Animations from a view's PNG frames: .ogv through VTK's Theora writer (always), and
// .mp4 (H.264) and .gif through ffmpeg when it is on the PATH (.ci/install-deps installs it).
#pragma once
#include <string>
#include <vector>

namespace dspdem::render {

/// Writes `base`.ogv (and `base`.mp4, `base`.gif with ffmpeg); returns the files written.
/// `jobs` > 1 runs ffmpeg's encodings beside VTK's (three processes at most), 1 one after
/// the other.
std::vector<std::string> write_animation(const std::vector<std::string>& pngs, const std::string& base, int fps,
                                         int jobs = 1);

/// One animation to write: its frames and the path without extension.
struct AnimationJob {
  std::vector<std::string> pngs;
  std::string base;
};

/// write_animation for each job, up to `jobs` at once (threads; each with its own encoders),
/// so a run's views are encoded side by side; returns each job's files, in the jobs' order.
/// The first error of any job is rethrown once all have ended.
std::vector<std::vector<std::string>> write_animations(const std::vector<AnimationJob>& todo, int fps, int jobs);

}  // namespace dspdem::render
