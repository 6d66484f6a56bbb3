// Where what is derived from a run goes when it is not the run's own folder: never beside another
// run, and a place filled from another run emptied first, but only one a report or render filled.
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <string>

#include "core/error.hpp"
#include "core/folder_lock.hpp"
#include "io/run_place.hpp"

using namespace dspdem;
namespace fs = std::filesystem;

namespace {

class RunPlace : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() / ("dspdem_run_place_" + std::to_string(::getpid()) + "_" +
                                        ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::remove_all(dir_);
    for (const char* r : {"a", "b"}) {
      fs::create_directories(dir_ / r);
      std::ofstream(dir_ / r / "summary.json") << "{}";
    }
  }
  void TearDown() override { fs::remove_all(dir_); }
  fs::path dir_;
};

}  // namespace

TEST_F(RunPlace, ARunsOwnFolderAndAnEmptyPlaceAreReadyAndAnotherRunIsRefused) {
  EXPECT_TRUE(holds_a_run((dir_ / "a").string()));
  prepare_derived_place((dir_ / "a").string(), (dir_ / "a" / ".").string());  // the run itself
  EXPECT_FALSE(fs::exists(dir_ / "a" / "derived_from"));
  prepare_derived_place((dir_ / "rep" / "run").string(), (dir_ / "a").string());
  EXPECT_TRUE(fs::exists(dir_ / "rep" / "run" / "derived_from"));
  EXPECT_THROW(prepare_derived_place((dir_ / "b").string(), (dir_ / "a").string()), Error);
  // A run killed outright leaves only its staging folder: still a run.
  fs::create_directories(dir_ / "c" / ".staging-12345");
  EXPECT_TRUE(holds_a_run((dir_ / "c").string()));
  EXPECT_THROW(prepare_derived_place((dir_ / "c").string(), (dir_ / "a").string()), Error);
  EXPECT_TRUE(fs::exists(dir_ / "c" / ".staging-12345"));
}

TEST_F(RunPlace, APlaceFilledFromAnotherRunIsEmptiedAndOneNoReportFilledIsRefused) {
  const std::string place = (dir_ / "rep" / "run").string();
  prepare_derived_place(place, (dir_ / "a").string());
  std::ofstream(fs::path(place) / "load.csv") << "from a";
  prepare_derived_place(place, (dir_ / "a").string());  // the same run: kept
  EXPECT_TRUE(fs::exists(fs::path(place) / "load.csv"));
  prepare_derived_place(place, (dir_ / "b").string());  // another: emptied
  EXPECT_FALSE(fs::exists(fs::path(place) / "load.csv"));
  EXPECT_TRUE(fs::exists(fs::path(place) / "derived_from"));
  // A folder with files but no record of a report is never emptied.
  fs::create_directories(dir_ / "mine");
  std::ofstream(dir_ / "mine" / "notes.txt") << "keep";
  EXPECT_THROW(prepare_derived_place((dir_ / "mine").string(), (dir_ / "a").string()), Error);
  EXPECT_TRUE(fs::exists(dir_ / "mine" / "notes.txt"));
}

