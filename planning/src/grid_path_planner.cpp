#include "ferret/planning/grid_path_planner.hpp"

#include <algorithm>
#include <array>

namespace ferret {
namespace {
constexpr int kStraight = 5, kDiagonal = 7;
constexpr int kBuckets = kDiagonal + 1;
constexpr int kDi[8] = {1, -1, 0, 0, 1, 1, -1, -1};
constexpr int kDj[8] = {0, 0, 1, -1, 1, -1, 1, -1};
}  // namespace

GridPathPlanner::GridPathPlanner(GridGeometry geometry)
    : geometry_(geometry),
      cost_(geometry.size(), -1),
      parent_(geometry.size(), -1),
      distance_m_(geometry.size(), kUnreachable),
      crossable_(geometry.size(), 0) {}

bool GridPathPlanner::crossable(std::size_t idx) const { return crossable_[idx] != 0; }

void GridPathPlanner::compute(const IrGrid& grid, Cell start, Traversal traversal,
                              std::span<const std::uint8_t> blocked) {
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
      distance_m_[idx] = static_cast<float>(current * to_m);
      const Cell c = geometry_.cell_of_index(idx);
      for (int k = 0; k < 8; ++k) {
        const Cell nb{c.i + kDi[k], c.j + kDj[k]};
        if (!geometry_.contains(nb)) continue;
        const std::size_t nidx = geometry_.index(nb);
        if (!crossable_[nidx]) continue;
        if (k >= 4 && (!crossable_[geometry_.index({c.i + kDi[k], c.j})] ||
                       !crossable_[geometry_.index({c.i, c.j + kDj[k]})]))
          continue;  // no corner cutting
        const int nc = current + (k < 4 ? kStraight : kDiagonal);
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
  for (std::int32_t idx = static_cast<std::int32_t>(geometry_.index(goal)); idx >= 0; idx = parent_[idx])
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
