// render::set_ogg_serial: the .ogv's pages get one fixed serial with valid checksums, their
// packets unchanged; a file that is not whole pages of one stream is refused and left as is.
#include <gtest/gtest.h>
#include <ogg/ogg.h>

#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "core/file.hpp"
#include "render/ogg_serial.hpp"

namespace fs = std::filesystem;
using dspdem::render::kOgvSerial;
using dspdem::render::set_ogg_serial;

namespace {
std::string slurp(const fs::path& p) { return dspdem::read_file(p); }

// Pages of one stream per serial, each holding `packets` packets of a few hundred bytes.
std::string ogg_bytes(const std::vector<int>& serials, int packets) {
  std::string out;
  for (int serial : serials) {
    ogg_stream_state os;
    ogg_stream_init(&os, serial);
    for (int k = 0; k < packets; ++k) {
      std::vector<unsigned char> data(300 + 17 * k, static_cast<unsigned char>(k));
      ogg_packet op{};
      op.packet = data.data();
      op.bytes = static_cast<long>(data.size());
      op.b_o_s = k == 0;
      op.e_o_s = k == packets - 1;
      op.granulepos = k;
      op.packetno = k;
      ogg_stream_packetin(&os, &op);
      ogg_page og;
      while (ogg_stream_flush(&os, &og) != 0) {  // a page per packet: several pages
        out.append(reinterpret_cast<char*>(og.header), og.header_len);
        out.append(reinterpret_cast<char*>(og.body), og.body_len);
      }
    }
    ogg_stream_clear(&os);
  }
  return out;
}

struct Read {
  std::vector<int> serials;
  std::vector<std::string> packets;
  bool bad_page = false;
};

// Every page as libogg reads it (pageout checks the checksum), and the packets of the stream.
Read read_ogg(const std::string& bytes) {
  Read r;
  ogg_sync_state sync;
  ogg_sync_init(&sync);
  char* buf = ogg_sync_buffer(&sync, static_cast<long>(bytes.size()));
  std::copy(bytes.begin(), bytes.end(), buf);
  ogg_sync_wrote(&sync, static_cast<long>(bytes.size()));
  ogg_stream_state os;
  bool started = false;
  ogg_page og;
  int rc = 0;
  while ((rc = ogg_sync_pageout(&sync, &og)) != 0) {
    if (rc < 0) {
      r.bad_page = true;
      continue;
    }
    r.serials.push_back(ogg_page_serialno(&og));
    if (!started) ogg_stream_init(&os, ogg_page_serialno(&og)), started = true;
    ogg_stream_pagein(&os, &og);
    ogg_packet op;
    while (ogg_stream_packetout(&os, &op) == 1)
      r.packets.emplace_back(reinterpret_cast<char*>(op.packet), static_cast<std::size_t>(op.bytes));
  }
  if (started) ogg_stream_clear(&os);
  ogg_sync_clear(&sync);
  return r;
}

fs::path write(const std::string& name, const std::string& bytes) {
  const fs::path p = fs::temp_directory_path() / name;
  std::ofstream(p, std::ios::binary) << bytes;
  return p;
}
}  // namespace

TEST(OggSerial, EveryPageGetsTheFixedSerialWithAValidChecksumAndTheSamePackets) {
  const std::string before = ogg_bytes({12345}, 6);
  const Read a = read_ogg(before);
  ASSERT_FALSE(a.bad_page);
  ASSERT_EQ(a.serials.size(), 6u);
  const fs::path p = write("dspdem_ogg_serial.ogg", before);
  set_ogg_serial(p.string());
  const std::string after = slurp(p);
  EXPECT_EQ(after.size(), before.size());
  const Read b = read_ogg(after);
  EXPECT_FALSE(b.bad_page) << "a page's checksum no longer matches";
  ASSERT_EQ(b.serials.size(), a.serials.size());
  for (int s : b.serials) EXPECT_EQ(static_cast<std::uint32_t>(s), kOgvSerial);
  EXPECT_EQ(b.packets, a.packets);
  // Two files that differ only in their serials become the same file.
  const fs::path q = write("dspdem_ogg_serial_2.ogg", ogg_bytes({999}, 6));
  set_ogg_serial(q.string());
  EXPECT_EQ(slurp(q), after);
}

TEST(OggSerial, TruncatedOrTwoStreamFilesAreRefusedAndLeftAsTheyWere) {
  const std::string whole = ogg_bytes({7}, 4);
  const std::string cut = whole.substr(0, whole.size() - 50);
  const fs::path p = write("dspdem_ogg_serial_cut.ogg", cut);
  EXPECT_THROW(set_ogg_serial(p.string()), std::exception);
  EXPECT_EQ(slurp(p), cut);
  const std::string two = ogg_bytes({7, 8}, 3);
  const fs::path q = write("dspdem_ogg_serial_two.ogg", two);
  EXPECT_THROW(set_ogg_serial(q.string()), std::exception);
  EXPECT_EQ(slurp(q), two);
  EXPECT_FALSE(fs::exists(q.string() + ".serial.tmp"));
  EXPECT_THROW(set_ogg_serial((fs::temp_directory_path() / "dspdem_no_such.ogg").string()), std::exception);
}
