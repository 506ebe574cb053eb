#include "ferret/planning/grid_path_planner.hpp"

#include <algorithm>
#include <array>
#include <cmath>

namespace ferret {
namespace {
constexpr int kStraight = 5, kDiagonal = 7;
constexpr int kBandPenalty = 10;  // per cell stepped into the escape band
constexpr int kBuckets = kDiagonal + kBandPenalty + 1;
constexpr int kDi[8] = {1, -1, 0, 0, 1, 1, -1, -1};
constexpr int kDj[8] = {0, 0, 1, -1, 1, -1, 1, -1};
}  // namespace

GridPathPlanner::GridPathPlanner(GridGeometry geometry)
    : geometry_(geometry),
      cost_(geometry.size(), -1),
      parent_(geometry.size(), -1),
      distance_m_(geometry.size(), kUnreachable),
      crossable_(geometry.size(), 0),
      band_(geometry.size(), 0),
      seen_(geometry.size(), 0) {}

bool GridPathPlanner::crossable(std::size_t idx) const { return crossable_[idx] != 0; }

void GridPathPlanner::compute(const IrGrid& grid, Cell start, Traversal traversal,
                              double escape_radius_m, std::span<const std::uint8_t> blocked) {
  start_ = start;
  std::fill(cost_.begin(), cost_.end(), -1);
  std::fill(distance_m_.begin(), distance_m_.end(), kUnreachable);
  const std::size_t n = geometry_.size();
  for (std::size_t idx = 0; idx < n; ++idx) {
    bool ok = traversal == Traversal::kKnownFree
                  ? grid.traversable(idx)
                  : grid.label_at(idx) != GridLabel::kOccupied && !grid.near_occupied(idx);
    if (ok && !blocked.empty() && blocked[idx]) ok = false;
    crossable_[idx] = ok ? 1 : 0;
  }
  // The escape band: cells inside the clearance band but not occupied (known free for
  // kKnownFree), connected to the start through such cells and within escape_radius_m.
  // They may be crossed, at a penalty, but are never goals (their distance stays
  // kUnreachable), so paths leave the band by the shortest way and do not hug walls.
  std::fill(band_.begin(), band_.end(), 0);
  if (escape_radius_m > 0 && geometry_.contains(start)) {
    const double r2 = std::pow(escape_radius_m / geometry_.resolution_m, 2);
    auto band_ok = [&](std::size_t idx) {
      if (crossable_[idx]) return false;
      const GridLabel label = grid.label_at(idx);
      const bool ok = traversal == Traversal::kKnownFree ? label == GridLabel::kFree
                                                         : label != GridLabel::kOccupied;
      return ok && (blocked.empty() || !blocked[idx]);
    };
    // Flood from the start through crossable and band cells (the robot may stand on
    // a small traversable island inside the band).
    std::vector<std::size_t> stack;
    std::vector<std::uint8_t>& seen = seen_;
    std::fill(seen.begin(), seen.end(), 0);
    const std::size_t s0 = geometry_.index(start);
    seen[s0] = 1;
    if (band_ok(s0)) band_[s0] = 1;
    stack.push_back(s0);
    while (!stack.empty()) {
      const Cell c = geometry_.cell_of_index(stack.back());
      stack.pop_back();
      for (int k = 0; k < 8; ++k) {
        const Cell nb{c.i + kDi[k], c.j + kDj[k]};
        if (!geometry_.contains(nb)) continue;
        const double di = nb.i - start.i, dj = nb.j - start.j;
        const std::size_t nidx = geometry_.index(nb);
        if (seen[nidx] || di * di + dj * dj > r2) continue;
        const bool band = band_ok(nidx);
        if (!band && !crossable_[nidx]) continue;
        seen[nidx] = 1;
        if (band) band_[nidx] = 1;
        stack.push_back(nidx);
      }
    }
    for (std::size_t idx = 0; idx < n; ++idx)
      if (band_[idx]) crossable_[idx] = 1;
  }
  if (!geometry_.contains(start)) return;
  // Dial's algorithm: edge costs are at most kDiagonal, so kDiagonal + 1 rotating
  // buckets hold every open cost.
  std::array<std::vector<std::size_t>, kBuckets> buckets;
  const std::size_t s = geometry_.index(start);
  cost_[s] = 0;
  parent_[s] = -1;
  buckets[0].push_back(s);
  std::size_t open = 1;
  const double to_m = geometry_.resolution_m / kStraight;
  for (int current = 0; open > 0; ++current) {
    auto& bucket = buckets[current % kBuckets];
    while (!bucket.empty()) {
      const std::size_t idx = bucket.back();
      bucket.pop_back();
      --open;
      if (cost_[idx] != current) continue;  // stale entry
      if (!band_[idx]) distance_m_[idx] = static_cast<float>(current * to_m);
      const Cell c = geometry_.cell_of_index(idx);
      for (int k = 0; k < 8; ++k) {
        const Cell nb{c.i + kDi[k], c.j + kDj[k]};
        if (!geometry_.contains(nb)) continue;
        const std::size_t nidx = geometry_.index(nb);
        if (!crossable_[nidx]) continue;
        if (k >= 4 && (!crossable_[geometry_.index({c.i + kDi[k], c.j})] ||
                       !crossable_[geometry_.index({c.i, c.j + kDj[k]})]))
          continue;  // no corner cutting
        const int nc = current + (k < 4 ? kStraight : kDiagonal) + (band_[nidx] ? kBandPenalty : 0);
        if (cost_[nidx] >= 0 && cost_[nidx] <= nc) continue;
        cost_[nidx] = nc;
        parent_[nidx] = static_cast<std::int32_t>(idx);
        buckets[nc % kBuckets].push_back(nidx);
        ++open;
      }
    }
  }
}

bool GridPathPlanner::line_of_sight(Cell a, Cell b) const {
  bool clear = true;
  trace_ray(geometry_, geometry_.center(a), geometry_.center(b), [&](Cell c, double) {
    clear = crossable_[geometry_.index(c)] != 0 || c == a;
    return clear;
  });
  return clear;
}

std::vector<Eigen::Vector2d> GridPathPlanner::path_to(Cell goal) const {
  if (!reachable(goal)) return {};
  std::vector<Cell> cells;
  for (std::int32_t idx = static_cast<std::int32_t>(geometry_.index(goal)); idx >= 0;
       idx = parent_[idx])
    cells.push_back(geometry_.cell_of_index(static_cast<std::size_t>(idx)));
  std::reverse(cells.begin(), cells.end());
  // Shortcut: from each anchor jump to the furthest following cell still in line of sight.
  std::vector<Eigen::Vector2d> out{geometry_.center(cells.front())};
  std::size_t anchor = 0;
  while (anchor + 1 < cells.size()) {
    // Greedy forward: linear in the path length times the shortcut length.
    std::size_t next = anchor + 1;
    while (next + 1 < cells.size() && line_of_sight(cells[anchor], cells[next + 1])) ++next;
    out.push_back(geometry_.center(cells[next]));
    anchor = next;
  }
  return out;
}

}  // namespace ferret
