// Checkpoint and restart (issue 21): a run stopped and continued from its checkpoint must
// write what the uninterrupted run writes, to the bit; a signal must leave whole outputs and
// a checkpoint; a checkpoint of another case, build or a damaged file must be refused.
//
// The scene: tests/data/notched_bar.toml pulled fast (0.25 m/s after 20 us) with contact on,
// so that within 0.3 ms its band cracks through (tens of joints broken, two halves) and the
// crack faces touch: joint states, failures, contact pairs and their history, candidate
// rebuilds all change during the run. About 10 s per run on 2 cores.
#include <fcntl.h>
#include <gtest/gtest.h>
#include <signal.h>
#include <sys/file.h>
#include <sys/wait.h>
#include <unistd.h>
#include <vtkNew.h>
#include <vtkUnstructuredGrid.h>
#include <vtkXMLUnstructuredGridReader.h>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <regex>
#include <thread>

#include "core/error.hpp"
#include "core/file.hpp"
#include "io/case_config.hpp"
#include "io/staging.hpp"
#include "report/resume.hpp"
#include "run/checkpoint.hpp"
#include "run/run_case.hpp"
#include "support/cli.hpp"

namespace fs = std::filesystem;
using namespace dspdem;

namespace {

// The .geo is meshed by every run in this process and by the executable: a restart refuses
// a model that differs from its checkpoint's, so this also checks that meshing is
// deterministic (gmsh's threaded mesher was not: 7758, then 7755 or 7672 nodes).
const std::vector<std::string> kSets = {"contact.enabled=true", "time.end=3e-4", "boundary.1.value=[0.25,0.0,0.0]",
                                        "boundary.1.ramp=2e-5", "output.frame_interval=5e-5"};
const std::string kCase = std::string(DSPDEM_SOURCE_DIR) + "/tests/data/notched_bar.toml";

// "" for a file that is not there: the comparisons then name it.
std::string slurp(const fs::path& p) { return dspdem::read_file_if(p).value_or(""); }

// Every output of a run folder byte for byte, except the summary's wall clock and thread
// count (a restarted run adds up its parts' wall times) and the executable that ran it (the
// test's own, in-process, or dspdem).
void expect_same_outputs(const fs::path& a, const fs::path& b) {
  for (const char* f : {"series.csv", "fragments.csv", "run.pvd", "joints.pvd", "case.resolved.toml"})
    EXPECT_TRUE(slurp(a / f) == slurp(b / f)) << f << " differs between " << a << " and " << b;
  std::vector<std::string> fa, fb;
  for (const auto& e : fs::directory_iterator(a / "frames")) fa.push_back(e.path().filename().string());
  for (const auto& e : fs::directory_iterator(b / "frames")) fb.push_back(e.path().filename().string());
  std::sort(fa.begin(), fa.end()), std::sort(fb.begin(), fb.end());
  ASSERT_EQ(fa, fb);
  for (const auto& f : fa) EXPECT_TRUE(slurp(a / "frames" / f) == slurp(b / "frames" / f)) << "frame " << f;
  auto summary = [](const fs::path& p) {
    auto j = nlohmann::json::parse(slurp(p / "summary.json"));
    for (const char* k : {"wall_s", "element_steps_per_s", "threads", "build"}) j.erase(k);
    return j;
  };
  EXPECT_EQ(summary(a), summary(b));
}

// `args` (DSPDEM_BIN first) as a process of its own, its stop signals at their defaults
// whatever ctest was started with (an ignored signal stays ignored in dspdem).
pid_t spawn_dspdem(std::vector<std::string> args) {
  const pid_t pid = fork();
  if (pid == 0) {
    for (int sig : {SIGINT, SIGTERM, SIGHUP}) signal(sig, SIG_DFL);
    std::vector<char*> argv;
    for (auto& a : args) argv.push_back(a.data());
    argv.push_back(nullptr);
    execv(DSPDEM_BIN, argv.data());
    _exit(127);
  }
  return pid;
}

// The test's case run into `dir` and stopped as by a SIGTERM during `step`, leaving its
// checkpoint in dir/interrupted_run; returns the run's options, ready for a restart.
RunOptions stopped_at(const fs::path& dir, long step) {
  RunOptions opt;
  opt.out_dir = dir.string();
  opt.sets = kSets;
  opt.interrupt_at_step = step;
  EXPECT_THROW(run_case(read_case(kCase, kSets), opt), Interrupted);
  opt.interrupt_at_step = -1;
  return opt;
}

// A test's own folder in the temporary directory, empty at the start and removed however the
// test ends (a failed ASSERT returns early).
struct ScratchDir {
  fs::path path;
  explicit ScratchDir(const std::string& name)
      : path(fs::temp_directory_path() / fmt::format("{}_{}", name, getpid())) {
    fs::remove_all(path);
  }
  ~ScratchDir() {
    std::error_code ec;
    fs::remove_all(path, ec);
  }
};

class Restart : public ::testing::Test {
 protected:
  static fs::path root_;
  static void SetUpTestSuite() {
    root_ = fs::temp_directory_path() / fmt::format("dspdem_restart_{}", getpid());
    fs::remove_all(root_);
  }
  static void TearDownTestSuite() { fs::remove_all(root_); }
  // The uninterrupted run the restarted ones must equal, run when a test first asks for it (a
  // run's outputs reach its folder once it has finished): ctest runs each test in a process of
  // its own, and two of them need none.
  static fs::path full() {
    const fs::path dir = root_ / "full";
    if (!fs::exists(dir / "summary.json")) {
      RunOptions opt;
      opt.out_dir = dir.string();
      run_case(read_case(kCase, kSets), opt);
    }
    return dir;
  }
};
fs::path Restart::root_;

TEST_F(Restart, FracturingRunWithContactStoppedTwiceEndsBitwiseAsTheUninterruptedOne) {
  // The reference run must exercise what a checkpoint holds: broken joints, two pieces,
  // touching crack faces (friction work), several contact rebuilds.
  auto j = nlohmann::json::parse(slurp(full() / "summary.json"));
  ASSERT_GT(j["broken_joints"].get<long>(), 20);
  ASSERT_GE(j["fragments"].get<long>(), 2);
  ASSERT_GT(j["largest_fragment_masses"][1].get<double>(), 0.3);
  ASSERT_GT(j["energy"]["friction"].get<double>(), 0.0);

  const fs::path dir = root_ / "stopped";
  const CaseConfig c = read_case(kCase, kSets);
  RunOptions opt;
  opt.out_dir = dir.string();
  opt.sets = kSets;
  opt.checkpoint_every = 5e-5;
  opt.interrupt_at_step = 4000;  // as if SIGTERM came during step 4000
  EXPECT_THROW(run_case(c, opt), Interrupted);
  ASSERT_TRUE(fs::exists(dir / "interrupted_run" / "checkpoint.bin"));
  EXPECT_EQ(nlohmann::json::parse(slurp(dir / "interrupted_run" / "summary.json"))["status"], "interrupted");

  // Second leg, on one thread (results do not depend on the thread count), stopped again. The
  // case read by another spelling of its path (`dspdem run --restart` reads it by the absolute
  // path the checkpoint keeps): the record still names it as the run was started with, so
  // case.resolved.toml is compared with the uninterrupted run's below.
  const CaseConfig c_again = read_case(fs::relative(kCase).string(), kSets);
  ASSERT_NE(c_again.resolved_toml, c.resolved_toml);
  opt.restart_file = find_checkpoint(dir.string()).path;
  opt.interrupt_at_step = 9000;
  const int threads = omp_get_max_threads();
  omp_set_num_threads(1);
  EXPECT_THROW(run_case(c_again, opt), Interrupted);
  omp_set_num_threads(threads);
  EXPECT_EQ(find_checkpoint(dir.string()).header.steps, 9000);

  opt.restart_file = find_checkpoint(dir.string()).path;
  opt.interrupt_at_step = -1;
  EXPECT_EQ(run_case(c_again, opt), 0);
  EXPECT_FALSE(fs::exists(dir / "interrupted_run"));  // superseded by the results
  EXPECT_FALSE(fs::exists(dir / "checkpoint.bin"));   // a finished run needs none
  expect_same_outputs(full(), dir);
}

// The same bar with extrinsic insertion: the step starts at the elements' and contact's and
// falls each time joints open (run/run_case.cpp), so a checkpoint must carry the step, and
// the run's end (in steps) worked out at the last fall. Stopped part way through the falls
// and continued on one thread, it ends as the uninterrupted run, to the bit.
TEST_F(Restart, AnExtrinsicRunWhoseStepFallsRestartsBitwise) {
  std::vector<std::string> sets = kSets;
  sets.push_back("bodies.0.fracture_insertion=\"extrinsic\"");
  const CaseConfig c = read_case(kCase, sets);
  const fs::path full = root_ / "extrinsic_full", dir = root_ / "extrinsic_stopped";
  RunOptions opt;
  opt.out_dir = full.string();
  opt.sets = sets;
  run_case(c, opt);
  auto j = nlohmann::json::parse(slurp(full / "summary.json"));
  ASSERT_LT(j["dt"].get<double>(), 0.9 * j["dt_start"].get<double>());  // the step fell
  ASSERT_GE(j["fragments"].get<long>(), 2);
  // The run's end, worked out again at each fall, is still [time] end, within a step.
  EXPECT_GE(j["t_end"].get<double>(), 3e-4 * (1 - 1e-9));
  EXPECT_LT(j["t_end"].get<double>(), 3e-4 + j["dt"].get<double>());

  // The first faces open between steps 1000 and 1100 (t = 34-37 us, as the pull reaches the
  // notches), and the step falls over the next 900 steps, to its last value at step 2000 of
  // some 12000.
  opt.out_dir = dir.string();
  opt.checkpoint_every = 5e-5;
  opt.interrupt_at_step = 1300;
  EXPECT_THROW(run_case(c, opt), Interrupted);
  // Stopped there, the step had fallen already and had still to fall.
  auto half = nlohmann::json::parse(slurp(dir / "interrupted_run" / "summary.json"));
  EXPECT_LT(half["dt"].get<double>(), j["dt_start"].get<double>());
  EXPECT_GT(half["dt"].get<double>(), j["dt"].get<double>());
  opt.restart_file = find_checkpoint(dir.string()).path;
  opt.interrupt_at_step = -1;
  const int threads = omp_get_max_threads();
  omp_set_num_threads(1);
  EXPECT_EQ(run_case(c, opt), 0);
  omp_set_num_threads(threads);
  expect_same_outputs(full, dir);
}

// A killed run's staging folder carries its pid. Pids repeat (a container started anew hands
// them out in the same order), so the restart can get the killed run's pid: its own staging
// folder then has the name of the one it restarts from, which must be moved aside, not
// emptied. Staged here in this process: the interrupted run's folder renamed as a killed
// run's of this pid. A finished run also clears the staging folders of killed runs.
TEST_F(Restart, ARestartGivenTheKilledRunsPidKeepsItsCheckpoint) {
  const fs::path dir = root_ / "same_pid";
  RunOptions opt = stopped_at(dir, 3000);
  const fs::path killed = dir / fmt::format(".staging-{}", getpid());
  fs::rename(dir / "interrupted_run", killed);
  fs::create_directories(dir / ".staging-999999999");  // a killed run's of a pid no process has
  opt.restart_file = find_checkpoint(dir.string()).path;
  ASSERT_EQ(fs::path(opt.restart_file), killed / "checkpoint.bin");
  EXPECT_EQ(run_case(read_case(kCase, kSets), opt), 0);
  expect_same_outputs(full(), dir);
  for (const auto& e : fs::directory_iterator(dir))
    EXPECT_NE(e.path().filename().string().rfind(".staging-", 0), 0u) << e.path() << " is left";
}

TEST_F(Restart, RefusesAnotherCaseADamagedFileAndAnotherBuild) {
  const fs::path dir = root_ / "refuse";
  RunOptions opt = stopped_at(dir, 50);
  const std::string ck = find_checkpoint(dir.string()).path;

  // Another case: the message names the case line that changed.
  std::vector<std::string> other = kSets;
  other.push_back("materials.concrete.tensile_strength=2.9e6");
  opt.restart_file = ck;
  try {
    run_case(read_case(kCase, other), opt);
    FAIL() << "a checkpoint of another case was accepted";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("changed since"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("tensile_strength"), std::string::npos) << e.what();
  }

  // The checkpoint's folder holding another run's series (a checkpoint copied into another
  // run's folder spliced the two runs' rows), missing a frame it lists, or holding one cut
  // short (it passed into the restarted run's results: a probe's): refused before anything is
  // written, the folder as it was.
  for (const std::string what : {"series", "frame", "cut"}) {
    const fs::path copy = root_ / ("refuse_" + what);
    fs::remove_all(copy);
    fs::copy(dir, copy, fs::copy_options::recursive);
    const fs::path series = copy / "interrupted_run" / "series.csv";
    if (what == "series") {
      std::string text = slurp(series);
      const std::size_t row = text.find('\n') + 1;  // the row at t = 0, within what the checkpoint's run wrote
      text[text.find(',', row) + 1] = text[text.find(',', row) + 1] == '1' ? '2' : '1';  // its step's first digit
      std::ofstream(series, std::ios::binary) << text;
    } else if (what == "frame") {
      fs::remove(copy / "interrupted_run" / "frames" / "frame_0000.vtu");
    } else {
      const fs::path last = copy / "interrupted_run" / "frames" / "frame_0000.vtu";
      fs::resize_file(last, fs::file_size(last) - 3);
    }
    const std::string before = slurp(series);
    RunOptions o = opt;
    o.out_dir = copy.string();
    o.restart_file = find_checkpoint(copy.string()).path;
    try {
      run_case(read_case(kCase, kSets), o);
      FAIL() << what << ": the restart went on";
    } catch (const Error& e) {
      EXPECT_NE(std::string(e.what()).find(what == "series"  ? "is not the file the checkpoint's run wrote"
                                           : what == "frame" ? "frame_0000.vtu' of the checkpoint's run is missing"
                                                             : "frame_0000.vtu' of the checkpoint's run is cut short"),
                std::string::npos)
          << e.what();
    }
    EXPECT_EQ(slurp(series), before) << what;
    EXPECT_TRUE(fs::exists(copy / "interrupted_run" / "checkpoint.bin")) << what;
    EXPECT_FALSE(fs::exists(copy / "summary.json")) << what;
  }

  // A flipped byte and a cut file: refused by the CRC; find_checkpoint then finds none.
  const std::string good = slurp(ck);
  for (const std::string& bad : {good.substr(0, good.size() / 2), [&] {
                                   std::string s = good;
                                   s[s.size() / 3] ^= 0x10;
                                   return s;
                                 }()}) {
    std::ofstream(ck, std::ios::binary) << bad;
    StateArchive body;
    try {
      read_checkpoint(ck, body);
      FAIL() << "a damaged checkpoint was read";
    } catch (const Error& e) {
      EXPECT_NE(std::string(e.what()).find("corrupt"), std::string::npos) << e.what();
    }
    EXPECT_THROW(find_checkpoint(dir.string()), Error);
  }

  // Another build: refused before anything is built.
  CheckpointHeader h;
  h.build = "0.0.0 another";
  write_checkpoint((dir / "other.bin").string(), h, StateArchive());
  StateArchive body;
  try {
    read_checkpoint((dir / "other.bin").string(), body);
    FAIL() << "a checkpoint of another build was read";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("another build"), std::string::npos) << e.what();
  }
  // Another format (an older dspdem's): refused by its number, not misread.
  h = CheckpointHeader{};
  h.format = 8;
  h.build = checkpoint_build_id();
  write_checkpoint((dir / "old.bin").string(), h, StateArchive());
  try {
    read_checkpoint((dir / "old.bin").string(), body);
    FAIL() << "a checkpoint of another format was read";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("has format 8"), std::string::npos) << e.what();
  }
  std::ofstream(dir / "not.bin") << "hello";
  EXPECT_THROW(read_checkpoint((dir / "not.bin").string(), body), Error);

  // `run --restart FILE`: a file that is no checkpoint, and another process's file of a
  // distributed run, whose process 0 would read it as its own.
  auto refused = [](const fs::path& p) {
    try {
      restart_checkpoint(p.string());
    } catch (const Error& e) {
      return std::string(e.what());
    }
    return std::string("accepted");
  };
  EXPECT_NE(refused(dir / "not.bin").find("not a dspdem checkpoint"), std::string::npos) << refused(dir / "not.bin");
  h = CheckpointHeader{};
  h.build = checkpoint_build_id();
  h.processes = 2, h.rank = 1;
  write_checkpoint((dir / "checkpoint.1.bin").string(), h, StateArchive());
  EXPECT_NE(refused(dir / "checkpoint.1.bin").find("process 1's checkpoint of a run on 2 processes"), std::string::npos)
      << refused(dir / "checkpoint.1.bin");
  EXPECT_NE(refused(dir / "none.bin").find("no such run folder or checkpoint file"), std::string::npos);
}

