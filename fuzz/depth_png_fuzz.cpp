// Bytes -> a 16-bit depth PNG (decode_depth_png); a frame that decodes is encoded again
// and must decode to the same millimetres.
#include <cstdint>
#include <cstdlib>
#include <vector>

#include "ferret/core/error.hpp"
#include "ferret/perception/image.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::vector<std::uint8_t> bytes(data, data + size);
  ferret::DepthImageMm depth;
  try {
    depth = ferret::decode_depth_png(bytes, "fuzz.png");
  } catch (const ferret::InputError&) {
    return 0;
  }
  if (depth.width_px < 1 || depth.height_px < 1 || depth.width_px > ferret::kMaxImageSidePx ||
      depth.height_px > ferret::kMaxImageSidePx ||
      depth.data.size() != static_cast<std::size_t>(depth.width_px) * depth.height_px)
    std::abort();
  const ferret::DepthImageMm back = ferret::decode_depth_png(ferret::encode_png(depth), "again");
  if (back.width_px != depth.width_px || back.height_px != depth.height_px ||
      back.data != depth.data)
    std::abort();
  return 0;
}
