#include "ferret/tether_model/required_length.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <utility>

namespace ferret::tether {

FixedWrapTether::FixedWrapTether(double entry_offset_m, Eigen::Vector2d p_WE,
                                 std::vector<WrapPoint> wrap_points)
    : entry_offset_m_(entry_offset_m),
      p_WE_(std::move(p_WE)),
      wrap_points_(std::move(wrap_points)) {
  if (!(entry_offset_m_ >= 0.0)) throw std::invalid_argument("FixedWrapTether: l_0 must be >= 0");
  double length = entry_offset_m_;
  Eigen::Vector2d previous = p_WE_;
  for (const auto& w : wrap_points_) {
    if (w.side < -1 || w.side > 1)
      throw std::invalid_argument("FixedWrapTether: side must be -1, 0 or +1");
    length += (w.p_W - previous).norm();
    cumulative_m_.push_back(length);
    previous = w.p_W;
  }
}

std::size_t FixedWrapTether::engaged_count(const Eigen::Vector2d& p_WG) const {
  Eigen::Vector2d anchor = p_WE_;
  std::size_t count = 0;
  for (const auto& w : wrap_points_) {
    const Eigen::Vector2d in = w.p_W - anchor, out = p_WG - w.p_W;
    const double turn = in.x() * out.y() - in.y() * out.x();  // > 0: counter-clockwise
    if (w.side != 0 && turn * w.side <= 0.0) break;
    anchor = w.p_W;
    ++count;
  }
  return count;
}

double FixedWrapTether::length_to_wrap_point_m(std::size_t index) const {
  if (index >= cumulative_m_.size())
    throw std::out_of_range("FixedWrapTether: no wrap point " + std::to_string(index));
  return cumulative_m_[index];
}

double FixedWrapTether::required_length_m(const Eigen::Vector2d& p_WG) const {
  const std::size_t engaged = engaged_count(p_WG);
  if (engaged == 0) return entry_offset_m_ + (p_WG - p_WE_).norm();
  return cumulative_m_[engaged - 1] + (p_WG - wrap_points_[engaged - 1].p_W).norm();
}

UgvMotion UgvMotion::extrapolated(double dt_s, double max_speed_mps,
                                  double acceleration_time_s) const {
  UgvMotion out = *this;
  if (dt_s <= 0.0) return out;
  const double speed = v_WG.norm();
  const double acc = a_WG.norm();
  // Time until the speed cap would be reached under constant acceleration (only
  // when the acceleration raises the speed); beyond it, coast at the cap.
  double t_acc = std::clamp(acceleration_time_s, 0.0, dt_s);
  if (acc > 1e-12) {
    const Eigen::Vector2d v_end = v_WG + a_WG * t_acc;
    if (v_end.norm() > max_speed_mps && v_end.norm() > speed) {
      // Solve |v + a t| = max_speed for the smallest t >= 0 (quadratic in t).
      const double qa = a_WG.squaredNorm(), qb = 2.0 * v_WG.dot(a_WG),
                   qc = v_WG.squaredNorm() - max_speed_mps * max_speed_mps;
      const double disc = qb * qb - 4.0 * qa * qc;
      t_acc = disc >= 0.0 ? std::max(0.0, (-qb + std::sqrt(disc)) / (2.0 * qa)) : 0.0;
      t_acc = std::min(t_acc, std::min(dt_s, acceleration_time_s));
    }
  }
  out.p_WG = p_WG + v_WG * t_acc + 0.5 * a_WG * t_acc * t_acc;
  out.v_WG = v_WG + a_WG * t_acc;
  if (t_acc < dt_s) {
    out.p_WG += out.v_WG * (dt_s - t_acc);
    out.a_WG.setZero();
  }
  return out;
}

namespace {
// Cubic Hermite segment of the preview holding dt_s (clamped to [0, last knot]):
// its first knot and the fraction u in [0, 1] into it.
std::pair<std::size_t, double> preview_segment(const UgvMotionPreview& p, double dt_s) {
  const std::size_t segments = p.displacement_m.size() - 1;
  const double x = std::clamp(dt_s / p.step_s, 0.0, static_cast<double>(segments));
  const std::size_t i = std::min(static_cast<std::size_t>(x), segments - 1);
  return {i, x - static_cast<double>(i)};
}
}  // namespace

Eigen::Vector2d UgvMotionPreview::at(double dt_s) const {
  if (empty() || dt_s <= 0.0) return Eigen::Vector2d::Zero();
  const double end_s = step_s * static_cast<double>(displacement_m.size() - 1);
  if (dt_s >= end_s) return displacement_m.back() + velocity_mps.back() * (dt_s - end_s);
  const auto [i, u] = preview_segment(*this, dt_s);
  const double u2 = u * u, u3 = u2 * u;
  return (2 * u3 - 3 * u2 + 1) * displacement_m[i] + (u3 - 2 * u2 + u) * step_s * velocity_mps[i] +
         (-2 * u3 + 3 * u2) * displacement_m[i + 1] + (u3 - u2) * step_s * velocity_mps[i + 1];
}

Eigen::Vector2d UgvMotionPreview::velocity_at(double dt_s) const {
  if (empty()) return Eigen::Vector2d::Zero();
  const double end_s = step_s * static_cast<double>(displacement_m.size() - 1);
  if (dt_s >= end_s) return velocity_mps.back();
  const auto [i, u] = preview_segment(*this, dt_s);
  const double u2 = u * u;
  return ((6 * u2 - 6 * u) * (displacement_m[i] - displacement_m[i + 1])) / step_s +
         (3 * u2 - 4 * u + 1) * velocity_mps[i] + (3 * u2 - 2 * u) * velocity_mps[i + 1];
}

UgvMotion planned_motion(const UgvMotion& at_message, const UgvMotionPreview& preview,
                         double dt_s) {
  UgvMotion out = at_message;
  out.p_WG += preview.at(dt_s);
  out.v_WG = preview.velocity_at(dt_s);
  out.a_WG.setZero();
  return out;
}

double required_length_rate_mps(const RequiredLengthModel& model, const UgvMotion& motion) {
  constexpr double kStep_s = 1e-3;
  const Eigen::Vector2d dp = motion.v_WG * kStep_s;
  return (model.required_length_m(motion.p_WG + dp) - model.required_length_m(motion.p_WG - dp)) /
         (2.0 * kStep_s);
}

}  // namespace ferret::tether
