#pragma once
// The miniUGV's hardware as its mission controller sees it: odometry, the IR scan,
// the camera's detections, a velocity command, the electro-permanent magnet (EPM) and
// a status. The simulator implements it (sim/sim_ugv_base.hpp); a robot's backend
// implements it over its microcontroller (issue 13). Controllers take a UgvBase&, never
// a concrete backend, so they cannot read ground truth.

#include <string>

#include "ferret/core/pose.hpp"
#include "ferret/mapping/ir_grid.hpp"
#include "ferret/mapping/object_map.hpp"

namespace ferret {

struct UgvStatus {
  double battery_fraction = 1.0;  ///< charge left, 0..1
  bool epm_on = false;
  /// The EPM side touches a ferromagnetic body (the magnet's hall sensor, or a bumper):
  /// with the EPM on, the object is held.
  bool contact = false;
};

class UgvBase {
 public:
  virtual ~UgvBase() = default;
  /// "sim" or "hw": printed in the run's first lines so nobody mistakes one for the other.
  [[nodiscard]] virtual std::string backend() const = 0;
  /// The pose estimate in the hidden space's frame (odometry, drift and all).
  [[nodiscard]] virtual Pose2 odometry() const = 0;
  /// Forward speed the wheels report, m/s.
  [[nodiscard]] virtual double speed_mps() const = 0;
  /// The IR fan from the current pose (sensor at the robot's origin, facing forward).
  [[nodiscard]] virtual RangeScan ir_scan() = 0;
  /// One camera frame: where the camera could see and the object detector's output.
  [[nodiscard]] virtual CameraFrame camera_frame(double time_s) = 0;
  /// Forward speed and yaw rate set-point, held until the next command. The base
  /// applies its own limits (a command beyond them is clipped, never an error).
  virtual void command_velocity(double v_mps, double w_radps) = 0;
  virtual void set_epm(bool on) = 0;
  [[nodiscard]] virtual UgvStatus status() const = 0;
};

}  // namespace ferret
