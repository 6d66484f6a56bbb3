// End-to-end tests of the dspdem executable: outputs of a good run, bad inputs rejected
// with a clear message and non-zero exit, earlier results never destroyed.
#include <fmt/format.h>
#include <gmsh.h>
#include <gtest/gtest.h>
#include <signal.h>
#include <sys/prctl.h>
#include <sys/wait.h>
#include <unistd.h>
#include <vtkCellData.h>
#include <vtkImageData.h>
#include <vtkNew.h>
#include <vtkPNGReader.h>
#include <vtkPointData.h>
#include <vtkUnstructuredGrid.h>
#include <vtkXMLUnstructuredGridReader.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>
#include <nlohmann/json.hpp>
#include <regex>
#include <set>
#include <sstream>
#include <thread>

#include "core/file.hpp"
#include "core/folder_lock.hpp"
#include "io/run_summary.hpp"
#include "mesh/gmsh_reader.hpp"
#include "report/run_data.hpp"
#include "run/series_units.hpp"
#include "support/cli.hpp"

namespace fs = std::filesystem;

namespace {
using Result = dspdem::testsupport::CliResult;

Result run(const std::string& args) {
  // Arguments starting with "env " are a whole command line. (The command built by appends:
  // GCC 12 at -O1 took the operator+ of a temporary for a write out of its bounds,
  // -Warray-bounds, once this file's inlining changed.)
  if (args.rfind("env ", 0) == 0) return dspdem::testsupport::shell(args);
  std::string cmd = DSPDEM_BIN;
  cmd += ' ';
  cmd += args;
  return dspdem::testsupport::shell(cmd);
}

// "" for a file that is not there (yet): the checks then name it.
std::string slurp(const fs::path& p) { return dspdem::read_file_if(p).value_or(""); }

// One CSV line's cells (no quoting: the report's CSV files have none).
std::vector<std::string> csv_fields(const std::string& line) {
  std::vector<std::string> f;
  std::stringstream ss(line);
  for (std::string c; std::getline(ss, c, ',');) f.push_back(c);
  return f;
}

// `cmd` through sh in a process group of its own, as a shell starts a foreground job, with
// the stop signals at their defaults whatever this test was started with (a script's
// background job has SIGINT ignored, and an ignored signal stays ignored in dspdem).
pid_t start_job(const std::string& cmd) {
  const pid_t pid = fork();
  if (pid == 0) {
    setpgid(0, 0);
    for (int sig : {SIGINT, SIGTERM, SIGHUP}) signal(sig, SIG_DFL);
    execl("/bin/sh", "sh", "-c", cmd.c_str(), static_cast<char*>(nullptr));
    _exit(127);
  }
  if (pid > 0) setpgid(pid, pid);
  return pid;
}

// Sends `sig` to the job's process group and waits for the job: its wait status.
int stop_job(pid_t pid, int sig) {
  kill(-pid, sig);
  int st = 0;
  waitpid(pid, &st, 0);
  return st;
}

// A report stopped by SIGINT (`st`, its wait status; `log`, its output): it exits 5 and says
// how to go on.
::testing::AssertionResult stopped_for_resume(int st, const std::string& log) {
  if (!WIFEXITED(st)) return ::testing::AssertionFailure() << "it did not exit (wait status " << st << "): " << log;
  if (WEXITSTATUS(st) != 5) return ::testing::AssertionFailure() << "exit " << WEXITSTATUS(st) << ", not 5: " << log;
  if (log.find("the same report with --resume") == std::string::npos)
    return ::testing::AssertionFailure() << "no --resume hint: " << log;
  return ::testing::AssertionSuccess();
}

// Whether a run of the sweep's speed folder `speed` has written `frames` frames into its
// staging folder (at most 120 s; the folders come and go meanwhile, hence the error codes).
bool wait_for_frames(const fs::path& speed, int frames) {
  for (int k = 0; k < 2400; ++k) {
    std::error_code ec;
    for (fs::directory_iterator it(speed, ec), end; !ec && it != end; it.increment(ec)) {
      if (it->path().filename().string().rfind(".staging-", 0) != 0) continue;
      const std::string pvd = slurp(it->path() / "run.pvd");
      int n = 0;
      for (auto q = pvd.find("<DataSet"); q != std::string::npos; q = pvd.find("<DataSet", q + 1)) ++n;
      if (n >= frames) return true;
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(50));
  }
  return false;
}

std::string replace(std::string s, const std::string& from, const std::string& to) {
  const auto p = s.find(from);
  EXPECT_NE(p, std::string::npos) << from;
  return p == std::string::npos ? s : s.replace(p, from.size(), to);
}

class Cli : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() /
           ("dspdem_cli_" + std::string(::testing::UnitTest::GetInstance()->current_test_info()->name()));
    fs::remove_all(dir_);
    fs::create_directories(dir_ / "meshes");
    fs::copy_file(fs::path(DSPDEM_SOURCE_DIR) / "cases/meshes/cantilever_hex.geo", dir_ / "meshes/cantilever_hex.geo");
    good_ = slurp(fs::path(DSPDEM_SOURCE_DIR) / "cases/cantilever.toml");
    // Short: 2 ms, 3 frames.
    good_ = replace(good_, "end = 0.05", "end = 2.0e-3");
    good_ = replace(good_, "frame_interval = 2.5e-3", "frame_interval = 1.0e-3");
  }
  fs::path write(const std::string& name, const std::string& text) {
    std::ofstream(dir_ / name) << text;
    return dir_ / name;
  }
  /// `dspdem -q report` of the shipped case cases/<name>.toml into dir_/<out>, without images,
  /// with `options` (further flags and --set overrides).
  Result report(const std::string& name, const std::string& options, const std::string& out = "rep") {
    // Built by appends, as run()'s command (GCC 12's -Warray-bounds on a temporary's operator+).
    std::string args = "-q report ";
    args += DSPDEM_SOURCE_DIR;
    args += "/cases/";
    args += name;
    args += ".toml --no-render --out ";
    args += (dir_ / out).string();
    args += ' ';
    args += options;
    return run(args);
  }
  fs::path dir_;
  std::string good_;
};
}  // namespace

TEST_F(Cli, GoodRunWritesCompleteOutputs) {
  const fs::path c = write("good.toml", good_), out = dir_ / "out";
  // popen gives a pipe, not a terminal: no progress line expected.
  const Result r2 = run("run " + c.string() + " --out " + out.string());
  ASSERT_EQ(r2.code, 0) << r2.out;
  EXPECT_NE(r2.out.find(out.string()), std::string::npos) << "results folder not printed";
  EXPECT_EQ(r2.out.find("ETA"), std::string::npos) << "progress line printed off a terminal";
  const std::string summary = slurp(out / "summary.json");
  for (const char* key : {"\"case\"", "\"steps\"", "\"dt\"", "\"t_end\"", "\"wall_s\"", "\"nodes\"", "\"elements\"",
                          "\"element_steps_per_s\"", "\"kinetic\"", "\"internal\"", "\"external_work\"", "\"damping\"",
                          "\"kick\"", "\"balance_error\""})
    EXPECT_NE(summary.find(key), std::string::npos) << key;
  EXPECT_NE(summary.find("\"status\": \"completed\""), std::string::npos);
  // PVD lists 3 frames with real times.
  const std::string pvd = slurp(out / "run.pvd");
  const std::regex dataset("<DataSet");
  EXPECT_EQ(std::distance(std::sregex_iterator(pvd.begin(), pvd.end(), dataset), std::sregex_iterator()), 3);
  EXPECT_NE(pvd.find("timestep=\"0.001"), std::string::npos) << pvd;
  // The last frame reads back with VTK: all points, cells and fields, zlib-compressed.
  const fs::path vtu = out / "frames/frame_0002.vtu";
  ASSERT_TRUE(fs::exists(vtu));
  EXPECT_NE(slurp(vtu).find("vtkZLibDataCompressor"), std::string::npos);
  vtkNew<vtkXMLUnstructuredGridReader> rd;
  rd->SetFileName(vtu.c_str());
  rd->Update();
  vtkUnstructuredGrid* g = rd->GetOutput();
  EXPECT_EQ(g->GetNumberOfPoints(), 1025);
  EXPECT_EQ(g->GetNumberOfCells(), 640);
  for (const char* a : {"displacement", "velocity"}) EXPECT_NE(g->GetPointData()->GetArray(a), nullptr) << a;
  for (const char* a : {"stress", "von_mises", "max_principal", "body", "material"})
    EXPECT_NE(g->GetCellData()->GetArray(a), nullptr) << a;
  EXPECT_EQ(g->GetCellData()->GetArray("stress")->GetNumberOfComponents(), 6);
  // series.csv: header with the monitors and one row per series step.
  const std::string csv = slurp(out / "series.csv");
  EXPECT_EQ(csv.rfind("time,step,kinetic,internal,external_work,damping,joint_elastic,fracture_I,fracture_II,broken_"
                      "joints,crack_area,kick,balance_error,tip_uy,clamp_reaction_y",
                      0),
            0u);
  EXPECT_TRUE(fs::exists(out / "case.resolved.toml"));
  for (const auto& e : fs::directory_iterator(out))
    EXPECT_EQ(e.path().filename().string().rfind(".staging", 0), std::string::npos) << "staging folder left behind";

  // --estimate sets the case up and times its first steps, writing nothing: the steps and
  // frames it gives are the run's (this case neither stops early nor lowers its step), also
  // for frames at an interval that does not divide the end (then a last one at the end); it
  // answers with -q too, and leaves a run's folder it is given as it was.
  const Result e = run("-q run " + c.string() + " --estimate --out " + out.string());
  ASSERT_EQ(e.code, 0) << e.out;
  const long steps = nlohmann::json::parse(summary)["steps"].get<long>();
  EXPECT_NE(e.out.find(fmt::format("estimate (nothing written): {} steps of ", steps)), std::string::npos)
      << e.out << "\nthe run: " << steps << " steps";
  EXPECT_NE(e.out.find(", 3 frames"), std::string::npos) << e.out;
  EXPECT_NE(e.out.find("at that rate the " + std::to_string(steps) + " steps take"), std::string::npos) << e.out;
  EXPECT_EQ(slurp(out / "summary.json"), summary);
  EXPECT_EQ(std::distance(fs::directory_iterator(out), fs::directory_iterator()), 6) << "a file added to the run";
  const std::string odd = " --set output.frame_interval=0.0007";
  const Result e2 = run("-q run " + c.string() + odd + " --estimate");
  const Result r3 = run("-q run " + c.string() + odd + " --out " + (dir_ / "odd").string());
  ASSERT_EQ(r3.code, 0) << r3.out;
  const std::string pvd3 = slurp(dir_ / "odd" / "run.pvd");
  const long frames3 = std::distance(std::sregex_iterator(pvd3.begin(), pvd3.end(), dataset), std::sregex_iterator());
  EXPECT_EQ(frames3, 4);  // 0, 0.7, 1.4 and the end, 2 ms
  EXPECT_NE(e2.out.find(fmt::format(", {} frames", frames3)), std::string::npos) << e2.out;
  // A case that stops on a load drop may take fewer steps and frames; one capped by max_steps
  // takes those.
  const Result stops = run("-q run " + c.string() + " --set time.stop_series=kinetic --estimate");
  EXPECT_NE(stops.out.find(fmt::format("(nothing written): at most {} steps", steps)), std::string::npos) << stops.out;
  EXPECT_NE(stops.out.find(", at most 3 frames"), std::string::npos) << stops.out;
  const Result capped = run("-q run " + c.string() + " --set time.max_steps=7 --estimate");
  EXPECT_NE(capped.out.find("(nothing written): 7 steps"), std::string::npos) << capped.out;
  EXPECT_NE(capped.out.find(", 2 frames"), std::string::npos) << capped.out;  // the start and the last step
  // A restart goes on from a checkpoint; the two are refused together, as a command-line error.
  EXPECT_EQ(run("run --restart " + out.string() + " --estimate").code, 1);
}

TEST_F(Cli, AnEstimateTakesTheStepsAsTheRunDoesWithItsExtrinsicChecks) {
  // The notched bar pulled apart with extrinsic insertion (tests/verification/test_restart.cpp:
  // its first faces open at steps 1000-1100, and its step falls over the next 900): the
  // estimate runs the run's checks with its steps, so it opens those faces and lowers its step
  // as the run does, and says so; the step it reaches is one the run passes through, down to
  // the run's last, and the steps it then counts at least as many as the run takes.
  const std::string bar = std::string(DSPDEM_SOURCE_DIR) + "/tests/data/notched_bar.toml";
  const std::string sets =
      " --set contact.enabled=true --set time.end=3e-4 --set boundary.1.value=[0.25,0.0,0.0] --set "
      "boundary.1.ramp=2e-5 --set 'bodies.0.fracture_insertion=\"extrinsic\"'";
  const Result e = run("-q -t 1 run " + bar + sets + " --estimate");
  ASSERT_EQ(e.code, 0) << e.out;
  std::smatch m, took;
  ASSERT_TRUE(std::regex_search(e.out, took, std::regex("the first ([0-9]+) steps took")) && took.size() == 2) << e.out;
  // Margin above the 1100 steps by which the first faces have opened.
  if (std::stol(took[1]) < 1300) GTEST_SKIP() << "the box gave the estimate under 1300 steps: " << e.out;
  ASSERT_TRUE(std::regex_search(
      e.out, m,
      std::regex("extrinsic insertion opened ([0-9]+) joint\\(s\\) during those steps; the "
                 "step fell from ([0-9.e+-]+) s to ([0-9.e+-]+) s, at which the run takes at least ([0-9]+) steps")))
      << e.out;
  EXPECT_GT(std::stol(m[1]), 0);
  const double from = std::stod(m[2]), to = std::stod(m[3]);
  EXPECT_NE(e.out.find(fmt::format("steps of {:.4g} s", from)), std::string::npos) << e.out;
  EXPECT_LT(to, from);
  const fs::path out = dir_ / "bar";
  const Result r = run("-q -t 1 run " + bar + sets + " --out " + out.string());
  ASSERT_EQ(r.code, 0) << r.out;
  const auto j = nlohmann::json::parse(slurp(out / "summary.json"));
  // The steps as printed, to 6 significant digits: within 5e-6 of them.
  EXPECT_NEAR(j["dt_start"].get<double>(), from, 5e-6 * from);
  EXPECT_GE(to, j["dt"].get<double>() * (1 - 5e-6));
  // At least the steps the run takes from the estimate's end at the step reached (all of them
  // here when the step has reached its last value by then).
  EXPECT_LE(std::stol(m[4]), j["steps"].get<long>());
  EXPECT_GT(std::stol(m[4]), std::stol(took[1]));
}

TEST_F(Cli, Msh4FileWrittenByGmshReadsEndToEnd) {
  {
    dspdem::GmshSession s;
    gmsh::open((dir_ / "meshes/cantilever_hex.geo").string());
    gmsh::model::mesh::generate(3);
    gmsh::option::setNumber("Mesh.MshFileVersion", 4.1);
    gmsh::write((dir_ / "meshes/beam.msh").string());
  }
  const fs::path c = write("msh.toml", replace(good_, "meshes/cantilever_hex.geo", "meshes/beam.msh"));
  const Result r = run("run " + c.string() + " --out " + (dir_ / "out").string());
  ASSERT_EQ(r.code, 0) << r.out;
  EXPECT_NE(r.out.find("1025 nodes, 640 elements"), std::string::npos) << r.out;
}

