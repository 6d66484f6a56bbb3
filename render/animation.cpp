#include "render/animation.hpp"

#include <vtkImageData.h>
#include <vtkNew.h>
#include <vtkOggTheoraWriter.h>
#include <vtkPNGReader.h>

#include <cstdlib>
#include <filesystem>

#include "core/error.hpp"
#include "core/log.hpp"

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
  if (std::system("command -v ffmpeg >/dev/null 2>&1") == 0) {
    const fs::path dir = fs::path(pngs[0]).parent_path();
    const std::string pattern = (dir / "frame_%04d.png").string();
    for (const char* ext : {"mp4", "gif"}) {
      const std::string tmp = base + ".tmp." + ext, dst = base + "." + ext;
      const std::string codec = std::string(ext) == "mp4"
                                    ? "-c:v libx264 -pix_fmt yuv420p -vf pad=ceil(iw/2)*2:ceil(ih/2)*2"
                                    : "-vf fps=" + std::to_string(fps) + ",scale=640:-1:flags=lanczos";
      const std::string cmd = "ffmpeg -loglevel error -y -framerate " + std::to_string(fps) + " -i '" + pattern + "' " +
                              codec + " '" + tmp + "' </dev/null";
      if (std::system(cmd.c_str()) == 0 && fs::exists(tmp)) {
        fs::rename(tmp, dst);
        out.push_back(dst);
      } else {
        log::warn("ffmpeg could not write '{}'", dst);
      }
    }
  }
  return out;
}

}  // namespace dspdem::render
