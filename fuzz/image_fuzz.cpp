// Bytes -> a colour camera frame (decode_rgb_image: PNG of any colour type and depth,
// JPEG), and the same bytes as a grey frame; both must agree on the size.
#include <cstdint>
#include <cstdlib>
#include <vector>

#include "ferret/core/error.hpp"
#include "ferret/perception/image.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::vector<std::uint8_t> bytes(data, data + size);
  ferret::RgbImage rgb;
  try {
    rgb = ferret::decode_rgb_image(bytes, "fuzz.img");
  } catch (const ferret::InputError&) {
    return 0;
  }
  if (rgb.width_px < 1 || rgb.height_px < 1 || rgb.width_px > ferret::kMaxImageSidePx ||
      rgb.height_px > ferret::kMaxImageSidePx ||
      rgb.data.size() != static_cast<std::size_t>(rgb.width_px) * rgb.height_px * 3)
    std::abort();
  // The grey decoder reads the same headers: it decodes too, at the same size.
  const ferret::GrayImage gray = ferret::decode_gray_image(bytes, "fuzz.img");
  if (gray.width_px != rgb.width_px || gray.height_px != rgb.height_px) std::abort();
  return 0;
}
