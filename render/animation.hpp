// Animations from a view's PNG frames: .ogv through VTK's Theora writer (always), and
// .mp4 (H.264) and .gif through ffmpeg when it is on the PATH (.ci/install-deps installs it).
#pragma once
#include <string>
#include <vector>

namespace dspdem::render {

/// Writes `base`.ogv (and `base`.mp4, `base`.gif with ffmpeg); returns the files written.
/// `jobs` > 1 starts ffmpeg's two encodings beside VTK's (three processes, and x264 its own
/// threads), 1 runs them one after the other.
std::vector<std::string> write_animation(const std::vector<std::string>& pngs, const std::string& base, int fps,
                                         int jobs = 1);

/// One animation to write: its frames and the path without extension.
struct AnimationJob {
  std::vector<std::string> pngs;
  std::string base;
};

/// write_animation for each job, up to `jobs` at once (threads, each with its own encoders:
/// with -j 2, two VTK encoders here and up to four ffmpeg processes), so a run's views are
/// encoded side by side; returns each job's files, in the jobs' order. Once all have ended,
/// the error of the first job in that order that failed is rethrown.
std::vector<std::vector<std::string>> write_animations(const std::vector<AnimationJob>& todo, int fps, int jobs);

}  // namespace dspdem::render
