// Animations from a view's PNG frames: .ogv through VTK's Theora writer (always), and
// .mp4 (H.264) and .gif through ffmpeg when it is on the PATH (.ci/install-deps installs it).
#pragma once
#include <string>
#include <vector>

namespace dspdem::render {

/// Writes `base`.ogv (and `base`.mp4, `base`.gif with ffmpeg); returns the files written.
std::vector<std::string> write_animation(const std::vector<std::string>& pngs, const std::string& base, int fps);

}  // namespace dspdem::render
