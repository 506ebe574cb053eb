#pragma once
// A base re-expressed in the frame of the hidden space it was set down in. On the robot
// the wheels' odometry starts wherever the process started (on the UAV's landing skid,
// in the workshop); a search request says where the winch set the robot down, in the
// UAV's world frame (the entry E and the heading into the space). anchor() makes the
// base read that pose from then on, so the mission's maps, the telemetry's poses and the
// UAV's tether model share one frame. Simulation needs none of it: its base starts where
// the world puts it.

#include "ferret/core/pose.hpp"
#include "ferret/ugv/ugv_base.hpp"

namespace ferret::ugv {

class AnchoredUgvBase final : public UgvBase {
 public:
  /// Until the first anchor() the base reads as `base` does.
  explicit AnchoredUgvBase(UgvBase& base) : base_(base) {}

  /// From now on the base's current pose reads as X_WG (its drift since is kept).
  void anchor(const Pose2& X_WG);
  /// The base's own odometry frame in the anchored frame.
  [[nodiscard]] const Pose2& X_WO() const { return X_WO_; }

  [[nodiscard]] std::string backend() const override { return base_.backend(); }
  [[nodiscard]] Pose2 odometry() const override { return X_WO_ * base_.odometry(); }
  [[nodiscard]] double speed_mps() const override { return base_.speed_mps(); }
  /// The base's scan, its sensor pose in the anchored frame (beams are in the sensor's).
  [[nodiscard]] RangeScan ir_scan() override;
  /// The base's frame, its view's sensor pose in the anchored frame (detections are in
  /// the camera's).
  [[nodiscard]] CameraFrame camera_frame(double time_s) override;
  void command_velocity(double v_mps, double w_radps) override {
    base_.command_velocity(v_mps, w_radps);
  }
  void set_epm(bool on) override { base_.set_epm(on); }
  [[nodiscard]] UgvStatus status() const override { return base_.status(); }

 private:
  UgvBase& base_;
  Pose2 X_WO_;
};

/// X_AB^-1: the pose of A in B's frame.
[[nodiscard]] Pose2 inverse(const Pose2& X_AB);

}  // namespace ferret::ugv
