#pragma once
// Frames drawn for the object detector's unit tests: a textured background (blocks of
// dull colours and some saturated non-object colours), rectangles of known pixel size
// and seeded pixel noise. Same seed, same bytes (core/random.hpp).

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>

#include "ferret/core/random.hpp"
#include "ferret/perception/image.hpp"

namespace ferret::test {

using Rgb = std::array<std::uint8_t, 3>;

inline std::uint8_t to_u8(double v) {
  return static_cast<std::uint8_t>(std::clamp(std::lround(v), 0L, 255L));
}

/// 8 x 8 blocks: mostly dull (saturation < 0.3) colours, one in eight a saturated
/// blue, green or purple (hues far from the object's orange).
inline RgbImage textured_background(int width_px, int height_px, std::uint64_t seed) {
  RgbImage img(width_px, height_px);
  Rng rng(seed);
  const Rgb saturated[] = {{20, 60, 220}, {30, 200, 40}, {150, 30, 200}, {0, 190, 190}};
  for (int by = 0; by < height_px; by += 8)
    for (int bx = 0; bx < width_px; bx += 8) {
      Rgb c;
      if (rng.uniform01() < 0.125) {
        c = saturated[rng.uniform_int(0, 3)];
      } else {
        const double v = rng.uniform(40, 220);
        const double s = rng.uniform(0.0, 0.25);
        const double r = rng.uniform(0, 1), g = rng.uniform(0, 1), b = rng.uniform(0, 1);
        c = {to_u8(v * (1 - s * r)), to_u8(v * (1 - s * g)), to_u8(v * (1 - s * b))};
      }
      for (int y = by; y < std::min(by + 8, height_px); ++y)
        for (int x = bx; x < std::min(bx + 8, width_px); ++x)
          for (int k = 0; k < 3; ++k) img.at(x, y, k) = c[static_cast<std::size_t>(k)];
    }
  return img;
}

/// Fills columns [x, x + w) and rows [y, y + h), clipped to the image.
inline void fill_rect(RgbImage& img, int x, int y, int w, int h, const Rgb& c) {
  for (int v = std::max(0, y); v < std::min(img.height_px, y + h); ++v)
    for (int u = std::max(0, x); u < std::min(img.width_px, x + w); ++u)
      for (int k = 0; k < 3; ++k) img.at(u, v, k) = c[static_cast<std::size_t>(k)];
}

/// Gaussian noise of `sigma` grey levels on every channel of every pixel.
inline void add_noise(RgbImage& img, double sigma, std::uint64_t seed) {
  Rng rng(seed);
  for (auto& v : img.data) v = to_u8(v + rng.normal(0.0, sigma));
}

inline constexpr Rgb kOrange{255, 110, 0};

}  // namespace ferret::test