// Where a restart from a checkpoint file writes by default: the run folder, also when the file
// lies in the folder an interrupted or a killed run left beside it; absolute, so that a file
// named from inside interrupted_run/ or through '.' still finds its run's folder.
TEST(RestartFile, ARunsFolderIsTheOneThatHoldsItsCheckpoint) {
  const fs::path run = fs::absolute("out/v7.5");
  EXPECT_EQ(run_folder_of("out/v7.5/checkpoint.bin"), run.string());
  EXPECT_EQ(run_folder_of("out/v7.5/interrupted_run/checkpoint.bin"), run.string());
  EXPECT_EQ(run_folder_of("out/v7.5/.staging-4242/checkpoint.bin"), run.string());
  EXPECT_EQ(run_folder_of("out/v7.5/interrupted_run/./checkpoint.bin"), run.string());
  EXPECT_EQ(run_folder_of("out/x/../v7.5/checkpoint.bin"), run.string());
  EXPECT_EQ(run_folder_of("interrupted_run/checkpoint.bin"), fs::current_path().string());
  EXPECT_EQ(run_folder_of("out/staging/checkpoint.bin"), fs::absolute("out/staging").string());  // not a staging name
}

// A checkpoint carries series.csv's CRC on from the last one's (run_case's write_ckpt): the
// CRC of a file's first n2 bytes, carried on from that of its first n1, is the CRC of the
// first n2 read at once: across the reader's 64 KiB blocks, at the file's ends, and where the
// known prefix says nothing of the bytes wanted (longer than them, or than the file now is),
// which is then read from the start. A missing file has no CRC, whatever was known.
TEST(RestartFile, AFilesCrcCarriedOnFromItsFirstBytesIsTheWholeOnes) {
  const fs::path p = fs::temp_directory_path() / fmt::format("dspdem_file_crc_{}.bin", getpid());
  std::string bytes(200000, '\0');
  std::uint32_t r = 12345;
  for (char& b : bytes) b = static_cast<char>((r = r * 1103515245u + 12345u) >> 24);
  std::ofstream(p, std::ios::binary) << bytes;
  const std::vector<std::uint64_t> ns{0, 1, 65535, 65536, 100000, 131073, 200000, 300000};
  for (const std::uint64_t n1 : ns)
    for (const std::uint64_t n2 : ns) {
      const FileCrc whole = file_crc(p.string(), n2), on = file_crc(p.string(), n2, file_crc(p.string(), n1));
      EXPECT_EQ(on.crc, whole.crc) << n1 << " " << n2;
      EXPECT_EQ(on.bytes, whole.bytes) << n1 << " " << n2;
    }
  EXPECT_NE(file_crc(p.string(), 100).crc, file_crc(p.string(), 101).crc);
  // The file cut shorter than the prefix known: read from the start, as far as it goes.
  const FileCrc known = file_crc(p.string(), 150000);
  fs::resize_file(p, 120000);
  const FileCrc cut = file_crc(p.string(), 150000, known);
  EXPECT_EQ(cut.bytes, 120000u);
  EXPECT_EQ(cut.crc, file_crc(p.string(), 120000).crc);
  fs::remove(p);
  EXPECT_EQ(file_crc(p.string(), 150000, known).bytes, 0u);
  EXPECT_EQ(file_crc(p.string(), 150000, known).crc, 0u);
}

