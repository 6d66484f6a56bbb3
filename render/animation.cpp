#include "render/animation.hpp"

#include <fmt/format.h>
#include <vtkImageData.h>
#include <vtkNew.h>
#include <vtkOggTheoraWriter.h>
#include <vtkPNGReader.h>

#include <filesystem>

#include "core/error.hpp"
#include "core/log.hpp"
#include "core/subprocess.hpp"

namespace dspdem::render {

namespace fs = std::filesystem;

std::vector<std::string> write_animation(const std::vector<std::string>& pngs, const std::string& base, int fps) {
  DSPDEM_CHECK(!pngs.empty(), "no frames for animation '{}'", base);
  std::vector<std::string> out;
  {
    const std::string tmp = base + ".tmp.ogv";
    vtkNew<vtkPNGReader> rd;
    rd->SetFileName(pngs[0].c_str());
    rd->Update();
    vtkNew<vtkOggTheoraWriter> w;
    w->SetInputConnection(rd->GetOutputPort());
    w->SetFileName(tmp.c_str());
    w->SetRate(fps);
    w->SetQuality(2);
    w->Start();
    for (const auto& p : pngs) {
      rd->SetFileName(p.c_str());
      rd->Modified();
      rd->Update();
      w->Write();
    }
    w->End();
    DSPDEM_CHECK(w->GetError() == 0 && fs::exists(tmp), "could not write animation '{}'", tmp);
    fs::rename(tmp, base + ".ogv");
    out.push_back(base + ".ogv");
  }
  const std::string ffmpeg = find_on_path("ffmpeg");
  if (ffmpeg.empty()) return out;
  // ffmpeg reads a numbered sequence; the frames drawn may be any subset of the run's
  // (--frames every:K), so number links to them 0, 1, 2, ... in a folder of their own.
  const fs::path seq = base + ".seq";
  fs::remove_all(seq);
  fs::create_directories(seq);
  for (std::size_t i = 0; i < pngs.size(); ++i) {
    const fs::path link = seq / fmt::format("{:06d}.png", i);
    std::error_code ec;
    fs::create_symlink(fs::absolute(pngs[i]), link, ec);
    if (ec) fs::copy_file(pngs[i], link, fs::copy_options::overwrite_existing, ec);  // no symlinks here
    if (ec) {
      fs::remove_all(seq);
      log::warn("no .mp4/.gif for '{}': cannot stage frame {} ({})", base, pngs[i], ec.message());
      return out;
    }
  }
  const std::string rate = std::to_string(fps), input = (seq / "%06d.png").string();
  for (const std::string ext : {"mp4", "gif"}) {
    const std::string tmp = base + ".tmp." + ext, dst = base + "." + ext;
    std::vector<std::string> args = {"-nostdin", "-loglevel", "error", "-y", "-framerate", rate, "-i", input};
    if (ext == "mp4")  // H.264 in yuv420p plays in every browser; it needs even sizes
      args.insert(args.end(), {"-c:v", "libx264", "-pix_fmt", "yuv420p", "-vf", "pad=ceil(iw/2)*2:ceil(ih/2)*2",
                               "-movflags", "+faststart", "-f", "mp4"});
    else  // one palette made for the whole animation: smooth colour maps without dithering bands
      args.insert(args.end(),
                  {"-vf", "scale=640:-1:flags=lanczos,split[a][b];[a]palettegen[p];[b][p]paletteuse", "-f", "gif"});
    args.push_back(tmp);
    const std::string log = base + "." + ext + ".log";
    if (run_program(ffmpeg, args, log) == 0 && fs::exists(tmp)) {
      fs::rename(tmp, dst);
      fs::remove(log);
      out.push_back(dst);
    } else {
      fs::remove(tmp);
      log::warn("ffmpeg could not write '{}' (its messages: {})", dst, log);
    }
  }
  fs::remove_all(seq);
  return out;
}

}  // namespace dspdem::render
