#pragma once
// What the UAV's mission controller sees of the hardware: the flight controller (the
// M100's position loop through DJI's onboard SDK on the robot, a point mass with the
// M100's limits in the simulator), its two cameras, and the miniUGV over the robot
// link. Small on purpose: a backend implements these and nothing else, so the same
// controller flies the simulator and the robot (docs/mission.md).

#include <Eigen/Core>
#include <optional>
#include <string>

#include "ferret/core/pose.hpp"
#include "ferret/perception/image.hpp"

namespace ferret {

struct FlightState {
  Eigen::Vector3d p_W = Eigen::Vector3d::Zero();  ///< base_link in the world
  double yaw_rad = 0.0;
  Eigen::Vector3d v_W = Eigen::Vector3d::Zero();
  bool on_ground = true;          ///< landed, motors idle
  double battery_fraction = 1.0;  ///< 1 full, 0 empty
  /// The pilot has taken over with the remote (DJI: the RC's mode switch out of P/F):
  /// the mission stops commanding the vehicle.
  bool rc_override = false;
};

class FlightController {
 public:
  virtual ~FlightController() = default;
  [[nodiscard]] virtual std::string backend() const = 0;  ///< "sim" or "hw"
  [[nodiscard]] virtual FlightState state() const = 0;
  /// Climb straight up (from the ground or a hover) to the height `z_m` in the world.
  virtual void command_takeoff(double z_m) = 0;
  /// Fly to a position setpoint and heading at most `speed_mps` (the vehicle's own
  /// limits still apply); holds there.
  virtual void command_position(const Eigen::Vector3d& p_W, double yaw_rad, double speed_mps) = 0;
  /// Descend where it is until on the ground, then idle the motors.
  virtual void command_land() = 0;
};

/// One frame and where the camera was: X_WC is the optical frame (x right, y down,
/// z forward) in the world, from the vehicle's state and the camera's mounting.
template <class ImageT>
struct CameraShot {
  ImageT image;
  Pose3 X_WC = Pose3::Identity();
};

class UavCameras {
 public:
  virtual ~UavCameras() = default;
  /// The forward marker camera's frame now; an empty image when there is none to look at
  /// (a dropped frame; the simulator's when no marker can be in it).
  [[nodiscard]] virtual CameraShot<GrayImage> marker_frame() = 0;
  /// The downward depth camera's frame now.
  [[nodiscard]] virtual CameraShot<DepthImageMm> depth_frame() = 0;
};

/// The miniUGV as the UAV sees it over the robot link.
struct UgvReport {
  bool running = false;           ///< its mission started and not done
  bool wants_retraction = false;  ///< at the entry, asking to be lifted out
  bool done = false;
  std::string outcome;       ///< its named outcome once done
  bool object_held = false;  ///< its EPM reports contact
  Eigen::Vector2d p_WG = Eigen::Vector2d::Zero();
  Eigen::Vector2d v_WG = Eigen::Vector2d::Zero();  ///< desired velocity
  /// Its taut tether: the last fixed point (last wrap point or the entry) and the
  /// length from the entry to it, so the winch prices its motion between reports.
  Eigen::Vector2d tether_anchor_W = Eigen::Vector2d::Zero();
  double tether_to_anchor_m = 0.0;
  /// How much longer its tether may be than that (its bound less its estimate, m).
  double tether_uncertainty_m = 0.0;
  double roll_rad = 0.0;  ///< its IMU attitude (the touchdown check)
  double pitch_rad = 0.0;
  double battery_fraction = 1.0;
  /// The link carries its messages: false once it has been silent past the link's
  /// timeout (the winch then holds its length). Always true in one process.
  bool link_ok = true;

  /// What the simulated world reports for a miniUGV set down where no hidden space is:
  /// done with nothing to search, asking to be lifted out.
  [[nodiscard]] static UgvReport nothing_to_search() {
    UgvReport r;
    r.done = true;
    r.outcome = "no_hidden_space";
    r.wants_retraction = true;
    return r;
  }
};

class UgvLink {
 public:
  virtual ~UgvLink() = default;
  /// The miniUGV is at the entry of a hidden space whose entry E and heading into it
  /// the UAV estimated: start its mission there.
  virtual void deploy(const Eigen::Vector3d& p_WE, double entry_yaw_rad) = 0;
  /// The winch has lifted it out.
  virtual void retracted() = 0;
  /// Switch the EPM off (drop what it holds), hanging under the UAV.
  virtual void release_object() = 0;
  /// End its mission (it stops where it is).
  virtual void abort(const std::string& reason) = 0;
  /// Call it back: it gives up its search and returns to the entry to be lifted out.
  virtual void recall(const std::string& reason) = 0;
  [[nodiscard]] virtual UgvReport report() const = 0;
};

}  // namespace ferret
