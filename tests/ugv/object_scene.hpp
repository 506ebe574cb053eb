#pragma once
// A small generated scene for the object detector (agreement test and bench): flat
// ground, grey walls 9 m out on every side (a backdrop like a hidden space's), and
// the object (an 8 x 8 x 5 cm box in kObjectColourRgb) at the origin. A robot's
// object camera is placed at a horizontal distance and bearing from the object; the
// same view goes to the simulator's renderer (SensorSimulator, for the image
// detector) and to the geometric detector (HiddenSpaceSim on an all-free truth map).

#include <fmt/format.h>

#include <cmath>
#include <optional>
#include <string>

#include "ferret/core/pose.hpp"
#include "ferret/mapping/occupancy_map_2d.hpp"
#include "ferret/mapping/world_spec.hpp"
#include "ferret/mission/search_robot.hpp"
#include "ferret/perception/camera_model.hpp"
#include "ferret/sim/hidden_space_sim.hpp"
#include "ferret/sim/sensor_sim.hpp"
#include "ferret/ugv/object_detector.hpp"
#include "ferret/urdf/robot_description.hpp"

namespace ferret::test {

/// Where the camera is: `distance_m` (horizontal, camera centre to object centre) and
/// `bearing_rad` (+ left of the optical axis) of the object, the camera looking along
/// world heading `heading_rad`. The object's yaw relative to the line of sight follows
/// from the heading (the object is axis-aligned).
struct ObjectView {
  double distance_m = 1.0;
  double bearing_rad = 0.0;
  double heading_rad = 0.0;
};

struct ObjectBox {
  double width_m = 0.08, depth_m = 0.08, height_m = 0.05;
};

inline WorldSpec object_world(const ObjectBox& box) {
  return parse_world(fmt::format(R"(name: object_scene
resolution_m: 0.05
bounds_m: {{min: [-10, -10, -0.5], max: [10, 10, 3]}}
ground: {{height_m: 0.0}}
objects:
  - {{name: object, position_m: [0, 0], size_m: [{}, {}, {}]}}
boxes:
  - {{name: north, center_m: [0, 9.1], size_m: [18.4, 0.2, 0.4]}}
  - {{name: south, center_m: [0, -9.1], size_m: [18.4, 0.2, 0.4]}}
  - {{name: east, center_m: [9.1, 0], size_m: [0.2, 18.4, 0.4]}}
  - {{name: west, center_m: [-9.1, 0], size_m: [0.2, 18.4, 0.4]}}
)",
                                 box.width_m, box.depth_m, box.height_m),
                     "object scene");
}

class ObjectScene {
 public:
  ObjectScene(const RobotDescription& robot, const ObjectSearchParams& search, ObjectBox box = {})
      : sensor_(robot.object_camera()),
        camera_(camera_model(sensor_, robot.source)),
        box_(box),
        sim_(object_world(box)),
        truth_(OccupancyMap2D::filled(GridGeometry{-9.0, -9.0, 0.05, 360, 360}, CellState::kFree)) {
    geometric_ = sensor_options_for(robot);
    // The geometric detector's model without its noise: the comparison is of the
    // two models (its noise terms are the experiments' choice, not the detector's).
    geometric_.object_size_m = box.width_m;
    geometric_.size_noise_px = 0.0;
    geometric_.bearing_noise_rad = 0.0;
    geometric_.confidence_noise = 0.0;
    geometric_.detection_probability = 1.0;
    geometric_.eta_m = search.eta_m;
  }

  /// The image detector for this camera: the object's size from the scene, no range
  /// limit (it sees as far as the blob survives; the geometric one stops at D_cam).
  [[nodiscard]] ugv::ColourObjectDetector::Options detector_options(
      const ObjectSearchParams& search) const {
    ugv::ColourObjectDetector::Options o;
    o.object_width_m = box_.width_m;
    o.object_height_m = box_.height_m;
    o.object_depth_m = box_.depth_m;
    o.search = search;
    return o;
  }

  [[nodiscard]] const CameraModel& camera() const { return camera_; }
  [[nodiscard]] const CameraSensor& sensor() const { return sensor_; }
  [[nodiscard]] double range_m() const { return sensor_.range_max_m; }  ///< D_cam

  /// The camera's centre in the world (its height: the URDF's) and heading.
  [[nodiscard]] Pose2 camera_pose_2d(const ObjectView& v) const {
    const double to_object = v.heading_rad + v.bearing_rad;
    return {-v.distance_m * std::cos(to_object), -v.distance_m * std::sin(to_object),
            v.heading_rad};
  }
  /// The robot's base on the ground such that its camera has camera_pose_2d(v).
  [[nodiscard]] Pose3 X_WB(const ObjectView& v) const {
    const Pose2 c = camera_pose_2d(v);
    const Eigen::Matrix3d R_BS = sensor_.X_BS.linear();
    const double yaw_BS = std::atan2(R_BS(1, 0), R_BS(0, 0));
    const double yaw_B = c.yaw_rad - yaw_BS;
    const Eigen::Vector2d t = sensor_.X_BS.translation().head<2>();
    const Eigen::Vector2d p_B = c.position() - Eigen::Rotation2Dd(yaw_B).toRotationMatrix() * t;
    Pose3 X = Pose3::Identity();
    X.translation() = Eigen::Vector3d(p_B.x(), p_B.y(), 0.0);
    X.linear() = Eigen::AngleAxisd(yaw_B, Eigen::Vector3d::UnitZ()).toRotationMatrix();
    return X;
  }
  /// The camera's optical frame in the world.
  [[nodiscard]] Pose3 X_WC(const ObjectView& v) const { return optical_pose(X_WB(v), sensor_); }
  /// Range from the optical centre to the object's centre (the 3D truth).
  [[nodiscard]] double true_range_m(const ObjectView& v) const {
    const Eigen::Vector3d p_WO(0.0, 0.0, box_.height_m / 2);
    return (X_WC(v).translation() - p_WO).norm();
  }

  [[nodiscard]] RgbImage frame(const ObjectView& v, const CameraFrameOptions& options,
                               std::uint64_t seed) const {
    return sim_.render_camera(camera_, X_WC(v), options, seed);
  }

  /// The geometric detector's detection of the same view (noise off), if any.
  [[nodiscard]] std::optional<::ferret::ObjectDetection> geometric(const ObjectView& v) const {
    HiddenSpaceSim sim(truth_, Eigen::Vector2d::Zero(), geometric_, 1);
    const CameraFrame f = sim.camera_frame(camera_pose_2d(v), 0.0);
    if (f.detections.empty()) return std::nullopt;
    return f.detections.front();
  }
  [[nodiscard]] const SensorOptions& geometric_options() const { return geometric_; }

 private:
  CameraSensor sensor_;
  CameraModel camera_;
  ObjectBox box_;
  SensorSimulator sim_;
  OccupancyMap2D truth_;
  SensorOptions geometric_;
};

}  // namespace ferret::test
