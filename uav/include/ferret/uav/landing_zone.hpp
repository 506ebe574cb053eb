#pragma once
// Landing zones from a downward depth frame, or from a hover's frames fused into one
// (docs/perception.md, "Landing zones").
//
// Pipeline: depth (mm along the optical axis, 0 = no return) -> points in the world
// (X_WC) -> a height grid of cells (count, mean, and the sums of a plane fit) ->
// candidate discs centred on every cell, of the UAV's footprint radius plus a margin
// -> per disc: least-squares plane z = a x + b y + c through the disc's cell means, slope,
// roughness (residual RMS), largest step (peak-to-peak deviation of the cell means
// from the plane), clearance from anything taller around it (judged in cells of half
// the size, so that a pole covering part of a cell is not averaged away); a disc with an
// unobserved cell is not safe (unknown is not free). Safe discs are ranked by their
// safety margin and their distance to the hidden space's opening.
//
// The cost per candidate is that of its disc's cells (about 150 at 0.1 m); it does
// not grow with the number of points.
//
// Also here: Px4LandingBaseline, the published rule of PX4-Avoidance's
// safe_landing_planner, producing the same LandingResult so both run on one frame.

#include <Eigen/Core>
#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "ferret/core/pose.hpp"
#include "ferret/perception/camera_model.hpp"
#include "ferret/perception/image.hpp"

namespace ferret {

struct RobotDescription;
struct MissionConfig;

/// One depth frame and the pose of the depth camera's optical frame it was taken from.
struct PosedDepthFrame {
  const DepthImageMm* depth = nullptr;
  Pose3 X_WC = Pose3::Identity();
};

/// The most frames of one hover fused (a D415's two seconds at 30 Hz): the mission's
/// uav.survey_frames and `ferret detect landing` keep to it.
inline constexpr int kMaxHoverFrames = 64;

/// A survey hover that judged `taken` frames and found no safe zone looks longer before it
/// gives up: the frames to judge next (twice as many, at most `most`), or `taken` once
/// `most` are in. A fused cell's noise falls with the square root of the frames, so a zone
/// that 8 frames' noise hides shows in 16 or 32 (docs/perception.md).
[[nodiscard]] constexpr int hover_frames_after_miss(int taken, int most) {
  return taken >= most ? taken : (2 * taken < most ? 2 * taken : most);
}

/// A hover's depth frames fused into one, at the first frame's pose (a temporal filter):
/// every return of every frame is re-projected into the first frame's pixels, and a
/// pixel's depth is the mean of the returns that land on it (0 where none does). The
/// depth noise then falls with the square root of the frames. (Pooling the frames'
/// points in the detector's cells would not do as well: a point's depth error also
/// moves it sideways, up to a cell at 4 m, which smears a wall's top into the cells
/// beside it however many frames are pooled.) Throws InputError for no frames, a frame
/// without its image or a frame of another size than the camera's.
[[nodiscard]] DepthImageMm fuse_depth_frames(const std::vector<PosedDepthFrame>& frames,
                                             const CameraModel& camera);

/// fuse_depth_frames a frame at a time, for a hover whose frames come one a control
/// cycle: each frame is re-projected once, as it comes. A survey that judges 8, 16, 32
/// and then 64 frames re-projects 64 frames, not 120, and no control step re-projects
/// more than one (64 at once took a 0.36 s step). The same sums in the same order:
/// fused() is fuse_depth_frames of the frames added, bit for bit.
class DepthFrameFusion {
 public:
  explicit DepthFrameFusion(CameraModel camera);
  /// Adds a frame taken from X_WC (the depth camera's optical frame in the world).
  /// Throws InputError for a frame of another size than the camera's.
  void add(const DepthImageMm& depth, const Pose3& X_WC);
  [[nodiscard]] std::size_t frames() const { return frames_; }
  /// The fused frame's pose: the first frame's.
  [[nodiscard]] const Pose3& X_WC() const { return X_WC_; }
  [[nodiscard]] const CameraModel& camera() const { return camera_; }
  /// The mean depth of the returns that landed on each pixel (0 where none did).
  /// Throws InputError when no frame was added.
  [[nodiscard]] DepthImageMm fused() const;
  void clear();