// The side folders' names, which find_checkpoint, run --restart and a finished restart's
// clean-up all go by (io/staging.hpp).
TEST(RestartFile, SideFoldersAreKnownByTheirNames) {
  EXPECT_TRUE(is_staging_folder("out/v7.5/.staging-4242"));
  EXPECT_TRUE(is_staging_folder("out/v7.5/.staging-4242.1"));     // a killed run's, moved aside
  EXPECT_FALSE(is_staging_folder("out/v7.5/.new-staging-4242"));  // still being set up: no run's yet
  EXPECT_FALSE(is_staging_folder("out/v7.5/staging-4242"));
  EXPECT_FALSE(is_staging_folder("out/.staging-4242/v7.5"));  // only the last component counts
  EXPECT_TRUE(is_side_folder("out/v7.5/interrupted_run"));
  EXPECT_TRUE(is_side_folder("out/v7.5/.staging-4242"));
  EXPECT_FALSE(is_side_folder("out/v7.5/failed_run"));  // kept for a look, never continued
  EXPECT_FALSE(is_side_folder("out/interrupted_run/v7.5"));
  EXPECT_FALSE(is_side_folder("out/v7.5/interrupted_run.old"));  // the name exactly
  EXPECT_TRUE(is_side_folder("out/v7.5/interrupted_run/"));      // a trailing slash aside
  EXPECT_TRUE(is_staging_folder("out/v7.5/.staging-4242/"));
}

