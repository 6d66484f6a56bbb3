#include "run/checkpoint.hpp"

#include <fcntl.h>
#include <unistd.h>
#include <zlib.h>

#include <algorithm>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string_view>
#include <vector>

#include "commit_id.hpp"  // generated at every build: DSPDEM_COMMIT
#include "core/error.hpp"
#include "core/file.hpp"
#include "io/case_config.hpp"
#include "io/staging.hpp"

namespace dspdem {

namespace {
namespace fs = std::filesystem;
const std::string kMagic = "DSPDEM-CHECKPOINT\n";

std::uint32_t crc_of(const char* p, std::size_t n) {
  uLong c = crc32(0L, Z_NULL, 0);
  while (n > 0) {  // zlib takes uInt lengths
    const uInt k = static_cast<uInt>(std::min<std::size_t>(n, 1u << 30));
    c = crc32(c, reinterpret_cast<const Bytef*>(p), k);
    p += k, n -= k;
  }
  return static_cast<std::uint32_t>(c);
}

// The header alone, checked for magic and CRC (body follows in the returned archive).
CheckpointHeader open_checked(const std::string& path, StateArchive& body) {
  std::string s = read_file(path, "checkpoint");
  DSPDEM_CHECK(s.size() >= kMagic.size() + 4 && s.compare(0, kMagic.size(), kMagic) == 0,
               "'{}' is not a dspdem checkpoint (no '{}' at its start)", path, kMagic.substr(0, kMagic.size() - 1));
  std::uint32_t stored;
  std::memcpy(&stored, s.data() + s.size() - 4, 4);
  const std::uint32_t crc = crc_of(s.data(), s.size() - 4);
  DSPDEM_CHECK(crc == stored, "checkpoint '{}' is corrupt or was cut short (CRC-32 {:08x}, stored {:08x})", path, crc,
               stored);
  // The format first (the header's first field, an int): another format's header has other
  // fields, which would not read as these.
  int format = 0;
  DSPDEM_CHECK(s.size() >= kMagic.size() + sizeof format + 4, "checkpoint '{}' is cut short", path);
  std::memcpy(&format, s.data() + kMagic.size(), sizeof format);
  DSPDEM_CHECK(format == CheckpointHeader{}.format, "checkpoint '{}' has format {}; this dspdem reads format {}", path,
               format, CheckpointHeader{}.format);
  // In place, without a second copy of a file that can be the size of the model's state.
  s.resize(s.size() - 4);
  s.erase(0, kMagic.size());
  body = StateArchive(std::move(s), path);
  CheckpointHeader h;
  body(h);
  return h;
}
}  // namespace

std::string checkpoint_piece(const std::string& path, int rank) {
  if (rank == 0) return path;
  return (fs::path(path).parent_path() / fmt::format("checkpoint.{}.bin", rank)).string();
}

std::string checkpoint_build_id() { return DSPDEM_BUILD_INFO " " DSPDEM_COMMIT " " DSPDEM_BUILD_TOOLS; }

FileCrc file_crc(const std::string& path, std::uint64_t bytes, FileCrc so_far) {
  // In blocks: the executable is some megabytes, a long run's series some more.
  std::ifstream f(path, std::ios::binary);
  if (!f) return {};
  // A known prefix longer than asked, or longer than the file now is, says nothing of the
  // bytes wanted: read from the start then.
  if (so_far.bytes > bytes) so_far = {};
  if (so_far.bytes > 0) {
    f.seekg(0, std::ios::end);
    if (!(f.tellg() >= static_cast<std::streamoff>(so_far.bytes))) so_far = {};
    f.seekg(static_cast<std::streamoff>(so_far.bytes));
  }
  std::vector<char> block(1 << 16);
  uLong c = so_far.bytes == 0 ? crc32(0L, Z_NULL, 0) : so_far.crc;
  std::uint64_t n = so_far.bytes;
  while (n < bytes && f) {
    const std::uint64_t want = std::min<std::uint64_t>(block.size(), bytes - n);
    f.read(block.data(), static_cast<std::streamsize>(want));
    const auto got = static_cast<std::uint64_t>(f.gcount());
    if (got == 0) break;
    c = crc32(c, reinterpret_cast<const Bytef*>(block.data()), static_cast<uInt>(got));
    n += got;
  }
  return {f.bad() ? 0 : static_cast<std::uint32_t>(c), f.bad() ? 0 : n};
}

std::string executable_id() {
  static const std::string id = [] {
    const FileCrc exe = file_crc("/proc/self/exe");
    return exe.bytes == 0 ? checkpoint_build_id() + " exe unknown"
                          : fmt::format("{} exe {:08x}", checkpoint_build_id(), exe.crc);
  }();
  return id;
}

void write_checkpoint(const std::string& path, const CheckpointHeader& h, const StateArchive& body, bool into_place) {
  StateArchive head;
  CheckpointHeader hc = h;
  head(hc);
  std::string s = kMagic;
  s.reserve(kMagic.size() + head.bytes().size() + body.bytes().size() + 4);
  s += head.bytes();
  s += body.bytes();
  const std::uint32_t crc = crc_of(s.data(), s.size());
  s.append(reinterpret_cast<const char*>(&crc), 4);
  // Temporary name, on disk before the rename: a crash leaves the old file or the new one.
  const std::string tmp = path + ".tmp";
  const int fd = ::open(tmp.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
  DSPDEM_CHECK(fd >= 0, "cannot write checkpoint '{}': {}", tmp, std::strerror(errno));
  std::size_t done = 0;
  while (done < s.size()) {
    const ssize_t w = ::write(fd, s.data() + done, s.size() - done);
    if (w < 0 && errno == EINTR) continue;
    if (w <= 0) {
      const int err = errno;
      ::close(fd);
      fail("error while writing checkpoint '{}': {}", tmp, std::strerror(err));
    }
    done += static_cast<std::size_t>(w);
  }
  const bool synced = ::fsync(fd) == 0;
  ::close(fd);
  DSPDEM_CHECK(synced, "cannot flush checkpoint '{}' to disk: {}", tmp, std::strerror(errno));
  if (into_place) move_checkpoint_into_place(path);
}

void move_checkpoint_into_place(const std::string& path) {
  std::error_code ec;
  fs::rename(path + ".tmp", path, ec);
  DSPDEM_CHECK(!ec, "cannot move checkpoint '{}' into place: {}", path, ec.message());
}

void require_this_build(const CheckpointHeader& h, const std::string& path) {
  DSPDEM_CHECK(h.build == checkpoint_build_id(),
               "checkpoint '{}' was written by another build of dspdem ({}); this one is {}: restart it with that "
               "build, or run the case again",
               path, h.build, checkpoint_build_id());
}

CheckpointHeader read_checkpoint(const std::string& path, StateArchive& body) {
  CheckpointHeader h = open_checked(path, body);
  require_this_build(h, path);
  return h;
}

std::vector<std::string> checkpoints_left(const std::string& run_dir) {
  std::vector<std::string> left;
  std::error_code ec;
  if (!fs::is_directory(run_dir, ec)) return left;
  if (const fs::path p = fs::path(run_dir) / interrupted_folder / "checkpoint.bin"; fs::is_regular_file(p, ec))
    left.push_back(p.string());
  // A killed run's staging folder, not a live run's: that one is still writing its outputs.
  for (fs::directory_iterator it(run_dir, ec), end; !ec && it != end; it.increment(ec)) {
    const fs::path p = it->path() / "checkpoint.bin";
    if (is_staging_folder(it->path().string()) && left_by_killed_run(it->path().string()) && fs::is_regular_file(p))
      left.push_back(p.string());
  }
  return left;
}

FoundCheckpoint find_checkpoint(const std::string& run_dir) {
  DSPDEM_CHECK(fs::is_directory(run_dir), "--restart {}: no such run folder", run_dir);
  std::vector<fs::path> cands = {fs::path(run_dir) / "checkpoint.bin"};
  for (const std::string& p : checkpoints_left(run_dir)) cands.emplace_back(p);
  FoundCheckpoint best;
  std::string errors;
  fs::file_time_type best_time = fs::file_time_type::min();
  for (const auto& p : cands) {
    if (!fs::is_regular_file(p)) continue;
    try {
      StateArchive body;
      const CheckpointHeader h = open_checked(p.string(), body);
      const auto t = fs::last_write_time(p);
      if (best.path.empty() || t > best_time) best_time = t, best = {p.string(), h};
    } catch (const Error& e) {
      errors += fmt::format("\n  {}", e.what());  // a damaged one does not hide a good one
    }
  }
  DSPDEM_CHECK(!best.path.empty(),
               "--restart {}: no usable checkpoint in the run folder (looked for checkpoint.bin there, in "
               "interrupted_run/ and in the .staging-* folder of a run that was killed){}",
               run_dir, errors);
  return best;
}

namespace {
// The folder that holds a checkpoint file, absolute and without '.' or '..': `--restart
// checkpoint.bin` given inside interrupted_run/ is seen in that folder.
fs::path holder_of(const std::string& checkpoint_file) {
  return fs::absolute(checkpoint_file).lexically_normal().parent_path();
}
}  // namespace

FoundCheckpoint restart_checkpoint(const std::string& path) {
  if (fs::is_directory(path)) return find_checkpoint(path);
  DSPDEM_CHECK(fs::is_regular_file(path), "--restart {}: no such run folder or checkpoint file", path);
  // As find_checkpoint: not a live run's, whose staging folder a finished restart would clear.
  const fs::path holder = holder_of(path);
  DSPDEM_CHECK(!is_staging_folder(holder.string()) || left_by_killed_run(holder.string()),
               "--restart {}: the checkpoint of a run at work (its staging folder is held); wait for it, or stop it",
               path);
  StateArchive body;
  FoundCheckpoint f{path, open_checked(path, body)};
  DSPDEM_CHECK(f.header.rank == 0,
               "--restart {}: this is process {}'s checkpoint of a run on {} processes; give process 0's, {}", path,
               f.header.rank, f.header.processes, (fs::path(path).parent_path() / "checkpoint.bin").string());
  return f;
}

std::string run_folder_of(const std::string& checkpoint_file) {
  const fs::path holder = holder_of(checkpoint_file);
  return (is_side_folder(holder.string()) ? holder.parent_path() : holder).string();
}

namespace {
std::string without_origin(const std::string& s) {
  if (s.rfind(kResolvedFrom, 0) != 0) return s;
  const std::size_t nl = s.find('\n');
  return nl == std::string::npos ? std::string() : s.substr(nl + 1);
}
}  // namespace

std::string case_origin(const std::string& resolved) {
  if (resolved.rfind(kResolvedFrom, 0) != 0) return {};
  const std::string line = resolved.substr(0, resolved.find('\n'));
  const std::size_t end = line.rfind(kResolvedFromEnd);
  return end == std::string::npos || end < kResolvedFrom.size()
             ? std::string()
             : line.substr(kResolvedFrom.size(), end - kResolvedFrom.size());
}

bool same_case(const std::string& a, const std::string& b) { return without_origin(a) == without_origin(b); }

std::string first_difference(const std::string& a, const std::string& b) {
  // As same_case: the origin line names the case file as it was given (relative, or absolute
  // after a restart) and is not a difference; the line numbers stay the files'.
  const std::string ra = without_origin(a), rb = without_origin(b);
  const int first = ra.size() != a.size() && rb.size() != b.size() ? 2 : 1;
  std::istringstream sa(first == 2 ? ra : a), sb(first == 2 ? rb : b);
  std::string la, lb;
  for (int line = first;; ++line) {
    const bool ea = !std::getline(sa, la), eb = !std::getline(sb, lb);
    if (ea && eb) return "";
    if (ea != eb || la != lb)
      return fmt::format("line {}: '{}' then, '{}' now", line, ea ? "<end>" : la, eb ? "<end>" : lb);
  }
}

}  // namespace dspdem