TEST_F(RunPlace, ACheckChangesNothingARunInsideThePlaceIsRefusedAndAClearEmptiesOnlyAReportsPlace) {
  const std::string place = (dir_ / "rep" / "run").string();
  prepare_derived_place(place, (dir_ / "a").string());
  std::ofstream(fs::path(place) / "load.csv") << "from a";
  check_derived_place(place, (dir_ / "b").string());  // fine for b, and nothing changed
  EXPECT_TRUE(fs::exists(fs::path(place) / "load.csv"));
  // A run inside the place would go with it when the place is emptied.
  fs::create_directories(fs::path(place) / "inner");
  std::ofstream(fs::path(place) / "inner" / "summary.json") << "{}";
  try {
    prepare_derived_place(place, (fs::path(place) / "inner").string());
    ADD_FAILURE() << "a run inside the place was taken";
  } catch (const Error& e) {  // said as it is, not as a run below that emptying would take
    EXPECT_NE(std::string(e.what()).find("lies inside"), std::string::npos) << e.what();
  }
  EXPECT_TRUE(fs::exists(fs::path(place) / "inner" / "summary.json"));
  // So would any other run below its top level: refused for another run, and not cleared.
  EXPECT_THROW(prepare_derived_place(place, (dir_ / "b").string()), Error);
  clear_derived_place(place);
  EXPECT_TRUE(fs::exists(fs::path(place) / "inner" / "summary.json"));
  fs::remove_all(fs::path(place) / "inner");
  fs::create_directories(fs::path(place) / "deep" / ".staging-4321");  // a killed run's, deeper
  EXPECT_THROW(check_derived_place(place, (dir_ / "b").string()), Error);
  fs::remove_all(fs::path(place) / "deep");
  // A report written into the place (or one being written there, its lock), at its top or
  // below: never emptied with it.
  for (const fs::path& at : {fs::path(place), fs::path(place) / "sub"})
    for (const char* marker : {"report.md", report_lock_file}) {
      fs::create_directories(at);
      std::ofstream(at / marker) << "a report";
      EXPECT_EQ(holds_a_report(at.string()), true) << marker;
      EXPECT_THROW(prepare_derived_place(place, (dir_ / "b").string()), Error) << marker;
      clear_derived_place(place);
      EXPECT_TRUE(fs::exists(at / marker)) << marker;
      fs::remove(at / marker);
    }
  fs::remove_all(fs::path(place) / "sub");
  EXPECT_NE(derived_from(place), std::nullopt);
  EXPECT_EQ(derived_from((dir_ / "a").string()), std::nullopt);
  // A run to be made in a place a report filled: emptied; in a run's folder or one no report
  // filled: nothing happens.
  clear_derived_place(place);
  EXPECT_TRUE(fs::exists(place) && fs::is_empty(place));
  std::ofstream(dir_ / "a" / "load.csv") << "the run's own";
  clear_derived_place((dir_ / "a").string());
  EXPECT_TRUE(fs::exists(dir_ / "a" / "load.csv"));
}

TEST_F(RunPlace, APlaceInsideAnotherRunsImagesOrAnotherRunsPlaceIsRefusedAndOneInsideTheRunDrawnIsNot) {
  // Inside another run's images/: a run made there again removes them.
  try {
    check_derived_place((dir_ / "b" / "images" / "pics").string(), (dir_ / "a").string());
    ADD_FAILURE() << "a place inside another run's images was taken";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("which a run made there again removes"), std::string::npos) << e.what();
  }
  EXPECT_THROW(check_derived_place((dir_ / "b" / "images").string(), (dir_ / "a").string()), Error);
  EXPECT_THROW(check_derived_place((dir_ / "b" / "images" / "x" / "y").string(), (dir_ / "a").string()), Error);
  // Elsewhere inside another run's folder nothing removes it, and derived_from says whose it is.
  prepare_derived_place((dir_ / "b" / "pics").string(), (dir_ / "a").string());
  EXPECT_EQ(derived_from((dir_ / "b" / "pics").string()), fs::weakly_canonical(dir_ / "a").string());
  // Inside the run drawn: nothing there is emptied by another run's render.
  prepare_derived_place((dir_ / "a" / "pics").string(), (dir_ / "a").string());
  EXPECT_TRUE(fs::exists(dir_ / "a" / "pics" / "derived_from"));
  // Inside a place filled from another run: a render of a third run into it would empty it.
  const std::string place = (dir_ / "drawn").string();
  prepare_derived_place(place, (dir_ / "b").string());
  try {
    check_derived_place((dir_ / "drawn" / "sub").string(), (dir_ / "a").string());
    ADD_FAILURE() << "a place inside one filled from another run was taken";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("which a render or a report filled from the run in"), std::string::npos)
        << e.what();
  }
  check_derived_place((dir_ / "drawn" / "sub").string(), (dir_ / "b").string());  // from the same run: fine
}