// `run --restart FILE` refuses the checkpoint of a run at work: when the restart ended, it
// would clear that run's staging folder. Staged in this process, whose own staging folder is
// held (as a run's at work is by its lock).
TEST(RestartFile, ALiveRunsCheckpointIsRefused) {
  const ScratchDir scratch("dspdem_restart_live");
  const Staging live(scratch.path.string());
  CheckpointHeader h;
  h.build = checkpoint_build_id();
  const fs::path ck = fs::path(live.path()) / "checkpoint.bin";
  write_checkpoint(ck.string(), h, StateArchive());
  try {
    restart_checkpoint(ck.string());
    FAIL() << "a live run's checkpoint was accepted";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("a run at work"), std::string::npos) << e.what();
  }
  // Given by its folder, the run folder holds no checkpoint of a run that is gone.
  EXPECT_THROW(restart_checkpoint(scratch.path.string()), Error);
}

// The executable, stopped by a real SIGTERM part way: exit status 5, whole frames and a
// collection that lists only them, a checkpoint; `--restart` then finishes the run as the
// uninterrupted one. A second run into the same folder, stopped by two signals, exits at
// once and leaves the finished results as they were.
TEST_F(Restart, SigtermLeavesAValidCollectionAndARestartableCheckpoint) {
  const fs::path dir = root_ / "sigterm";
  std::vector<std::string> args = {DSPDEM_BIN, "-q", "-t", "2", "run", kCase, "--out", dir.string()};
  for (const auto& s : kSets) args.insert(args.end(), {"--set", s});
  auto spawn = [&]() { return spawn_dspdem(args); };
  // Waits until the running job's collection lists `frames` frames (at most 120 s); if it
  // does not, the job is killed (a failed test must not leave it running).
  auto wait_frames = [&](pid_t pid, int frames) {
    const fs::path pvd = dir / fmt::format(".staging-{}", pid) / "run.pvd";
    for (int k = 0; k < 2400; ++k) {
      const std::string s = slurp(pvd);
      int n = 0;
      for (auto k = s.find("<DataSet"); k != std::string::npos; k = s.find("<DataSet", k + 1)) ++n;
      if (n >= frames) return true;
      std::this_thread::sleep_for(std::chrono::milliseconds(50));
    }
    kill(pid, SIGKILL);
    waitpid(pid, nullptr, 0);
    return false;
  };
  const pid_t pid = spawn();
  ASSERT_GT(pid, 0);
  ASSERT_TRUE(wait_frames(pid, 2)) << "the run wrote no frames";
  kill(pid, SIGTERM);
  int st = 0;
  waitpid(pid, &st, 0);
  ASSERT_TRUE(WIFEXITED(st));
  EXPECT_EQ(WEXITSTATUS(st), kExitInterrupted);

  // Every frame the collection lists is there and reads as a whole grid.
  const fs::path kept = dir / "interrupted_run";
  const std::string pvd = slurp(kept / "run.pvd");
  EXPECT_NE(pvd.find("</VTKFile>"), std::string::npos);
  const std::regex file_re("file=\"([^\"]+)\"");
  int listed = 0;
  for (auto m = std::sregex_iterator(pvd.begin(), pvd.end(), file_re); m != std::sregex_iterator(); ++m, ++listed) {
    vtkNew<vtkXMLUnstructuredGridReader> r;
    r->SetFileName((kept / (*m)[1].str()).c_str());
    r->Update();
    EXPECT_GT(r->GetOutput()->GetNumberOfCells(), 1000) << (*m)[1].str();
  }
  EXPECT_GE(listed, 2);
  ASSERT_TRUE(fs::exists(kept / "checkpoint.bin"));

  // Given the checkpoint file itself, not the folder: the outputs go to the run folder that
  // holds interrupted_run/.
  const auto res =
      testsupport::shell(fmt::format("{} -q -t 2 run --restart {}", DSPDEM_BIN, (kept / "checkpoint.bin").string()));
  ASSERT_EQ(res.code, 0) << res.out;
  expect_same_outputs(full(), dir);

  // Two signals: the second ends the job at once; the finished results stay as they were.
  const std::string series = slurp(dir / "series.csv"), summary = slurp(dir / "summary.json");
  const pid_t pid2 = spawn();
  ASSERT_TRUE(wait_frames(pid2, 1));
  // Two of the same signal sent at once can merge into one delivery; SIGTERM then SIGINT
  // cannot. The job must not get as far as keeping its outputs: its staging folder stays
  // (a killed run's, which --restart would look in).
  kill(pid2, SIGTERM);
  kill(pid2, SIGINT);
  waitpid(pid2, &st, 0);
  ASSERT_TRUE(WIFEXITED(st));
  EXPECT_EQ(WEXITSTATUS(st), kExitInterrupted);
  EXPECT_TRUE(fs::exists(dir / fmt::format(".staging-{}", pid2)));
  EXPECT_FALSE(fs::exists(dir / "interrupted_run"));
  EXPECT_TRUE(slurp(dir / "series.csv") == series);
  EXPECT_TRUE(slurp(dir / "summary.json") == summary);
  // The CLI refuses what makes no sense.
  EXPECT_EQ(testsupport::shell(fmt::format("{} run --restart {} {}", DSPDEM_BIN, dir.string(), kCase)).code, 1);
  const auto none = testsupport::shell(fmt::format("{} run --restart {}", DSPDEM_BIN, (root_ / "nothing").string()));
  EXPECT_EQ(none.code, 2);
  EXPECT_NE(none.out.find("no such run folder"), std::string::npos) << none.out;
}

