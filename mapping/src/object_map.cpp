#include "ferret/mapping/object_map.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "ferret/mapping/object_search_params.hpp"

namespace ferret {

ObjectMap::Options ObjectMap::Options::from(const ObjectSearchParams& params,
                                            double camera_range_m) {
  Options o;
  o.lambda1 = params.lambda1;
  o.lambda2 = params.lambda2;
  o.eta_m = params.eta_m;
  o.conf_floor = params.conf_floor;
  o.conf_cap = params.conf_cap;
  o.miss_likelihood = params.miss_likelihood;
  o.camera_range_m = camera_range_m;
  return o;
}

ObjectMap::ObjectMap(GridGeometry geometry, Options options)
    : geometry_(geometry),
      options_(options),
      l_clamp_(static_cast<float>(logit(options.clamp_probability))),
      log_odds_(geometry.size(), 0.0f),
      last_conf_(geometry.size(), 0.0f),
      last_x_(geometry.size(), 0.0f),
      last_y_(geometry.size(), 0.0f),
      last_yaw_(geometry.size(), 0.0f),
      last_time_(geometry.size(), -1e30f),
      evidence_pos_(geometry.size(), -1),
      stamp_(geometry.size(), 0) {
  if (geometry.width <= 0 || geometry.height <= 0 || geometry.resolution_m <= 0)
    throw std::invalid_argument("ObjectMap: empty grid geometry");
  if (!(options.lambda1 > 0 && options.lambda1 < 0.5 && options.lambda2 > 0.5 &&
        options.lambda2 < 1))
    throw std::invalid_argument("ObjectMap: need 0 < lambda1 < 0.5 < lambda2 < 1");
  if (!(options.conf_floor >= 0.5 && options.conf_floor <= options.conf_cap &&
        options.conf_cap < 1))
    throw std::invalid_argument("ObjectMap: need 0.5 <= conf_floor <= conf_cap < 1");
  if (!(options.miss_likelihood > 0 && options.miss_likelihood <= 0.5))
    throw std::invalid_argument("ObjectMap: need 0 < miss_likelihood <= 0.5");
}

double ObjectMap::probability_at(std::size_t idx) const { return inverse_logit(log_odds_[idx]); }

double distance_confidence(double eta_m, double distance_m) { return eta_m / distance_m; }

double clip_confidence(double raw, double conf_floor, double conf_cap) {
  return std::clamp(raw, conf_floor, conf_cap);
}

double ObjectMap::detection_confidence(double raw) const {
  return clip_confidence(raw, options_.conf_floor, options_.conf_cap);
}

double ObjectMap::miss_likelihood(double distance_m) const {
  const double w = std::clamp(1.0 - distance_m / options_.camera_range_m, 0.0, 1.0);
  return 0.5 - (0.5 - options_.miss_likelihood) * w;
}

ObjectLabel ObjectMap::label_of(double p) const {
  if (p < options_.lambda1) return ObjectLabel::kFree;
  if (p > options_.lambda2) return ObjectLabel::kObject;
  return ObjectLabel::kUnknown;
}

double ObjectMap::labelled_probability(double p) const {
  switch (label_of(p)) {
    case ObjectLabel::kFree:
      return 0.0;
    case ObjectLabel::kUnknown:
      return 0.5;
    case ObjectLabel::kObject:
      return p;
  }
  return p;
}

void ObjectMap::fuse(Cell c, double p_measurement) {
  const std::size_t idx = geometry_.index(c);
  float& l = log_odds_[idx];
  l = std::clamp(static_cast<float>(l + logit(p_measurement)), -l_clamp_, l_clamp_);
  revisions_.touch(idx);
  track_evidence(idx);
}

void ObjectMap::set_cell(Cell c, double probability, double last_confidence) {
  const std::size_t idx = geometry_.index(c);
  const double p = std::clamp(probability, 1e-9, 1.0 - 1e-9);
  log_odds_[idx] = std::clamp(static_cast<float>(logit(p)), -l_clamp_, l_clamp_);
  last_conf_[idx] = static_cast<float>(std::clamp(last_confidence, 0.0, 1.0));
  // A cell whose probability is not the prior's was measured where the map was made.
  if (std::abs(p - 0.5) > 1e-6 && !observed(idx)) last_time_[idx] = 0.0f;
  revisions_.touch(idx);
  track_evidence(idx);
}

void ObjectMap::track_evidence(std::size_t idx) {
  const bool evidence = log_odds_[idx] > 0.0f;
  if (evidence && evidence_pos_[idx] < 0) {
    evidence_pos_[idx] = static_cast<std::int32_t>(evidence_.size());
    evidence_.push_back(idx);
  } else if (!evidence && evidence_pos_[idx] >= 0) {
    const auto pos = static_cast<std::size_t>(evidence_pos_[idx]);
    evidence_[pos] = evidence_.back();
    evidence_pos_[evidence_[pos]] = static_cast<std::int32_t>(pos);
    evidence_.pop_back();
    evidence_pos_[idx] = -1;
  }
}

bool ObjectMap::new_viewpoint(std::size_t idx, const Pose2& X_WC, double time_s) const {
  if (!options_.gate_viewpoints || !observed(idx)) return true;
  if (time_s - last_time_[idx] >= options_.max_period_s) return true;
  if (std::hypot(X_WC.x_m - last_x_[idx], X_WC.y_m - last_y_[idx]) >= options_.min_move_m)
    return true;
  return std::abs(wrap_angle_rad(X_WC.yaw_rad - last_yaw_[idx])) >= options_.min_turn_rad;
}

void ObjectMap::remember_viewpoint(std::size_t idx, const Pose2& X_WC, double time_s) {
  last_x_[idx] = static_cast<float>(X_WC.x_m);
  last_y_[idx] = static_cast<float>(X_WC.y_m);
  last_yaw_[idx] = static_cast<float>(X_WC.yaw_rad);
  if (!observed(idx))
    revisions_.touch(idx);  // its mass in a search changes (unobserved to observed)
  last_time_[idx] = static_cast<float>(time_s);
}

void ObjectMap::integrate_frame(const CameraFrame& frame) {
  if (++frame_id_ == 0) {
    std::fill(stamp_.begin(), stamp_.end(), 0);
    frame_id_ = 1;
  }
  const Pose2& X_WC = frame.view.X_WS;
  const Eigen::Vector2d origin = X_WC.position();
  // Detections first: their cells take the detection, not a miss, in this frame.
  for (const auto& det : frame.detections) {
    const double a = X_WC.yaw_rad + det.bearing_rad;
    const Eigen::Vector2d p = origin + det.distance_m * Eigen::Vector2d(std::cos(a), std::sin(a));
    const double conf = detection_confidence(det.confidence);
    const Cell c0 = geometry_.cell_at(p.x(), p.y());
    const int r = static_cast<int>(std::ceil(options_.object_radius_m / geometry_.resolution_m));
    for (int dj = -r; dj <= r; ++dj)
      for (int di = -r; di <= r; ++di) {
        const Cell c{c0.i + di, c0.j + dj};
        if (!geometry_.contains(c) ||
            (geometry_.center(c) - p).norm() > options_.object_radius_m + 1e-9)
          continue;
        const std::size_t idx = geometry_.index(c);
        if (stamp_[idx] == frame_id_) continue;
        stamp_[idx] = frame_id_;
        if (!new_viewpoint(idx, X_WC, frame.time_s)) continue;
        fuse(c, conf);
        last_conf_[idx] = static_cast<float>(conf);
        remember_viewpoint(idx, X_WC, frame.time_s);
      }
  }
  // Everything else the camera sees: a mild "no object", weaker with distance.
  for (const auto& beam : frame.view.beams) {
    const double range = std::min(beam.range_m, frame.view.max_range_m);
    const double a = X_WC.yaw_rad + beam.bearing_rad;
    const Eigen::Vector2d end = origin + range * Eigen::Vector2d(std::cos(a), std::sin(a));
    trace_ray(geometry_, origin, end, [&](Cell c, double distance_m) {
      const std::size_t idx = geometry_.index(c);
      if (stamp_[idx] == frame_id_) return true;
      stamp_[idx] = frame_id_;
      if (!new_viewpoint(idx, X_WC, frame.time_s)) return true;
      fuse(c, miss_likelihood(distance_m));
      remember_viewpoint(idx, X_WC, frame.time_s);
      return true;
    });
  }
}

std::optional<Cell> ObjectMap::found_cell() const {
  std::optional<std::size_t> best;
  for (const std::size_t idx : evidence_)
    if (probability_at(idx) > options_.lambda2 && (!best || log_odds_[idx] > log_odds_[*best]))
      best = idx;
  if (!best) return std::nullopt;
  return geometry_.cell_of_index(*best);
}

}  // namespace ferret
