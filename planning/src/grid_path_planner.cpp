#include "ferret/planning/grid_path_planner.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

namespace ferret {
namespace {
constexpr int kStraight = 5, kDiagonal = 7;
constexpr int kBandPenalty = 10;  // per cell stepped into the escape band
constexpr int kDi[8] = {1, -1, 0, 0, 1, 1, -1, -1};
constexpr int kDj[8] = {0, 0, 1, -1, 1, -1, 1, -1};
}  // namespace

GridPathPlanner::GridPathPlanner(GridGeometry geometry, double body_radius_m)
    : geometry_(geometry),
      body_radius_m_(std::isfinite(body_radius_m) ? std::max(0.0, body_radius_m) : 0.0),
      padded_width_(static_cast<std::size_t>(std::max(0, geometry.width)) + 2),
      cost_(geometry.size(), -1),
      parent_(geometry.size(), -1),
      distance_m_(geometry.size(), kUnreachable),
      cross_(padded_width_ * (static_cast<std::size_t>(std::max(0, geometry.height)) + 2), 0),
      seen_(geometry.size(), 0) {
  for (int k = 0; k < 8; ++k) {
    grid_step_[k] = kDi[k] + static_cast<std::ptrdiff_t>(kDj[k]) * geometry_.width;
    padded_step_[k] = kDi[k] + kDj[k] * static_cast<std::ptrdiff_t>(padded_width_);
  }
  if (body_radius_m_ > 0.0 && geometry_.resolution_m > 0.0) {
    const double reach = body_radius_m_ / geometry_.resolution_m + 0.5;  // in cells
    const int n = static_cast<int>(std::floor(reach));
    for (int dj = -n; dj <= n; ++dj)
      for (int di = -n; di <= n; ++di)
        if (di * di + dj * dj <= reach * reach) body_offsets_.push_back({di, dj});
  }
  // Queue entries hold 32-bit indices.
  if (cross_.size() > std::numeric_limits<std::uint32_t>::max())
    throw std::invalid_argument("GridPathPlanner: grid of " + std::to_string(geometry.size()) +
                                " cells is too large");
}

void GridPathPlanner::set_crossable(const IrGrid& grid, Traversal traversal,
                                    std::span<const std::uint8_t> blocked, Cell c) {
  const std::size_t idx = geometry_.index(c);
  bool ok = traversal == Traversal::kKnownFree
                ? grid.traversable(idx)
                : grid.label_at(idx) != GridLabel::kOccupied && !grid.near_occupied(idx);
  if (ok && !blocked.empty() && blocked[idx]) ok = false;
  cross_[padded(c)] = ok ? 1 : 0;
}

void GridPathPlanner::refresh_crossable(const IrGrid& grid, Traversal traversal,
                                        std::span<const std::uint8_t> blocked) {
  const BlockRevisions& revisions = grid.label_revisions();
  // Whether a cell may be crossed depends on the labels within the clearance of it
  // (near_occupied): a block is looked at again when a block within that reach changed.
  const bool same = crossable_from_.valid && crossable_from_.lineage == revisions.lineage() &&
                    crossable_from_.traversal == traversal && blocked.empty();
  const int reach =
      static_cast<int>(std::ceil(grid.options().clearance_m / geometry_.resolution_m)) + 1;
  const int b = revisions.block_cells();
  for (int j0 = 0; j0 < geometry_.height; j0 += b)
    for (int i0 = 0; i0 < geometry_.width; i0 += b) {
      const int i1 = std::min(i0 + b, geometry_.width) - 1,
                j1 = std::min(j0 + b, geometry_.height) - 1;
      if (same && revisions.unchanged_since(crossable_from_.revision, {i0 - reach, j0 - reach},
                                            {i1 + reach, j1 + reach}))
        continue;
      for (int j = j0; j <= j1; ++j)
        for (int i = i0; i <= i1; ++i) set_crossable(grid, traversal, blocked, {i, j});
    }
  // A field with blocked cells is not kept: the next one may block others.
  crossable_from_ = {revisions.lineage(), revisions.revision(), traversal, blocked.empty()};
}

void GridPathPlanner::compute(const IrGrid& grid, Cell start, Traversal traversal,
                              double escape_radius_m, std::span<const std::uint8_t> blocked) {
  const GridGeometry& gg = grid.geometry();
  if (gg.width != geometry_.width || gg.height != geometry_.height)
    throw std::invalid_argument("GridPathPlanner: the grid's size differs from the planner's");
  start_ = start;
  for (const std::size_t idx : reached_) {
    cost_[idx] = -1;
    distance_m_[idx] = kUnreachable;
  }
  reached_.clear();
  for (const std::size_t p : band_cells_) cross_[p] = 0;  // band cells are never crossable
  band_cells_.clear();
  refresh_crossable(grid, traversal, blocked);
  // The escape band: cells inside the clearance band but not occupied (known free for
  // kKnownFree), connected to the start through such cells and within escape_radius_m.
  // They may be crossed, at a penalty, but are never goals (their distance stays
  // kUnreachable), so paths leave the band by the shortest way and do not hug walls.
  if (escape_radius_m > 0 && geometry_.contains(start)) {
    const double r2 = std::pow(escape_radius_m / geometry_.resolution_m, 2);
    // A robot already touching a wall may back off through what touches it too, near it
    // and never closer to the wall than it stands.
    const double body_r2 = std::pow(body_radius_m_ / geometry_.resolution_m, 2);
    const int start_gap2 = nearest_occupied2(grid, start);
    auto band_ok = [&](Cell c, std::size_t idx) {
      if (cross_[padded(c)] == 1) return false;
      const GridLabel label = grid.label_at(idx);
      const bool ok = traversal == Traversal::kKnownFree ? label == GridLabel::kFree
                                                         : label != GridLabel::kOccupied;
      if (!ok || (!blocked.empty() && blocked[idx])) return false;
      const int gap2 = nearest_occupied2(grid, c);
      if (gap2 == kNoneNear) return true;
      const double di = c.i - start.i, dj = c.j - start.j;
      return start_gap2 != kNoneNear && gap2 >= start_gap2 && di * di + dj * dj <= body_r2;
    };
    auto mark_band = [&](Cell c) {
      const std::size_t p = padded(c);
      cross_[p] = 2;
      band_cells_.push_back(p);
    };
    // Flood from the start through crossable and band cells (the robot may stand on
    // a small traversable island inside the band).
    for (const std::size_t idx : seen_cells_) seen_[idx] = 0;
    seen_cells_.clear();
    std::vector<Cell> stack;
    const std::size_t s0 = geometry_.index(start);
    seen_[s0] = 1;
    seen_cells_.push_back(s0);
    if (band_ok(start, s0)) mark_band(start);
    stack.push_back(start);
    while (!stack.empty()) {
      const Cell c = stack.back();
      stack.pop_back();
      for (int k = 0; k < 8; ++k) {
        const Cell nb{c.i + kDi[k], c.j + kDj[k]};
        if (!geometry_.contains(nb)) continue;
        const double di = nb.i - start.i, dj = nb.j - start.j;
        const std::size_t nidx = geometry_.index(nb);
        if (seen_[nidx] || di * di + dj * dj > r2) continue;
        const bool band = band_ok(nb, nidx);
        if (!band && cross_[padded(nb)] != 1) continue;
        seen_[nidx] = 1;
        seen_cells_.push_back(nidx);
        if (band) mark_band(nb);
        stack.push_back(nb);
      }
    }
  }
  for (auto& bucket : buckets_) bucket.clear();  // what the last field left open
  open_ = 0;
  current_ = 0;
  if (!geometry_.contains(start)) return;
  const std::size_t s = geometry_.index(start);
  cost_[s] = 0;
  parent_[s] = -1;
  reached_.push_back(s);
  buckets_[0].push_back({static_cast<std::uint32_t>(s), static_cast<std::uint32_t>(padded(start))});
  open_ = 1;
}

// Dial's algorithm: edge costs are at most kDiagonal + kBandPenalty, so that many plus
// one rotating buckets hold every open cost. Each entry carries the cell's index in the
// grid and in the padded layout, so neighbours are found by adding offsets.
void GridPathPlanner::expand_bucket() const {
  static_assert(kBuckets == kDiagonal + kBandPenalty + 1);
  auto& bucket = buckets_[static_cast<std::size_t>(current_ % kBuckets)];
  const double to_m = geometry_.resolution_m / kStraight;
  const std::uint8_t* cross = cross_.data();
  const auto pw = static_cast<std::ptrdiff_t>(padded_width_);
  while (!bucket.empty()) {
    const Entry e = bucket.back();
    bucket.pop_back();
    --open_;
    if (cost_[e.grid] != current_) continue;  // stale entry
    if (cross[e.padded] != 2) distance_m_[e.grid] = static_cast<float>(current_ * to_m);
    for (int k = 0; k < 8; ++k) {
      const std::size_t np = static_cast<std::size_t>(e.padded + padded_step_[k]);
      if (!cross[np]) continue;
      if (k >= 4 && (!cross[e.padded + kDi[k]] || !cross[e.padded + kDj[k] * pw]))
        continue;  // no corner cutting
      const auto nidx = static_cast<std::size_t>(e.grid + grid_step_[k]);
      const int nc =
          current_ + (k < 4 ? kStraight : kDiagonal) + (cross[np] == 2 ? kBandPenalty : 0);
      if (cost_[nidx] >= 0 && cost_[nidx] <= nc) continue;
      if (cost_[nidx] < 0) reached_.push_back(nidx);
      cost_[nidx] = nc;
      parent_[nidx] = static_cast<std::int32_t>(e.grid);
      buckets_[static_cast<std::size_t>(nc % kBuckets)].push_back(
          {static_cast<std::uint32_t>(nidx), static_cast<std::uint32_t>(np)});
      ++open_;
    }
  }
  ++current_;
}

int GridPathPlanner::nearest_occupied2(const IrGrid& grid, Cell c) const {
  int best = kNoneNear;
  for (const Cell& d : body_offsets_) {
    const Cell n{c.i + d.i, c.j + d.j};
    if (geometry_.contains(n) && grid.label(n) == GridLabel::kOccupied)
      best = std::min(best, d.i * d.i + d.j * d.j);
  }
  return best;
}

bool GridPathPlanner::line_of_sight(Cell a, Cell b) const {
  bool clear = true;
  trace_ray(geometry_, geometry_.center(a), geometry_.center(b), [&](Cell c, double) {
    clear = cross_[padded(c)] != 0 || c == a;
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
