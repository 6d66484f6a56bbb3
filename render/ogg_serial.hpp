// A fixed stream serial for the Ogg files VTK writes, so that the same frames give the same
// .ogv byte for byte.
#pragma once
#include <cstdint>
#include <string>

namespace dspdem::render {

/// The serial number every .ogv of dspdem carries ("dsp" and a version byte).
inline constexpr std::uint32_t kOgvSerial = 0x64737001;

/// Sets the serial number of every page of the single-stream Ogg file `path` to `serial` and
/// recomputes each page's checksum (libogg's), in place. VTK 9.1's Theora writer seeds rand()
/// with time(NULL) and takes the serial from it, so two renders of the same frames a second
/// apart gave different files; the Theora packets themselves do not change. Throws, leaving
/// the file as it was, when it is not a sequence of whole Ogg pages of one stream.
void set_ogg_serial(const std::string& path, std::uint32_t serial = kOgvSerial);

}  // namespace dspdem::render
