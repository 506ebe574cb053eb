#pragma once
// The camera models of a robot, as `ferret config --dump` prints them: for each URDF
// camera the pinhole and distortion its camera_model() gives, its fields of view, and
// where each value came from.

#include <string>

namespace ferret {

struct RobotDescription;

/// A YAML block `camera_models:` (a list, one entry a camera, in URDF order) with
/// size, fx, fy, cx, cy, skew, distortion model and coefficients (k1, k2, p1, p2, k3),
/// horizontal and vertical fov in degrees and radians, the roles the camera plays and
/// a provenance map (urdf:FILE:LINE, with a note where a value is computed).
[[nodiscard]] std::string camera_models_yaml(const RobotDescription& robot);

}  // namespace ferret
