// The render command's option texts read whole: "WIDTHxHEIGHT" and "MIN:MAX". sscanf's
// "%dx%d" took "100x100x5" as 100x100 and "%lf:%lf" took "1:2:3" as 1:2, silently.
#pragma once
#include <string>
#include <string_view>

namespace dspdem {

/// Whether `text` is, whole, one number (no sign or space around it for a float, no trailing
/// characters), stored in `v`.
bool whole_number(std::string_view text, long& v);
bool whole_number(std::string_view text, int& v);
bool whole_number(std::string_view text, double& v);

/// The image sizes a frame is drawn at: as the case's [render] width and height allow.
inline constexpr int kMinImageSide = 16, kMaxImageSide = 8192;

/// "WIDTHxHEIGHT", each a whole number of pixels within [kMinImageSide, kMaxImageSide];
/// throws Error naming `option` and the text otherwise.
void parse_image_size(const std::string& text, const std::string& option, int& width, int& height);

/// "MIN:MAX", two finite numbers with MIN < MAX; throws Error naming `option` and the text
/// otherwise.
void parse_range(const std::string& text, const std::string& option, double& min, double& max);

}  // namespace dspdem
