#include "ferret/ugv/anchored_ugv_base.hpp"

#include <cmath>

namespace ferret::ugv {

Pose2 inverse(const Pose2& X_AB) {
  const double c = std::cos(X_AB.yaw_rad), s = std::sin(X_AB.yaw_rad);
  return {-(c * X_AB.x_m + s * X_AB.y_m), s * X_AB.x_m - c * X_AB.y_m,
          wrap_angle_rad(-X_AB.yaw_rad)};
}

void AnchoredUgvBase::anchor(const Pose2& X_WG) { X_WO_ = X_WG * inverse(base_.odometry()); }

RangeScan AnchoredUgvBase::ir_scan() {
  RangeScan scan = base_.ir_scan();
  scan.X_WS = X_WO_ * scan.X_WS;
  return scan;
}

CameraFrame AnchoredUgvBase::camera_frame(double time_s) {
  CameraFrame frame = base_.camera_frame(time_s);
  frame.view.X_WS = X_WO_ * frame.view.X_WS;
  return frame;
}

}  // namespace ferret::ugv