// Killed outright (SIGKILL: no handler runs, nothing is tidied), a run loses only what came
// after its last checkpoint by wall time: `--restart` finds it in the killed run's staging
// folder and ends the run as the uninterrupted one, and the staging folder goes.
TEST_F(Restart, AKilledRunGoesOnFromItsLastCheckpointByWallTime) {
  const fs::path dir = root_ / "killed";
  std::vector<std::string> args = {DSPDEM_BIN,          "-q", "-t", "2", "run", kCase, "--out", dir.string(),
                                   "--checkpoint-wall", "0.2"};
  for (const auto& s : kSets) args.insert(args.end(), {"--set", s});
  const pid_t pid = spawn_dspdem(args);
  ASSERT_GT(pid, 0);
  const fs::path staging = dir / fmt::format(".staging-{}", pid);
  bool written = false;
  for (int k = 0; k < 2400 && !written; ++k) {
    written = fs::exists(staging / "checkpoint.bin");
    if (!written) std::this_thread::sleep_for(std::chrono::milliseconds(50));
  }
  const bool judged_live = !left_by_killed_run(staging.string());  // its lock held
  kill(pid, SIGKILL);
  int st = 0;
  waitpid(pid, &st, 0);
  ASSERT_TRUE(written) << "no checkpoint by wall time in " << staging;
  ASSERT_TRUE(WIFSIGNALED(st)) << "the run ended before it was killed: make it longer";
  EXPECT_TRUE(judged_live) << "a running run's staging folder was judged a killed run's";
  EXPECT_TRUE(fs::exists(staging / ".lock"));
  EXPECT_TRUE(left_by_killed_run(staging.string())) << "the kernel let go of its lock";
  const FoundCheckpoint found = find_checkpoint(dir.string());
  EXPECT_EQ(fs::path(found.path), staging / "checkpoint.bin");
  const CheckpointHeader& h = found.header;
  EXPECT_GT(h.steps, 0);
  EXPECT_EQ(h.checkpoint_wall, 0.2);  // what the restart keeps unless given anew
  const auto res = testsupport::shell(fmt::format("{} -q -t 1 run --restart {}", DSPDEM_BIN, dir.string()));
  ASSERT_EQ(res.code, 0) << res.out;
  expect_same_outputs(full(), dir);
  EXPECT_FALSE(fs::exists(staging));
  EXPECT_FALSE(fs::exists(dir / ".lock"));
}