TEST_F(RunPlace, TheRendersLockIsNotAFileOfThePlaceAndEmptyingKeepsTheLocks) {
  // A render takes its lock in the place before it checks it: the lock alone is not files no
  // report or render derived.
  const fs::path place = dir_ / "drawn";
  fs::create_directories(place);
  std::ofstream(place / render_lock_file) << "";
  prepare_derived_place(place.string(), (dir_ / "a").string());
  EXPECT_TRUE(fs::exists(place / "derived_from"));
  // Emptied for another run: the files go, the render's lock stays (one removed under its
  // holder would let a second render in).
  std::ofstream(place / "load.csv") << "from a";
  prepare_derived_place(place.string(), (dir_ / "b").string());
  EXPECT_FALSE(fs::exists(place / "load.csv"));
  EXPECT_TRUE(fs::exists(place / render_lock_file));
  EXPECT_EQ(derived_from(place.string()), fs::weakly_canonical(dir_ / "b").string());
}

TEST_F(RunPlace, ARenderDrawingIntoThePlaceOrBelowItKeepsItFromBeingEmptied) {
  const fs::path place = dir_ / "drawn";
  prepare_derived_place(place.string(), (dir_ / "a").string());
  std::ofstream(place / "load.csv") << "from a";
  {
    // A render drawing into the place: a run made there does not empty it under the render,
    // and a report's place for another run is not taken.
    const FolderLock drawing(place.string(), render_lock_file, "the test");
    EXPECT_TRUE(FolderLock::held(place.string(), render_lock_file));
    EXPECT_THROW(clear_derived_place(place.string()), Error);
    EXPECT_THROW(take_derived_place(place.string(), (dir_ / "b").string()), Error);
    EXPECT_TRUE(fs::exists(place / "load.csv"));
    EXPECT_EQ(derived_from(place.string()), fs::weakly_canonical(dir_ / "a").string());
  }
  EXPECT_FALSE(FolderLock::held(place.string(), render_lock_file));
  // One drawing below it: emptying the place would take its folder.
  {
    const FolderLock drawing((place / "sub").string(), render_lock_file, "the test");
    try {
      check_derived_place(place.string(), (dir_ / "b").string());
      ADD_FAILURE() << "a place with a render drawing below it was taken";
    } catch (const Error& e) {
      EXPECT_NE(std::string(e.what()).find("a render drawing now below it"), std::string::npos) << e.what();
    }
    // A run made there meanwhile is refused: it would go on beside what was derived from a.
    try {
      clear_derived_place(place.string());
      ADD_FAILURE() << "a run into a place with a render drawing below it went on";
    } catch (const Error& e) {
      EXPECT_NE(std::string(e.what()).find("a render is drawing into"), std::string::npos) << e.what();
    }
    EXPECT_TRUE(fs::exists(place / "load.csv"));
  }
  // A lock file a killed render left, held by none, keeps nothing.
  fs::create_directories(place / "sub");
  std::ofstream(place / "sub" / render_lock_file) << "";
  take_derived_place(place.string(), (dir_ / "b").string());
  EXPECT_FALSE(fs::exists(place / "load.csv"));
  EXPECT_FALSE(fs::exists(place / "sub"));
  EXPECT_FALSE(fs::exists(place / render_lock_file));  // the one the taker held, removed as it let go
}

