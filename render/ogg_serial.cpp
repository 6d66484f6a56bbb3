#include "render/ogg_serial.hpp"

#include <ogg/ogg.h>

#include <cstring>
#include <filesystem>
#include <fstream>
#include <system_error>

#include "core/error.hpp"
#include "core/file.hpp"

namespace dspdem::render {

void set_ogg_serial(const std::string& path, std::uint32_t serial) {
  const std::string bytes = read_file(path, "Ogg file");
  ogg_sync_state sync;
  ogg_sync_init(&sync);
  char* buf = ogg_sync_buffer(&sync, static_cast<long>(bytes.size()));
  std::memcpy(buf, bytes.data(), bytes.size());
  ogg_sync_wrote(&sync, static_cast<long>(bytes.size()));
  std::string out;
  out.reserve(bytes.size());
  ogg_page page;
  int r = 0, pages = 0, first = 0;
  bool one_stream = true;
  // pageout checks each page's checksum and returns -1 on a gap or a bad page.
  while ((r = ogg_sync_pageout(&sync, &page)) == 1) {
    if (pages++ == 0) first = ogg_page_serialno(&page);
    one_stream = one_stream && ogg_page_serialno(&page) == first;
    // The serial is bytes 14-17 of the page header, little-endian (RFC 3533).
    for (int k = 0; k < 4; ++k) page.header[14 + k] = static_cast<unsigned char>(serial >> (8 * k));
    ogg_page_checksum_set(&page);
    out.append(reinterpret_cast<const char*>(page.header), static_cast<std::size_t>(page.header_len));
    out.append(reinterpret_cast<const char*>(page.body), static_cast<std::size_t>(page.body_len));
  }
  ogg_sync_clear(&sync);
  DSPDEM_CHECK(r == 0 && pages > 0 && out.size() == bytes.size(),
               "'{}' is not a sequence of whole Ogg pages (read {} pages, {} of {} bytes)", path, pages, out.size(),
               bytes.size());
  DSPDEM_CHECK(one_stream, "'{}' holds more than one Ogg stream: its serials were left as they are", path);
  const std::string tmp = path + ".serial.tmp";
  std::ofstream o(tmp, std::ios::binary | std::ios::trunc);
  o.write(out.data(), static_cast<std::streamsize>(out.size()));
  o.close();
  if (!o.good()) {
    std::error_code ec;
    std::filesystem::remove(tmp, ec);
    fail("could not write '{}'", tmp);
  }
  std::error_code ec;
  std::filesystem::rename(tmp, path, ec);
  if (ec) {
    std::filesystem::remove(tmp, ec);
    fail("could not replace '{}' by its re-serialled copy", path);
  }
}

}  // namespace dspdem::render
