#include "render/animation.hpp"

#include <fmt/format.h>
#include <signal.h>
#include <vtkImageData.h>
#include <vtkNew.h>
#include <vtkOggTheoraWriter.h>
#include <vtkPNGReader.h>

#include <algorithm>
#include <array>
#include <atomic>
#include <exception>
#include <filesystem>
#include <system_error>
#include <thread>

#include "core/error.hpp"
#include "core/log.hpp"
#include "core/subprocess.hpp"
#include "render/ogg_serial.hpp"

namespace dspdem::render {

namespace fs = std::filesystem;

namespace {

void write_ogv(const std::vector<std::string>& pngs, const std::string& base, int fps) {
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
  try {
    set_ogg_serial(tmp);  // VTK's serial comes from the clock: the same frames, the same file
  } catch (const Error& e) {
    log::warn("{}: kept VTK's own stream serial (the file plays, but differs from render to render)", e.what());
  }
  fs::rename(tmp, base + ".ogv");
}

// ffmpeg reads a numbered sequence; the frames drawn may be any subset of the run's
// (--frames every:K), so number links to them 0, 1, 2, ... in a folder of their own.
bool stage_sequence(const std::vector<std::string>& pngs, const fs::path& seq, const std::string& base) {
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
      return false;
    }
  }
  return true;
}

std::vector<std::string> ffmpeg_args(const std::string& ext, const std::string& input, int fps,
                                     const std::string& out) {
  std::vector<std::string> args = {"-nostdin",   "-loglevel",         "error", "-y",
                                   "-framerate", std::to_string(fps), "-i",    input};
  if (ext == "mp4")  // H.264 in yuv420p plays in every browser; it needs even sizes
    args.insert(args.end(), {"-c:v", "libx264", "-pix_fmt", "yuv420p", "-vf", "pad=ceil(iw/2)*2:ceil(ih/2)*2",
                             "-movflags", "+faststart", "-f", "mp4"});
  else  // one palette made for the whole animation: smooth colour maps without dithering bands
    args.insert(args.end(),
                {"-vf", "scale=640:-1:flags=lanczos,split[a][b];[a]palettegen[p];[b][p]paletteuse", "-f", "gif"});
  args.push_back(out);
  return args;
}

// ffmpeg's two encodings of `base` and their files: each child is waited for once (its pid
// then -1). On the way out the frame links and temporary files go; on an early one (an
// exception, `done` unset) the children still running are stopped first and their logs go
// too, so no encoder goes on writing from a folder that is being removed.
struct Encoders {
  static constexpr std::array<const char*, 2> exts = {"mp4", "gif"};
  std::string base;
  fs::path seq = base + ".seq";
  std::array<pid_t, 2> pids = {-1, -1};
  bool done = false;
  std::string tmp_file(const std::string& ext) const { return base + ".tmp." + ext; }
  std::string log_file(const std::string& ext) const { return base + "." + ext + ".log"; }
  ~Encoders() {
    for (pid_t& p : pids)
      if (p > 0) {
        kill(p, SIGTERM);
        wait_program(p);
        p = -1;
      }
    std::error_code ec;
    for (const std::string ext : exts) {
      fs::remove(tmp_file(ext), ec);
      if (!done) fs::remove(log_file(ext), ec);
    }
    fs::remove_all(seq, ec);
  }
};

}  // namespace

std::vector<std::string> write_animation(const std::vector<std::string>& pngs, const std::string& base, int fps,
                                         int jobs) {
  DSPDEM_CHECK(!pngs.empty(), "no frames for animation '{}'", base);
  std::vector<std::string> out;
  const std::string ffmpeg = find_on_path("ffmpeg");
  Encoders enc{base};
  const bool staged = !ffmpeg.empty() && stage_sequence(pngs, enc.seq, base);
  auto start = [&](const std::string& ext) {
    return spawn_program(ffmpeg, ffmpeg_args(ext, (enc.seq / "%06d.png").string(), fps, enc.tmp_file(ext)),
                         {.log = enc.log_file(ext)});
  };
  // With more than one job ffmpeg's two encodings run beside VTK's, which takes longer than
  // both together (measured on a 2-core AMD EPYC: .ogv 2.3 s, .mp4 0.7 s, .gif 0.9 s for 45
  // frames of 1280x720): the three in about the .ogv's time instead of their sum.
  if (staged && jobs > 1)
    for (std::size_t k = 0; k < enc.exts.size(); ++k) enc.pids[k] = start(enc.exts[k]);
  write_ogv(pngs, base, fps);
  out.push_back(base + ".ogv");
  if (!staged) return out;
  for (std::size_t k = 0; k < enc.exts.size(); ++k) {
    const std::string ext = enc.exts[k];
    if (jobs <= 1) enc.pids[k] = start(ext);
    const int rc = wait_program(enc.pids[k]);
    enc.pids[k] = -1;
    const std::string tmp = enc.tmp_file(ext), dst = base + "." + ext;
    std::error_code ec;
    bool ok = rc == 0 && fs::exists(tmp, ec);  // not dst: an older render may have left one
    if (ok) fs::rename(tmp, dst, ec), ok = !ec;
    if (ok) {
      fs::remove(enc.log_file(ext), ec);
      out.push_back(dst);
    } else {
      log::warn("ffmpeg could not write '{}' (exit {}{}; its messages: {})", dst, rc,
                ec ? ", " + ec.message() : std::string(), enc.log_file(ext));
    }
  }
  enc.done = true;
  return out;
}

std::vector<std::vector<std::string>> write_animations(const std::vector<AnimationJob>& todo, int fps, int jobs) {
  std::vector<std::vector<std::string>> files(todo.size());
  std::vector<std::exception_ptr> errors(todo.size());
  std::atomic<std::size_t> next{0};
  // A view's encoding is independent of the others': VTK's reader and Theora writer are made
  // anew in each, ffmpeg runs as its own process. With two jobs on two cores, VTK's .ogv of
  // one view runs beside another's (each beside its ffmpeg encodings).
  auto work = [&]() {
    for (std::size_t i = next++; i < todo.size(); i = next++) {
      try {
        files[i] = write_animation(todo[i].pngs, todo[i].base, fps, jobs);
      } catch (...) {
        errors[i] = std::current_exception();
      }
    }
  };
  const std::size_t threads = std::min<std::size_t>(todo.size(), static_cast<std::size_t>(std::max(1, jobs)));
  std::vector<std::thread> pool;
  try {
    for (std::size_t t = 1; t < threads; ++t) pool.emplace_back(work);
  } catch (const std::system_error&) {  // no more threads: those started and this one do the rest
  }
  work();
  for (auto& t : pool) t.join();
  for (const auto& e : errors)
    if (e) std::rethrow_exception(e);
  return files;
}

}  // namespace dspdem::render
