#include "ferret/core/grid_morphology.hpp"

#include <algorithm>
#include <cstddef>
#include <deque>

namespace ferret {
namespace {

// Separable min (erode) or max (dilate) over the square; in-grid cells only (so the
// outside counts as set for the min, unset for the max). On 0/1 masks both are counts
// over a sliding window: the min is set when every in-grid cell of it is, the max when
// any is. O(1) a cell whatever r (a decision cycle opens the whole map).
std::vector<std::uint8_t> filter(const std::vector<std::uint8_t>& in, int w, int h, int r,
                                 bool erode) {
  std::vector<std::uint8_t> rows(in.size()), out(in.size());
  const auto at = [w](int i, int j) { return static_cast<std::size_t>(j) * w + i; };
  const auto decide = [erode](int count, int cells) -> std::uint8_t {
    return erode ? count == cells : count > 0;
  };
  std::vector<int> prefix(static_cast<std::size_t>(w) + 1);
  for (int j = 0; j < h; ++j) {
    for (int i = 0; i < w; ++i) prefix[i + 1] = prefix[i] + in[at(i, j)];
    for (int i = 0; i < w; ++i) {
      const int lo = std::max(0, i - r), hi = std::min(w - 1, i + r);
      rows[at(i, j)] = decide(prefix[hi + 1] - prefix[lo], hi - lo + 1);
    }
  }
  // Columns: a running sum of each column over rows [j - r, j + r].
  std::vector<int> sum(static_cast<std::size_t>(w), 0);
  for (int k = 0; k <= std::min(h - 1, r); ++k)
    for (int i = 0; i < w; ++i) sum[i] += rows[at(i, k)];
  for (int j = 0; j < h; ++j) {
    const int lo = std::max(0, j - r), hi = std::min(h - 1, j + r);
    for (int i = 0; i < w; ++i) out[at(i, j)] = decide(sum[i], hi - lo + 1);
    if (j + r + 1 < h)
      for (int i = 0; i < w; ++i) sum[i] += rows[at(i, j + r + 1)];
    if (j - r >= 0)
      for (int i = 0; i < w; ++i) sum[i] -= rows[at(i, j - r)];
  }
  return out;
}

}  // namespace

std::vector<std::uint8_t> open_square(const std::vector<std::uint8_t>& mask, int width, int height,
                                      int r) {
  std::vector<std::uint8_t> unit(mask.size());
  for (std::size_t i = 0; i < mask.size(); ++i) unit[i] = mask[i] != 0;
  std::vector<std::uint8_t> opened =
      filter(filter(unit, width, height, r, true), width, height, r, false);
  for (std::size_t i = 0; i < opened.size(); ++i) opened[i] &= unit[i];
  return opened;
}

std::vector<std::uint8_t> grow_within(const std::vector<std::uint8_t>& seeds,
                                      const std::vector<std::uint8_t>& room, int width, int height,
                                      double radius_cells) {
  // Breadth-first from every seed at once, each cell carrying the seed it came from;
  // a neighbour is taken when it is room and within the radius of that seed.
  std::vector<std::uint8_t> grown(room.size(), 0);
  std::vector<int> source(room.size(), -1);
  std::deque<int> queue;
  for (std::size_t i = 0; i < seeds.size(); ++i)
    if (seeds[i]) {
      source[i] = static_cast<int>(i);
      queue.push_back(static_cast<int>(i));
    }
  const double r2 = radius_cells * radius_cells;
  while (!queue.empty()) {
    const int c = queue.front();
    queue.pop_front();
    const int ci = c % width, cj = c / width;
    const int s = source[static_cast<std::size_t>(c)];
    const int si = s % width, sj = s / width;
    for (int dj = -1; dj <= 1; ++dj)
      for (int di = -1; di <= 1; ++di) {
        const int ni = ci + di, nj = cj + dj;
        if ((di == 0 && dj == 0) || ni < 0 || nj < 0 || ni >= width || nj >= height) continue;
        const auto n = static_cast<std::size_t>(nj) * width + ni;
        if (source[n] >= 0 || !room[n]) continue;
        const double dx = ni - si, dy = nj - sj;
        if (!(dx * dx + dy * dy <= r2)) continue;  // (a NaN radius grows nothing)
        source[n] = s;
        grown[n] = 1;
        queue.push_back(static_cast<int>(n));
      }
  }
  return grown;
}

}  // namespace ferret