TEST_F(RunPlace, ARunsReplacedImagesGoUnlessARunLiesInsideThemOrARenderDrawsThem) {
  using Fate = ReplacedImages::Fate;
  const fs::path run = dir_ / "a";
  const fs::path images = run / "images";
  fs::create_directories(run);
  EXPECT_EQ(remove_replaced_images(run.string()).fate, Fate::none);  // none there: nothing to do
  fs::create_directories(images / "stress");
  std::ofstream(images / "stress" / "frame_0040.png") << "drawn from the replaced run";
  // A render drawing into the run's folder now (its lock held): kept, whatever lies inside.
  {
    const FolderLock drawing(run.string(), render_lock_file, "a render");
    EXPECT_EQ(remove_replaced_images(run.string()).fate, Fate::render_drawing);
    EXPECT_TRUE(fs::exists(images / "stress" / "frame_0040.png"));
  }
  // A run made inside them by hand: kept, with them, and named.
  fs::create_directories(images / "x");
  std::ofstream(images / "x" / "summary.json") << "{}";
  const ReplacedImages kept = remove_replaced_images(run.string());
  EXPECT_EQ(kept.fate, Fate::holds_inside);
  EXPECT_EQ(kept.inside, (images / "x").string());
  EXPECT_TRUE(fs::exists(images / "x" / "summary.json"));
  EXPECT_TRUE(fs::exists(images / "stress" / "frame_0040.png"));
  fs::remove_all(images / "x");
  // A file a render does not write (someone's own, in a folder that held a summary.json): kept.
  std::ofstream(images / "site_photo.jpg") << "not drawn";
  const ReplacedImages own = remove_replaced_images(run.string());
  EXPECT_EQ(own.fate, Fate::not_drawn);
  EXPECT_EQ(own.inside, (images / "site_photo.jpg").string());
  EXPECT_TRUE(fs::exists(images / "stress" / "frame_0040.png"));
  fs::remove(images / "site_photo.jpg");
  fs::create_directories(images / "notes");
  EXPECT_EQ(remove_replaced_images(run.string()).fate, Fate::not_drawn);  // a folder no view has
  fs::remove(images / "notes");
  std::ofstream(images / "stress" / "notes.txt") << "mine";
  EXPECT_EQ(remove_replaced_images(run.string()).fate, Fate::not_drawn);  // in a view's folder
  fs::remove(images / "stress" / "notes.txt");
  // What a render writes: frames, animations, the links an encoding stages, plots.
  for (const char* f :
       {"stress.ogv", "stress.mp4", "stress.gif", "plots/energy.png", "heap_front.png", "stress.mp4.log"})
    fs::create_directories((images / f).parent_path()), std::ofstream(images / f) << "drawn";
  fs::create_directories(images / "stress.seq");
  fs::create_symlink(images / "stress" / "frame_0040.png", images / "stress.seq" / "000000.png");
  EXPECT_EQ(remove_replaced_images(run.string()).fate, Fate::removed);
  EXPECT_FALSE(fs::exists(images));
  EXPECT_TRUE(fs::exists(run / "summary.json"));     // the run itself is not touched
  EXPECT_FALSE(fs::exists(run / render_lock_file));  // the lock it took went as it let go
  // A lock that cannot be taken for another reason (here no folder to hold it) is an error of
  // its own, not read as a render drawing there.
  const fs::path not_a_folder = dir_ / "file";
  std::ofstream(not_a_folder) << "a file";
  try {
    remove_replaced_images(not_a_folder.string());
    ADD_FAILURE() << "a lock file was made inside a file";
  } catch (const FolderBusy& e) {
    ADD_FAILURE() << "read as a render drawing: " << e.what();
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("cannot open the lock file"), std::string::npos) << e.what();
  }
}

TEST_F(RunPlace, ARunsFramesFolderHoldingAnythingARunDoesNotWriteIsRefusedUnchanged) {
  const fs::path frames = dir_ / "a" / "frames";
  fs::create_directories(frames);
  check_run_frames((dir_ / "none").string());  // no folder: nothing to check
  check_run_frames((dir_ / "a").string());     // empty
  for (const char* f : {"frame_0000.vtu", "joints_0000.vtu", "frame_12345.pvtu", "frame_0003_1.vtu", "joints_0003.pvtu",
                        "joints_0003_12.vtu"})
    std::ofstream(frames / f) << "x";
  check_run_frames((dir_ / "a").string());
  // A file of the user's, a near miss, and another run made inside frames/.
  for (const char* f : {"mine.txt", "frame_0000.vtu.bak", "frame_01.vtu"}) {
    std::ofstream(frames / f) << "mine";
    try {
      check_run_frames((dir_ / "a").string());
      ADD_FAILURE() << f << " accepted";
    } catch (const Error& e) {
      EXPECT_NE(std::string(e.what()).find(std::string("'") + f + "' is not a run's frame"), std::string::npos)
          << e.what();
    }
    EXPECT_TRUE(fs::exists(frames / f));
    fs::remove(frames / f);
  }
  fs::create_directories(frames / "inner");
  std::ofstream(frames / "inner" / "summary.json") << "{}";
  EXPECT_THROW(check_run_frames((dir_ / "a").string()), Error);
  EXPECT_TRUE(fs::exists(frames / "inner" / "summary.json"));
}
