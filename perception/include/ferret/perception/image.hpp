#pragma once
// Images as plain buffers, so that headers across ferret stay free of OpenCV: 8-bit
// grey and colour frames, and 16-bit depth frames in millimetres along the optical
// axis (the RealSense convention; 0 = no return). Rows top to bottom, pixels left to
// right, channels interleaved (colour: R, G, B).

#include <cstdint>
#include <filesystem>
#include <vector>

namespace ferret {

template <typename T, int Channels>
struct Image {
  int width_px = 0;
  int height_px = 0;
  std::vector<T> data;  ///< width * height * Channels values

  Image() = default;
  Image(int width, int height, T fill = T{})
      : width_px(width),
        height_px(height),
        data(static_cast<std::size_t>(width) * static_cast<std::size_t>(height) * Channels, fill) {}

  [[nodiscard]] bool empty() const { return data.empty(); }
  [[nodiscard]] T& at(int x, int y, int c = 0) {
    return data[(static_cast<std::size_t>(y) * static_cast<std::size_t>(width_px) +
                 static_cast<std::size_t>(x)) *
                    Channels +
                static_cast<std::size_t>(c)];
  }
  [[nodiscard]] const T& at(int x, int y, int c = 0) const {
    return data[(static_cast<std::size_t>(y) * static_cast<std::size_t>(width_px) +
                 static_cast<std::size_t>(x)) *
                    Channels +
                static_cast<std::size_t>(c)];
  }
};

using GrayImage = Image<std::uint8_t, 1>;
using RgbImage = Image<std::uint8_t, 3>;
/// Millimetres along the optical axis; 0 = no return.
using DepthImageMm = Image<std::uint16_t, 1>;

/// Largest width or height ferret reads (a larger image is bad input, not a long run).
inline constexpr int kMaxImageSidePx = 16384;

/// Reads a colour or grey camera frame (PNG or JPEG),
/// converted to grey / RGB. Throws InputError naming the file for a missing file, a
/// file that is not an image, and a size beyond kMaxImageSidePx.
[[nodiscard]] GrayImage read_gray_image(const std::filesystem::path& path);
[[nodiscard]] RgbImage read_rgb_image(const std::filesystem::path& path);
/// Reads a depth frame: a single-channel 16-bit PNG of millimetres. An 8-bit or colour
/// PNG is bad input (InputError naming the bit depth found).
[[nodiscard]] DepthImageMm read_depth_png(const std::filesystem::path& path);

/// PNG bytes (8-bit grey, 8-bit RGB, 16-bit grey), for an OutputSet or a file.
[[nodiscard]] std::vector<std::uint8_t> encode_png(const GrayImage& image);
[[nodiscard]] std::vector<std::uint8_t> encode_png(const RgbImage& image);
[[nodiscard]] std::vector<std::uint8_t> encode_png(const DepthImageMm& image);
/// Decoders of in-memory bytes (the readers above and the fuzz targets); `source`
/// names the input in errors.
[[nodiscard]] RgbImage decode_rgb_image(const std::vector<std::uint8_t>& bytes,
                                        const std::string& source);
[[nodiscard]] GrayImage decode_gray_image(const std::vector<std::uint8_t>& bytes,
                                          const std::string& source);
[[nodiscard]] DepthImageMm decode_depth_png(const std::vector<std::uint8_t>& bytes,
                                            const std::string& source);

}  // namespace ferret
