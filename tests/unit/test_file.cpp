// core/file: a whole file read byte for byte; what cannot be read is named, with the reason.
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <string>

#include "core/error.hpp"
#include "core/file.hpp"

namespace fs = std::filesystem;
using dspdem::read_file;
using dspdem::read_file_if;

namespace {
fs::path scratch() {
  const fs::path d = fs::temp_directory_path() / ("dspdem_test_file_" + std::to_string(::getpid()));
  fs::create_directories(d);
  return d;
}

std::string message_of(const fs::path& p, const char* what) {
  try {
    read_file(p, what);
  } catch (const dspdem::Error& e) {
    return e.what();
  }
  return "";
}
}  // namespace

TEST(ReadFile, ReturnsEveryByteOfABinaryFile) {
  const fs::path p = scratch() / "bytes.bin";
  std::string bytes;
  for (int k = 0; k < 70000; ++k) bytes.push_back(static_cast<char>(k * 7919 % 256));  // NULs, \r, \n, 0xff
  std::ofstream(p, std::ios::binary) << bytes;
  EXPECT_TRUE(read_file(p) == bytes);
  EXPECT_TRUE(read_file_if(p).value() == bytes);
  std::ofstream(p, std::ios::binary | std::ios::trunc).flush();
  EXPECT_EQ(read_file(p), "");  // an empty file is read, not refused
  fs::remove_all(p.parent_path());
}

TEST(ReadFile, NamesWhatCannotBeReadAndWhy) {
  const fs::path d = scratch();
  EXPECT_EQ(message_of(d / "none.bin", "checkpoint"),
            "cannot read checkpoint '" + (d / "none.bin").string() + "': No such file or directory");
  EXPECT_EQ(message_of(d, "mesh file"), "cannot read mesh file '" + d.string() + "': it is a folder");
  EXPECT_FALSE(read_file_if(d / "none.bin"));
  EXPECT_FALSE(read_file_if(d));
  fs::remove_all(d);
}
