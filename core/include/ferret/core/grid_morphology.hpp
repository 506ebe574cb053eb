#pragma once
// Binary morphology on a grid's cells (row-major masks, 0 or 1 a cell).

#include <cstdint>
#include <vector>

namespace ferret {

/// Opening by a (2r+1) x (2r+1) square: erosion, then dilation. What remains of the
/// mask are the places a whole square fits in it; specks and strips narrower than the
/// square vanish. Cells outside the grid count as set during the erosion (a region at
/// the border is not shaved off by the border). The result is a subset of `mask`.
/// @pre mask.size() == width * height, r >= 0
[[nodiscard]] std::vector<std::uint8_t> open_square(const std::vector<std::uint8_t>& mask, int width,
                                                    int height, int r);

}  // namespace ferret