TEST_F(Cli, BadInputsFailClearlyAndKeepEarlierResults) {
  const fs::path out = dir_ / "out";
  ASSERT_EQ(run("run " + write("good.toml", good_).string() + " --out " + out.string()).code, 0);
  const std::string before = slurp(out / "summary.json"), pvd_before = slurp(out / "run.pvd");

  // An inverted tetrahedron (nodes 1 3 2 4), as a gmsh 2.2 ASCII file.
  write("meshes/inverted.msh",
        "$MeshFormat\n2.2 0 8\n$EndMeshFormat\n$PhysicalNames\n1\n3 1 \"beam\"\n$EndPhysicalNames\n"
        "$Nodes\n4\n1 0 0 0\n2 1 0 0\n3 0 1 0\n4 0 0 1\n$EndNodes\n$Elements\n1\n1 4 2 1 1 1 3 2 4\n$EndElements\n");
  // A script that would run for hours: stopped at [mesh] time_limit.
  write("meshes/forever.geo", "For i In {1:2000000000}\nEndFor\n");
  // A script whose message carries a terminal's escape sequences (retitle, clear the screen).
  write("meshes/escape.geo", "Error(\"A\033]0;T\007B\033[2J\");\n");
  struct Bad {
    std::string name, text, args;
    std::vector<std::string> expect;
  };
  const std::vector<Bad> cases = {
      {"syntax", replace(good_, "nu = 0.2", "nu = 0.2 0.3"), "", {"syntax.toml:", "syntax error"}},
      {"unknown_key", replace(good_, "nu = 0.2", "nu = 0.2\npoisson = 0.2"), "", {"unknown key 'poisson'"}},
      {"E", replace(good_, "E = 30.0e9", "E = -1.0"), "", {"'E'", "out of range"}},
      {"nu", replace(good_, "nu = 0.2", "nu = 0.5"), "", {"'nu'", "out of range"}},
      {"density", replace(good_, "density = 2400.0", "density = -2400.0"), "", {"'density'"}},
      {"dt", replace(good_, "end = 2.0e-3", "end = 2.0e-3\ndt = 0.0"), "", {"'dt'"}},
      {"dt_unstable", good_, "--set time.dt=1.0", {"exceeds the critical step", "element"}},
      {"missing_mesh",
       replace(good_, "meshes/cantilever_hex.geo", "meshes/none.msh"),
       "",
       {"none.msh", "does not exist"}},
      {"inverted",
       replace(good_, "meshes/cantilever_hex.geo", "meshes/inverted.msh"),
       "",
       {"inverted", "element tags: 1"}},
      {"geo_escape",
       replace(good_, "meshes/cantilever_hex.geo", "meshes/escape.geo"),
       "",
       {"escape.geo", "A\\x1b]0;T\\x07B\\x1b[2J"}},
      {"geo_time_limit",
       replace(good_, "meshes/cantilever_hex.geo", "meshes/forever.geo"),
       "--set mesh.time_limit=1",
       {"forever.geo", "gmsh did not finish within 1 s", "[mesh] time_limit"}},
      {"stop_series", good_, "--set time.stop_series=plate_fy", {"stop_series = \"plate_fy\"", "known:"}},
      {"stop_reach", good_, "--set time.stop_reach=1e3", {"[time] stop_reach", "needs stop_series"}},
      // Written as numbers but not numbers TOML reads: said so, not "must be a number, got a string".
      {"set_huge", good_, "--set time.end=1e400", {"1e400 is not a number TOML reads", "could not be interpreted"}},
      {"set_bare_point", good_, "--set time.end=.5", {".5 is not a number TOML reads", "expected decimal digit"}},
      {"string_for_number", good_, "--set time.end=soon", {"'end' must be a number, got the string \"soon\""}},
      // A body inside a box wall, or behind a plane wall: no contact pushed it out, and a box
      // holding it whole was never touched (a probe's: the run went on as if it were not there).
      {"wall_engulfs",
       good_ + "\n[contact]\nenabled = true\n\n[[walls]]\nname = \"b\"\ntype = \"box\"\npoint = [0.5, 0.05, "
               "0.05]\nhalf_size = [2.0, 2.0, 2.0]\n",
       "",
       {"element", "starts inside the box of wall 'b'", "place the wall outside the bodies"}},
      {"wall_behind",
       good_ + "\n[contact]\nenabled = true\n\n[[walls]]\nname = \"p\"\ntype = \"plane\"\npoint = [0.5, 0.05, "
               "0.05]\nnormal = [0.0, 1.0, 0.0]\n",
       "",
       {"starts behind the plane of wall 'p'"}},
      // A step lost to rounding was said to come of "only rigid bodies" (a probe's): a damping
      // so large that the step's formula cancelled, a density so small that it overflowed.
      {"damping_beta_huge",
       good_,
       "--set materials.concrete.damping_beta=1e300",
       {"more than 1e+10", "limited by element", "(E, density, damping_beta)"}},
      {"density_tiny",
       good_,
       "--set materials.concrete.density=1e-300",
       {"has a critical step of", "material 'concrete' (density 1e-300 kg/m^3"}},
      // A line break in a value: what followed read as more keys, left unread (a probe's).
      {"set_two_lines",
       good_,
       "--set 'time.end=2e-3\nbogus = 1'",
       {"bogus = 1': the value holds more TOML than one value"}},
      // A step count past any run's (past 2^63 it turned negative and the run "completed" in 0 steps).
      {"steps_end", good_, "--set time.end=1e300", {"[time] end = 1e+300 s", "more than 1e+10", "max_steps"}},
      {"steps_stiff", replace(good_, "E = 30.0e9", "E = 1.0e300"), "", {"steps, more than 1e+10", "limited by"}},
      {"unknown_group",
       replace(good_, "group = \"tip\"\ntype = \"force\"", "group = \"top\"\ntype = \"force\""),
       "",
       {"'top'", "clamp, tip"}},
  };
  for (const auto& b : cases) {
    const fs::path c = write(b.name + ".toml", b.text);
    const Result r = run("run " + c.string() + " --out " + out.string() + " " + b.args);
    EXPECT_EQ(r.code, 2) << b.name << ": " << r.out;
    EXPECT_EQ(r.out.find('\033'), std::string::npos) << b.name << ": a terminal's escape in " << r.out;
    EXPECT_NE(r.out.find("error:"), std::string::npos) << b.name << ": " << r.out;
    for (const auto& e : b.expect)
      EXPECT_NE(r.out.find(e), std::string::npos) << b.name << ": '" << e << "' in " << r.out;
    EXPECT_EQ(slurp(out / "summary.json"), before) << b.name << " changed earlier results";
    EXPECT_EQ(slurp(out / "run.pvd"), pvd_before) << b.name << " changed earlier results";
  }
  // A file of the user's in the run's frames/, which a run replaces whole: refused, kept.
  std::ofstream(out / "frames" / "mine.txt") << "mine";
  const Result rf = run("run " + write("good.toml", good_).string() + " --out " + out.string());
  EXPECT_EQ(rf.code, 2) << rf.out;
  EXPECT_NE(rf.out.find("'mine.txt' is not a run's frame"), std::string::npos) << rf.out;
  EXPECT_EQ(slurp(out / "frames" / "mine.txt"), "mine");
  EXPECT_EQ(slurp(out / "summary.json"), before);
  // An end nearer than 1e-9 of a step (the cantilever's is about 3e-6 s): that one step, said
  // (it took none and "completed").
  const fs::path one = dir_ / "one_step";
  const Result r = run("run " + write("one.toml", good_).string() + " --out " + one.string() + " --set time.end=1e-18");
  ASSERT_EQ(r.code, 0) << r.out;
  EXPECT_NE(r.out.find("shorter than one step"), std::string::npos) << r.out;
  EXPECT_EQ(dspdem::read_run_summary((one / "summary.json").string()).steps, 1);
}

TEST_F(Cli, NumericalFailureNamesStepAndElementAndKeepsEarlierResults) {
  const fs::path out = dir_ / "out";
  const fs::path c = write("good.toml", good_);
  ASSERT_EQ(run("run " + c.string() + " --out " + out.string()).code, 0);
  const std::string before = slurp(out / "summary.json");
  const Result r =
      run("run " + c.string() + " --out " + out.string() + " --set time.dt=1.2e-5 --set time.allow_unstable=true");
  EXPECT_EQ(r.code, 3) << r.out;
  EXPECT_TRUE(std::regex_search(r.out, std::regex("element [0-9]+"))) << r.out;
  EXPECT_TRUE(std::regex_search(r.out, std::regex("step [0-9]+, t = "))) << r.out;
  EXPECT_EQ(slurp(out / "summary.json"), before);
  EXPECT_NE(slurp(out / "failed_run/summary.json").find("\"status\": \"failed\""), std::string::npos);
  EXPECT_TRUE(fs::exists(out / "failed_run/frames/frame_0000.vtu"));
}

TEST_F(Cli, AnOpenEnergyLedgerIsWarnedOnceWithItsStepAndTheRunGoesOn) {
  // The good case's ledger closes well under 1 %: silent at the default limit; at a limit
  // below any error it has the one warning comes, naming step and time, and the run completes.
  const fs::path c = write("good.toml", good_);
  const Result quiet = run("-q run " + c.string() + " --out " + (dir_ / "a").string());
  ASSERT_EQ(quiet.code, 0) << quiet.out;
  EXPECT_EQ(quiet.out.find("energy balance off"), std::string::npos) << quiet.out;
  const Result r =
      run("-q run " + c.string() + " --out " + (dir_ / "b").string() + " --set checks.energy_balance_warn=1e-300");
  ASSERT_EQ(r.code, 0) << r.out;
  EXPECT_TRUE(std::regex_search(r.out, std::regex("energy balance off by .* at step [0-9]+, t = "))) << r.out;
  const std::regex once("energy balance off");
  EXPECT_EQ(std::distance(std::sregex_iterator(r.out.begin(), r.out.end(), once), std::sregex_iterator()), 1) << r.out;
  EXPECT_NE(slurp(dir_ / "b" / "summary.json").find("\"status\": \"completed\""), std::string::npos);
}

TEST_F(Cli, AJointZoneIsCountedInTheLogAndOneHoldingNoJointIsWarnedOf) {
  // The good beam (40 x 4 x 4 hexes of 25 mm) made fracturable, with a stronger joint material
  // in a zone box. Over the first two layers of hexes (32 elements) the box holds 64 faces
  // between its own elements: 16 across the layers and 24 in each layer. Around one hex it
  // holds none, and a zone that changes nothing is warned of, also under -q.
  std::string text = replace(good_, "damping_mode = \"mass\"",
                             "damping_mode = \"mass\"\ntensile_strength = 3.0e6\nfracture_energy_I = 100.0\n"
                             "cohesion = 10.0e6\nfriction_angle = 30.0\nfracture_energy_II = 1000.0\n"
                             "[materials.strong]\ndensity = 2400.0\nE = 30.0e9\nnu = 0.2\n"
                             "tensile_strength = 6.0e6\nfracture_energy_I = 200.0\ncohesion = 20.0e6\n"
                             "friction_angle = 30.0\nfracture_energy_II = 2000.0");
  text = replace(text, "material = \"concrete\"",
                 "material = \"concrete\"\nfracture = \"all\"\nzone_material = \"strong\"\n"
                 "zone_box_min = [0.0, 0.0, 0.0]\nzone_box_max = [0.05, 0.1, 0.1]");
  text = replace(text, "end = 2.0e-3", "end = 2.0e-6");
  const fs::path c = write("zone.toml", text);
  const Result r = run("run " + c.string() + " --out " + (dir_ / "a").string());
  ASSERT_EQ(r.code, 0) << r.out;
  EXPECT_NE(r.out.find("joint zone of body 'beam': 64 joint(s) take the joint parameters of material 'strong'"),
            std::string::npos)
      << r.out;
  EXPECT_EQ(r.out.find("warning"), std::string::npos) << r.out;
  const Result one = run("-q run " + c.string() + " --out " + (dir_ / "b").string() +
                         " --set \"bodies.0.zone_box_max=[0.025, 0.025, 0.025]\"");
  ASSERT_EQ(one.code, 0) << one.out;
  EXPECT_NE(one.out.find("warning: [[bodies]] 'beam': no joint lies inside its zone"), std::string::npos) << one.out;
}

TEST_F(Cli, ProgressLineOnRequest) {
  const Result r =
      run("run " + write("good.toml", good_).string() + " --out " + (dir_ / "out").string() + " --progress");
  ASSERT_EQ(r.code, 0) << r.out;
  // The loop reports every 0.5 s of wall time; a 2 ms case may finish before the first
  // report, so ask for a longer one.
  const Result r2 = run("run " + write("long.toml", good_).string() + " --out " + (dir_ / "out").string() +
                        " --progress --set time.end=0.05");
  ASSERT_EQ(r2.code, 0) << r2.out;
  for (const char* s : {"step ", "t = ", "steps/s", "ETA"})
    EXPECT_NE(r2.out.find(s), std::string::npos) << s << " in " << r2.out;
}

TEST_F(Cli, GeneratedMeshRunsEndToEndAndIsCached) {
  // A coarse sphere-on-plate case from cases/, meshed by its generator on demand.
  const std::string cache = (dir_ / "cache").string();
  const std::string args = "run " + std::string(DSPDEM_SOURCE_DIR) + "/cases/sphere_impact.toml --out " +
                           (dir_ / "out").string() + " --set mesh.sphere_plate.size=0.05 --set time.end=2e-5";
  const Result first = run("env DSPDEM_MESH_CACHE=" + cache + " " + std::string(DSPDEM_BIN) + " " + args);
  ASSERT_EQ(first.code, 0) << first.out;
  EXPECT_NE(first.out.find("generated by 'sphere_plate'"), std::string::npos) << first.out;
  const Result second = run("env DSPDEM_MESH_CACHE=" + cache + " " + std::string(DSPDEM_BIN) + " " + args);
  ASSERT_EQ(second.code, 0) << second.out;
  EXPECT_NE(second.out.find("reused cached"), std::string::npos) << second.out;
  // A changed parameter is a different mesh.
  const Result third = run("env DSPDEM_MESH_CACHE=" + cache + " " + std::string(DSPDEM_BIN) + " " + args +
                           " --set mesh.sphere_plate.size=0.045");
  EXPECT_NE(third.out.find("generated by"), std::string::npos) << third.out;
  EXPECT_NE(slurp(dir_ / "out/summary.json").find("\"status\": \"completed\""), std::string::npos);
}

TEST_F(Cli, MeshCommandWritesMshAndQuality) {
  const Result r =
      run("mesh " + std::string(DSPDEM_SOURCE_DIR) + "/cases/murray_beam.toml --out " + (dir_ / "m").string());
  ASSERT_EQ(r.code, 0) << r.out;
  EXPECT_TRUE(fs::exists(dir_ / "m/murray_beam.msh"));
  const std::string q = slurp(dir_ / "m/quality.json");
  for (const char* k : {"\"beam\": 4080", "\"min_dihedral_deg\"", "\"quality_p01\"", "\"slivers\""})
    EXPECT_NE(q.find(k), std::string::npos) << k << " in " << q;
  const Result bad =
      run("mesh " + std::string(DSPDEM_SOURCE_DIR) +
          "/cases/galvez_beam.toml --set mesh.galvez_beam.notch_depth=0.3 --out " + (dir_ / "m2").string());
  EXPECT_EQ(bad.code, 2);
  EXPECT_NE(bad.out.find("mesh.galvez_beam.notch_depth"), std::string::npos) << bad.out;
  // A case meshed from a .geo: the .msh written is gmsh's mesh of it (it was the script
  // copied under the new name), and a run on it has the .geo's nodes and elements.
  const std::string nb = std::string(DSPDEM_SOURCE_DIR) + "/tests/data/notched_bar.toml";
  ASSERT_EQ(run("-q mesh " + nb + " --out " + (dir_ / "m3").string()).code, 0);
  EXPECT_EQ(slurp(dir_ / "m3/notched_bar.msh").rfind("$MeshFormat", 0), 0u);
  const std::string once = " --set time.end=1e-9 --out ";
  ASSERT_EQ(run("-q run " + nb + once + (dir_ / "geo").string()).code, 0);
  ASSERT_EQ(run("-q run " + nb + " --set 'mesh.file=\"" + (dir_ / "m3/notched_bar.msh").string() + "\"'" + once +
                (dir_ / "msh").string())
                .code,
            0);
  auto counts = [&](const char* d) {
    const std::string s = slurp(dir_ / d / "summary.json");
    return s.substr(s.find("\"nodes\""), 40);
  };
  EXPECT_EQ(counts("geo"), counts("msh"));
  // Meshed into its own folder under its own name, the .msh would replace the case's mesh file
  // (a probe's finding: gmsh wrote it back as 4.1, without its elements outside every group).
  const std::string own = (dir_ / "m3/notched_bar.msh").string(), before = slurp(own);
  const Result over = run("mesh " + nb + " --set 'mesh.file=\"" + own + "\"' --out " + (dir_ / "m3").string());
  EXPECT_EQ(over.code, 2) << over.out;
  EXPECT_NE(over.out.find("the case's own mesh file"), std::string::npos) << over.out;
  EXPECT_EQ(slurp(own), before);
  // A file where the folder should be: named, exit 2 (it was "unexpected failure", exit 4).
  write("afile", "x");
  const Result file = run("mesh " + nb + " --out " + (dir_ / "afile").string());
  EXPECT_EQ(file.code, 2) << file.out;
  EXPECT_NE(file.out.find("a file is there, not a folder"), std::string::npos) << file.out;
  const Result below = run("mesh " + nb + " --out " + (dir_ / "afile" / "sub").string());
  EXPECT_EQ(below.code, 2) << below.out;
  EXPECT_NE(below.out.find("cannot make the folder"), std::string::npos) << below.out;
  // A quality.json that dspdem mesh did not write is not replaced (a probe's finding); one it
  // wrote is (m3's, meshed again).
  fs::create_directories(dir_ / "theirs");
  write("theirs/quality.json", "{\"their\": \"notes\"}\n");
  const Result theirs = run("mesh " + nb + " --out " + (dir_ / "theirs").string());
  EXPECT_EQ(theirs.code, 2) << theirs.out;
  EXPECT_NE(theirs.out.find("is not a quality.json that dspdem mesh wrote"), std::string::npos) << theirs.out;
  EXPECT_EQ(slurp(dir_ / "theirs/quality.json"), "{\"their\": \"notes\"}\n");
  EXPECT_FALSE(fs::exists(dir_ / "theirs/notched_bar.msh"));
  EXPECT_EQ(run("-q mesh " + nb + " --out " + (dir_ / "m3").string()).code, 0);
}

