#include "ferret/mapping/ir_grid.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace ferret {

IrGrid::IrGrid(GridGeometry geometry, Options options)
    : geometry_(geometry),
      options_(options),
      l_hit_(static_cast<float>(logit(options.prob_hit))),
      l_miss_(static_cast<float>(logit(options.prob_miss))),
      l_min_(static_cast<float>(logit(options.clamp_min))),
      l_max_(static_cast<float>(logit(options.clamp_max))),
      log_odds_(geometry.size(), 0.0f),
      label_(geometry.size(), static_cast<std::uint8_t>(GridLabel::kUnknown)),
      inflation_(geometry.size(), 0),
      changed_flag_(geometry.size(), 0),
      hit_stamp_(geometry.size(), 0),
      free_stamp_(geometry.size(), 0) {
  if (geometry.width <= 0 || geometry.height <= 0 || geometry.resolution_m <= 0)
    throw std::invalid_argument("IrGrid: empty grid geometry");
  if (!(options.prob_hit > 0.5 && options.prob_hit < 1 && options.prob_miss > 0 &&
        options.prob_miss < 0.5 && options.clamp_min > 0 && options.clamp_min < 0.5 &&
        options.clamp_max > 0.5 && options.clamp_max < 1))
    throw std::invalid_argument(
        "IrGrid: hit must be in (0.5, 1), miss in (0, 0.5), clamps around 0.5");
  const int r = static_cast<int>(std::ceil(options.clearance_m / geometry.resolution_m));
  const double r2 =
      std::pow(options.clearance_m / geometry.resolution_m, 2) + 1e-9;  // 0.15 / 0.05 is 2.9999...
  for (int dj = -r; dj <= r; ++dj)
    for (int di = -r; di <= r; ++di)
      if (di * di + dj * dj <= r2) inflation_offsets_.push_back({di, dj});
}

double IrGrid::probability(Cell c) const { return inverse_logit(log_odds(c)); }

void IrGrid::set_label(std::size_t idx, GridLabel label) {
  const auto old = static_cast<GridLabel>(label_[idx]);
  if (old == label) return;
  label_[idx] = static_cast<std::uint8_t>(label);
  label_revisions_.touch(idx);
  if (!changed_flag_[idx]) {
    changed_flag_[idx] = 1;
    changed_.push_back(idx);
  }
  const bool was_occ = old == GridLabel::kOccupied, is_occ = label == GridLabel::kOccupied;
  if (was_occ == is_occ) return;
  const Cell c = geometry_.cell_of_index(idx);
  for (const Cell& o : inflation_offsets_) {
    const Cell n{c.i + o.i, c.j + o.j};
    if (!geometry_.contains(n)) continue;
    auto& count = inflation_[geometry_.index(n)];
    count = static_cast<std::uint16_t>(is_occ ? count + 1 : count - 1);
  }
}

void IrGrid::update_cell(Cell c, bool hit) {
  const std::size_t idx = geometry_.index(c);
  float& l = log_odds_[idx];
  l = std::clamp(l + (hit ? l_hit_ : l_miss_), l_min_, l_max_);
  set_label(idx, l >= 0.0f ? GridLabel::kOccupied : GridLabel::kFree);
}

void IrGrid::set_probability(Cell c, double p_occupied) {
  const std::size_t idx = geometry_.index(c);
  const double p = std::clamp(p_occupied, options_.clamp_min, options_.clamp_max);
  log_odds_[idx] = std::clamp(static_cast<float>(std::log(p / (1.0 - p))), l_min_, l_max_);
  set_label(idx, log_odds_[idx] >= 0.0f ? GridLabel::kOccupied : GridLabel::kFree);
}

void IrGrid::integrate_scan(const RangeScan& scan) {
  if (++scan_id_ == 0) {  // stamps wrapped: reset so stale stamps never match
    std::fill(hit_stamp_.begin(), hit_stamp_.end(), 0);
    std::fill(free_stamp_.begin(), free_stamp_.end(), 0);
    scan_id_ = 1;
  }
  const Eigen::Vector2d origin = scan.X_WS.position();
  std::vector<std::size_t> hits;
  for (const auto& beam : scan.beams) {
    if (!(beam.range_m < scan.max_range_m) || beam.range_m < 0) continue;
    const double a = scan.X_WS.yaw_rad + beam.bearing_rad;
    const Eigen::Vector2d end = origin + beam.range_m * Eigen::Vector2d(std::cos(a), std::sin(a));
    const Cell c = geometry_.cell_at(end.x(), end.y());
    if (!geometry_.contains(c)) continue;
    const std::size_t idx = geometry_.index(c);
    if (hit_stamp_[idx] != scan_id_) {
      hit_stamp_[idx] = scan_id_;
      hits.push_back(idx);
    }
  }
  std::vector<std::size_t> frees;
  for (const auto& beam : scan.beams) {
    if (beam.range_m < 0) continue;
    const bool returned = beam.range_m < scan.max_range_m;
    const double range = std::min(beam.range_m, scan.max_range_m);
    const double a = scan.X_WS.yaw_rad + beam.bearing_rad;
    const Eigen::Vector2d end = origin + range * Eigen::Vector2d(std::cos(a), std::sin(a));
    const Cell end_cell = geometry_.cell_at(end.x(), end.y());
    trace_ray(geometry_, origin, end, [&](Cell c, double) {
      if (returned && c == end_cell) return false;
      const std::size_t idx = geometry_.index(c);
      if (hit_stamp_[idx] != scan_id_ && free_stamp_[idx] != scan_id_) {
        free_stamp_[idx] = scan_id_;
        frees.push_back(idx);
      }
      return true;
    });
  }
  for (const std::size_t idx : frees) update_cell(geometry_.cell_of_index(idx), false);
  for (const std::size_t idx : hits) update_cell(geometry_.cell_of_index(idx), true);
}

void IrGrid::mark_free_disk(const Eigen::Vector2d& p_W, double radius_m) {
  const Cell c0 = geometry_.cell_at(p_W.x(), p_W.y());
  const int r = static_cast<int>(std::ceil(radius_m / geometry_.resolution_m)) + 1;
  for (int dj = -r; dj <= r; ++dj)
    for (int di = -r; di <= r; ++di) {
      const Cell c{c0.i + di, c0.j + dj};
      if (!geometry_.contains(c) || (geometry_.center(c) - p_W).norm() > radius_m) continue;
      const std::size_t idx = geometry_.index(c);
      log_odds_[idx] = std::min(log_odds_[idx], l_miss_);
      set_label(idx, GridLabel::kFree);
    }
}

std::vector<std::size_t> IrGrid::take_changed_cells() {
  std::vector<std::size_t> out;
  out.swap(changed_);
  for (const std::size_t idx : out) changed_flag_[idx] = 0;
  return out;
}

}  // namespace ferret