 private:
  CameraModel camera_;
  std::shared_ptr<const std::vector<Eigen::Vector2f>> rays_;   // x/z, y/z per pixel
  std::vector<double> sum_m_;                                  // per pixel of the first frame
  std::vector<std::uint32_t> count_;                           // returns summed there
  Pose3 X_WC_ = Pose3::Identity(), X_RW_ = Pose3::Identity();  // R: the first frame
  std::size_t frames_ = 0;
};

/// Why a candidate disc is not a landing zone.
enum class LandingReject {
  kNone,        ///< safe
  kUnobserved,  ///< a cell of the disc has too few returns (unknown is not free)
  kSlope,       ///< the fitted plane is too steep
  kRoughness,   ///< residual RMS of the cell means too large
  kStep,        ///< a step or bump inside the disc
  kClearance,   ///< something taller too close around the disc (or not observed)
  kOutOfReach,  ///< the miniUGV cannot reach the opening on its tether from here
};
[[nodiscard]] const char* to_string(LandingReject reason);

struct LandingZone {
  Eigen::Vector3d center_m = Eigen::Vector3d::Zero();  ///< on the fitted plane, world frame
  double slope_deg = 0.0;
  /// The slope's standard error, from the plane fit's residuals over the disc's cells.
  double slope_sigma_deg = 0.0;
  double roughness_m = 0.0;  ///< RMS of the cell means about the plane
  double step_m = 0.0;       ///< peak-to-peak of the cell means about the plane
  double clearance_m = 0.0;  ///< from the disc's edge to the nearest taller cell (capped)
  /// Horizontal distance from the zone's winch point to the point above the opening;
  /// NaN when no opening was given.
  double distance_to_opening_m = 0.0;
  double score = 0.0;  ///< higher is better
  LandingReject reject = LandingReject::kNone;
};

struct LandingResult {
  std::vector<LandingZone> zones;  ///< safe zones, best first, at least a footprint apart
  bool no_safe_zone = true;
  std::string reason;  ///< why nothing is safe ("" when zones is not empty)
  /// A sample of rejected candidates with their reason (for overlays and diagnosis).
  std::vector<LandingZone> rejected;
};

class LandingZoneDetector {
 public:
  struct Options {
    /// The UAV's footprint: a disc that covers it at any heading
    /// (RobotDescription::circumscribed_radius_m; the M100's is 0.49 m).
    double footprint_radius_m = 0.49;
    /// Added to the footprint radius, for the disc's tests and the start of its clearance
    /// ring: half a cell, so that a feature reaching over the footprint's rim from
    /// outside covers a whole cell of the disc (a partly covered cell's mean holds only
    /// part of it).
    double margin_m = 0.05;
    /// The steepest plane the UAV lands on. A zone's fitted slope must lie under it by
    /// `slope_sigmas` of its standard error (LandingZone::slope_sigma_deg), and by at
    /// least `slope_allowance_deg` at `cell_size_m`. The noise: of a frame's hundreds of
    /// candidates the one chosen is the one whose noise made it flattest, and the error
    /// shrinks with the returns (a hover's frames fused, nearer ground). The allowance:
    /// the disc's cells reach past the footprint's rim by up to a margin and a half
    /// cell, and a step there tilts the plane they fit (a 15.2 degree slope with steps
    /// was fitted at 14.4 from one frame's 0.1 m cells); it scales with the cell.
    double max_slope_deg = 15.0;
    double slope_sigmas = 3.0;
    double slope_allowance_deg = 1.0;
    double max_roughness_m = 0.04;
    /// The highest step or bump the UAV's legs stand on, and what the measured step must
    /// stay under it by at `cell_size_m`: a block narrower than the step test's windows
    /// reads lower than it stands. The allowance scales with the cell (as the margin does),
    /// so the hover's cells of half the size leave half of it.
    double max_step_m = 0.10;
    double step_allowance_m = 0.02;
    /// Free space required around the disc, from its edge, to anything taller than
    /// the plane by `taller_than_m` or more (props, walls, poles).
    double min_clearance_m = 0.30;
    double taller_than_m = 0.20;
    /// How far under `taller_than_m` the clearance's windows judge a thing taller at
    /// `cell_size_m`: a pole or a corner covering part of a window raises its mean by
    /// only the part it covers. Scaled with the cell, as the step's allowance is.
    double taller_allowance_m = 0.05;
    double cell_size_m = 0.10;
    /// The cells for a hover's frames fused (at least `hover_min_frames` of them): their
    /// mean's noise is a fraction of one frame's, so a cell can be smaller and still hold
    /// a mean as steady as a 0.1 m cell's of one frame (a quarter of the returns, twice
    /// the noise, over sqrt(8) from 8 frames: 0.71 of it; from 4 frames only 1.0, and
    /// the found rate then went up on one seed and down on another). A feature at the
    /// disc's rim then covers a whole cell sooner, so the margin (half a cell) shrinks
    /// with the cell: margin_m * hover_cell_size_m / cell_size_m. 0: a hover uses
    /// cell_size_m too.
    double hover_cell_size_m = 0.05;
    int hover_min_frames = 8;
    int min_points_per_cell = 5;
    double min_depth_m = 0.3;  ///< returns nearer or farther are ignored
    double max_depth_m = 10.0;
    /// The opening p_WE and the reach l_0 (the mission's tether.entry_offset_m): a zone
    /// qualifies only when its winch point lies within l_0 (horizontally) of the point
    /// above the opening.
    std::optional<Eigen::Vector3d> p_WE;
    double reach_m = 1.0;
    /// The winch point in the zone's frame, horizontally (the winch under the body).
    Eigen::Vector2d p_ZW_xy_m = Eigen::Vector2d::Zero();
    int max_zones = 20;

