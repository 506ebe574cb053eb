#pragma once
// The miniUGV's hardware as its mission controller sees it: odometry, the IR scan,
// the camera's detections, a velocity command, the electro-permanent magnet (EPM) and
// a status. The simulator implements it (sim/sim_ugv_base.hpp); a robot's backend
// implements it over its microcontroller. Controllers take a UgvBase&, never
// a concrete backend, so they cannot read ground truth.

#include <cstdint>
#include <string>

#include "ferret/core/pose.hpp"
#include "ferret/mapping/ir_grid.hpp"
#include "ferret/mapping/object_map.hpp"

namespace ferret {

/// What keeps a base from doing what it is told: bits of UgvStatus::faults. A real
/// backend sets them (hw_ugv_base.hpp says when); the simulator has none.
enum class UgvFault : std::uint32_t {
  /// No telemetry from the robot's microcontroller within the link's timeout: the base
  /// commands the wheels to 0 and drops velocity commands, odometry holds its last
  /// pose, IR scans and camera frames carry nothing. Clears itself when telemetry
  /// resumes; driving resumes with the first command after that.
  kLinkLost = 1u << 0,
  /// The microcontroller speaks another protocol version (its frames are ignored).
  kProtocolVersion = 1u << 1,
  /// A motor, encoder or battery cut-off fault the microcontroller reports.
  kDrive = 1u << 2,
  /// An IR sensor or the IMU is not answering (IR scans may lack beams).
  kSensor = 1u << 3,
  /// No camera, or no new frame for the camera's timeout: frames carry nothing.
  kCamera = 1u << 4,
  /// The EPM did not switch (the magnet's driver or its GPIO line failed).
  kEpm = 1u << 5,
};
/// "link_lost", "camera", ...
[[nodiscard]] const char* to_string(UgvFault fault);
/// The names of the set bits, comma separated; "none" for 0.
[[nodiscard]] std::string describe_faults(std::uint32_t faults);

struct UgvStatus {
  double battery_fraction = 1.0;  ///< charge left, 0..1
  bool epm_on = false;
  /// The EPM side touches a ferromagnetic body (the magnet's hall sensor, or a bumper):
  /// with the EPM on, the object is held.
  bool contact = false;
  /// UgvFault bits; 0: healthy.
  std::uint32_t faults = 0;

  [[nodiscard]] bool has(UgvFault fault) const {
    return (faults & static_cast<std::uint32_t>(fault)) != 0;
  }
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
