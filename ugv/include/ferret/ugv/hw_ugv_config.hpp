#pragma once
// The configuration of the miniUGV's hardware backend (HwUgvBase, hw_ugv_base.hpp):
// the serial link to its microcontroller, the camera, the EPM's driver and the
// odometry's geometry. A mission YAML carries it under `ugv.base` (docs/robots.md,
// "Configuration"):
//
//   ugv:
//     base:
//       backend: hw
//       serial: {port: /dev/ttyAMA0, baud: 115200}
//       camera: {device: /dev/video0}     # or an index, or a video file
//       epm: {via: mcu}                   # or {via: gpio, chip: gpiochip0, line: 17}
//       odometry: {wheel_radius_m: 0.02, ticks_per_rev: 360, track_width_m: 0.105}
//
// What the URDF describes (the IR sensors' poses, fields of view and ranges, the
// object camera's pose and image size, the motion limits) is not repeated here.

#include <yaml-cpp/yaml.h>

#include <string>

#include "ferret/ugv/diff_drive_odometry.hpp"

namespace ferret::ugv {

struct HwUgvConfig {
  /// Where the values came from, for errors ("mission.yaml", or "defaults").
  std::string source = "defaults";

  struct Serial {
    /// The MCU's UART: /dev/ttyAMA0 (the Pi's PL011 on GPIO 14/15), /dev/serial0, a USB
    /// adapter (/dev/ttyUSB0, /dev/ttyACM0), or a pseudo-terminal (/dev/pts/N: the fake
    /// MCU). Required: there is no safe guess.
    std::string port;
    /// 8N1, no flow control. 115200 carries the 50 Hz STATE stream with room to spare
    /// (about 2 kB/s of 11.5 kB/s).
    int baud = 115200;
  } serial;

  struct Link {
    /// At start: how long to wait for the MCU's INFO reply to HELLO (HELLO repeats
    /// every 0.2 s meanwhile) before giving up with an error.
    double connect_timeout_s = 2.0;
    /// While running: no valid STATE for this long and the link counts as lost
    /// (UgvFault::kLinkLost): the wheels are commanded to 0 and sensors give nothing.
    /// Several STATE periods (20 ms at 50 Hz), and under a second, so that the robot
    /// is not driven blind.
    double telemetry_timeout_s = 0.5;
    /// DRIVE frames a second: the set-point, repeated, is also the MCU's keepalive;
    /// 20 Hz puts 6 frames in the MCU's 300 ms watchdog.
    double command_rate_hz = 20.0;
    /// A controller that has sent no command_velocity() for this long is taken as
    /// stalled and the wheels are set to 0 (the mission controller commands every
    /// tick). 0: hold the last command forever, as UgvBase allows.
    double command_timeout_s = 1.0;
    /// While the MCU's EPM state differs from the wanted one, EPM is sent again this
    /// often (the MCU pulses only on a change; a pulse that failed is retried this slowly
    /// so the magnet's driver is not fired back to back).
    double epm_retry_s = 0.5;
  } link;

  struct Camera {
    /// The object camera: "none" (no camera: every frame is empty, UgvFault::kCamera),
    /// a device index ("0"), a V4L2 device path (/dev/video0), or a video file or URL
    /// that OpenCV's FFmpeg backend reads (a file replays in a loop, one frame a call:
    /// how the tests feed frames). Required.
    std::string device;
    /// At start: the first valid colour frame must arrive within this, otherwise the
    /// device is not the capture device it should be (an error).
    double first_frame_timeout_s = 5.0;
    /// While running: no new frame from a live camera for this long is a camera fault.
    double frame_timeout_s = 1.0;
  } camera;

  struct Epm {
    enum class Via {
      kMcu,   ///< EPM frames to the MCU, which fires the magnet's pulse and reports its state
      kGpio,  ///< a GPIO line of the Pi (libgpiod) drives the EPM driver's input
    };
    Via via = Via::kMcu;
    /// kGpio: the chip by name (gpiochip0) or path (/dev/gpiochip0), and the line offset
    /// on it (the Pi's BCM number on gpiochip0: line 17 is header pin 11).
    std::string chip;
    unsigned line = 0;
    /// kGpio: the driver's input is active low (the line is low for "on").
    bool active_low = false;
  } epm;

  /// Wheel geometry and encoders. The defaults are placeholders until measured on the
  /// robot: the URDF's 20 mm wheel radius and 105 mm between the wheels' centres, and
  /// 360 counts a wheel revolution. A skid-steered robot turns as if its track were
  /// wider than the wheels' spacing: calibrate track_width_m by turning on the spot.
  DiffDriveParams odometry;

  /// Throws InputError(source, "ugv.base.FIELD", expected, got) for the first invalid
  /// field.
  void check() const;
};

[[nodiscard]] const char* to_string(HwUgvConfig::Epm::Via via);  ///< "mcu" / "gpio"

/// Reads the `ugv.base` mapping of a mission YAML (`node`, found at `path`, for field
/// names in errors), with every default above for a key left out. `backend`, when given,
/// must be `sim` or `hw`; which backend runs is ugv_base_config_from_yaml's choice
/// (ugv_base_factory.hpp). Throws InputError naming the file and the field for an unknown key, a
/// missing port or camera, a number out of range (NaN, negative radius ...) or a key
/// without a value.
[[nodiscard]] HwUgvConfig hw_ugv_config_from_yaml(const YAML::Node& node, const std::string& source,
                                                  const std::string& path = "ugv.base");

/// Emits every field of `config` as the keys of a mapping already begun (`serial`, `link`,
/// `camera`, `epm`, `odometry`), so that hw_ugv_config_from_yaml reads it back.
void emit_hw_ugv_config(YAML::Emitter& e, const HwUgvConfig& config);

}  // namespace ferret::ugv