// `report --resume` (report::earlier_run) goes on from a killed run's last checkpoint, in its
// staging folder, only when the run's process is gone (a live one is another report's, at work
// in the folder) and the checkpoint is of this executable and this case. Staged in this process,
// whose runs' checkpoints carry its own executable: an interrupted run's folder renamed as a
// killed run's. Not of the fixture: it needs no uninterrupted run.
TEST(RestartReport, AReportResumesAKilledRunOnlyWhenItsProcessIsGone) {
  const ScratchDir scratch("dspdem_restart_report");
  const fs::path& dir = scratch.path;
  const CaseConfig c = read_case(kCase, kSets);
  stopped_at(dir, 50);
  const report::EarlierRun stopped = report::earlier_run(dir.string(), c.resolved_toml);
  ASSERT_EQ(stopped.state, report::Earlier::Interrupted);
  EXPECT_EQ(stopped.checkpoint, (dir / "interrupted_run" / "checkpoint.bin").string());
  fs::remove(dir / "interrupted_run" / "summary.json");  // a killed run leaves none
  EXPECT_EQ(report::earlier_run(dir.string(), c.resolved_toml).state, report::Earlier::None);

  const fs::path dead = dir / ".staging-999999999", live = dir / fmt::format(".staging-{}", getppid());
  fs::rename(dir / "interrupted_run", dead);
  ASSERT_EQ(kill(999999999, 0), -1) << "a process has pid 999999999";
  const report::EarlierRun killed = report::earlier_run(dir.string(), c.resolved_toml);
  EXPECT_EQ(killed.state, report::Earlier::Interrupted);
  EXPECT_EQ(killed.checkpoint, (dead / "checkpoint.bin").string()) << "the run goes on from another checkpoint";
  EXPECT_EQ(report::earlier_run(dir.string(), read_case(kCase, {"time.end=1e-4"}).resolved_toml).state,
            report::Earlier::None)
      << "another case's checkpoint was taken";
  fs::rename(dead, live);
  EXPECT_EQ(report::earlier_run(dir.string(), c.resolved_toml).state, report::Earlier::None)
      << "a live process's staging folder was taken";
  fs::rename(live, dead);
  // A run at work holds its staging folder's lock, which answers before the pid does: a pid no
  // process here has, as a run in another PID namespace (another container) would show.
  {
    const int fd = ::open((dead / ".lock").c_str(), O_CREAT | O_RDWR | O_CLOEXEC, 0644);
    ASSERT_GE(fd, 0);
    ASSERT_EQ(flock(fd, LOCK_EX | LOCK_NB), 0);
    EXPECT_EQ(report::earlier_run(dir.string(), c.resolved_toml).state, report::Earlier::None)
        << "a staging folder whose lock is held was taken";
    ::close(fd);
  }
  EXPECT_EQ(report::earlier_run(dir.string(), c.resolved_toml).state, report::Earlier::Interrupted)
      << "the lock let go of, its run is gone";
  // A killed run of this very pid (pids repeat, in a container started anew): its folder is not
  // this process's, whose folders are those it holds, so it is continued.
  const fs::path same_pid = dir / fmt::format(".staging-{}", getpid());
  fs::rename(dead, same_pid);
  EXPECT_EQ(report::earlier_run(dir.string(), c.resolved_toml).state, report::Earlier::Interrupted)
      << "a killed run of this pid was taken for this process's own";
  fs::rename(same_pid, dead);

  // Another executable's checkpoint (what a rebuild leaves): the same header but its id. The
  // header rewritten as it was first (earlier_run reads no further), then with another id.
  StateArchive body;
  CheckpointHeader h = read_checkpoint((dead / "checkpoint.bin").string(), body);
  write_checkpoint((dead / "checkpoint.bin").string(), h, StateArchive());
  ASSERT_EQ(report::earlier_run(dir.string(), c.resolved_toml).state, report::Earlier::Interrupted);
  h.executable += " (another)";
  write_checkpoint((dead / "checkpoint.bin").string(), h, StateArchive());
  EXPECT_EQ(report::earlier_run(dir.string(), c.resolved_toml).state, report::Earlier::None)
      << "another executable's checkpoint was taken";
}

