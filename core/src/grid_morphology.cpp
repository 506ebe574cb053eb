#include "ferret/core/grid_morphology.hpp"

#include <algorithm>
#include <cstddef>

namespace ferret {
namespace {

// Separable min (erode) or max (dilate) over the square; in-grid cells only (so the
// outside counts as set for the min, unset for the max).
std::vector<std::uint8_t> filter(const std::vector<std::uint8_t>& in, int w, int h, int r, bool erode) {
  std::vector<std::uint8_t> rows(in.size()), out(in.size());
  const auto at = [w](int i, int j) { return static_cast<std::size_t>(j) * w + i; };
  for (int j = 0; j < h; ++j)
    for (int i = 0; i < w; ++i) {
      std::uint8_t v = erode ? 1 : 0;
      for (int k = std::max(0, i - r); k <= std::min(w - 1, i + r); ++k)
        v = erode ? (v & in[at(k, j)]) : (v | in[at(k, j)]);
      rows[at(i, j)] = v;
    }
  for (int j = 0; j < h; ++j)
    for (int i = 0; i < w; ++i) {
      std::uint8_t v = erode ? 1 : 0;
      for (int k = std::max(0, j - r); k <= std::min(h - 1, j + r); ++k)
        v = erode ? (v & rows[at(i, k)]) : (v | rows[at(i, k)]);
      out[at(i, j)] = v;
    }
  return out;
}

}  // namespace

std::vector<std::uint8_t> open_square(const std::vector<std::uint8_t>& mask, int width, int height, int r) {
  std::vector<std::uint8_t> unit(mask.size());
  for (std::size_t i = 0; i < mask.size(); ++i) unit[i] = mask[i] != 0;
  std::vector<std::uint8_t> opened = filter(filter(unit, width, height, r, true), width, height, r, false);
  for (std::size_t i = 0; i < opened.size(); ++i) opened[i] &= unit[i];
  return opened;
}

}  // namespace ferret
