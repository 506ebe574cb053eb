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
[[nodiscard]] std::vector<std::uint8_t> open_square(const std::vector<std::uint8_t>& mask,
                                                    int width, int height, int r);

/// The cells of `room` within `radius_cells` (Euclidean, centre to centre) of a cell of
/// `seeds`, reached from that seed through cells of `room` (8-connected): how far a
/// region reaches into its neighbourhood without jumping gaps. The seeds are not in
/// the result. Each cell keeps the seed that reached it first (a brushfire), so in
/// room bent round corners a cell may be left out that a true geodesic distance would
/// take; never one farther than the radius.
/// @pre seeds.size() == room.size() == width * height, radius_cells >= 0
[[nodiscard]] std::vector<std::uint8_t> grow_within(const std::vector<std::uint8_t>& seeds,
                                                    const std::vector<std::uint8_t>& room,
                                                    int width, int height, double radius_cells);

}  // namespace ferret
