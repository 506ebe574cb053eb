#include "ferret/sim/hidden_space_sim.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace ferret {
namespace {
int beams_for(double fov_rad, double range_m, double resolution_m) {
  // Adjacent beams at most one cell apart at full range.
  return std::max(2, static_cast<int>(std::ceil(fov_rad * range_m / resolution_m)) + 1);
}

double beam_bearing(int k, int n, double fov_rad) { return -fov_rad / 2 + fov_rad * k / (n - 1); }
}  // namespace

HiddenSpaceSim::HiddenSpaceSim(const OccupancyMap2D& truth, const Eigen::Vector2d& object_W,
                               SensorOptions options, std::uint64_t seed)
    : truth_(truth), object_W_(object_W), options_(options), rng_(seed) {
  if (truth.cells.size() != truth.geometry.size())
    throw std::invalid_argument("HiddenSpaceSim: malformed truth map");
  const double res = truth.geometry.resolution_m;
  // No beam reaches past the map: beyond its diagonal a longer range adds no cells, and
  // the beam count must not grow with a range a user typed (100 km: 10^6 beams).
  const double reach_m = std::hypot(truth.geometry.width_m(), truth.geometry.height_m());
  const auto beams_for = [&](double fov_rad, double range_m, double resolution_m) {
    return ::ferret::beams_for(fov_rad, std::min(range_m, reach_m), resolution_m);
  };
  ir_beams_ = !options.ir_bearings_rad.empty() ? static_cast<int>(options.ir_bearings_rad.size())
              : options.ir_beams > 0           ? options.ir_beams
                                     : beams_for(options.ir_fov_rad, options.ir_range_m, res);
  camera_beams_ = options.camera_beams > 0
                      ? options.camera_beams
                      : beams_for(options.camera_fov_rad, options.camera_range_m, res);
}

bool HiddenSpaceSim::blocks(Cell c) const {
  return !truth_.geometry.contains(c) || truth_.at(c) != CellState::kFree;
}

double HiddenSpaceSim::cast(const Eigen::Vector2d& from, double angle_rad,
                            double max_range_m) const {
  const Eigen::Vector2d dir(std::cos(angle_rad), std::sin(angle_rad));
  double hit = max_range_m;
  bool inside = false;
  trace_ray(truth_.geometry, from, from + max_range_m * dir, [&](Cell c, double distance_m) {
    inside = true;
    if (truth_.at(c) != CellState::kFree) {
      hit = std::min(distance_m, max_range_m);
      return false;
    }
    return true;
  });
  return inside ? hit : 0.0;
}

bool HiddenSpaceSim::line_of_sight(const Eigen::Vector2d& a, const Eigen::Vector2d& b) const {
  bool clear = true;
  const Cell end = truth_.geometry.cell_at(b.x(), b.y());
  trace_ray(truth_.geometry, a, b, [&](Cell c, double) {
    if (c == end) return false;
    clear = truth_.at(c) == CellState::kFree;
    return clear;
  });
  return clear;
}

double HiddenSpaceSim::focal_length_px() const {
  return 0.5 * options_.image_width_px / std::tan(options_.camera_fov_rad / 2);
}

RangeScan HiddenSpaceSim::ir_scan(const Pose2& X_WS) {
  RangeScan scan{X_WS, options_.ir_range_m, {}};
  scan.beams.reserve(static_cast<std::size_t>(ir_beams_));
  const Eigen::Vector2d p = X_WS.position();
  for (int k = 0; k < ir_beams_; ++k) {
    const double bearing = options_.ir_bearings_rad.empty()
                               ? beam_bearing(k, ir_beams_, options_.ir_fov_rad)
                               : options_.ir_bearings_rad[static_cast<std::size_t>(k)];
    const double range = cast(p, X_WS.yaw_rad + bearing, options_.ir_range_m);
    const double noise = rng_.normal(0.0, options_.ir_noise_m);
    if (rng_.bernoulli(options_.ir_dropout))
      continue;  // drawn for every beam: same stream either way
    scan.beams.push_back({bearing, range < options_.ir_range_m ? std::max(0.0, range + noise)
                                                               : options_.ir_range_m});
  }
  return scan;
}

CameraFrame HiddenSpaceSim::camera_frame(const Pose2& X_WC, double time_s) {
  CameraFrame frame;
  frame.time_s = time_s;
  frame.view = {X_WC, options_.camera_range_m, {}};
  frame.view.beams.reserve(static_cast<std::size_t>(camera_beams_));
  const Eigen::Vector2d p = X_WC.position();
  for (int k = 0; k < camera_beams_; ++k) {
    const double bearing = beam_bearing(k, camera_beams_, options_.camera_fov_rad);
    frame.view.beams.push_back({bearing, cast(p, X_WC.yaw_rad + bearing, options_.camera_range_m)});
  }
  // The detector. Draw every random number every frame so that a miss here does not
  // shift the noise of later frames (keeps methods comparable under one seed).
  const Eigen::Vector2d to = object_W_ - p;
  const double d = to.norm();
  const double bearing = wrap_angle_rad(std::atan2(to.y(), to.x()) - X_WC.yaw_rad);
  const double size_noise = rng_.normal(0.0, options_.size_noise_px);
  const double bearing_noise = rng_.normal(0.0, options_.bearing_noise_rad);
  const double conf_noise = rng_.normal(0.0, options_.confidence_noise);
  const bool detected_by_chance = rng_.bernoulli(options_.detection_probability);
  if (d > options_.camera_range_m || d < 1e-3 || std::abs(bearing) > options_.camera_fov_rad / 2 ||
      !detected_by_chance || !line_of_sight(p, object_W_))
    return frame;
  const double f = focal_length_px();
  const double width_px = f * options_.object_size_m / d + size_noise;  // apparent size
  if (width_px < 1.0) return frame;
  const double gamma = width_px / options_.object_size_m;  // pixels per metre
  const double d_measured = f / gamma;                     // d = k_c / gamma
  frame.detections.push_back(
      {bearing + bearing_noise, d_measured,
       std::max(0.0, distance_confidence(options_.eta_m, d_measured) + conf_noise)});
  return frame;
}

}  // namespace ferret