TEST_F(Cli, AMeshSizeGmshCannotMeshIsAnErrorNamingTheKeyNotAnAbort) {
  // gmsh threw ("identical points in triangulation") inside its own OpenMP region, where nothing
  // catches it: the process aborted (134) with "terminate called after throwing an instance of
  // 'std::string'", until a terminate handler named the mesh. Since session 107 the generator
  // refuses such a size before gmsh meshes anything (meshing/generator.hpp, check_tet_count);
  // the handler stays for gmsh's other throws, with no input left that reaches one quickly.
  // stdin from /dev/null: gmsh must not wait there for an answer to its large-mesh question.
  const Result r = run("mesh " + std::string(DSPDEM_SOURCE_DIR) +
                       "/cases/sphere_impact.toml --set mesh.sphere_plate.size=1e-6 --out " + (dir_ / "m").string() +
                       " < /dev/null");
  EXPECT_EQ(r.code, 2) << r.out;
  EXPECT_NE(r.out.find("error: mesh.sphere_plate.size = 1e-06: about"), std::string::npos) << r.out;
  EXPECT_FALSE(fs::exists(dir_ / "m" / "sphere_impact.msh"));
}

namespace {
// Starts `command` (its output into `log`), and once it has said that its run started (its
// signal handlers are in by then) and half a second more, into gmsh, sends it SIGTERM.
// Returns the wait status and the log; `started` says whether it got that far.
struct Stopped {
  bool started = false;
  int status = 0;
  std::string log;
};
Stopped stop_while_meshing(const std::string& command, const fs::path& log) {
  Stopped r;
  const pid_t pid = start_job(fmt::format("exec {} < /dev/null > {} 2>&1", command, log.string()));
  if (pid <= 0) return r;
  for (int k = 0; k < 1200 && !r.started; ++k) {
    r.started = slurp(log).find("dspdem run: case") != std::string::npos;
    if (!r.started) std::this_thread::sleep_for(std::chrono::milliseconds(50));
  }
  std::this_thread::sleep_for(std::chrono::milliseconds(500));
  r.status = stop_job(pid, SIGTERM);
  r.log = slurp(log);
  return r;
}
// A process stopped that way: it exited 5 with the set-up's message.
void expect_stopped_in_setup(const Stopped& r) {
  ASSERT_TRUE(r.started) << r.log;
  ASSERT_TRUE(WIFEXITED(r.status)) << "wait status " << r.status << ": " << r.log;
  EXPECT_EQ(WEXITSTATUS(r.status), 5) << r.log;
  EXPECT_NE(r.log.find("stopped by a signal during the set-up"), std::string::npos) << r.log;
}
}  // namespace

TEST_F(Cli, ASignalWhileMeshingEndsTheRunAtOnce) {
  // gmsh cannot be asked to stop, and there is nothing to keep yet: a SIGTERM during the
  // set-up ends the run there (exit 5), instead of after minutes of meshing and one step.
  // A sphere of about 1.5 million tetrahedra: minutes of meshing.
  const fs::path out = dir_ / "out";
  const Stopped run = stop_while_meshing(
      fmt::format("env DSPDEM_MESH_CACHE={} {} -t 1 run {}/cases/sphere_impact.toml --set mesh.sphere_plate.size=0.002 "
                  "--out {}",
                  (dir_ / "cache").string(), DSPDEM_BIN, DSPDEM_SOURCE_DIR, out.string()),
      dir_ / "meshing.log");
  expect_stopped_in_setup(run);
  if (HasFatalFailure()) return;
  EXPECT_EQ(run.log.find("interrupted at step"), std::string::npos) << run.log;
  EXPECT_FALSE(fs::exists(out / "interrupted_run")) << run.log;
  EXPECT_EQ(run.log.find("--resume"), std::string::npos) << "a lone run has nothing to resume: " << run.log;

  // A report that runs its case in its own process (the disc) says how to keep what it had
  // finished before the run it was setting up.
  const Stopped report = stop_while_meshing(
      fmt::format("env DSPDEM_MESH_CACHE={} {} -t 1 report {}/cases/brazilian_disc.toml --no-render "
                  "--set mesh.brazilian_disc.size=0.001 --out {}",
                  (dir_ / "cache").string(), DSPDEM_BIN, DSPDEM_SOURCE_DIR, (dir_ / "report").string()),
      dir_ / "report_meshing.log");
  expect_stopped_in_setup(report);
  if (HasFatalFailure()) return;
  EXPECT_NE(report.log.find("the same report with --resume"), std::string::npos) << report.log;
}

TEST_F(Cli, ANewRunDoesNotSilentlyReplaceAnInterruptedOne) {
  // The same command given again instead of --restart: a finished run would supersede the
  // interrupted one, checkpoint and all. Refused unless asked for, and the checkpoint kept.
  const fs::path c = write("good.toml", good_), out = dir_ / "out", kept = out / "interrupted_run" / "checkpoint.bin";
  fs::create_directories(kept.parent_path());
  std::ofstream(kept) << "a checkpoint";
  const Result refused = run("run " + c.string() + " --out " + out.string());
  EXPECT_EQ(refused.code, 2) << refused.out;
  EXPECT_NE(refused.out.find("--restart " + out.string()), std::string::npos) << refused.out;
  EXPECT_NE(refused.out.find("--discard-interrupted"), std::string::npos) << refused.out;
  EXPECT_EQ(slurp(kept), "a checkpoint");
  EXPECT_FALSE(fs::exists(out / "summary.json"));
  // An estimate writes nothing, so it is not refused there, and leaves the folder as it was.
  const Result estimate = run("-q run " + c.string() + " --estimate --out " + out.string());
  EXPECT_EQ(estimate.code, 0) << estimate.out;
  EXPECT_EQ(slurp(kept), "a checkpoint");
  EXPECT_EQ(std::distance(fs::directory_iterator(out), fs::directory_iterator()), 1);
  const Result fresh = run("-q run " + c.string() + " --discard-interrupted --out " + out.string());
  ASSERT_EQ(fresh.code, 0) << fresh.out;
  EXPECT_FALSE(fs::exists(out / "interrupted_run"));
  EXPECT_TRUE(fs::exists(out / "summary.json"));
  // A run killed outright leaves its last checkpoint by wall time in its staging folder (no
  // lock held, its pid gone): the same.
  const fs::path killed = out / ".staging-999999999" / "checkpoint.bin";
  fs::create_directories(killed.parent_path());
  std::ofstream(killed) << "a checkpoint by wall time";
  const Result again = run("run " + c.string() + " --out " + out.string());
  EXPECT_EQ(again.code, 2) << again.out;
  EXPECT_NE(again.out.find(killed.string()), std::string::npos) << again.out;
  EXPECT_TRUE(fs::exists(killed));
  // Nor a run made inside a side folder that holds a checkpoint (a probe's): the checkpoint's
  // outputs went, and a restart given such an --out ended "completed" in a folder its own end
  // removed. Refused by the folder's name, anywhere on the path, the checkpoint kept.
  for (const fs::path& inside : {killed.parent_path(), killed.parent_path() / "frames", out / "failed_run"}) {
    const Result in = run("run " + c.string() + " --discard-interrupted --out " + inside.string());
    EXPECT_EQ(in.code, 2) << in.out;
    EXPECT_NE(in.out.find("lies in"), std::string::npos) << in.out;
    EXPECT_NE(in.out.find("give --out the run's own folder (" + out.string() + ")"), std::string::npos) << in.out;
  }
  EXPECT_EQ(slurp(killed), "a checkpoint by wall time");
  EXPECT_FALSE(fs::exists(killed.parent_path() / "frames"));
}

TEST_F(Cli, ARunThatReplacesAnotherTakesItsImagesAway) {
  // Images are drawn from a run's frames: those of the run replaced are stale beside the new
  // results. A failed run replaces nothing, and keeps them.
  const fs::path c = write("good.toml", good_), out = dir_ / "out", old = out / "images" / "stress" / "frame_0040.png";
  ASSERT_EQ(run("-q run " + c.string() + " --out " + out.string()).code, 0);
  fs::create_directories(old.parent_path());
  std::ofstream(old) << "drawn from the run before";
  EXPECT_EQ(run("-q run " + c.string() + " --out " + out.string() + " --set time.dt=1.0").code, 2);
  EXPECT_TRUE(fs::exists(old));
  // A run made inside them by hand would go with them: they are kept, and the run says why.
  const fs::path inner = out / "images" / "x";
  ASSERT_EQ(run("-q run " + c.string() + " --out " + inner.string()).code, 0);
  const Result kept = run("run " + c.string() + " --out " + out.string());
  ASSERT_EQ(kept.code, 0) << kept.out;
  EXPECT_NE(kept.out.find("the images of the run this one replaced were kept, since " + inner.string()),
            std::string::npos)
      << kept.out;
  EXPECT_TRUE(fs::exists(inner / "summary.json"));
  fs::remove_all(inner);
  ASSERT_EQ(run("-q run " + c.string() + " --out " + out.string()).code, 0);
  EXPECT_FALSE(fs::exists(out / "images"));
  EXPECT_TRUE(fs::exists(out / "summary.json"));
  // A first run into a folder replaces no run: an images/ there is not its to remove.
  const fs::path other = dir_ / "other" / "images" / "photo.png";
  fs::create_directories(other.parent_path());
  std::ofstream(other) << "someone's";
  ASSERT_EQ(run("-q run " + c.string() + " --out " + (dir_ / "other").string()).code, 0);
  EXPECT_TRUE(fs::exists(other));
}

TEST_F(Cli, NotchedBarBreaksAtTheNotchIntoTwoPieces) {
  // tests/data/notched_bar.toml: a double-edge-notched bar pulled slowly; joints in the band
  // around the notch. It must end in two main fragments of about half the mass each (the
  // crack through the notch ligament; a few single elements may come loose along it), with
  // the energy balance closed to 1e-3 of the largest term.
  const fs::path out = dir_ / "nb";
  const Result r =
      run("-q run " + std::string(DSPDEM_SOURCE_DIR) + "/tests/data/notched_bar.toml --out " + out.string());
  ASSERT_EQ(r.code, 0) << r.out;
  const std::string s = slurp(out / "summary.json");
  const dspdem::RunSummary sum = dspdem::read_run_summary((out / "summary.json").string());
  const std::vector<double>& masses = sum.largest_fragment_masses;
  double total = 0;
  for (double v : masses) total += v;
  ASSERT_GE(masses.size(), 2u);
  const double big = 0.01 * total;
  EXPECT_EQ(std::count_if(masses.begin(), masses.end(), [big](double v) { return v > big; }), 2) << s;
  EXPECT_NEAR(masses[0] / (masses[0] + masses[1]), 0.5, 0.1) << s;
  EXPECT_LT(sum.energy.balance_error, 1e-3) << s;
  EXPECT_TRUE(fs::exists(out / "joints.pvd"));
  EXPECT_NE(slurp(out / "series.csv").find("broken_joints,crack_area"), std::string::npos);
  {
    // The joints' file has the mid-surface's displacement, by which a magnified drawing moves
    // the cracks with the bodies: a joint's point less it is where its two nodes started, a
    // point of the frame less the frame's displacement (both nodes of a joint start there).
    auto read = [](const fs::path& f) {
      vtkNew<vtkXMLUnstructuredGridReader> rd;
      rd->SetFileName(f.c_str());
      rd->Update();
      vtkSmartPointer<vtkUnstructuredGrid> g = rd->GetOutput();
      return g;
    };
    const auto frame = read(out / "frames/frame_0010.vtu"), joints = read(out / "frames/joints_0010.vtu");
    vtkDataArray *uf = frame->GetPointData()->GetArray("displacement"),
                 *uj = joints->GetPointData()->GetArray("displacement");
    ASSERT_NE(uf, nullptr);
    ASSERT_NE(uj, nullptr);
    // Start positions rounded to 1e-9 m (the bar's nodes are 1e-3 m apart and more).
    auto start = [](vtkUnstructuredGrid* g, vtkDataArray* u, vtkIdType i) {
      double p[3], d[3];
      g->GetPoint(i, p);
      u->GetTuple(i, d);
      return std::array<long, 3>{std::lround(1e9 * (p[0] - d[0])), std::lround(1e9 * (p[1] - d[1])),
                                 std::lround(1e9 * (p[2] - d[2]))};
    };
    std::set<std::array<long, 3>> starts;
    for (vtkIdType i = 0; i < frame->GetNumberOfPoints(); ++i) starts.insert(start(frame, uf, i));
    double largest = 0;
    int off = 0;
    for (vtkIdType i = 0; i < joints->GetNumberOfPoints(); ++i) {
      off += starts.count(start(joints, uj, i)) == 0;
      double d[3];
      uj->GetTuple(i, d);
      largest = std::max(largest, std::hypot(d[0], d[1], d[2]));
    }
    EXPECT_GT(joints->GetNumberOfPoints(), 0);
    EXPECT_EQ(off, 0) << "joint points whose start is no node's";
    EXPECT_GT(largest, 1e-6) << "the bar is pulled apart: its joints have moved";
  }
  // The cracks view draws the broken joints from the joints dataset.
  const Result rr = run("-q render " + out.string() +
                        " --view cracks --view fragments --frames last --size 320x240 "
                        "--no-animation");
  EXPECT_EQ(rr.code, 0) << rr.out;
  EXPECT_TRUE(fs::exists(out / "images/cracks/frame_0010.png"));
  // With --out the images go there and the run's folder is only read, also by the second
  // process's share of the frames (-j 2 over frames 0, 5 and 10).
  const fs::path drawn = dir_ / "drawn";
  const Result ro = run("-q render " + out.string() + " --out " + drawn.string() +
                        " --view cracks --frames every:5 --size 160x120 --no-animation -j 2");
  EXPECT_EQ(ro.code, 0) << ro.out;
  for (const char* f : {"frame_0000.png", "frame_0005.png", "frame_0010.png"}) {
    EXPECT_TRUE(fs::exists(drawn / "images/cracks" / f)) << f;
    EXPECT_EQ(fs::exists(out / "images/cracks" / f), std::string(f) == "frame_0010.png") << f;
  }
  EXPECT_TRUE(fs::exists(drawn / "images/plots/energy.png"));
  // Another run drawn into the same folder: what was drawn from the first goes, so that frames
  // not drawn again do not sit beside the second's as its own (a copy is another run).
  fs::copy(out, dir_ / "nb2", fs::copy_options::recursive);
  fs::remove_all(dir_ / "nb2" / "images");
  const Result r2 = run("-q render " + (dir_ / "nb2").string() + " --out " + drawn.string() +
                        " --view cracks --frames last --size 160x120 --no-animation");
  EXPECT_EQ(r2.code, 0) << r2.out;
  EXPECT_TRUE(fs::exists(drawn / "images/cracks/frame_0010.png"));
  EXPECT_FALSE(fs::exists(drawn / "images/cracks/frame_0000.png"));
  EXPECT_NE(slurp(drawn / "derived_from").find("nb2"), std::string::npos);
  // A folder of files no render or report derived from a run is refused and left as it is.
  fs::create_directories(dir_ / "mine");
  std::ofstream(dir_ / "mine" / "notes.txt") << "mine";
  const Result r3 = run("-q render " + out.string() + " --out " + (dir_ / "mine").string() + " --frames last");
  EXPECT_NE(r3.code, 0);
  EXPECT_NE(r3.out.find("no report or render derived from a run"), std::string::npos) << r3.out;
  EXPECT_EQ(slurp(dir_ / "mine" / "notes.txt"), "mine");
  EXPECT_FALSE(fs::exists(dir_ / "mine" / "images"));
  // A render lets go of its lock as it ends, in the run's own folder and in --out.
  EXPECT_FALSE(fs::exists(out / ".render.lock"));
  EXPECT_FALSE(fs::exists(drawn / ".render.lock"));
  {
    // One render at a time into a folder: a second is refused while the first draws, and draws
    // nothing there.
    const dspdem::FolderLock held(drawn.string(), ".render.lock", "the test");
    const Result busy = run("-q render " + out.string() + " --out " + drawn.string() + " --frames last");
    EXPECT_EQ(busy.code, 2) << busy.out;
    EXPECT_NE(busy.out.find("another render (or a run or a report emptying it) is writing into this folder now"),
              std::string::npos)
        << busy.out;
    EXPECT_NE(slurp(drawn / "derived_from").find("nb2"), std::string::npos);
  }
  // A place inside another run's images/ (a run made there again removes them), or inside a
  // place drawn from another run (a render of a third run there would empty it), is refused, and
  // not made; one inside the run drawn is not.
  const Result in_run =
      run("-q render " + out.string() + " --out " + (dir_ / "nb2" / "images" / "x" / "pics").string() +
          " --view cracks --frames last --size 160x120 --no-animation");
  EXPECT_EQ(in_run.code, 2) << in_run.out;
  EXPECT_NE(in_run.out.find("which a run made there again removes"), std::string::npos) << in_run.out;
  EXPECT_FALSE(fs::exists(dir_ / "nb2" / "images"));  // nor what is above it
  const Result in_drawn = run("-q render " + out.string() + " --out " + (drawn / "pics").string() +
                              " --view cracks --frames last --size 160x120 --no-animation");
  EXPECT_EQ(in_drawn.code, 2) << in_drawn.out;
  EXPECT_NE(in_drawn.out.find("which a render or a report filled from the run in"), std::string::npos) << in_drawn.out;
  EXPECT_FALSE(fs::exists(drawn / "pics"));
  const Result own = run("-q render " + out.string() + " --out " + (out / "pics").string() +
                         " --view cracks --frames last --size 160x120 --no-animation");
  EXPECT_EQ(own.code, 0) << own.out;
  EXPECT_TRUE(fs::exists(out / "pics" / "images/cracks/frame_0010.png"));
  {
    // A render that fails after starting its workers stops them and waits for them before it
    // lets go of its lock: once it has returned none draws on. With -j 2 the first process draws
    // frames 0, 2, 4, ..., so a truncated frame 2 fails it and not its worker. This test takes in
    // the render's orphans (a subreaper), so a worker it did not wait for, alive or ended, is
    // this test's child after it returns, found without a race.
    const fs::path broken = dir_ / "nb3";
    fs::copy(out, broken, fs::copy_options::recursive);
    for (const char* drawn_there : {"images", "pics"}) fs::remove_all(broken / drawn_there);
    fs::resize_file(broken / "frames" / "frame_0002.vtu", 200);
    ASSERT_EQ(prctl(PR_SET_CHILD_SUBREAPER, 1), 0);
    const Result failed = run("-q render " + broken.string() + " --view fragments --size 160x120 --no-animation -j 2");
    int st = 0;
    const pid_t orphan = waitpid(-1, &st, WNOHANG);
    const int why = errno;
    prctl(PR_SET_CHILD_SUBREAPER, 0);
    EXPECT_EQ(orphan, -1) << "a worker the render did not wait for";
    EXPECT_EQ(why, ECHILD);
    EXPECT_EQ(failed.code, 2) << failed.out;
    EXPECT_NE(failed.out.find("frame_0002.vtu' is truncated or unreadable"), std::string::npos) << failed.out;
    EXPECT_FALSE(fs::exists(broken / ".render.lock"));
  }
  {
    // Not while a render draws there: it would read the frames this run replaces.
    const dspdem::FolderLock held(drawn.string(), ".render.lock", "the test");
    const Result busy =
        run("-q run " + std::string(DSPDEM_SOURCE_DIR) + "/tests/data/bar_tension.toml --out " + drawn.string());
    EXPECT_EQ(busy.code, 2) << busy.out;
    EXPECT_NE(busy.out.find("a render is drawing into this folder now"), std::string::npos) << busy.out;
    EXPECT_TRUE(fs::exists(drawn / "derived_from"));
    EXPECT_FALSE(fs::exists(drawn / "summary.json"));
  }
  // A run made into the drawn folder empties it first: nothing drawn from nb2 stays beside it.
  const Result r4 =
      run("-q run " + std::string(DSPDEM_SOURCE_DIR) + "/tests/data/bar_tension.toml --out " + drawn.string());
  EXPECT_EQ(r4.code, 0) << r4.out;
  EXPECT_TRUE(fs::exists(drawn / "summary.json"));
  EXPECT_FALSE(fs::exists(drawn / "derived_from"));
  EXPECT_FALSE(fs::exists(drawn / "images"));
  const Result both = run("-q render " + out.string() + " " + out.string() + " --montage " + (dir_ / "m.png").string() +
                          " --out " + drawn.string());
  EXPECT_NE(both.code, 0);
  EXPECT_NE(both.out.find("render: --out and --montage"), std::string::npos) << both.out;
}