// A staging folder of this process's pid that a run at work holds (its lock held: a run of the
// same pid in another container, writing into the same folder) is neither moved aside nor
// emptied: the new run is refused, naming it. Let go of, it is a killed run's, moved aside.
TEST(RestartStaging, AFolderOfThisPidThatARunAtWorkHoldsIsLeftAlone) {
  const ScratchDir scratch("dspdem_staging_lock");
  const fs::path& out = scratch.path;
  const fs::path other = out / fmt::format(".staging-{}", getpid());
  fs::create_directories(other);
  std::ofstream(other / "checkpoint.bin") << "theirs";
  const int fd = ::open((other / ".lock").c_str(), O_CREAT | O_RDWR | O_CLOEXEC, 0644);
  ASSERT_GE(fd, 0);
  ASSERT_EQ(flock(fd, LOCK_EX | LOCK_NB), 0);
  try {
    Staging s(out.string());
    FAIL() << "a staging folder a run at work holds was taken";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("a run at work holds"), std::string::npos) << e.what();
  }
  EXPECT_EQ(slurp(other / "checkpoint.bin"), "theirs");
  ::close(fd);
  {
    Staging s(out.string());
    EXPECT_EQ(s.moved_aside(), 1);
    EXPECT_EQ(slurp(fs::path(other.string() + ".1") / "checkpoint.bin"), "theirs");
    EXPECT_TRUE(fs::exists(fs::path(s.path()) / ".lock"));
  }
}

}  // namespace

