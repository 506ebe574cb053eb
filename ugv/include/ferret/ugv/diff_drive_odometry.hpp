#pragma once
// Differential-drive odometry from cumulative wheel encoder counts (the miniUGV's four
// wheels are driven as two sides: skid steering, read as a differential drive whose
// track width is the effective one, measured, not the wheels' spacing).
//
// Between two samples each side has driven d_l, d_r (counts x 2 pi r / counts a
// revolution); the robot drove ds = (d_l + d_r) / 2 and turned dtheta = (d_r - d_l) / b.
// The pose moves along the arc of that length and turn (exact for wheel speeds that
// are constant between samples; a straight segment when dtheta is zero).

#include <cstdint>
#include <deque>

#include "ferret/core/pose.hpp"

namespace ferret::ugv {

struct DiffDriveParams {
  double wheel_radius_m = 0.02;
  double ticks_per_rev = 360.0;
  double track_width_m = 0.105;
  /// The forward speed is averaged over at least this much MCU time (one encoder count
  /// in one 20 ms STATE interval is 17 mm/s at the defaults: too coarse alone).
  double speed_window_s = 0.1;
  /// A step that implies a wheel faster than this is an encoder glitch or a counter
  /// reset, not motion: the counts are taken as the new baseline and the step dropped.
  double max_plausible_wheel_speed_mps = 10.0;
};

class DiffDriveOdometry {
 public:
  DiffDriveOdometry(DiffDriveParams params, const Pose2& X_WG_start);

  /// One sample: cumulative counts (+ forward; they wrap at 2^32) at the MCU's time.
  /// The first sample only sets the baseline. A time that goes backwards means the MCU
  /// restarted (its counts restart too): the sample becomes the new baseline.
  void update(std::int32_t left_ticks, std::int32_t right_ticks, std::uint32_t mcu_time_ms);
  /// Forget the baseline: the next sample starts counting again (the pose stays).
  void reset_baseline();

  [[nodiscard]] const Pose2& pose() const { return pose_; }
  /// Forward speed over the last speed_window_s of MCU time, m/s (+ forward).
  [[nodiscard]] double speed_mps() const { return speed_mps_; }
  /// Samples dropped as implausible or as restarts.
  [[nodiscard]] std::uint64_t rebaselines() const { return rebaselines_; }
  /// Metres one count of a wheel is.
  [[nodiscard]] double metres_per_tick() const;

 private:
  struct Sample {
    double time_s;
    double distance_m;  ///< cumulative forward distance
  };
  DiffDriveParams params_;
  Pose2 pose_;
  bool have_baseline_ = false;
  std::int32_t left_ = 0, right_ = 0;
  std::uint32_t time_ms_ = 0;
  double time_s_ = 0.0;  ///< MCU time unwrapped since the baseline
  double distance_m_ = 0.0;
  std::deque<Sample> window_;
  double speed_mps_ = 0.0;
  std::uint64_t rebaselines_ = 0;
};

}  // namespace ferret::ugv
