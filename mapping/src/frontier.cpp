#include "ferret/mapping/frontier.hpp"

#include <algorithm>
#include <cmath>

namespace ferret {
namespace {
constexpr int kDi[8] = {1, -1, 0, 0, 1, 1, -1, -1};
constexpr int kDj[8] = {0, 0, 1, -1, 1, -1, 1, -1};
}  // namespace

FrontierTracker::FrontierTracker(GridGeometry geometry, Options options)
    : geometry_(geometry),
      options_(options),
      flag_(geometry.size(), 0),
      pos_(geometry.size(), -1),
      blacklist_(geometry.size(), 0) {}

void FrontierTracker::refresh(const IrGrid& grid, std::size_t idx) {
  bool frontier = false;
  if (grid.label_at(idx) == GridLabel::kFree) {
    const Cell c = geometry_.cell_of_index(idx);
    for (int k = 0; k < 8 && !frontier; ++k) {
      const Cell n{c.i + kDi[k], c.j + kDj[k]};
      frontier = geometry_.contains(n) && grid.label(n) == GridLabel::kUnknown;
    }
  }
  if (frontier == (flag_[idx] != 0)) return;
  flag_[idx] = frontier ? 1 : 0;
  if (frontier) {
    pos_[idx] = static_cast<std::int32_t>(cells_.size());
    cells_.push_back(idx);
  } else {
    const auto p = static_cast<std::size_t>(pos_[idx]);
    cells_[p] = cells_.back();
    pos_[cells_[p]] = static_cast<std::int32_t>(p);
    cells_.pop_back();
    pos_[idx] = -1;
  }
}

void FrontierTracker::update(IrGrid& grid) {
  for (const std::size_t idx : grid.take_changed_cells()) {
    const Cell c = geometry_.cell_of_index(idx);
    refresh(grid, idx);
    for (int k = 0; k < 8; ++k) {
      const Cell n{c.i + kDi[k], c.j + kDj[k]};
      if (geometry_.contains(n)) refresh(grid, geometry_.index(n));
    }
  }
}

void FrontierTracker::rebuild(const IrGrid& grid) {
  for (std::size_t idx = 0; idx < geometry_.size(); ++idx) refresh(grid, idx);
}

void FrontierTracker::clear_blacklist(std::uint8_t kind) {
  for (auto& b : blacklist_)
    if (b == kind) b = 0;
}

void FrontierTracker::blacklist(Cell c, std::uint8_t kind) {
  const int r = static_cast<int>(std::ceil(options_.blacklist_radius_m / geometry_.resolution_m));
  const Eigen::Vector2d p = geometry_.center(c);
  for (int dj = -r; dj <= r; ++dj)
    for (int di = -r; di <= r; ++di) {
      const Cell n{c.i + di, c.j + dj};
      if (geometry_.contains(n) &&
          (geometry_.center(n) - p).norm() <= options_.blacklist_radius_m + 1e-9 &&
          blacklist_[geometry_.index(n)] == 0)
        blacklist_[geometry_.index(n)] = kind;
    }
}

FrontierSets FrontierTracker::extract(std::span<const float> path_distance_m, const Pose2& X_WS,
                                      double ir_fov_rad, double ir_range_m) const {
  FrontierSets out;
  // Sorted so that the sets (and every choice made from them) do not depend on the
  // order in which cells became frontier.
  std::vector<std::size_t> members;
  for (const std::size_t idx : cells_)
    if (!blacklist_[idx] && path_distance_m[idx] != kUnreachable) members.push_back(idx);
  std::sort(members.begin(), members.end());
  const Eigen::Vector2d p_WS = X_WS.position();
  for (const std::size_t idx : members) {
    const Cell c = geometry_.cell_of_index(idx);
    out.global.push_back(c);
    const Eigen::Vector2d d = geometry_.center(c) - p_WS;
    if (d.norm() <= ir_range_m &&
        std::abs(wrap_angle_rad(std::atan2(d.y(), d.x()) - X_WS.yaw_rad)) <= ir_fov_rad / 2)
      out.visible.push_back(c);
  }
  // Cluster F_g: flood fill over 8-neighbours that are members too. The marks (1 a
  // member, 2 a member seen) are cleared again through the members, so a call costs
  // what the frontier holds, not the grid's size.
  std::vector<std::uint8_t>& mark = cluster_marks_;
  if (mark.size() != geometry_.size()) mark.assign(geometry_.size(), 0);
  for (const std::size_t idx : members) mark[idx] = 1;
  std::vector<std::size_t> stack;
  for (const std::size_t seed : members) {
    if (mark[seed] == 2) continue;
    FrontierCluster cluster;
    mark[seed] = 2;
    stack.push_back(seed);
    while (!stack.empty()) {
      const std::size_t idx = stack.back();
      stack.pop_back();
      const Cell c = geometry_.cell_of_index(idx);
      cluster.cells.push_back(c);
      cluster.centroid_W += geometry_.center(c);
      for (int k = 0; k < 8; ++k) {
        const Cell n{c.i + kDi[k], c.j + kDj[k]};
        if (!geometry_.contains(n)) continue;
        const std::size_t nidx = geometry_.index(n);
        if (mark[nidx] == 1) {
          mark[nidx] = 2;
          stack.push_back(nidx);
        }
      }
    }
    cluster.centroid_W /= static_cast<double>(cluster.cells.size());
    double best = 1e300;
    for (const Cell& c : cluster.cells) {
      const double d = (geometry_.center(c) - cluster.centroid_W).squaredNorm();
      if (d < best) {
        best = d;
        cluster.representative = c;
      }
    }
    out.clusters.push_back(std::move(cluster));
  }
  for (const std::size_t idx : members) mark[idx] = 0;
  return out;
}

}  // namespace ferret
