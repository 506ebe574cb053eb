#pragma once
// The search's coverage pattern (paper sect. III): a boustrophedon over the search area
// at the search altitude, its legs spaced by what the marker camera resolves, and a
// second pass across the first. The mission flies its waypoints in order; this class
// knows the waypoints and how far the search got through them.

#include <Eigen/Core>
#include <cstddef>
#include <vector>

#include "ferret/perception/camera_model.hpp"
#include "ferret/uav/marker_detector.hpp"

namespace ferret {

class CoveragePattern {
 public:
  CoveragePattern() = default;
  /// Legs along x over `area_m` ([x0, y0, x1, y1]) `leg_spacing_m` apart at
  /// `altitude_m`, then (passes 2) legs along y.
  CoveragePattern(const Eigen::Vector4d& area_m, double altitude_m, int passes,
                  double leg_spacing_m);

  /// The spacing the marker camera allows: legs one lateral reach apart, at about half
  /// the range where a marker of `marker` still spans its min_marker_side_px.
  [[nodiscard]] static double camera_leg_spacing_m(const MarkerDetectorOptions& marker,
                                                   const CameraModel& marker_camera);

  [[nodiscard]] const std::vector<Eigen::Vector3d>& waypoints() const { return waypoints_; }
  /// Waypoints of the first pass (legs along x); the second pass follows.
  [[nodiscard]] std::size_t first_pass_waypoints() const { return first_pass_end_; }
  [[nodiscard]] double leg_spacing_m() const { return leg_spacing_m_; }

  /// The waypoint flown to now; the ones before it are flown (or were unreachable).
  [[nodiscard]] std::size_t next_index() const { return next_; }
  [[nodiscard]] bool done() const { return next_ >= waypoints_.size(); }
  /// @pre !done()
  [[nodiscard]] const Eigen::Vector3d& next_waypoint() const { return waypoints_[next_]; }
  /// On to the next waypoint (this one reached, or unreachable).
  void advance() { ++next_; }

 private:
  std::vector<Eigen::Vector3d> waypoints_;
  std::size_t first_pass_end_ = 0;
  double leg_spacing_m_ = 0.0;
  std::size_t next_ = 0;
};

}  // namespace ferret