    /// The robot's footprint (circumscribed radius, winch position) and, when given,
    /// the mission's l_0.
    [[nodiscard]] static Options for_robot(const RobotDescription& robot,
                                           const MissionConfig* mission = nullptr);
    /// Throws InputError(source, field, ...) for a value out of its range.
    void check(const std::string& source) const;
  };

  explicit LandingZoneDetector(Options options);
  [[nodiscard]] const Options& options() const { return options_; }

  /// Zones in the frame. X_WC is the pose of the depth camera's optical frame.
  /// Throws InputError when the frame's size differs from the camera's.
  [[nodiscard]] LandingResult detect(const DepthImageMm& depth, const CameraModel& camera,
                                     const Pose3& X_WC) const;
  /// Zones in a hover's frames, fused by fuse_depth_frames, at the first frame's pose;
  /// judged in the hover's cells (Options::hover_cell_size_m) from hover_min_frames on.
  [[nodiscard]] LandingResult detect(const std::vector<PosedDepthFrame>& frames,
                                     const CameraModel& camera) const;
  /// The same, for frames fused as they came. Throws InputError when none were added.
  [[nodiscard]] LandingResult detect(const DepthFrameFusion& frames) const;
  /// The options a hover of `frames` frames is judged with.
  [[nodiscard]] const Options& options_for_frames(std::size_t frames) const {
    return for_frames(frames).options();
  }

 private:
  /// A window two strides wide round a point on a stride boundary (window a covers
  /// [a, a + 2] strides from it), with the distance from the point to its nearest point.
  struct WindowOffset {
    int di, dj;
    double dist;
  };
  /// The detector a hover of `frames` frames is judged by: hover_ or this one.
  [[nodiscard]] const LandingZoneDetector& for_frames(std::size_t frames) const;
  /// Every such window of stride `unit` that comes within `limit`, nearest first.
  [[nodiscard]] static std::vector<WindowOffset> window_offsets(double unit, double limit);

  Options options_;
  /// The detector for a hover's fused frames, with the hover's cells (none when they are
  /// this one's).
  std::shared_ptr<const LandingZoneDetector> hover_;
  /// Fixed by the options, so made once: the clearance test's windows (a quarter cell's
  /// stride) out to the clearance reported, and the step test's (half a cell's stride)
  /// that overlap the disc.
  std::vector<WindowOffset> ring_, step_disc_;
};

/// PX4-Avoidance's safe_landing_planner, as its source and parameter file publish it:
/// points binned into square cells of 0.25 m on a grid of 10 m around the vehicle; a
/// cell is landable with >= 100 points and a height standard deviation <= 0.2 m; a
/// cell is then kept when its 11 x 11 neighbourhood (smoothing_size 5) holds more than
/// 70 landable cells and at most 70 cells whose mean height differs from its own by
/// more than 0.1 m. Empty cells have mean 0, as in the original grid. Over several
/// frames the original's temporal low-pass (alpha) applies. The chosen zone is the
/// landable cell nearest to the vehicle (its waypoint generator lands where it is when
/// it can), or to the opening when one is given.
class Px4LandingBaseline {
 public:
  struct Options {
    double cell_size_m = 0.25;
    double grid_size_m = 10.0;
    int n_points_threshold = 100;
    double std_dev_threshold_m = 0.2;
    int smoothing_size = 5;
    double mean_diff_threshold_m = 0.1;
    int max_n_mean_diff_cells = 70;
    int min_n_land_cells = 70;
    /// The history kept in the cells' mean and variance from frame to frame (the
    /// original's temporal low-pass, `alpha`), over a hover's frames.
    double alpha = 0.9;
    double min_depth_m = 0.3;
    double max_depth_m = 10.0;
    std::optional<Eigen::Vector3d> p_WE;
    int max_zones = 20;
  };

  explicit Px4LandingBaseline(Options options) : options_(std::move(options)) {}
  [[nodiscard]] const Options& options() const { return options_; }
  /// `p_WV`: the vehicle's position (the grid's centre); slope, roughness and clearance
  /// of the zones are not part of the rule and are left 0.
  [[nodiscard]] LandingResult detect(const DepthImageMm& depth, const CameraModel& camera,
                                     const Pose3& X_WC, const Eigen::Vector3d& p_WV) const;
  /// A hover's frames at `p_WV`, through the original's temporal low-pass (alpha):
  /// the same information ferret's detector gets from them. The low-pass starts from the
  /// first frame, as if the grid had held that view before.
  [[nodiscard]] LandingResult detect(const std::vector<PosedDepthFrame>& frames,
                                     const CameraModel& camera, const Eigen::Vector3d& p_WV) const;

 private:
  Options options_;
};

/// The depth frame false-coloured (near red to far blue, no return black) with the
/// candidates drawn: rejected in red, safe zones in green, the best one ringed in white.
[[nodiscard]] RgbImage landing_overlay(const DepthImageMm& depth, const CameraModel& camera,
                                       const Pose3& X_WC, const LandingResult& result,
                                       double footprint_radius_m);

}  // namespace ferret