// A run started as `dspdem run cases/x.toml` records the case by its absolute path, and the
// restart reads it from there: the resolved texts then differ in their first comment only
// (the file as it was given), which must not refuse the restart (it did until session 41).
TEST(RestartCase, TheSameCaseGivenByARelativeOrAnAbsolutePathIsTheSameCase) {
  const fs::path abs = fs::path(DSPDEM_SOURCE_DIR) / "tests" / "data" / "notched_bar.toml";
  const fs::path rel = fs::relative(abs);
  ASSERT_TRUE(rel.is_relative());
  const std::string a = read_case(abs.string(), {}).resolved_toml, b = read_case(rel.string(), {}).resolved_toml;
  EXPECT_NE(a, b) << "the first comment names the file as given";
  EXPECT_TRUE(same_case(a, b));
  EXPECT_EQ(case_origin(a), abs.string());  // what a restart records as the case file
  EXPECT_EQ(case_origin(b), rel.string());
  EXPECT_EQ(case_origin("[case]\n"), "");
  const std::string changed = read_case(abs.string(), {"time.end=1e-4"}).resolved_toml;
  EXPECT_FALSE(same_case(a, changed));
  // The refusal's message names the key that changed, not the first comment.
  EXPECT_EQ(first_difference(a, b), "");
  const std::string d = first_difference(b, changed);
  EXPECT_NE(d.find("end = "), std::string::npos) << d;
  EXPECT_EQ(d.find("Resolved from"), std::string::npos) << d;
}

// A run's summary.json and its checkpoints name the build; its commit is the one of the code
// it was built from (cmake/commit_id.cmake, run at every build), not the one CMake was
// configured at: an incremental build after a commit named the older commit before. The same
// script run now on the sources must give what the build holds; outside a git checkout both
// say "no-git".
TEST(BuildId, NamesTheCommitOfTheCodeItWasBuiltFrom) {
  const fs::path out = fs::temp_directory_path() / "dspdem_test_commit_id.hpp";
  fs::remove(out);
  const auto r =
      testsupport::shell(fmt::format("'{}' -DGIT='{}' -DSRC='{}' -DOUT='{}' -P '{}/cmake/commit_id.cmake'",
                                     DSPDEM_CMAKE, DSPDEM_GIT, DSPDEM_SOURCE_DIR, out.string(), DSPDEM_SOURCE_DIR));
  ASSERT_EQ(r.code, 0) << r.out;
  std::ifstream f(out);
  std::string line;
  std::getline(f, line);
  std::smatch m;
  ASSERT_TRUE(std::regex_search(line, m, std::regex("\"([^\"]+)\""))) << line;
  const std::string now = m[1];
  EXPECT_NE(checkpoint_build_id().find(" " + now + " "), std::string::npos)
      << "build id '" << checkpoint_build_id() << "', the code now at " << now
      << " (the code committed or changed since this build?)";
  if (now != "no-git") {
    EXPECT_GE(now.size(), 12u) << now;
  }
  fs::remove(out);
}
