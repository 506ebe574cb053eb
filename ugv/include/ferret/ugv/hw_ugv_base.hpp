#pragma once
// The miniUGV's real hardware behind UgvBase (docs/robots.md, "miniUGV"): its
// motor/sensor microcontroller over a serial link (ugv_mcu_protocol.hpp), the object
// camera through OpenCV, the EPM through the MCU or a GPIO line (libgpiod).
//
// - Odometry: differential drive from the MCU's cumulative encoder counts
//   (diff_drive_odometry.hpp), on the MCU's clock.
// - IR scan: one range per `ir` sensor of the URDF (the MCU reports them in the URDF's
//   order), applied to each of that sensor's beams (a single-zone range sensor returns
//   the nearest surface in its cone). Each return is re-expressed from the robot's
//   origin, where the controllers take the scan (UgvBase::ir_scan): the hit point stays
//   where the sensor, 6.5 cm ahead, saw it. Each reading is handed out once.
// - Camera frame: the newest frame, the object detector's detections re-expressed from
//   the robot's origin, and as the view (where the camera saw no object) the IR beams
//   inside the camera's field of view: the camera alone cannot tell how far it sees.
// - Faults (UgvStatus::faults): see UgvFault. While the link is lost the wheels are
//   commanded to 0 and sensors give nothing; the base recovers by itself.
//
// Threads: one thread owns the serial port (reads telemetry, sends DRIVE at the
// control rate and EPM while it differs); a live camera has a grabbing thread. Every
// public call is safe from any one controller thread. No OpenCV or libgpiod type
// appears here (pimpl).

#include <cstdint>
#include <memory>
#include <optional>
#include <stdexcept>
#include <string>

#include "ferret/core/pose.hpp"
#include "ferret/mapping/object_search_params.hpp"
#include "ferret/ugv/hw_ugv_config.hpp"
#include "ferret/ugv/object_detector.hpp"
#include "ferret/ugv/ugv_base.hpp"
#include "ferret/ugv/ugv_mcu_protocol.hpp"
#include "ferret/urdf/robot_description.hpp"

namespace ferret::ugv {

/// A failure to bring the hardware up, each kind with its own message naming the device.
class HwUgvError : public std::runtime_error {
 public:
  enum class Kind {
    kSerialMissing,    ///< the serial port does not exist or cannot be opened
    kNoResponse,       ///< the port opened, but nothing came back to HELLO
    kWrongDevice,      ///< bytes came back, but no valid frame: another device or baud rate
    kProtocolVersion,  ///< valid frames of another protocol version
    kMismatch,         ///< the MCU reports another IR sensor count than the URDF has
    kCameraMissing,    ///< the camera cannot be opened
    kCameraNoFrames,   ///< it opened, but gave no valid colour frame in time
    kGpio,             ///< the EPM's gpio chip or line cannot be had
  };
  HwUgvError(Kind kind, const std::string& message) : std::runtime_error(message), kind_(kind) {}
  [[nodiscard]] Kind kind() const { return kind_; }

 private:
  Kind kind_;
};
[[nodiscard]] const char* to_string(HwUgvError::Kind kind);

/// What the link has seen so far (for bring-up and logs).
struct HwLinkStats {
  mcu::ReaderStats reader;         ///< frames, bad CRCs, bad lengths, other versions, noise
  std::uint64_t states = 0;        ///< STATE frames used
  std::uint64_t bad_payloads = 0;  ///< frames of a known type whose payload did not decode
  std::uint64_t unknown_types = 0;
  std::uint64_t lost_states = 0;   ///< gaps in the STATE sequence numbers
  std::uint64_t link_losses = 0;   ///< times the link was declared lost
  std::uint64_t mcu_restarts = 0;  ///< times the MCU's clock went backwards
  std::uint64_t drive_frames_sent = 0;
  std::uint64_t epm_frames_sent = 0;
};

/// The MCU's last word, as it said it.
struct McuTelemetry {
  std::optional<mcu::McuInfo> info;    ///< from the connection's HELLO
  std::optional<mcu::McuState> state;  ///< the newest STATE
};

class HwUgvBase final : public UgvBase {
 public:
  /// Brings the robot up: opens the serial port, identifies the MCU (HELLO -> INFO
  /// within link.connect_timeout_s) and checks its IR count against the URDF's `ir`
  /// sensors, opens the camera and waits for its first valid frame, claims the EPM's
  /// GPIO line (via: gpio), and starts the link's thread. The odometry starts at
  /// X_WG_start. The object detector is the ColourObjectDetector with the mission's
  /// object-search constants, limited to the object camera's range (D_cam).
  /// @throws InputError for an invalid config (naming the field) or a URDF without an
  ///         `ir` array or object camera; HwUgvError for hardware that is missing, silent
  ///         or not what it should be (the message names the device and what to check).
  HwUgvBase(const HwUgvConfig& config, const RobotDescription& robot,
            const ObjectSearchParams& search = {}, const Pose2& X_WG_start = {});
  /// The same with a detector of the caller's (detector must not be null).
  HwUgvBase(const HwUgvConfig& config, const RobotDescription& robot,
            std::unique_ptr<ObjectDetector> detector, const Pose2& X_WG_start = {});
  /// Commands the wheels to 0 (a few DRIVE 0 frames) and stops the threads. The EPM is
  /// left as it is: an object on the magnet stays there.
  ~HwUgvBase() override;
  HwUgvBase(const HwUgvBase&) = delete;
  HwUgvBase& operator=(const HwUgvBase&) = delete;

  [[nodiscard]] std::string backend() const override { return "hw"; }
  [[nodiscard]] Pose2 odometry() const override;
  /// 0 while the link is lost.
  [[nodiscard]] double speed_mps() const override;
  /// A new IR reading, or no beams: none came since the last call, or the link is lost.
  [[nodiscard]] RangeScan ir_scan() override;
  /// A new camera frame; no beams and no detections when there is none (no camera, no
  /// new frame, the link lost: a pose the base does not know).
  [[nodiscard]] CameraFrame camera_frame(double time_s) override;
  /// Clipped to the URDF's limits (NaN: 0), turned into wheel speeds with the track
  /// width (scaled down together if a wheel would exceed its limit) and sent at the
  /// control rate.
  void command_velocity(double v_mps, double w_radps) override;
  void set_epm(bool on) override;
  /// Battery and contact as the MCU reports them (the last known while the link is
  /// lost); epm_on as the MCU reports it (via: mcu) or as the GPIO line is set.
  [[nodiscard]] UgvStatus status() const override;

  [[nodiscard]] McuTelemetry telemetry() const;
  [[nodiscard]] HwLinkStats link_stats() const;
  /// One line: what is wrong now and why ("link lost: no STATE for 0.62 s on
  /// /dev/ttyAMA0 (14 frames with a bad CRC)"), or "ok".
  [[nodiscard]] std::string diagnosis() const;
  /// The wheel set-points in mm/s the last command gives (after the limits), left/right.
  [[nodiscard]] mcu::DriveCommand wheel_command(double v_mps, double w_radps) const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace ferret::ugv
