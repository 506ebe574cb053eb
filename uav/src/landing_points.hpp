#pragma once
// Depth frame -> points in the world, shared by the landing-zone detector and the PX4
// baseline so that both see exactly the same points.

#include <Eigen/Core>
#include <vector>

#include "ferret/core/pose.hpp"
#include "ferret/perception/camera_model.hpp"
#include "ferret/perception/image.hpp"

namespace ferret {
struct PosedDepthFrame;
}

namespace ferret::internal {

/// Throws InputError for no frames or a frame without its image.
void require_frames(const std::vector<PosedDepthFrame>& frames);

/// The points of every pixel with a return in [min_depth_m, max_depth_m], in W.
/// Throws InputError when the frame's size is not the camera's. With `border`, the
/// points of the image's outermost pixels go there instead: the ground beyond them is
/// not seen, so a cell they fall in is only partly observed.
[[nodiscard]] std::vector<Eigen::Vector3d> depth_to_world_points(
    const DepthImageMm& depth, const CameraModel& camera, const Pose3& X_WC, double min_depth_m,
    double max_depth_m, std::vector<Eigen::Vector3d>* border = nullptr);

}  // namespace ferret::internal
