// io/staging's write_files_atomic: a report's files are replaced together or not at all.
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <string>

#include "core/error.hpp"
#include "core/file.hpp"
#include "io/staging.hpp"

namespace fs = std::filesystem;

TEST(WriteFilesAtomic, AFailedWriteReplacesNoneAndLeavesNoTemporary) {
  const fs::path d = fs::temp_directory_path() / ("dspdem_write_atomic_" + std::to_string(::getpid()));
  fs::remove_all(d);
  fs::create_directories(d);
  std::ofstream(d / "report.md") << "earlier";
  std::ofstream(d / "report.html") << "earlier page";
  // The third file's folder does not exist: its temporary cannot be written.
  EXPECT_THROW(dspdem::write_files_atomic({{(d / "report.md").string(), "new"},
                                           {(d / "report.html").string(), "new page"},
                                           {(d / "gone" / "headline.json").string(), "{}"}}),
               dspdem::Error);
  EXPECT_EQ(dspdem::read_file((d / "report.md").string()), "earlier");
  EXPECT_EQ(dspdem::read_file((d / "report.html").string()), "earlier page");
  EXPECT_FALSE(fs::exists(d / "report.md.tmp"));
  EXPECT_FALSE(fs::exists(d / "report.html.tmp"));
  dspdem::write_files_atomic({{(d / "report.md").string(), "new"}, {(d / "report.html").string(), "new page"}});
  EXPECT_EQ(dspdem::read_file((d / "report.md").string()), "new");
  EXPECT_EQ(dspdem::read_file((d / "report.html").string()), "new page");
  EXPECT_EQ(std::distance(fs::directory_iterator(d), fs::directory_iterator()), 2);
  fs::remove_all(d);
}
