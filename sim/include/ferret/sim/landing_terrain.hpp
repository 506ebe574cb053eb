#pragma once
// Terrains for the landing-zone evaluation, with their ground truth.
//
// landing_terrain(seed, index) is a WorldSpec (built from world YAML text, so it obeys
// the world schema): sloped ground (0-25 degrees, any direction), a hidden space whose
// opening faces the middle of the site, and a mix of rubble fields, steps (platforms),
// walls and poles. Obstacles are at least 0.3 m across (docs/perception.md says why).
//
// TerrainGroundTruth answers "is this disc safe to land on?" from the geometry (the
// ground plane, every solid box and cylinder, rasterised as a 2 cm height map of the
// highest surface), never from a depth frame.

#include <Eigen/Core>
#include <cstdint>
#include <string>
#include <vector>

#include "ferret/core/pose.hpp"
#include "ferret/mapping/world_spec.hpp"
#include "ferret/perception/camera_model.hpp"
#include "ferret/perception/image.hpp"
#include "ferret/sim/sensor_sim.hpp"
#include "ferret/urdf/robot_description.hpp"

namespace ferret {

struct LandingTerrain {
  WorldSpec world;
  std::string kind;  ///< what it holds, e.g. "slope 12.3 deg, rubble, walls"
  double slope_deg = 0.0;
  Eigen::Vector2d view_center_m = Eigen::Vector2d::Zero();  ///< where the UAV looks from above
};

/// Terrain `index` of the family `seed`: the same (seed, index), the same world.
[[nodiscard]] LandingTerrain landing_terrain(std::uint64_t seed, int index);

/// What the ground truth calls safe for a footprint disc.
struct LandingCriteria {
  double max_slope_deg = 15.0;
  double max_step_m = 0.10;       ///< peak-to-peak of the surface about its plane in the disc
  double min_clearance_m = 0.30;  ///< free ring beyond the disc ...
  double taller_than_m = 0.20;    ///< ... of anything taller than the plane by this
};

class TerrainGroundTruth {
 public:
  /// Rasterises the highest solid surface of `world` over its bounds (2 cm cells).
  explicit TerrainGroundTruth(const WorldSpec& world, double cell_m = 0.02);

  /// The top of the highest solid at (x, y): ground, box, cylinder or enclosure.
  [[nodiscard]] double surface_height(double x_m, double y_m) const;

  /// Is the disc of `radius_m` around `center_m` (x, y) safe: inside the world, its
  /// surface a plane within max_slope_deg and max_step_m, and nothing taller than
  /// taller_than_m within min_clearance_m of its edge?
  [[nodiscard]] bool is_safe(const Eigen::Vector2d& center_m, double radius_m,
                             const LandingCriteria& criteria) const;

  /// The highest surface within `radius_m` of `center_m` (x, y).
  [[nodiscard]] double highest_within(const Eigen::Vector2d& center_m, double radius_m) const;

  /// Is the whole disc of `radius_m` visible in the camera (every point of its rim and
  /// its centre inside the image and not hidden behind a taller surface)?
  [[nodiscard]] bool in_view(const Eigen::Vector2d& center_m, double radius_m,
                             const CameraModel& camera, const Pose3& X_WC) const;

  /// Does the camera see a safe disc of `radius_m` whose surroundings out to
  /// `view_radius_m` are in view? Candidates on a `step_m` grid over the image.
  [[nodiscard]] bool safe_zone_in_view(double radius_m, double view_radius_m,
                                       const LandingCriteria& criteria, const CameraModel& camera,
                                       const Pose3& X_WC, double step_m = 0.1) const;

 private:
  [[nodiscard]] double at(int i, int j) const {
    return h_[static_cast<std::size_t>(j) * static_cast<std::size_t>(nx_) +
              static_cast<std::size_t>(i)];
  }
  double cell_m_;
  Eigen::Vector2d lo_;
  int nx_ = 0, ny_ = 0;
  std::vector<float> h_;
};

/// One evaluation frame: the UAV hovering over a terrain, its depth frame rendered by
/// SensorSimulator, and whether the ground truth sees a safe zone in it.
struct LandingFrame {
  double height_m = 0.0;  ///< base_link above the surface under it
  Pose3 X_WB = Pose3::Identity();
  Pose3 X_WC = Pose3::Identity();  ///< the depth camera's optical frame
  DepthImageMm depth;
  bool safe_zone_in_view = false;
  /// The hover's further frames (LandingSceneOptions::frames_per_view - 1), each from
  /// the optical pose drifted within hover_drift_m and hover_drift_rad, with its own
  /// noise; the truth is judged from X_WC.
  std::vector<DepthImageMm> more_depth;
  std::vector<Pose3> more_X_WC;
};

struct LandingScene {
  LandingTerrain terrain;
  TerrainGroundTruth truth;
  std::vector<LandingFrame> frames;
};

/// What landing_scene needs to know about the UAV and the evaluation.
struct LandingSceneOptions {
  /// One frame at each; a height at which the UAV's disc (footprint_radius_m round the
  /// base) would reach within hover_clearance_m of something below it (a pole taller than
  /// the height flown) is not flown, and that frame is not made.
  std::vector<double> heights_m{2.0, 3.0, 4.0};
  double hover_clearance_m = 0.3;
  double footprint_radius_m = 0.49;  ///< ground truth's disc
  /// How much around a zone's centre must be in view for the detector to judge it
  /// (its disc plus margin plus clearance).
  double view_radius_m = 0.84;
  LandingCriteria criteria;
  double max_tilt_rad = deg_to_rad(3.0);  ///< hover roll and pitch, uniform in +-
  DepthFrameOptions depth;                ///< the D415 model the frames are rendered with
  /// Frames a hover takes at each height (1: the single frame, drawn as before).
  int frames_per_view = 1;
  /// How far the further frames of a hover drift from the first, uniform in +- per axis.
  double hover_drift_m = 0.03;
  double hover_drift_rad = deg_to_rad(0.5);
};

/// Terrain `index` of family `seed`, with a frame at each height from the robot's
/// depth camera (`sensor` mounts it, `camera` is its model: the URDF's, or the same
/// field of view at another resolution). Seeded: the same arguments, the same bytes.
[[nodiscard]] LandingScene landing_scene(std::uint64_t seed, int index, const CameraSensor& sensor,
                                         const CameraModel& camera,
                                         const LandingSceneOptions& options);

}  // namespace ferret