// `dspdem render --montage`: the runs side by side, a column per run and a row per --rows
// entry, each panel --size; a name that does not end in .png gets it (a dot in the name is
// kept), another image type's extension, a folder and a label count that does not match the
// runs are refused before anything is drawn.
TEST_F(Cli, RenderMontageTilesRunsByRowsAndWritesAPng) {
  const fs::path out = dir_ / "run";
  ASSERT_EQ(run("-q run " + write("good.toml", good_).string() + " --out " + out.string()).code, 0);
  // The width and height of a PNG, as VTK reads it (0 x 0: no readable PNG there).
  auto png_size = [](const fs::path& p) {
    vtkNew<vtkPNGReader> rd;
    if (!fs::exists(p) || !rd->CanReadFile(p.c_str())) return std::pair(0, 0);
    rd->SetFileName(p.c_str());
    rd->Update();
    int d[3];
    rd->GetOutput()->GetDimensions(d);
    return std::pair(d[0], d[1]);
  };
  const std::string runs = out.string() + " " + out.string();
  const Result r = run("-q render " + runs + " --montage " + (dir_ / "m_v7.5").string() +
                       " --rows stress,fragments:z,fragments --label first second --size 160x120");
  ASSERT_EQ(r.code, 0) << r.out;
  EXPECT_FALSE(fs::exists(dir_ / "m_v7.5"));
  EXPECT_EQ(png_size(dir_ / "m_v7.5.png"), std::pair(2 * 160, 3 * 120));  // two runs, three rows

  const Result jpg = run("-q render " + runs + " --montage " + (dir_ / "m.jpg").string() + " --size 160x120");
  EXPECT_NE(jpg.code, 0);
  EXPECT_NE(jpg.out.find("m.jpg: a montage is a PNG image"), std::string::npos) << jpg.out;
  EXPECT_FALSE(fs::exists(dir_ / "m.jpg"));
  const Result folder = run("-q render " + runs + " --montage " + (dir_ / "sub/").string() + " --size 160x120");
  EXPECT_NE(folder.code, 0);
  EXPECT_NE(folder.out.find("names a folder, not an image file"), std::string::npos) << folder.out;
  const Result labels = run("-q render " + runs + " --montage " + (dir_ / "l.png").string() + " --label one");
  EXPECT_NE(labels.code, 0);
  EXPECT_NE(labels.out.find("1 label(s) for 2 run folder(s)"), std::string::npos) << labels.out;
  EXPECT_FALSE(fs::exists(dir_ / "l.png"));
  // A time far past the run's end is its last frame (a probe's: every distance rounded to the
  // same, and the first frame, t = 0, won the tie).
  const Result late =
      run("render " + out.string() + " --montage " + (dir_ / "late.png").string() + " --time 1e15 --size 160x120");
  ASSERT_EQ(late.code, 0) << late.out;
  EXPECT_NE(late.out.find("its panel shows t = 0.002001 s"), std::string::npos) << late.out;
}

TEST_F(Cli, RunEndsOnceTheLoadHasDroppedAndThePiecesSeparated) {
  // [time] stop_series: the notched bar's reaction peaks near 0.38 ms and falls below 0.3 of
  // its peak at 0.5 ms while the crack runs; 0.2 ms later the two halves are apart. The run
  // must end there (not at 1 ms), say why, and leave a finished run with its last frame.
  const fs::path out = dir_ / "nb_stop";
  const Result r = run("-q run " + std::string(DSPDEM_SOURCE_DIR) + "/tests/data/notched_bar.toml --out " +
                       out.string() + " --set time.stop_series=force --set time.stop_delay=2e-4");
  ASSERT_EQ(r.code, 0) << r.out;
  const dspdem::RunSummary s = dspdem::read_run_summary((out / "summary.json").string());
  EXPECT_EQ(s.status, "completed");
  std::smatch m;
  ASSERT_TRUE(std::regex_search(
      s.message, m,
      std::regex("fell below 0.3 of its peak [0-9.]+ at t = ([0-9.e-]+) s; stopped at t = ([0-9.e-]+) s")))
      << s.message;
  const double t_drop = std::stod(m[1].str()), t_stop = std::stod(m[2].str());
  EXPECT_GT(t_drop, 3e-4);
  EXPECT_NEAR(t_stop - t_drop, 2e-4, 2e-5);  // within two series rows (1e-5 s each)
  EXPECT_LT(s.t_end, 0.9e-3);
  ASSERT_GE(s.largest_fragment_masses.size(), 2u);
  const double m0 = s.largest_fragment_masses[0], m1 = s.largest_fragment_masses[1];
  EXPECT_NEAR(m0 / (m0 + m1), 0.5, 0.1);
  EXPECT_LT(s.frames, 11);  // the full run writes 11
  EXPECT_TRUE(fs::exists(out / fmt::format("frames/frame_{:04d}.vtu", s.frames - 1)));
  EXPECT_NE(slurp(out / "run.pvd").find(fmt::format("frame_{:04d}.vtu", s.frames - 1)), std::string::npos);
}

TEST_F(Cli, RunEndsOnceTheLoadHasReachedAGivenValue) {
  // [time] stop_reach: a run wanted only up to a load (the Brazilian disc's stress check)
  // ends at the first series row whose |stop_series| has reached the value, says so, and
  // leaves a finished run with its last frame there. The notched bar's reaction peaks at
  // 3.24 kN at 0.39 ms (no joint broken before 0.4 ms); half of it comes at about 0.2 ms.
  const fs::path out = dir_ / "nb_reach";
  constexpr double reach = 1600;  // N
  const Result r = run("-q run " + std::string(DSPDEM_SOURCE_DIR) + "/tests/data/notched_bar.toml --out " +
                       out.string() + fmt::format(" --set time.stop_series=force --set time.stop_reach={}", reach));
  ASSERT_EQ(r.code, 0) << r.out;
  const dspdem::RunSummary s = dspdem::read_run_summary((out / "summary.json").string());
  EXPECT_EQ(s.status, "completed");
  std::smatch m;
  ASSERT_TRUE(std::regex_search(s.message, m,
                                std::regex("reached [0-9.e+]+ \\(([-0-9.e+]+)\\) at t = ([0-9.e-]+) s; stopped at t = "
                                           "([0-9.e-]+) s")))
      << s.message;
  EXPECT_GE(std::abs(std::stod(m[1].str())), reach);
  EXPECT_EQ(m[2].str(), m[3].str());  // no stop_delay: it stops at that row
  const dspdem::report::Series series((out / "series.csv").string());
  const auto& f = series["force"];
  ASSERT_GE(f.size(), 3u);
  EXPECT_GE(std::abs(f.back()), reach);
  for (std::size_t i = 0; i + 1 < f.size(); ++i) EXPECT_LT(std::abs(f[i]), reach) << "row " << i;
  EXPECT_LT(s.t_end, 0.3e-3);
  EXPECT_EQ(s.broken_joints, 0);
  EXPECT_TRUE(fs::exists(out / fmt::format("frames/frame_{:04d}.vtu", s.frames - 1)));
}

TEST_F(Cli, HelpListsSubcommands) {
  const Result r = run("--help");
  EXPECT_EQ(r.code, 0);
  EXPECT_NE(r.out.find("run"), std::string::npos);
  EXPECT_NE(r.out.find("keys"), std::string::npos);
}

// Command-line errors exit 1 (README) and say what was wrong in the words of the tool.
TEST_F(Cli, AMisspeltCommandOrAMissingCaseIsACommandLineError) {
  const Result bogus = run("-q rnu case.toml");
  EXPECT_EQ(bogus.code, 1) << bogus.out;
  EXPECT_NE(bogus.out.find("unknown command 'rnu'"), std::string::npos) << bogus.out;
  EXPECT_NE(bogus.out.find("run, "), std::string::npos) << "lists the commands: " << bogus.out;
  const Result none = run("run");
  EXPECT_EQ(none.code, 1) << none.out;
  EXPECT_NE(none.out.find("give a case file, or --restart RUN_DIR"), std::string::npos) << none.out;
  const Result no_command = run("-q");
  EXPECT_EQ(no_command.code, 1) << no_command.out;
}

TEST(Docs, CasesReadmeHoldsTheSchemaTable) {
  // cases/README.md must carry `dspdem keys` verbatim, so the documentation cannot drift.
  const Result r = run("keys");
  ASSERT_EQ(r.code, 0);
  const std::string doc = slurp(fs::path(DSPDEM_SOURCE_DIR) / "cases/README.md");
  EXPECT_NE(doc.find(r.out), std::string::npos) << "regenerate the table with: build/dspdem keys";
}

