#include "ferret/tether_model/taut_tether.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>

#include "ferret/mapping/occupancy_map_2d.hpp"

namespace ferret {
namespace {

const std::array<Eigen::Vector2d, 4> kQuadrantDiagonal{
    Eigen::Vector2d{1, 1}, Eigen::Vector2d{-1, 1}, Eigen::Vector2d{-1, -1}, Eigen::Vector2d{1, -1}};

double cross(const Eigen::Vector2d& a, const Eigen::Vector2d& b) {
  return a.x() * b.y() - a.y() * b.x();
}

// Whether an obstacle at the corner lies on the `side` of the line from the anchor
// through the corner (direction v): only then can a sweep turning that way hit it.
bool obstacle_on_side(const TetherCorner& c, const Eigen::Vector2d& v, int side) {
  for (int q = 0; q < 4; ++q)
    if ((c.occupied_quadrants >> q & 1) && side * cross(v, kQuadrantDiagonal[q]) > 0) return true;
  return false;
}

}  // namespace

TetherCorners::TetherCorners(std::vector<TetherCorner> corners) : corners_(std::move(corners)) {
  if (corners_.empty()) return;
  Eigen::Vector2d hi = corners_.front().p_W;
  lo_ = hi;
  for (const auto& c : corners_) {
    lo_ = lo_.cwiseMin(c.p_W);
    hi = hi.cwiseMax(c.p_W);
  }
  // About a few corners a bucket: side length from the extent and the count.
  const Eigen::Vector2d ext = (hi - lo_).cwiseMax(1e-3);
  bucket_m_ =
      std::max(std::sqrt(ext.x() * ext.y() * 4.0 / static_cast<double>(corners_.size())), 0.05);
  nx_ = static_cast<int>(ext.x() / bucket_m_) + 1;
  ny_ = static_cast<int>(ext.y() / bucket_m_) + 1;
  buckets_.assign(static_cast<std::size_t>(nx_) * ny_, {});
  for (std::uint32_t k = 0; k < corners_.size(); ++k) {
    const int i =
        std::clamp(static_cast<int>((corners_[k].p_W.x() - lo_.x()) / bucket_m_), 0, nx_ - 1);
    const int j =
        std::clamp(static_cast<int>((corners_[k].p_W.y() - lo_.y()) / bucket_m_), 0, ny_ - 1);
    buckets_[static_cast<std::size_t>(j) * nx_ + i].push_back(k);
  }
}

std::shared_ptr<const TetherCorners> TetherCorners::from_list(std::vector<TetherCorner> corners) {
  return std::shared_ptr<const TetherCorners>(new TetherCorners(std::move(corners)));
}

std::shared_ptr<const TetherCorners> TetherCorners::from_grid(
    const GridGeometry& g, const std::function<bool(Cell)>& blocked) {
  std::vector<char> occ(g.size());
  for (std::size_t k = 0; k < g.size(); ++k) occ[k] = blocked(g.cell_of_index(k)) ? 1 : 0;
  auto at = [&](int i, int j) { return g.contains({i, j}) && occ[g.index({i, j})]; };
  std::vector<TetherCorner> corners;
  // Grid vertex (i, j) is the lower-left corner of cell (i, j). Its quadrants, in
  // kQuadrantDiagonal order, are the cells (i, j), (i-1, j), (i-1, j-1), (i, j-1).
  for (int j = 0; j <= g.height; ++j) {
    for (int i = 0; i <= g.width; ++i) {
      const std::uint8_t q = static_cast<std::uint8_t>(at(i, j) | at(i - 1, j) << 1 |
                                                       at(i - 1, j - 1) << 2 | at(i, j - 1) << 3);
      // Convex for the free space's point of view: one occupied quadrant, or two
      // opposite ones (a pinch, convex on both sides).
      if (q == 1 || q == 2 || q == 4 || q == 8 || q == 5 || q == 10)
        corners.push_back(
            {{g.origin_x_m + i * g.resolution_m, g.origin_y_m + j * g.resolution_m}, q});
    }
  }
  return from_list(std::move(corners));
}

std::shared_ptr<const TetherCorners> TetherCorners::from_map(const OccupancyMap2D& map,
                                                             bool unknown_blocks) {
  return from_grid(map.geometry, [&](Cell c) {
    const CellState s = map.at(c);
    return s == CellState::kOccupied || (unknown_blocks && s == CellState::kUnknown);
  });
}

void TetherCorners::for_each_in_box(const Eigen::Vector2d& lo, const Eigen::Vector2d& hi,
                                    const std::function<void(const TetherCorner&)>& visit) const {
  if (corners_.empty()) return;
  const int i0 = std::max(static_cast<int>(std::floor((lo.x() - lo_.x()) / bucket_m_)), 0);
  const int j0 = std::max(static_cast<int>(std::floor((lo.y() - lo_.y()) / bucket_m_)), 0);
  const int i1 = std::min(static_cast<int>(std::floor((hi.x() - lo_.x()) / bucket_m_)), nx_ - 1);
  const int j1 = std::min(static_cast<int>(std::floor((hi.y() - lo_.y()) / bucket_m_)), ny_ - 1);
  for (int j = j0; j <= j1; ++j)
    for (int i = i0; i <= i1; ++i)
      for (const std::uint32_t k : buckets_[static_cast<std::size_t>(j) * nx_ + i])
        visit(corners_[k]);
}

TautTether::TautTether(std::shared_ptr<const TetherCorners> corners, const Eigen::Vector2d& p_WE,
                       const Eigen::Vector2d& p_WR)
    : corners_(std::move(corners)), p_WE_(p_WE), p_WR_(p_WR) {}

TautTether::TautTether(std::shared_ptr<const TetherCorners> corners, const Eigen::Vector2d& p_WE,
                       std::vector<WrapPoint> wraps, const Eigen::Vector2d& p_WR)
    : corners_(std::move(corners)), p_WE_(p_WE), p_WR_(p_WR), wraps_(std::move(wraps)) {
  update_fixed_length();
}

void TautTether::update_fixed_length() {
  fixed_length_m_ = 0.0;
  Eigen::Vector2d from = p_WE_;
  for (const auto& w : wraps_) {
    fixed_length_m_ += (w.p_W - from).norm();
    from = w.p_W;
  }
}

std::vector<Eigen::Vector2d> TautTether::polyline() const {
  std::vector<Eigen::Vector2d> out{p_WE_};
  for (const auto& w : wraps_) out.push_back(w.p_W);
  out.push_back(p_WR_);
  return out;
}

void TautTether::move_to(const Eigen::Vector2d& p_target) {
  constexpr double kEps = 1e-9;
  Eigen::Vector2d p = p_WR_;
  // Each event (a wrap or an unwrap) consumes part of the motion; the guard only
  // protects against a degenerate geometry cycling at one point.
  for (int guard = 0; guard < 100000; ++guard) {
    const Eigen::Vector2d d = p_target - p;
    if (d.squaredNorm() < kEps * kEps) break;
    const Eigen::Vector2d a = anchor();
    double best_t = std::numeric_limits<double>::infinity();
    const TetherCorner* wrap = nullptr;
    bool unwrap = false;

    // Unwrap: the robot crosses the line through the previous anchor and the last
    // wrap point to the side where the tether no longer bends around the corner.
    if (!wraps_.empty()) {
      const Eigen::Vector2d prev = wraps_.size() >= 2 ? wraps_[wraps_.size() - 2].p_W : p_WE_;
      const WrapPoint& w = wraps_.back();
      const Eigen::Vector2d u = w.p_W - prev;
      const double f0 = w.side * cross(u, p - w.p_W);
      const double f1 = w.side * cross(u, d);
      if (f1 < 0) {
        const double t = std::max(f0 / -f1, 0.0);
        if (t <= 1.0) {
          best_t = t;
          unwrap = true;
        }
      }
    }

    // Wrap: the first corner the sweeping segment (a, p + t d) meets.
    const double turn = cross(p - a, d);
    if (std::abs(turn) > kEps * kEps) {
      const int side = turn > 0 ? 1 : -1;
      const Eigen::Vector2d lo = a.cwiseMin(p).cwiseMin(p_target),
                            hi = a.cwiseMax(p).cwiseMax(p_target);
      double best_dist = std::numeric_limits<double>::infinity();
      corners_->for_each_in_box(lo.array() - kEps, hi.array() + kEps, [&](const TetherCorner& c) {
        const Eigen::Vector2d v = c.p_W - a;
        const double dist2 = v.squaredNorm();
        if (dist2 < kEps * kEps) return;
        const double den = cross(v, d);
        if (std::abs(den) < kEps * kEps) return;
        const double t = -cross(v, p - a) / den;
        if (t < -kEps || t > 1.0 || t > best_t + kEps) return;
        const Eigen::Vector2d q = p + std::max(t, 0.0) * d - a;
        if (v.dot(q) <= 0 || dist2 > q.squaredNorm() + kEps) return;
        if (!obstacle_on_side(c, v, side)) return;
        const bool better = t < best_t - kEps || (!unwrap && dist2 < best_dist);
        if (!better) return;
        best_t = std::max(t, 0.0);
        best_dist = dist2;
        wrap = &c;
        unwrap = false;
      });
      if (wrap) wraps_.push_back({wrap->p_W, side});
    }

    if (!wrap && !unwrap) break;
    p += best_t * d;
    if (unwrap) wraps_.pop_back();
    update_fixed_length();  // a handful of segments
  }
  p_WR_ = p_target;
}

std::vector<Eigen::Vector2d> way_back_along_tether(const TautTether& tether, double offset_m) {
  constexpr double kStraightBend = 0.1;  // |in - out| = 2 sin(bend / 2): bends under ~6 degrees
  const auto line = tether.polyline();   // entry, wraps, robot: line[k] is wraps[k - 1]
  const auto& wraps = tether.wrap_points();
  std::vector<Eigen::Vector2d> out;
  for (std::size_t k = line.size() - 2; k >= 1; --k) {
    const Eigen::Vector2d in = (line[k] - line[k + 1]).normalized(),
                          out_dir = (line[k - 1] - line[k]).normalized();
    Eigen::Vector2d away = in - out_dir;  // from the corner to the outside of the bend
    // A nearly straight bend (the staircase corners of a slanted edge lie in a line, and
    // the tether touches several): the bisector's direction is rounding noise and may
    // point into the obstacle. The side the tether turns to there is exact: it turns
    // counter-clockwise (side +1, towards the robot) round an obstacle on its left.
    if (away.norm() < kStraightBend) {
      const Eigen::Vector2d to_robot = -(in + out_dir).normalized();
      away = wraps[k - 1].side * Eigen::Vector2d(to_robot.y(), -to_robot.x());
    }
    out.push_back(line[k] + offset_m * away.normalized());
  }
  return out;
}

}  // namespace ferret
