#pragma once
// The simulated hidden space of the object search: ground truth from a map_server
// map plus one object, and the miniUGV's sensors on it (docs/object_search.md):
//  - IR: a fan of beams over fov beta to range D_IR, Gaussian range noise, dropouts;
//  - camera: a range finder over fov alpha to D_cam (where it can see, on the truth)
//    and the object detector: the object is detected if it is in the field of view,
//    within D_cam, in line of sight on the truth, and not missed (probability
//    1 - detection_probability). Its distance comes from its apparent size in a
//    pinhole model, d = k_c / gamma (gamma: pixels per metre of the object, k_c: the
//    focal length in pixels), with pixel noise; its confidence is eta / d plus noise.
// Only the simulator reads the truth. Seeded and deterministic.

#include <Eigen/Core>
#include <cstdint>
#include <vector>

#include "ferret/core/pose.hpp"
#include "ferret/core/random.hpp"
#include "ferret/mapping/object_map.hpp"
#include "ferret/mapping/occupancy_map_2d.hpp"

namespace ferret {

struct SensorOptions {
  double ir_fov_rad = deg_to_rad(30.0);  ///< beta
  double ir_range_m = 4.0;               ///< D_IR
  double ir_rate_hz = 20.0;
  int ir_beams = 0;  ///< 0: enough to touch every cell at D_IR
  /// The IR beams' bearings from the heading (a URDF's beams, search_robot.hpp); when
  /// given they replace the even fan of ir_beams over ir_fov_rad.
  std::vector<double> ir_bearings_rad;
  double ir_noise_m = 0.01;                  ///< range noise (standard deviation)
  double ir_dropout = 0.02;                  ///< probability that a beam returns nothing usable
  double camera_fov_rad = deg_to_rad(90.0);  ///< alpha
  double camera_range_m = 4.0;               ///< D_cam
  double camera_rate_hz = 10.0;
  int camera_beams = 0;          ///< 0: enough to touch every cell at D_cam
  int image_width_px = 640;      ///< the focal length follows from this and alpha
  double object_size_m = 0.2;    ///< the object's width (its apparent size gives d)
  double object_radius_m = 0.1;  ///< cells of the truth covered by the object
  double size_noise_px = 0.5;    ///< noise of the measured apparent width
  double bearing_noise_rad = 0.005;
  double detection_probability = 0.9;
  double confidence_noise = 0.02;             ///< added to eta / d
  double eta_m = ObjectSearchParams{}.eta_m;  ///< conf = eta / d
};

class HiddenSpaceSim {
 public:
  /// @param truth     the hidden space; occupied and unknown cells block sensing
  /// @param object_W  the object's position (on a free cell)
  HiddenSpaceSim(const OccupancyMap2D& truth, const Eigen::Vector2d& object_W,
                 SensorOptions options, std::uint64_t seed);

  /// One IR scan from the sensor pose X_WS.
  [[nodiscard]] RangeScan ir_scan(const Pose2& X_WS);
  /// One camera frame from the camera pose X_WC at time_s.
  [[nodiscard]] CameraFrame camera_frame(const Pose2& X_WC, double time_s);

  /// Distance to the first blocking truth cell along a beam, or max_range_m.
  [[nodiscard]] double cast(const Eigen::Vector2d& from, double angle_rad,
                            double max_range_m) const;
  /// True if no blocking truth cell lies between the two points.
  [[nodiscard]] bool line_of_sight(const Eigen::Vector2d& a, const Eigen::Vector2d& b) const;
  [[nodiscard]] bool blocks(Cell c) const;
  /// k_c: the focal length in pixels, (width / 2) / tan(alpha / 2).
  [[nodiscard]] double focal_length_px() const;

  [[nodiscard]] const OccupancyMap2D& truth() const { return truth_; }
  [[nodiscard]] const Eigen::Vector2d& object() const { return object_W_; }
  [[nodiscard]] const SensorOptions& options() const { return options_; }

 private:
  const OccupancyMap2D& truth_;
  Eigen::Vector2d object_W_;
  SensorOptions options_;
  Rng rng_;
  int ir_beams_ = 0, camera_beams_ = 0;
};

}  // namespace ferret