TEST_F(Cli, ReportRefusesACaseWithoutASceneAndListsTheScenes) {
  // A case that is no benchmark scene (no [case] scene, a mesh file without a scene of its
  // own), or names an unknown scene, is bad input (exit 2) and the message lists the scenes.
  const fs::path c = write("cantilever.toml", good_);
  Result r = run("report " + c.string() + " --out " + (dir_ / "rep").string());
  EXPECT_EQ(r.code, 2) << r.out;
  EXPECT_NE(r.out.find("[case] scene"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("known: packing, brazilian_disc, galvez_beam, murray_beam, sphere_impact"), std::string::npos)
      << r.out;  // the paper's order, 2.1 to 2.5
  r = run("report " + c.string() + " --out " + (dir_ / "rep").string() + " --set case.scene=galvez");
  EXPECT_EQ(r.code, 2) << r.out;
  EXPECT_NE(r.out.find("scene = \"galvez\" is not a scene"), std::string::npos) << r.out;
  EXPECT_FALSE(fs::exists(dir_ / "rep" / "report.md"));
  // A run refuses the unknown scene too, before it runs: it would surface only at the report.
  r = run("run " + c.string() + " --out " + (dir_ / "run").string() + " --set case.scene=galvez");
  EXPECT_EQ(r.code, 2) << r.out;
  EXPECT_NE(r.out.find("scene = \"galvez\" is not a scene"), std::string::npos) << r.out;
  EXPECT_FALSE(fs::exists(dir_ / "run" / "summary.json"));
  r = run("scenes");
  EXPECT_EQ(r.code, 0);
  EXPECT_NE(r.out.find("brazilian_disc"), std::string::npos) << r.out;
}

TEST_F(Cli, SpeedListsAndOutputFoldersAreReadWhole) {
  // CLI11's delimiter dropped an empty entry: "5,,7" ran two speeds. And an empty --out meant
  // the default folder, not the one the user meant to name.
  const std::string sphere = (fs::path(DSPDEM_SOURCE_DIR) / "cases/sphere_impact.toml").string();
  const std::string out = " --out " + (dir_ / "rep").string();
  for (const std::string& bad :
       {std::string("--speeds 5,,7"), std::string("--speeds 5,"), std::string("--speeds 0"),
        std::string("--speeds nan"), std::string("--speeds 5x"), std::string("--study-speeds 7.5,,20")}) {
    const Result r = run("report " + sphere + out + " --no-render " + bad);
    EXPECT_EQ(r.code, 2) << bad << ": " << r.out;
    EXPECT_NE(r.out.find("is not a speed"), std::string::npos) << bad << ": " << r.out;
    EXPECT_FALSE(fs::exists(dir_ / "rep")) << bad;
  }
  const fs::path c = write("cantilever.toml", good_);
  for (const std::string& cmd : {"run " + c.string(), "mesh " + c.string(), "report " + sphere})
    for (const char* opt : {" --out ''", " -o ''"}) {
      const Result r = run(cmd + opt);
      EXPECT_EQ(r.code, 1) << cmd << opt << ": " << r.out;  // a command-line error, as CLI11's own
      EXPECT_NE(r.out.find("must name a path"), std::string::npos) << r.out;
    }
}

TEST_F(Cli, WallsNeedContactAndNameTheirKey) {
  // A wall without [contact] enabled is refused; a box without extents names half_size.
  const fs::path a = write("a.toml", good_ + "\n[[walls]]\nname = \"floor\"\ntype = \"plane\"\n");
  Result r = run("run " + a.string() + " --out " + (dir_ / "a").string());
  EXPECT_EQ(r.code, 2) << r.out;
  EXPECT_NE(r.out.find("[contact] enabled = false"), std::string::npos) << r.out;
  const fs::path b =
      write("b.toml", good_ + "\n[contact]\nenabled = true\n\n[[walls]]\nname = \"b\"\ntype = \"box\"\n");
  r = run("run " + b.string() + " --out " + (dir_ / "b").string());
  EXPECT_EQ(r.code, 2) << r.out;
  EXPECT_NE(r.out.find("half_size"), std::string::npos) << r.out;
}

TEST_F(Cli, FreeCylinderWallStrikesTheBeamAndIsTracedInTheSeries) {
  // A free steel cylinder (radius 16 mm, axis across the beam) dropped at 2 m/s onto the
  // cantilever's top face half a millimetre below it: series.csv carries its force, centre
  // and velocity, and it has bounced off by the end.
  const fs::path a = write("cyl.toml", good_ +
                                           "\n[contact]\nenabled = true\n\n[[walls]]\nname = \"roller\"\n"
                                           "type = \"cylinder\"\npoint = [0.5, 0.1165, 0.05]\naxis = [0.0, 0.0, 1.0]\n"
                                           "radius = 0.016\nlength = 0.12\nfree = true\ndensity = 7800.0\n"
                                           "velocity = [0.0, -2.0, 0.0]\n");
  const Result r = run("-q run " + a.string() + " --out " + (dir_ / "cyl").string());
  ASSERT_EQ(r.code, 0) << r.out;
  std::ifstream f(dir_ / "cyl" / "series.csv");
  std::string head, line, last;
  std::getline(f, head);
  auto cells = [](const std::string& l) {
    std::vector<std::string> c;
    std::stringstream ss(l);
    for (std::string x; std::getline(ss, x, ',');) c.push_back(x);
    return c;
  };
  const auto names = cells(head);
  const auto col = [&](const std::string& n) {
    return static_cast<std::size_t>(std::find(names.begin(), names.end(), n) - names.begin());
  };
  for (const char* n : {"roller_fy", "roller_x", "roller_y", "roller_vy"}) ASSERT_LT(col(n), names.size()) << n;
  // Every column the run writes has the unit its plot's axis names (run/series_units.hpp).
  const dspdem::CaseConfig cc = dspdem::read_case(a.string());
  for (const auto& n : names) EXPECT_NE(dspdem::series_unit(cc, n), "") << n;
  EXPECT_EQ(dspdem::series_unit(cc, "roller_fy"), "N");
  EXPECT_EQ(dspdem::series_unit(cc, "roller_y"), "m");
  EXPECT_EQ(dspdem::series_unit(cc, "roller_vy"), "m/s");
  EXPECT_EQ(dspdem::series_unit(cc, "kinetic"), "J");
  EXPECT_EQ(dspdem::series_axis_title(cc, "tip_uy"), "tip_uy [m]");
  EXPECT_EQ(dspdem::series_axis_title(cc, "clamp_reaction_y"), "clamp_reaction_y [N]");
  EXPECT_EQ(dspdem::series_axis_title(cc, "contacts"), "contacts");
  EXPECT_EQ(dspdem::series_unit(cc, "no_such_column"), "");
  while (std::getline(f, line)) last = line;
  // The impact lasts less than the series interval (0.1 ms), so its force is not sampled
  // here; its effect is: the cylinder has bounced (the beam is far heavier than it).
  EXPECT_GT(std::stod(cells(last)[col("roller_vy")]), 0.0) << "the cylinder did not bounce off the beam";
  EXPECT_GT(std::stod(cells(last)[col("roller_y")]), 0.1165) << "it is below where it started";
  EXPECT_NEAR(std::stod(cells(last)[col("roller_x")]), 0.5, 1e-3);
}

TEST_F(Cli, AMonitorNamedAsASeriesColumnIsRefusedBeforeTheRun) {
  // series.csv's names must be unique: a broken_joints monitor called broken_joints (or a
  // wall's force column) would be read back as the run's own column. Refused at the start,
  // naming the monitor, with nothing written.
  const std::string nb = std::string(DSPDEM_SOURCE_DIR) + "/tests/data/notched_bar.toml";
  const fs::path out = dir_ / "clash";
  const Result r = run("-q run " + nb + " --set 'monitors.2={name=\"broken_joints\", type=\"broken_joints\"}' --out " +
                       out.string());
  EXPECT_NE(r.code, 0);
  EXPECT_NE(r.out.find("name 'broken_joints' is already a column of series.csv"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("notched_bar.toml"), std::string::npos) << r.out;
  EXPECT_FALSE(fs::exists(out / "series.csv"));

  // A sweep's report refuses it too, before it makes its folder: otherwise every one of its
  // runs would start, fail the same way, and leave the report to say so run by run.
  const std::string sphere = std::string(DSPDEM_SOURCE_DIR) + "/cases/sphere_impact.toml";
  const fs::path rep = dir_ / "clash_rep";
  const Result s = run("-q report " + sphere +
                       " --no-render --speeds 2.5,5 --set 'monitors.1={name=\"plate_fy\", type=\"broken_joints\"}' "
                       "--out " +
                       rep.string());
  EXPECT_NE(s.code, 0);
  EXPECT_NE(s.out.find("name 'plate_fy' is already a column of series.csv"), std::string::npos) << s.out;
  EXPECT_FALSE(fs::exists(rep));
}

TEST_F(Cli, ASecondReportIntoAFolderIsRefusedWhileTheFirstWrites) {
  // Two reports into one folder would set each other's files aside and write over each other's
  // runs and report: the second is refused at its start, and changes nothing there.
  const std::string disc = std::string(DSPDEM_SOURCE_DIR) + "/cases/brazilian_disc.toml";
  const fs::path rep = dir_ / "rep";
  fs::create_directories(rep);
  std::ofstream(rep / "report.md") << "earlier";
  {
    const dspdem::FolderLock held(rep.string(), ".report.lock", "the test");
    const Result r = run("report " + disc + " --no-render --out " + rep.string());
    EXPECT_EQ(r.code, 2) << r.out;
    EXPECT_NE(r.out.find("another report is writing into this folder now"), std::string::npos) << r.out;
    EXPECT_NE(r.out.find(rep.string()), std::string::npos) << r.out;
    EXPECT_EQ(slurp(rep / "report.md"), "earlier");
    EXPECT_FALSE(fs::exists(rep / "run"));
  }
  // A report refused once it holds the lock lets go of it, and leaves no folder it made.
  const fs::path fresh = dir_ / "fresh";
  const Result f = run("report " + disc + " --from-run " + (dir_ / "nothing").string() + " --out " + fresh.string());
  EXPECT_EQ(f.code, 2) << f.out;
  EXPECT_NE(f.out.find("summary.json"), std::string::npos) << f.out;
  EXPECT_FALSE(fs::exists(fresh));
  EXPECT_FALSE(fs::exists(rep / ".report.lock"));
  // A folder a render drew into from a run (derived_from) is not a report's: a later render or
  // run into it would empty it, a report with it.
  const fs::path drawn = dir_ / "drawn";
  fs::create_directories(drawn / "images");
  std::ofstream(drawn / "derived_from") << "/somewhere/run";
  const Result d = run("report " + disc + " --no-render --out " + drawn.string());
  EXPECT_EQ(d.code, 2) << d.out;
  EXPECT_NE(d.out.find("holds what a render or a report drew from the run in /somewhere/run"), std::string::npos)
      << d.out;
  EXPECT_FALSE(fs::exists(drawn / "run"));
}

TEST_F(Cli, ReportFromRunNeedsAFinishedRun) {
  // --from-run analyses an existing run; a folder without summary.json is bad input.
  const std::string disc = std::string(DSPDEM_SOURCE_DIR) + "/cases/brazilian_disc.toml";
  const Result r =
      run("report " + disc + " --from-run " + (dir_ / "nothing").string() + " --out " + (dir_ / "rep").string());
  EXPECT_EQ(r.code, 2) << r.out;
  EXPECT_NE(r.out.find("summary.json"), std::string::npos) << r.out;
  // Several folders merge a velocity sweep's runs; the disc analyses one run, and says so
  // instead of taking the first.
  const Result two = run("report " + disc + " --from-run " + (dir_ / "a").string() + " --from-run " +
                         (dir_ / "b").string() + " --out " + (dir_ / "rep").string());
  EXPECT_EQ(two.code, 2) << two.out;
  EXPECT_NE(two.out.find("--from-run given 2 times: scene 'brazilian_disc' analyses one run"), std::string::npos)
      << two.out;
  // A run of another scene: it was analysed as its own scene under the disc's command (a
  // probe's finding: "report galvez_beam.toml --from-run DISC_RUN" wrote the disc's report).
  fs::create_directories(dir_ / "galvez_run");
  fs::copy_file(fs::path(DSPDEM_SOURCE_DIR) / "cases/galvez_beam.toml", dir_ / "galvez_run" / "case.resolved.toml");
  const Result other =
      run("report " + disc + " --from-run " + (dir_ / "galvez_run").string() + " --out " + (dir_ / "rep").string());
  EXPECT_EQ(other.code, 2) << other.out;
  EXPECT_NE(other.out.find("is a run of the scene 'galvez_beam'"), std::string::npos) << other.out;
  EXPECT_FALSE(fs::exists(dir_ / "rep" / "report.md"));
  // A run's folder without its case.resolved.toml: the case given was analysed as the run's
  // (a probe's), its overrides and all. Refused.
  fs::create_directories(dir_ / "no_case");
  std::ofstream(dir_ / "no_case" / "summary.json") << "{}";
  const Result no_case =
      run("report " + disc + " --from-run " + (dir_ / "no_case").string() + " --out " + (dir_ / "rep").string());
  EXPECT_EQ(no_case.code, 2) << no_case.out;
  EXPECT_NE(no_case.out.find("no case.resolved.toml there"), std::string::npos) << no_case.out;
  EXPECT_FALSE(fs::exists(dir_ / "rep" / "report.md"));
}

TEST_F(Cli, ReportStudyRunsEveryVariantAndTabulatesThem) {
  // The sweep's machinery on a 1083-tet disc for 0.2 ms with plates 10x faster (this checks
  // the variants run and are tabulated, not their numbers): the reference row reuses the
  // main run, the elastic row the stress check (run under stress_check/ on a finer mesh),
  // the fifteen others run under study/, and study.csv has one row for each fracture run.
  const Result r = report("brazilian_disc",
                          "--study --set mesh.brazilian_disc.size=0.02 --set materials.rock.joint_penalty=30"
                          " --set time.end=2e-4 --set output.frame_interval=2e-5"
                          " --set walls.0.velocity=[0,-0.2,0] --set walls.1.velocity=[0,0.2,0]");
  ASSERT_EQ(r.code, 0) << r.out;
  const std::string md = slurp(dir_ / "rep" / "report.md");
  for (const char* row : {"| size_32.0mm |", "| size_25.0mm |", "| size_20.0mm | reference |", "| penalty_100 |",
                          "| graded_loads |", "| elastic_fine |", "| gauss_joints |", "| rate_x4 |", "| corotational |",
                          "| band_0.2D |", "| split_plane |", "| paper_law |", "| paper_joints |", "| bearing_inter |",
                          "| bearing_joint_free |", "| flat_plates |", "| extrinsic |"})
    EXPECT_NE(md.find(row), std::string::npos) << row;
  // The case loads through curved jaws: the report says so, not the paper's plates.
  EXPECT_NE(md.find("Peak jaw load P ="), std::string::npos) << md;
  EXPECT_EQ(md.find("Peak plate load"), std::string::npos) << md;
  const auto row = md.find("| elastic_fine |");
  ASSERT_NE(row, std::string::npos);
  EXPECT_NE(md.substr(row, md.find('\n', row) - row).find("| no joints |"), std::string::npos);
  // The extrinsic row's step as its summary gives it. This short run opens no face, so the
  // row has one step; the first-and-last form is Document.AStepThatFellDuringTheRunIsGivenFirstAndLast's.
  const auto ext = md.find("| extrinsic |");
  ASSERT_NE(ext, std::string::npos);
  const std::string ext_row = md.substr(ext, md.find('\n', ext) - ext);
  const dspdem::RunSummary ext_sum =
      dspdem::read_run_summary((dir_ / "rep" / "study" / "extrinsic" / "summary.json").string());
  EXPECT_NE(ext_row.find("| " + dspdem::report::step_text(ext_sum.dt_start, ext_sum.dt, "") + " |"), std::string::npos)
      << ext_row;
  EXPECT_EQ(md.find("Closest to f_t: elastic_fine"), std::string::npos);
  EXPECT_EQ(md.find("splits in two: elastic_fine"), std::string::npos);
  EXPECT_FALSE(fs::exists(dir_ / "rep" / "study" / "size_20.0mm"));  // reused, not run again
  EXPECT_FALSE(fs::exists(dir_ / "rep" / "study" / "elastic_fine"));
  EXPECT_TRUE(fs::exists(dir_ / "rep" / "stress_check" / "profile.csv"));
  EXPECT_NE(md.find("### Stress check on a mesh that resolves the loads"), std::string::npos);
  const std::string check = slurp(dir_ / "rep" / "stress_check" / "summary.json");
  EXPECT_NE(check.find("\"joints\": 0"), std::string::npos) << check;
  EXPECT_TRUE(fs::exists(dir_ / "rep" / "study" / "band_0.2D" / "summary.json"));
  std::ifstream csv(dir_ / "rep" / "study" / "study.csv");
  int lines = 0;
  for (std::string l; std::getline(csv, l);) ++lines;
  EXPECT_EQ(lines, 1 + 16);
  EXPECT_TRUE(fs::exists(dir_ / "rep" / "run" / "images" / "plots" / "study.png"));

  // Again with --resume: every run is the same finished run (the report's, the stress
  // check's and the study's fifteen), kept as it is; the tables are written anew, the same.
  std::map<fs::path, fs::file_time_type> ran;
  for (const auto& e : fs::recursive_directory_iterator(dir_ / "rep"))
    if (e.path().filename() == "summary.json") ran[e.path()] = e.last_write_time();
  EXPECT_EQ(ran.size(), 17u);
  const std::string table = slurp(dir_ / "rep" / "study" / "study.csv");
  const Result again = report("brazilian_disc",
                              "--study --set mesh.brazilian_disc.size=0.02 --set materials.rock.joint_penalty=30"
                              " --set time.end=2e-4 --set output.frame_interval=2e-5"
                              " --set walls.0.velocity=[0,-0.2,0] --set walls.1.velocity=[0,0.2,0] --resume");
  ASSERT_EQ(again.code, 0) << again.out;
  for (const auto& [p, t] : ran) EXPECT_EQ(fs::last_write_time(p), t) << p << " was run again";
  EXPECT_EQ(slurp(dir_ / "rep" / "study" / "study.csv"), table);
}

TEST_F(Cli, ReportStudyOfTheGalvezBeamRunsEveryVariant) {
  // The beam's sweep machinery for 0.1 ms (this checks the variants run and are tabulated,
  // not their numbers): its nine rows, the held line's other loading condition (free) and
  // the extrinsic row among them.
  const Result r = report("galvez_beam", "--study --set time.end=1e-4 --set output.frame_interval=2e-5");
  ASSERT_EQ(r.code, 0) << r.out;
  const std::string md = slurp(dir_ / "rep" / "report.md");
  for (const char* row :
       {"| crack_size_15.0mm | reference |", "| crack_size_10.0mm |", "| crack_size_22.5mm |", "| rate_x0.5 |",
        "| penalty_other |", "| paper_law |", "| joints_everywhere |", "| extrinsic |", "| proportional |"})
    EXPECT_NE(md.find(row), std::string::npos) << row;
  EXPECT_NE(md.find("held in y: the nonproportional loading"), std::string::npos);
  // The free row's case lets the second top line free: a zero force on it, no constraint.
  const std::string free = slurp(dir_ / "rep" / "study" / "proportional" / "case.resolved.toml");
  EXPECT_NE(free.find("group = 'load_outer'\nramp = 0.0\ntype = 'force'"), std::string::npos) << free;
}

TEST_F(Cli, ReportRealisationsRunEachSpeedAgainOnTurnedMeshes) {
  // --realisations 3: each speed on the case's mesh and on two turned ones (orientations 1
  // and 2, each run with its own resolved case), tabulated per speed and in orientations.csv.
  // This checks the machinery on a 330-tet sphere for 0.1 ms after contact, not the numbers.
  const Result r = report("sphere_impact",
                          "--speeds 2.5,7.5 --realisations 3 -j 2 --set mesh.sphere_plate.size=0.04"
                          " --set time.end=1e-4 --set output.frame_interval=2.5e-5");
  ASSERT_EQ(r.code, 0) << r.out;
  const std::string md = slurp(dir_ / "rep" / "report.md");
  EXPECT_NE(md.find("### The pattern over 3 orientations of the mesh"), std::string::npos) << md;
  EXPECT_NE(md.find("| 7.5 | a few large pieces | 3 |"), std::string::npos) << md;
  // Each count with its 95 % interval (Wilson's): with 3 meshes even 0 of 3 reaches 0.56.
  EXPECT_NE(md.find(" of 3 (95 %: "), std::string::npos) << md;
  // Over two speeds, per orientation the first speed with a through crack and with a few
  // large pieces, and their median: the rows in order, each cell one of the speeds run or
  // none by the highest (the machinery, not the numbers).
  const auto onset_rows = [](const std::string& text) {
    std::vector<std::vector<std::string>> rows;
    const auto head = text.find("| orientation | first through crack | first a few large pieces |");
    if (head == std::string::npos) return rows;
    std::istringstream in(text.substr(head));
    std::string line;
    std::getline(in, line), std::getline(in, line);  // the header and its rule
    while (std::getline(in, line) && line.rfind("| ", 0) == 0) {
      std::vector<std::string> cells;
      for (std::size_t a = 2, b; (b = line.find(" |", a)) != std::string::npos; a = b + 3)
        cells.push_back(line.substr(a, b - a));
      rows.push_back(cells);
    }
    return rows;
  };
  const auto rows = onset_rows(md);
  ASSERT_EQ(rows.size(), 5u) << md;
  // The median's interval (report::median_interval) needs six meshes: with three, said so.
  EXPECT_EQ(rows[4], (std::vector<std::string>{"its 95 % interval", "too few meshes", "too few meshes"})) << md;
  for (std::size_t k = 0; k < 4; ++k) {
    ASSERT_EQ(rows[k].size(), 3u) << md;
    EXPECT_EQ(rows[k][0], k < 3 ? std::to_string(k) : "median");
    for (int c : {1, 2})
      EXPECT_TRUE(rows[k][c] == "2.5" || rows[k][c] == "7.5" || rows[k][c] == "none by 7.5") << rows[k][c];
  }
  for (const char* o : {"v2.5_o1", "v2.5_o2", "v7.5_o1", "v7.5_o2"})
    EXPECT_TRUE(fs::exists(dir_ / "rep" / "orientations" / o / "summary.json")) << o;
  // The runs read as an impact test: each event's breakage probability over all six runs
  // (report/breakage_probability.hpp), per speed what was seen, and its plot.
  const auto runs_of_event = [](const std::string& text, const std::string& event) {
    const auto at = text.find("| " + event + " | ");
    if (at == std::string::npos) return std::string("missing");
    const auto from = text.find(" of ", at + event.size() + 4);
    return from == std::string::npos ? std::string("no count") : text.substr(from, text.find(" |", from) - from);
  };
  EXPECT_NE(md.find("### Breakage probability against the impact energy"), std::string::npos) << md;
  EXPECT_NE(md.find("| at 50 % (95 %, runs) | 95 %, meshes resampled |"), std::string::npos) << md;
  EXPECT_EQ(runs_of_event(md, "a crack through (a second piece >= 1 % or the largest < 90 %)"), " of 6") << md;
  EXPECT_EQ(runs_of_event(md, "broken (the largest piece < 90 %)"), " of 6") << md;
  EXPECT_NE(md.find("| speed [m/s] | a crack through | P fitted, a crack through | broken | P fitted, broken |"),
            std::string::npos)
      << md;
  EXPECT_TRUE(fs::exists(dir_ / "rep" / "images" / "breakage_probability.png"));
  EXPECT_NE(slurp(dir_ / "rep" / "orientations" / "v7.5_o2" / "case.resolved.toml").find("orientation = 2"),
            std::string::npos);
  std::ifstream csv(dir_ / "rep" / "orientations.csv");
  std::vector<std::string> lines;
  for (std::string l; std::getline(csv, l);) lines.push_back(l);
  ASSERT_EQ(lines.size(), 1u + 6u);
  EXPECT_EQ(lines[1].rfind("2.5,0,330,", 0), 0u) << lines[1];  // the case's own mesh first
  EXPECT_EQ(lines[6].rfind("7.5,2,", 0), 0u) << lines[6];
  // Each run's largest balance error, last: the turned meshes' ledgers are checked as the
  // sweep's are (these short runs close well under 1 %).
  EXPECT_EQ(lines[0].substr(lines[0].rfind(',') + 1), "balance_max") << lines[0];
  EXPECT_NE(lines[0].find(",crack_top,broken_contact,joints_contact,broken_upper_half,joints_upper_half,"),
            std::string::npos)
      << lines[0];
  for (std::size_t k = 1; k < lines.size(); ++k) {
    const double bal = std::stod(lines[k].substr(lines[k].rfind(',') + 1));
    EXPECT_TRUE(bal >= 0 && bal < 0.01) << lines[k];
  }
  // Per mesh, the paper's pattern at every speed run: the meshes whose rows all have
  // paper_pattern 1, counted in the report and in the headline.
  // And when the large pieces came free (split_timing.hpp): per speed the count over the three
  // meshes, rising to the meshes whose two_large_after_contact_ms is a time.
  std::map<std::string, bool> every;
  std::map<std::string, int> freed;
  for (std::size_t k = 1; k < lines.size(); ++k) {
    const std::vector<std::string> f = csv_fields(lines[k]);
    ASSERT_EQ(f.size(), 18u) << lines[k];
    // The contact band's and the upper half's joints, broken and all: the upper half holds
    // about half the sphere's joints and the 0.1 D band far fewer, and no band breaks more
    // joints than it has. Each run has joints frames, so none reads -1.
    const long bc = std::stol(f[13]), jc = std::stol(f[14]), bu = std::stol(f[15]), ju = std::stol(f[16]);
    EXPECT_TRUE(bc >= 0 && bc <= jc && bu >= 0 && bu <= ju) << lines[k];
    EXPECT_GT(ju, 3 * jc) << lines[k];
    every.try_emplace(f[1], true).first->second &= f[9] == "1";
    freed[f[0]] += std::stod(f[10]) >= 0;
  }
  const auto timing = md.find("| speed [m/s] | meshes | two pieces >= 10 % by the compared frame |");
  ASSERT_NE(timing, std::string::npos) << md;
  {
    // Three meshes give the median no 95 % interval (report::median_interval needs six): each
    // speed's row says so in that column, the second last.
    std::istringstream in(md.substr(timing));
    std::string line;
    std::getline(in, line);
    EXPECT_NE(line.find(" | its 95 % interval [ms] | runs left out"), std::string::npos) << line;
    std::getline(in, line);  // the rule
    int speeds = 0;
    while (std::getline(in, line) && line.rfind("| ", 0) == 0) {
      const auto end = line.rfind(" | ");
      EXPECT_EQ(line.substr(line.rfind(" | ", end - 1) + 3, end - line.rfind(" | ", end - 1) - 3), "too few meshes")
          << line;
      ++speeds;
    }
    EXPECT_GE(speeds, 1) << md;
  }
  std::ifstream freed_csv(dir_ / "rep" / "large_pieces_time.csv");
  std::string freed_line;
  std::getline(freed_csv, freed_line);
  EXPECT_EQ(freed_line, "speed,after_contact_ms,meshes,with_two_large");
  std::map<std::string, int> freed_last;  // each speed's last row: the count at the latest compared frame
  for (std::string l; std::getline(freed_csv, l);) {
    const std::vector<std::string> f = csv_fields(l);
    ASSERT_EQ(f.size(), 4u) << l;
    EXPECT_EQ(f[2], "3") << l;
    freed_last[f[0]] = std::stoi(f[3]);
  }
  EXPECT_EQ(freed_last, freed);
  const auto whole = std::count_if(every.begin(), every.end(), [](const auto& e) { return e.second; });
  const std::string count = fmt::format("{} of 3 (95 %: ", whole);
  EXPECT_NE(
      md.find("The paper's pattern at every speed run that the paper describes (2.5, 7.5 m/s), mesh by mesh: " + count),
      std::string::npos)
      << md;
  const auto headline = nlohmann::json::parse(slurp(dir_ / "rep" / "headline.json"));
  bool in_headline = false;
  for (const auto& row : headline["rows"])
    if (row["quantity"] == "meshes with the paper's pattern at every speed run that the paper describes")
      in_headline =
          row["dspdem"].get<std::string>().rfind(count, 0) == 0 && row["agrees"] == (2 * whole > 3 ? "yes" : "no");
  EXPECT_TRUE(in_headline) << headline.dump(1);
  // --from-run analyses those runs again without running any; it needs every realisation asked for.
  const auto from_run = [&](const std::string& out, int realisations) {
    return report("sphere_impact",
                  fmt::format("--from-run {} --realisations {} --speeds 2.5,7.5 --set mesh.sphere_plate.size=0.04 "
                              "--set time.end=1e-4 --set output.frame_interval=2.5e-5",
                              (dir_ / "rep").string(), realisations),
                  out);
  };
  const Result again = from_run("again", 3);
  ASSERT_EQ(again.code, 0) << again.out;
  EXPECT_EQ(slurp(dir_ / "again" / "orientations.csv"), slurp(dir_ / "rep" / "orientations.csv"));
  // The same folder for a report of the case's mesh alone: the files of the three meshes'
  // report are gone, not left beside a report.md that no longer names them.
  {
    const Result three = from_run("again_one", 3);
    ASSERT_EQ(three.code, 0) << three.out;
    for (const char* f : {"orientations.csv", "large_pieces_time.csv", "images/breakage_probability.png"})
      ASSERT_TRUE(fs::exists(dir_ / "again_one" / f)) << f;
    const Result one_mesh = from_run("again_one", 1);
    ASSERT_EQ(one_mesh.code, 0) << one_mesh.out;
    for (const char* f : {"orientations.csv", "large_pieces_time.csv", "images/breakage_probability.png"})
      EXPECT_FALSE(fs::exists(dir_ / "again_one" / f)) << f;
    EXPECT_TRUE(fs::exists(dir_ / "again_one" / "fragment_masses.csv"));
  }
  const Result more = from_run("again", 4);
  EXPECT_EQ(more.code, 2) << more.out;
  EXPECT_NE(more.out.find("v2.5_o3"), std::string::npos) << more.out;
  EXPECT_TRUE(fs::exists(dir_ / "again" / "orientations.csv"));  // a report refused leaves the earlier one
  // Several earlier reports merge into one: the runs at 2.5 m/s in one folder, those at 7.5
  // in another read as the one report they were, each folder named with its count.
  for (const auto& [part, v] : {std::pair{"part_a", "v2.5"}, std::pair{"part_b", "v7.5"}}) {
    fs::create_directories(dir_ / part / "speeds");
    fs::create_directories(dir_ / part / "orientations");
    fs::copy(dir_ / "rep" / "speeds" / v, dir_ / part / "speeds" / v, fs::copy_options::recursive);
    for (const char* o : {"_o1", "_o2"})
      fs::copy(dir_ / "rep" / "orientations" / (std::string(v) + o),
               dir_ / part / "orientations" / (std::string(v) + o), fs::copy_options::recursive);
  }
  // What a report derives from a run is the report's: the copies are left without it, and a
  // report merging them writes it into its own folder, leaving theirs as they were.
  const std::vector<std::string> derived = {"pieces_time.csv", "sphere_series.csv", "fragment_masses.csv"};
  std::vector<fs::path> to_remove;
  for (const char* part : {"part_a", "part_b"})
    for (const auto& e : fs::recursive_directory_iterator(dir_ / part))
      if (std::find(derived.begin(), derived.end(), e.path().filename().string()) != derived.end())
        to_remove.push_back(e.path());
  for (const auto& p : to_remove) fs::remove(p);
  const auto merged = [&](const std::string& out, const std::vector<fs::path>& parts, const std::string& sets) {
    std::string from;
    for (const auto& p : parts) from += " --from-run " + p.string();
    return report("sphere_impact",
                  "--realisations 3 --speeds 2.5,7.5 --set mesh.sphere_plate.size=0.04 --set time.end=1e-4 "
                  "--set output.frame_interval=2.5e-5" +
                      sets + from,
                  out);
  };
  const Result both = merged("merged", {dir_ / "part_a", dir_ / "part_b"}, "");
  ASSERT_EQ(both.code, 0) << both.out;
  for (const char* part : {"part_a", "part_b"})
    for (const auto& e : fs::recursive_directory_iterator(dir_ / part))
      EXPECT_TRUE(std::find(derived.begin(), derived.end(), e.path().filename().string()) == derived.end())
          << "written into an earlier report's folder: " << e.path();
  for (const char* run : {"speeds/v2.5", "speeds/v7.5", "orientations/v2.5_o1", "orientations/v7.5_o2"})
    for (const auto& f : derived) {
      EXPECT_TRUE(fs::exists(dir_ / "merged" / run / f)) << run << "/" << f;
      EXPECT_EQ(slurp(dir_ / "merged" / run / f), slurp(dir_ / "rep" / run / f)) << run << "/" << f;
    }
  // Nor beside another run: a folder with runs of its own is refused as the merged report's,
  // its runs' files left as they were.
  const std::string rep_pieces = slurp(dir_ / "rep" / "speeds" / "v2.5" / "pieces_time.csv");
  const Result into_runs = merged("rep", {dir_ / "part_a", dir_ / "part_b"}, "");
  EXPECT_EQ(into_runs.code, 2) << into_runs.out;
  EXPECT_NE(into_runs.out.find("holds a run of its own"), std::string::npos) << into_runs.out;
  EXPECT_EQ(slurp(dir_ / "rep" / "speeds" / "v2.5" / "pieces_time.csv"), rep_pieces);
  // Drawn too: the sweep's frames into the merged report's folder, none into the parts'.
  const Result drawn = run("-q report " + std::string(DSPDEM_SOURCE_DIR) + "/cases/sphere_impact.toml --out " +
                           (dir_ / "merged_drawn").string() +
                           " --speeds 2.5,7.5 --set mesh.sphere_plate.size=0.04 --set time.end=1e-4 "
                           "--set output.frame_interval=2.5e-5 --from-run " +
                           (dir_ / "part_a").string() + " --from-run " + (dir_ / "part_b").string());
  ASSERT_EQ(drawn.code, 0) << drawn.out;
  for (const char* v : {"v2.5", "v7.5"}) {
    EXPECT_TRUE(fs::exists(dir_ / "merged_drawn" / "speeds" / v / "images" / "fragments" / "frame_0000.png")) << v;
    EXPECT_FALSE(fs::exists(dir_ / "part_a" / "speeds" / v / "images")) << v;
    EXPECT_FALSE(fs::exists(dir_ / "part_b" / "speeds" / v / "images")) << v;
  }
  EXPECT_NE(slurp(dir_ / "merged_drawn" / "report.md").find("](./speeds/v7.5/images/fragments.ogv)"),
            std::string::npos);
  EXPECT_EQ(slurp(dir_ / "merged" / "orientations.csv"), slurp(dir_ / "rep" / "orientations.csv"));
  const std::string mmd = slurp(dir_ / "merged" / "report.md");
  EXPECT_NE(mmd.find("none run here: `../part_a` (3 runs), `../part_b` (3 runs), made by one build of dspdem ("),
            std::string::npos)
      << mmd;
  // Its text points at the runs where they are, not at a speeds/ of its own that it does not
  // have; a report of its own runs at its own.
  for (const char* at : {"in its own folder under `../part_a/speeds/`, `../part_b/speeds/` with its",
                         "is the sweep's own runs in `../part_a/speeds/`, `../part_b/speeds/`). Folders: "
                         "`../part_a/orientations/`, `../part_b/orientations/`;",
                         "is written here at the run's place (`speeds/`, `orientations/`, `draws/`); the earlier "
                         "reports' folders are only read."})
    EXPECT_NE(mmd.find(at), std::string::npos) << at << "\n" << mmd;
  EXPECT_NE(md.find("in its own folder under `speeds/` with its"), std::string::npos) << md;
  EXPECT_NE(md.find("Folders: `orientations/`;"), std::string::npos) << md;
  // With one speed the paper describes, the headline still counts the meshes with its pattern
  // there, as the table's row does, and says whether that is most.
  const Result one = report("sphere_impact",
                            fmt::format("--from-run {} --realisations 3 --speeds 7.5 --set mesh.sphere_plate.size=0.04 "
                                        "--set time.end=1e-4 --set output.frame_interval=2.5e-5 --no-render",
                                        (dir_ / "rep").string()),
                            "one");
  ASSERT_EQ(one.code, 0) << one.out;
  int at_75 = 0;  // orientations.csv's rows at 7.5 m/s with paper_pattern 1
  for (std::size_t k = 1; k < lines.size(); ++k) {
    const std::vector<std::string> f = csv_fields(lines[k]);
    at_75 += f[0] == "7.5" && f[9] == "1";
  }
  bool one_row = false;
  const auto one_headline = nlohmann::json::parse(slurp(dir_ / "one" / "headline.json"));
  for (const auto& row : one_headline["rows"])
    if (row["quantity"] == "meshes with the paper's pattern at 7.5 m/s")
      one_row = row["dspdem"].get<std::string>().rfind(fmt::format("{} of 3 (95 %: ", at_75), 0) == 0 &&
                row["agrees"] == (2 * at_75 > 3 ? "yes" : "no");
  EXPECT_TRUE(one_row) << at_75 << " of 3 expected:\n" << one_headline.dump(1);
  // One part alone lacks the other speed's runs, and names the first missing.
  const Result half = merged("half", {dir_ / "part_a"}, "");
  EXPECT_EQ(half.code, 2) << half.out;
  EXPECT_NE(half.out.find("none has run speeds/v7.5 (the speeds/, orientations/ and draws/ folders"), std::string::npos)
      << half.out;
  // Runs of the case with other overrides are not this report's runs: refused, the folder
  // and the first line that differs named, rather than mixed in.
  const Result other = merged("other", {dir_ / "part_a", dir_ / "part_b"}, " --set materials.rock.friction=0.7");
  EXPECT_EQ(other.code, 2) << other.out;
  EXPECT_NE(other.out.find("is not a run of this report's case as it resolves now (line "), std::string::npos)
      << other.out;
  EXPECT_NE(other.out.find("friction"), std::string::npos) << other.out;
  // A run an earlier report left failed is a failed row with its reason, not analysed: its
  // summary in failed_run/ inside its folder, as a failed run leaves it (io/staging.hpp).
  {
    const fs::path run = dir_ / "part_b" / "orientations" / "v7.5_o2";
    fs::create_directories(run / "failed_run");
    std::string js = slurp(run / "summary.json");
    const auto at = js.find("\"completed\"");
    ASSERT_NE(at, std::string::npos) << js;
    js.replace(at, 11, "\"failed\"");
    std::ofstream(run / "failed_run" / "summary.json") << js;
    fs::copy_file(run / "case.resolved.toml", run / "failed_run" / "case.resolved.toml");
    fs::remove(run / "summary.json");
  }
  const Result bad = merged("bad", {dir_ / "part_a", dir_ / "part_b"}, "");
  ASSERT_EQ(bad.code, 0) << bad.out;
  const std::string bmd = slurp(dir_ / "bad" / "report.md");
  EXPECT_NE(bmd.find("- 7.5 m/s, orientation 2: the run in "), std::string::npos) << bmd;
  EXPECT_NE(bmd.find("v7.5_o2 failed"), std::string::npos) << bmd;
  // A realisation that ran and was lost (its log is there, its results are not) is a failed
  // row, named by its orientation, and the others keep their own orientation numbers.
  fs::remove(dir_ / "rep" / "orientations" / "v2.5_o1" / "summary.json");
  const Result lost = from_run("again2", 3);
  ASSERT_EQ(lost.code, 0) << lost.out;
  const std::string md2 = slurp(dir_ / "again2" / "report.md");
  EXPECT_NE(md2.find("- 2.5 m/s, orientation 1: no finished run"), std::string::npos) << md2;
  // The mesh with a failed run is left out of the every-speed count, and named.
  const auto every2 = md2.find("m/s), mesh by mesh: ");
  ASSERT_NE(every2, std::string::npos) << md2;
  EXPECT_EQ(md2.find(" of 2 (95 %: ", every2), md2.find(" of ", every2)) << md2;
  EXPECT_NE(md2.find("; not counted, a run failed: orientation 1."), std::string::npos) << md2;
  EXPECT_NE(md2.find("| 2.5 | no through crack | 2 |"), std::string::npos) << md2;
  EXPECT_NE(md2.find("0: 1, 2: 1 |"), std::string::npos) << md2;
  EXPECT_EQ(runs_of_event(md2, "broken (the largest piece < 90 %)"), " of 5") << md2;  // the lost run left out
  // Its first speeds are then upper bounds only, and say so; the others' do not.
  const auto rows2 = onset_rows(md2);
  ASSERT_EQ(rows2.size(), 5u) << md2;  // three meshes, the median and its interval
  for (int c : {1, 2}) {
    EXPECT_NE(rows2[1][c].find("(a run below failed)"), std::string::npos) << rows2[1][c];
    EXPECT_EQ(rows2[0][c].find("failed"), std::string::npos) << rows2[0][c];
  }
  // A scene without a velocity sweep refuses the sweep's options instead of ignoring them.
  const Result disc = report("brazilian_disc", "--realisations 2");
  EXPECT_EQ(disc.code, 2) << disc.out;
  EXPECT_NE(disc.out.find("scene 'brazilian_disc' has none"), std::string::npos) << disc.out;
}

TEST_F(Cli, ReportDrawsRunEachMeshAgainWithTheSpeedNudged) {
  // --draws 3 on two meshes at one speed: each run twice more on its own mesh, the speed
  // raised by 1e-5 m/s per draw, tabulated per mesh with the test whether the meshes differ;
  // on the 330-tet sphere for 0.1 ms after contact (the machinery, not the numbers).
  const std::string sets =
      "--speeds 7.5 --realisations 2 --draws 3 --set mesh.sphere_plate.size=0.04 --set time.end=1e-4 "
      "--set output.frame_interval=2.5e-5";
  const Result r = report("sphere_impact", sets + " -j 2");
  ASSERT_EQ(r.code, 0) << r.out;
  const std::string md = slurp(dir_ / "rep" / "report.md");
  EXPECT_NE(md.find("### Chance on one mesh against the mesh: 3 draws of each run"), std::string::npos) << md;
  for (const char* d : {"v7.5_o0_d1", "v7.5_o0_d2", "v7.5_o1_d1", "v7.5_o1_d2"})
    EXPECT_TRUE(fs::exists(dir_ / "rep" / "draws" / d / "summary.json")) << d;
  // A turned mesh's draw runs on that mesh.
  EXPECT_NE(slurp(dir_ / "rep" / "draws" / "v7.5_o1_d2" / "case.resolved.toml").find("orientation = 1"),
            std::string::npos);
  // draws.csv: every draw, the case's mesh first, draw 0 the run itself; each at its nudged
  // speed and judged at the sweep's.
  std::ifstream csv(dir_ / "rep" / "draws.csv");
  std::vector<std::vector<std::string>> rows;
  std::string head;
  std::getline(csv, head);
  EXPECT_EQ(head.rfind("speed,speed_run,orientation,draw,through_crack,few_large_pieces,paper_pattern,", 0), 0u)
      << head;
  for (std::string l; std::getline(csv, l);) {
    rows.push_back(csv_fields(l));
  }
  ASSERT_EQ(rows.size(), 6u);
  int through = 0;
  for (std::size_t k = 0; k < rows.size(); ++k) {
    ASSERT_EQ(rows[k].size(), 11u);
    EXPECT_EQ(rows[k][0], "7.5");
    EXPECT_EQ(rows[k][2], k < 3 ? "0" : "1");
    EXPECT_EQ(rows[k][3], std::to_string(k % 3));
    EXPECT_NEAR(std::stod(rows[k][1]), 7.5 + 1e-5 * (k % 3), 1e-12) << rows[k][1];
    through += rows[k][4] == "1";
  }
  // Draw 0 is the sweep's and the turned mesh's own run: as orientations.csv has it.
  std::ifstream oc(dir_ / "rep" / "orientations.csv");
  std::vector<std::string> olines;
  for (std::string l; std::getline(oc, l);) olines.push_back(l);
  ASSERT_EQ(olines.size(), 3u);
  for (int o : {0, 1}) {
    const std::vector<std::string> f = csv_fields(olines[1 + o]);
    ASSERT_EQ(f.size(), 18u) << olines[1 + o];
    EXPECT_EQ(f[6], rows[3 * o][8]) << olines[1 + o];      // the largest piece
    EXPECT_EQ(f.back(), rows[3 * o][9]) << olines[1 + o];  // the balance's largest error, which differs by draw
    EXPECT_EQ(f[10], rows[3 * o][10]) << olines[1 + o];    // when two pieces of 10 % first came free
  }
  // The draws do not enter the realisations' count: two meshes, one run each.
  EXPECT_NE(md.find("| 7.5 | a few large pieces | 2 |"), std::string::npos) << md;
  EXPECT_NE(md.find("| 7.5 | 0 | 3 | "), std::string::npos) << md;
  EXPECT_NE(md.find("| 7.5 | 1 | 3 | "), std::string::npos) << md;
  EXPECT_NE(md.find(fmt::format("| 7.5 | a crack through | {} of 6 |", through)), std::string::npos) << md;
  // Analysed again from the folder, the same; one draw more than was run is named.
  const Result again = report("sphere_impact", sets + " --from-run " + (dir_ / "rep").string(), "again");
  ASSERT_EQ(again.code, 0) << again.out;
  EXPECT_EQ(slurp(dir_ / "again" / "draws.csv"), slurp(dir_ / "rep" / "draws.csv"));
  EXPECT_NE(slurp(dir_ / "again" / "report.md").find("Folders: `../rep/draws/`;"), std::string::npos);
  const Result more = report("sphere_impact",
                             "--speeds 7.5 --realisations 2 --draws 4 --set mesh.sphere_plate.size=0.04 --set "
                             "time.end=1e-4 --set output.frame_interval=2.5e-5 --from-run " +
                                 (dir_ / "rep").string(),
                             "more");
  EXPECT_EQ(more.code, 2) << more.out;
  EXPECT_NE(more.out.find("none has run draws/v7.5_o0_d3"), std::string::npos) << more.out;
  EXPECT_NE(more.out.find("with as many --realisations and --draws"), std::string::npos) << more.out;
  // A scene without a sweep refuses it.
  const Result disc = report("brazilian_disc", "--draws 2");
  EXPECT_EQ(disc.code, 2) << disc.out;
  EXPECT_NE(disc.out.find("--draws belong to a velocity sweep"), std::string::npos) << disc.out;
}

TEST_F(Cli, ReportResumeKeepsFinishedRunsAndContinuesInterruptedOnes) {
  // A sweep stopped by Ctrl-C (SIGINT to its process group) while its second speed runs: the
  // report passes one SIGTERM on to that run (in a group of its own, it does not get the
  // SIGINT too, which as a second signal would stop it without its checkpoint) and exits with
  // 5. --resume then keeps the first speed's finished run and continues the second from its
  // checkpoint, bitwise as a sweep never stopped; given the case by another path (relative,
  // from the source folder), a further --resume keeps both; another override starts both again.
  // A report stopped after it replaced a finished run leaves the earlier report marked outdated.
  const std::string file = std::string(DSPDEM_SOURCE_DIR) + "/cases/sphere_impact.toml";
  // 2.1 ms at 7.5 m/s on a 330-tet sphere: about 5 s on one core, stopped at 0.4 ms.
  const std::string opts =
      "--speeds 2.5,7.5 -j 1 --set mesh.sphere_plate.size=0.04 --set time.end=2e-3 --set output.frame_interval=2e-4";
  const fs::path rep = dir_ / "rep", v25 = rep / "speeds" / "v2.5", v75 = rep / "speeds" / "v7.5";
  const std::string cmd = fmt::format("exec {} -q report {} --no-render --out {} {} > {} 2>&1", DSPDEM_BIN, file,
                                      rep.string(), opts, (dir_ / "stopped.log").string());
  const pid_t pid = start_job(cmd);
  ASSERT_GT(pid, 0);
  const bool running = wait_for_frames(v75, 2);
  // Either way: the report then stops its run too, and nothing is left running.
  const int st = stop_job(pid, SIGINT);
  const std::string stopped = slurp(dir_ / "stopped.log");
  ASSERT_TRUE(running) << "the second speed never ran: " << stopped;
  ASSERT_TRUE(stopped_for_resume(st, stopped));
  EXPECT_NE(stopped.find("SIGINT: 1 job(s) stopped, 0 not started"), std::string::npos) << stopped;
  ASSERT_TRUE(fs::exists(v25 / "summary.json"));
  ASSERT_TRUE(fs::exists(v75 / "interrupted_run" / "checkpoint.bin"));
  ASSERT_FALSE(fs::exists(v75 / "summary.json"));
  const std::string first = slurp(v25 / "summary.json");
  const auto first_time = fs::last_write_time(v25 / "summary.json");

  const Result resumed = run("report " + file + " --no-render --out " + rep.string() + " " + opts + " --resume");
  ASSERT_EQ(resumed.code, 0) << resumed.out;
  EXPECT_NE(resumed.out.find("--resume: 1 run(s) kept, 1 continued, 0 started"), std::string::npos) << resumed.out;
  EXPECT_EQ(slurp(v25 / "summary.json"), first);
  EXPECT_EQ(fs::last_write_time(v25 / "summary.json"), first_time);
  EXPECT_FALSE(fs::exists(v75 / "interrupted_run"));  // a finished restart clears it
  // Its log holds both parts: where it stopped, and the continued part after it.
  const std::string log = slurp(rep / "speeds" / "v7.5.log");
  const auto stop_at = log.find("interrupted at step"), went_on = log.find("--resume: continued from its checkpoint");
  EXPECT_NE(stop_at, std::string::npos) << log;
  EXPECT_NE(went_on, std::string::npos) << log;
  EXPECT_LT(stop_at, went_on) << log;
  EXPECT_TRUE(fs::exists(rep / "report.md"));

  // The same sweep never stopped: the continued run ends with the same bits.
  const Result whole = report("sphere_impact", opts, "whole");
  ASSERT_EQ(whole.code, 0) << whole.out;
  for (const char* f : {"series.csv", "fragments.csv"})
    EXPECT_EQ(slurp(v75 / f), slurp(dir_ / "whole" / "speeds" / "v7.5" / f)) << f;
  const auto a = dspdem::read_run_summary((v75 / "summary.json").string());
  const auto b = dspdem::read_run_summary((dir_ / "whole" / "speeds" / "v7.5" / "summary.json").string());
  EXPECT_EQ(a.steps, b.steps);
  EXPECT_EQ(a.energy.balance_error, b.energy.balance_error);
  EXPECT_EQ(a.largest_fragment_masses, b.largest_fragment_masses);

  // The case by a relative path: the continued run's case names it by its absolute one (a
  // restart reads the path its checkpoint recorded), and is still the same case.
  const Result again =
      run(fmt::format("env sh -c 'cd {} && {} report cases/sphere_impact.toml --no-render --out {} {} "
                      "--resume'",
                      DSPDEM_SOURCE_DIR, DSPDEM_BIN, rep.string(), opts));
  ASSERT_EQ(again.code, 0) << again.out;
  EXPECT_NE(again.out.find("--resume: 2 run(s) kept, 0 continued, 0 started"), std::string::npos) << again.out;

  // Another override makes other runs: none is kept.
  const Result changed = run("report " + file + " --no-render --out " + rep.string() + " " + opts +
                             " --set output.frame_interval=4e-4 --resume");
  ASSERT_EQ(changed.code, 0) << changed.out;
  EXPECT_NE(changed.out.find("--resume: 0 run(s) kept, 0 continued, 2 started"), std::string::npos) << changed.out;

  // A report that has replaced a finished run (the first speed's) and is stopped in the next
  // leaves the earlier report.md marked outdated under its title, naming the run, its text
  // otherwise as it was, and report.html and headline.json marked with it; resumed, it writes
  // its own report, unmarked.
  const std::string earlier_md = slurp(rep / "report.md");
  ASSERT_EQ(earlier_md.rfind("# ", 0), 0U) << earlier_md;
  const std::size_t title_end = earlier_md.find('\n') + 1;
  const pid_t p2 = start_job(fmt::format("exec {} -q report {} --no-render --out {} {} > {} 2>&1", DSPDEM_BIN, file,
                                         rep.string(), opts, (dir_ / "replacing.log").string()));
  ASSERT_GT(p2, 0);
  const bool replacing = wait_for_frames(v75, 2);
  const int st2 = stop_job(p2, SIGINT);
  const std::string replacing_log = slurp(dir_ / "replacing.log");
  ASSERT_TRUE(replacing) << "the second speed never ran again: " << replacing_log;
  ASSERT_TRUE(stopped_for_resume(st2, replacing_log));
  const std::string marked = slurp(rep / "report.md");
  EXPECT_EQ(marked.substr(0, title_end), earlier_md.substr(0, title_end));
  EXPECT_EQ(marked.find("\n> **Outdated.** A report started into this folder has replaced a run this text describes "
                        "(`speeds/v2.5/`, at "),
            title_end)
      << marked;
  EXPECT_EQ(marked.substr(marked.find("\n\n", title_end + 1) + 1), earlier_md.substr(title_end)) << marked;
  EXPECT_NE(slurp(rep / "report.html").find("Outdated."), std::string::npos);
  EXPECT_NE(slurp(rep / "headline.json").find("Outdated."), std::string::npos) << slurp(rep / "headline.json");
  const Result finished = run("report " + file + " --no-render --out " + rep.string() + " " + opts + " --resume");
  ASSERT_EQ(finished.code, 0) << finished.out;
  EXPECT_NE(finished.out.find("--resume: 1 run(s) kept, 1 continued, 0 started"), std::string::npos) << finished.out;
  EXPECT_EQ(slurp(rep / "report.md").find("Outdated."), std::string::npos);

  // --resume does not go with --from-run.
  const Result both = report("sphere_impact", "--resume --from-run " + rep.string(), "both");
  EXPECT_EQ(both.code, 2) << both.out;
  EXPECT_NE(both.out.find("--resume and --from-run"), std::string::npos) << both.out;
}

TEST_F(Cli, AReportStoppedOrKilledInItsOwnRunResumesIt) {
  // A scene's report runs its case in its own process (the disc, at its quick size). Stopped
  // by Ctrl-C, it keeps the run's checkpoint and says how to go on; --resume continues the run
  // in-process to the bits of a plain run of the same case, and a further --resume keeps it.
  // Stopped during its stress check, the report stops, and when it has replaced the finished
  // run first it leaves the earlier report.md marked outdated. Killed outright, --resume goes on
  // from the run's last checkpoint by wall time.
  const std::string file = std::string(DSPDEM_SOURCE_DIR) + "/cases/brazilian_disc.toml";
  const std::string sets = "--set mesh.brazilian_disc.size=0.02";
  const std::string opts = "--no-render --no-stress-check " + sets;
  const fs::path rep = dir_ / "disc", run_dir = rep / "run";
  const pid_t pid = start_job(fmt::format("exec {} -q report {} --out {} {} > {} 2>&1", DSPDEM_BIN, file, rep.string(),
                                          opts, (dir_ / "disc.log").string()));
  ASSERT_GT(pid, 0);
  const bool running = wait_for_frames(run_dir, 2);
  const int st = stop_job(pid, SIGINT);
  const std::string stopped = slurp(dir_ / "disc.log");
  ASSERT_TRUE(running) << "the run never wrote its frames: " << stopped;
  ASSERT_TRUE(stopped_for_resume(st, stopped));
  ASSERT_TRUE(fs::exists(run_dir / "interrupted_run" / "checkpoint.bin")) << stopped;

  const std::string cmd = "report " + file + " --out " + rep.string() + " " + opts + " --resume";
  const Result resumed = run(cmd);
  ASSERT_EQ(resumed.code, 0) << resumed.out;
  EXPECT_NE(resumed.out.find("--resume: continuing the run in " + run_dir.string()), std::string::npos) << resumed.out;
  EXPECT_FALSE(fs::exists(run_dir / "interrupted_run"));
  EXPECT_TRUE(fs::exists(rep / "report.md"));
  const Result plain = run("-q run " + file + " " + sets + " --out " + (dir_ / "plain").string());
  ASSERT_EQ(plain.code, 0) << plain.out;
  for (const char* f : {"series.csv", "fragments.csv"}) EXPECT_EQ(slurp(run_dir / f), slurp(dir_ / "plain" / f)) << f;

  const auto first = fs::last_write_time(run_dir / "summary.json");
  const Result kept = run(cmd);
  ASSERT_EQ(kept.code, 0) << kept.out;
  EXPECT_NE(kept.out.find("--resume: kept the finished run in " + run_dir.string()), std::string::npos) << kept.out;
  EXPECT_EQ(fs::last_write_time(run_dir / "summary.json"), first);

  // Stopped during the stress check (the report's second run, in-process), the report stops
  // there too, with the hint, instead of taking the stop for a failed check and going on.
  const auto report_time = fs::last_write_time(rep / "report.md");
  const pid_t c = start_job(fmt::format("exec {} -q report {} --out {} --no-render {} --resume > {} 2>&1", DSPDEM_BIN,
                                        file, rep.string(), sets, (dir_ / "check.log").string()));
  ASSERT_GT(c, 0);
  const bool checking = wait_for_frames(rep / "stress_check", 1);
  // A second report into the folder while this one writes there is refused at once.
  const Result second = run("-q report " + file + " --out " + rep.string() + " --no-render " + sets);
  const int cst = stop_job(c, SIGINT);
  EXPECT_EQ(second.code, 2) << second.out;
  EXPECT_NE(second.out.find("another report is writing into this folder now"), std::string::npos) << second.out;
  const std::string check_log = slurp(dir_ / "check.log");
  ASSERT_TRUE(checking) << "the stress check never wrote a frame: " << check_log;
  ASSERT_TRUE(stopped_for_resume(cst, check_log));
  EXPECT_TRUE(fs::exists(rep / "stress_check" / "interrupted_run" / "checkpoint.bin")) << check_log;
  EXPECT_EQ(fs::last_write_time(rep / "report.md"), report_time) << "the report went on after the stop";

  // Without --resume the report runs its case again, replacing the finished run: stopped in its
  // stress check after that, it leaves the earlier report.md marked outdated, naming the run.
  const std::string earlier_md = slurp(rep / "report.md");
  const pid_t c2 = start_job(fmt::format("exec {} -q report {} --out {} --no-render {} > {} 2>&1", DSPDEM_BIN, file,
                                         rep.string(), sets, (dir_ / "replaced.log").string()));
  ASSERT_GT(c2, 0);
  const bool checking_again = wait_for_frames(rep / "stress_check", 1);
  const int cst2 = stop_job(c2, SIGINT);
  const std::string replaced_log = slurp(dir_ / "replaced.log");
  ASSERT_TRUE(checking_again) << "the stress check never wrote a frame: " << replaced_log;
  ASSERT_TRUE(stopped_for_resume(cst2, replaced_log));
  const std::string marked = slurp(rep / "report.md");
  const std::size_t title_end = earlier_md.find('\n') + 1;
  EXPECT_EQ(marked.find("\n> **Outdated.** A report started into this folder has replaced a run this text describes "
                        "(`run/`, at "),
            title_end)
      << marked;
  EXPECT_NE(marked.find(earlier_md.substr(title_end)), std::string::npos) << marked;

  // Killed outright (SIGKILL: no handler runs, no summary is written), with a checkpoint every
  // 0.2 s of wall time: --resume goes on from the last one, in the killed run's staging folder,
  // to the same bits, and the staging folder goes.
  const fs::path rep_k = dir_ / "disc_killed", run_k = rep_k / "run";
  const pid_t k = start_job(fmt::format("exec {} -q report {} --out {} {} --checkpoint-wall 0.2 > {} 2>&1", DSPDEM_BIN,
                                        file, rep_k.string(), opts, (dir_ / "killed.log").string()));
  ASSERT_GT(k, 0);
  const fs::path staging = run_k / fmt::format(".staging-{}", k);
  bool written = false;
  for (int n = 0; n < 1200 && !written; ++n) {
    written = fs::exists(staging / "checkpoint.bin");
    if (!written) std::this_thread::sleep_for(std::chrono::milliseconds(50));
  }
  const int killed = stop_job(k, SIGKILL);
  ASSERT_TRUE(written) << "no checkpoint by wall time: " << slurp(dir_ / "killed.log");
  ASSERT_TRUE(WIFSIGNALED(killed)) << "the report ended before it was killed: " << slurp(dir_ / "killed.log");
  const Result after_kill = run("report " + file + " --out " + rep_k.string() + " " + opts + " --resume");
  ASSERT_EQ(after_kill.code, 0) << after_kill.out;
  EXPECT_NE(after_kill.out.find("--resume: continuing the run in " + run_k.string() + " from its checkpoint " +
                                (staging / "checkpoint.bin").string()),
            std::string::npos)
      << after_kill.out;
  EXPECT_FALSE(fs::exists(staging));
  for (const char* f : {"series.csv", "fragments.csv"}) EXPECT_EQ(slurp(run_k / f), slurp(dir_ / "plain" / f)) << f;
}

TEST_F(Cli, ASweepGoesOnThroughAnIgnoredHangUpAndStopsItsRunsWhenKilled) {
  // Started as `nohup` starts it (SIGHUP ignored), a sweep goes on through a hang-up. Killed
  // outright (SIGKILL, which it cannot catch), its run gets a SIGTERM from the kernel: it
  // keeps its checkpoint and stops, instead of running on with no report to wait for it.
  const std::string file = std::string(DSPDEM_SOURCE_DIR) + "/cases/sphere_impact.toml";
  const std::string opts =
      "--speeds 7.5 -j 1 --set mesh.sphere_plate.size=0.04 --set time.end=2e-3 --set output.frame_interval=2e-4";
  const fs::path rep = dir_ / "hup", v75 = rep / "speeds" / "v7.5";
  const pid_t pid = start_job(fmt::format("trap '' HUP; exec {} -q report {} --no-render --out {} {} > {} 2>&1",
                                          DSPDEM_BIN, file, rep.string(), opts, (dir_ / "hup.log").string()));
  ASSERT_GT(pid, 0);
  const bool running = wait_for_frames(v75, 2);
  kill(-pid, SIGHUP);  // the report's group: the run, in a group of its own, does not get it
  // Had the report taken the hang-up, it would have stopped its run, whose staging folder
  // would then be gone: the run writing a further frame shows it went on.
  const bool went_on = running && wait_for_frames(v75, 3);
  int st = 0;
  const pid_t ended = waitpid(pid, &st, WNOHANG);
  if (ended == 0) stop_job(pid, SIGKILL);
  ASSERT_TRUE(running) << "the run never started: " << slurp(dir_ / "hup.log");
  EXPECT_TRUE(went_on) << "the run stopped at the ignored hang-up: " << slurp(dir_ / "hup.log");
  EXPECT_EQ(ended, 0) << "the report stopped at the ignored hang-up: " << slurp(dir_ / "hup.log");
  // The run writes its checkpoint and summary, and moves its folder, before it exits.
  bool kept = false;
  for (int k = 0; k < 1200 && !kept; ++k) {
    kept = fs::exists(v75 / "interrupted_run" / "summary.json");
    if (!kept) std::this_thread::sleep_for(std::chrono::milliseconds(50));
  }
  ASSERT_TRUE(kept) << "the run did not stop with its report: " << slurp(rep / "speeds" / "v7.5.log");
  EXPECT_TRUE(fs::exists(v75 / "interrupted_run" / "checkpoint.bin"));
  EXPECT_NE(slurp(rep / "speeds" / "v7.5.log").find("interrupted at step"), std::string::npos);
}

TEST_F(Cli, ReportStudyOfARunThatNeverLoadsStillWritesTheReport) {
  // Plates too slow to reach the disc in 0.2 ms: no profile load, so the stress check is
  // skipped (and said so) and the study's elastic row fails with a reason; the other rows
  // and report.md are still written.
  const Result r =
      report("brazilian_disc",
             "--study --set mesh.brazilian_disc.size=0.02 --set time.end=2e-4 --set output.frame_interval=5e-5");
  ASSERT_EQ(r.code, 0) << r.out;
  const std::string md = slurp(dir_ / "rep" / "report.md");
  EXPECT_NE(md.find("Stress check skipped"), std::string::npos);
  EXPECT_NE(md.find("| elastic_fine | "), std::string::npos);
  const auto row = md.find("| elastic_fine | ");
  EXPECT_NE(md.substr(row, md.find('\n', row) - row).find("failed:"), std::string::npos);
  EXPECT_NE(md.find("| band_0.2D | "), std::string::npos);
}

TEST_F(Cli, ReportWithoutStressCheckRunsTheSceneOnly) {
  // --no-stress-check: the report has the scene's profile and no check section or folder.
  const Result r = report(
      "brazilian_disc",
      "--no-stress-check --set mesh.brazilian_disc.size=0.02 --set time.end=2e-4 --set output.frame_interval=5e-5");
  ASSERT_EQ(r.code, 0) << r.out;
  const std::string md = slurp(dir_ / "rep" / "report.md");
  EXPECT_NE(md.find("## Stresses along the loaded diameter"), std::string::npos);
  EXPECT_EQ(md.find("Stress check"), std::string::npos);
  EXPECT_FALSE(fs::exists(dir_ / "rep" / "stress_check"));
  // --from-run reads the run and writes what it derives into the new report's run/, leaving
  // the run given (here another report's) as it was; a folder whose run/ is another run is
  // refused rather than written beside it.
  const std::string sets =
      " --no-stress-check --set mesh.brazilian_disc.size=0.02 --set time.end=2e-4 --set output.frame_interval=5e-5";
  for (const char* f : {"load.csv", "profile.csv", "profile_analytic.csv", "images"})
    fs::remove_all(dir_ / "rep" / "run" / f);
  const Result again = report("brazilian_disc", "--from-run " + (dir_ / "rep" / "run").string() + sets, "again");
  ASSERT_EQ(again.code, 0) << again.out;
  for (const char* f : {"load.csv", "profile.csv", "profile_analytic.csv", "images/plots/load_closure.png"}) {
    EXPECT_TRUE(fs::exists(dir_ / "again" / "run" / f)) << f;
    EXPECT_FALSE(fs::exists(dir_ / "rep" / "run" / f)) << f;
  }
  EXPECT_FALSE(fs::exists(dir_ / "again" / "run" / "summary.json"));
  const std::string again_md = slurp(dir_ / "again" / "report.md");
  EXPECT_NE(again_md.find("run in `../rep/run/`"), std::string::npos) << again_md;
  EXPECT_NE(again_md.find("](run/images/plots/load_closure.png)"), std::string::npos) << again_md;
  fs::copy(dir_ / "rep" / "run", dir_ / "copy", fs::copy_options::recursive);
  const Result beside = report("brazilian_disc", "--from-run " + (dir_ / "copy").string() + sets, "rep");
  EXPECT_EQ(beside.code, 2) << beside.out;
  EXPECT_NE(beside.out.find("holds a run of its own"), std::string::npos) << beside.out;
  EXPECT_FALSE(fs::exists(dir_ / "rep" / "run" / "load.csv"));
}

TEST_F(Cli, ThreadCountDoesNotChangeTheResult) {
  // --threads picks the solver threads; the sums are gathered in a fixed order, so a disc
  // with joints and plate contact gives a bitwise equal series on 1 and 2 threads.
  const std::string disc = std::string(DSPDEM_SOURCE_DIR) + "/cases/brazilian_disc.toml";
  const std::string opts =
      " --set mesh.brazilian_disc.size=0.02 --set time.end=2.5e-4 --set output.series_interval=2e-6"
      " --set walls.0.velocity=[0,-0.2,0] --set walls.1.velocity=[0,0.2,0]";
  for (int t : {1, 2})
    ASSERT_EQ(
        run(fmt::format("-q -t {} run {} --out {}{}", t, disc, (dir_ / fmt::format("t{}", t)).string(), opts)).code, 0);
  const std::string a = slurp(dir_ / "t1" / "series.csv"), b = slurp(dir_ / "t2" / "series.csv");
  EXPECT_GT(a.size(), 1000u);
  EXPECT_EQ(a, b);
  EXPECT_NE(slurp(dir_ / "t1" / "summary.json").find("\"threads\": 1"), std::string::npos);
  EXPECT_NE(slurp(dir_ / "t2" / "summary.json").find("\"threads\": 2"), std::string::npos);
  // The plates have reached the disc: the last row has contacts.
  const std::string last = a.substr(a.rfind('\n', a.size() - 2) + 1);
  const std::string head = a.substr(0, a.find('\n'));
  int col = 0;
  for (std::size_t p = 0; p < head.find("contacts"); ++p) col += head[p] == ',';
  std::stringstream row(last);
  std::string cell;
  for (int k = 0; k <= col; ++k) std::getline(row, cell, ',');
  EXPECT_GT(std::stod(cell), 0) << head << "\n" << last;
  const Result bad = run("-t -1 keys");
  EXPECT_EQ(bad.code, 1) << bad.out;
}

TEST_F(Cli, BoundaryConditionsThatDisagreeOnANodeAreNamed) {
  // A probe's finding: a velocity on the nodes another [[boundary]] fixes silently replaced it
  // there (the later one holds, as before); the run now says which two and on how many.
  const std::string bar = std::string(DSPDEM_SOURCE_DIR) + "/tests/data/bar_tension.toml";
  const Result r = run("run " + bar + " --estimate --set 'boundary.1.group=\"left\"'");
  EXPECT_EQ(r.code, 0) << r.out;
  EXPECT_NE(r.out.find("bar_tension.toml:18: sets 9 node component(s) that"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("bar_tension.toml:15 also sets"), std::string::npos) << r.out;
  // The same condition twice is no disagreement: a zero velocity on fixed nodes, whatever its
  // ramp (a review's finding: it warned).
  const Result same = run("run " + bar +
                          " --estimate --set 'boundary.1.group=\"left\"' --set 'boundary.1.value=[0.0, 0.0, 0.0]' "
                          "--set boundary.1.ramp=1e-5");
  EXPECT_EQ(same.code, 0) << same.out;
  EXPECT_EQ(same.out.find("also sets"), std::string::npos) << same.out;
}
