#include "run/render_args.hpp"

#include <charconv>
#include <cmath>

#include "core/error.hpp"

namespace dspdem {

namespace {
template <typename T>
bool whole(std::string_view t, T& v) {
  if (t.empty()) return false;
  const auto [end, ec] = std::from_chars(t.data(), t.data() + t.size(), v);
  return ec == std::errc() && end == t.data() + t.size();
}
}  // namespace

bool whole_number(std::string_view text, long& v) { return whole(text, v); }
bool whole_number(std::string_view text, int& v) { return whole(text, v); }
bool whole_number(std::string_view text, double& v) { return whole(text, v); }

void parse_image_size(const std::string& text, const std::string& option, int& width, int& height) {
  const std::size_t x = text.find('x');
  int w = 0, h = 0;
  DSPDEM_CHECK(x != std::string::npos && whole_number(std::string_view(text).substr(0, x), w) &&
                   whole_number(std::string_view(text).substr(x + 1), h),
               "{} {}: expected WIDTHxHEIGHT in whole pixels, e.g. 1280x720", option, text);
  DSPDEM_CHECK(w >= kMinImageSide && w <= kMaxImageSide && h >= kMinImageSide && h <= kMaxImageSide,
               "{} {}: each side must be {} to {} pixels (as [render] width and height)", option, text, kMinImageSide,
               kMaxImageSide);
  width = w, height = h;
}

void parse_range(const std::string& text, const std::string& option, double& min, double& max) {
  const std::size_t colon = text.find(':');
  double lo = 0, hi = 0;
  DSPDEM_CHECK(colon != std::string::npos && whole_number(std::string_view(text).substr(0, colon), lo) &&
                   whole_number(std::string_view(text).substr(colon + 1), hi) && std::isfinite(lo) && std::isfinite(hi),
               "{} {}: expected MIN:MAX, two numbers, e.g. 0:25", option, text);
  DSPDEM_CHECK(lo < hi, "{} {}: MIN must be below MAX", option, text);
  min = lo, max = hi;
}

}  // namespace dspdem
