#include "ferret/ugv/hw_ugv_base.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <atomic>
#include <chrono>
#include <cmath>
#include <filesystem>
#include <limits>
#include <mutex>
#include <thread>
#include <vector>

#include "ferret/core/error.hpp"
#include "ferret/link/serial_port.hpp"
#include "ferret/perception/camera_model.hpp"
#include "gpio_line.hpp"
#include "hw_camera.hpp"

namespace ferret::ugv {
namespace {

using Clock = std::chrono::steady_clock;
using Kind = HwUgvError::Kind;

double seconds_since(Clock::time_point t, Clock::time_point now) {
  return std::chrono::duration<double>(now - t).count();
}

Clock::duration to_duration(double s) {
  return std::chrono::duration_cast<Clock::duration>(std::chrono::duration<double>(s));
}

double yaw_of(const Pose3& X) {
  const Eigen::Matrix3d& R = X.linear();
  return std::atan2(R(1, 0), R(0, 0));
}

/// One beam of an IR sensor in the base frame B.
struct Beam {
  Eigen::Vector2d p_BO;   ///< where it starts
  Eigen::Vector2d dir_B;  ///< unit direction
};

/// An `ir` sensor: its beams, in the URDF's order, and its range limits.
struct IrSensor {
  std::string name;
  std::vector<Beam> beams;
  double range_min_m = 0.0, range_max_m = 0.0;
};

std::vector<IrSensor> ir_sensors_of(const RobotDescription& robot) {
  (void)robot.ir_array();  // throws InputError naming the URDF when there is none
  std::vector<IrSensor> out;
  for (const auto& name : robot.roles.at(std::string(kRoleIr))) {
    const RangeSensor* r = robot.find_range_sensor(name);
    if (r == nullptr) continue;
    IrSensor s{name, {}, r->range_min_m, r->range_max_m};
    for (int i = 0; i < r->samples; ++i) {
      // Flattened to B's xy plane, as RobotDescription::ir_array does.
      const double a = r->beam_angle_rad(i);
      const Eigen::Vector3d d = r->X_BS.linear() * Eigen::Vector3d(std::cos(a), std::sin(a), 0.0);
      s.beams.push_back(
          {r->X_BS.translation().head<2>(), Eigen::Vector2d(d.x(), d.y()).normalized()});
    }
    out.push_back(std::move(s));
  }
  return out;
}

}  // namespace

const char* to_string(HwUgvError::Kind kind) {
  switch (kind) {
    case Kind::kSerialMissing:
      return "serial_missing";
    case Kind::kNoResponse:
      return "no_response";
    case Kind::kWrongDevice:
      return "wrong_device";
    case Kind::kProtocolVersion:
      return "protocol_version";
    case Kind::kMismatch:
      return "mismatch";
    case Kind::kCameraMissing:
      return "camera_missing";
    case Kind::kCameraNoFrames:
      return "camera_no_frames";
    case Kind::kGpio:
      return "gpio";
  }
  return "unknown";
}

struct HwUgvBase::Impl {
  HwUgvConfig config;
  std::string port;
  // What the URDF describes.
  std::vector<IrSensor> ir;
  double ir_scan_range_m = 0.0;  ///< the farthest any beam reaches from B's origin
  bool has_camera = false;
  Eigen::Vector2d p_BC = Eigen::Vector2d::Zero();  ///< the object camera in B
  double yaw_BC_rad = 0.0;
  double camera_hfov_rad = 0.0;
  double camera_range_m = 0.0;  ///< D_cam
  std::optional<CameraModel> camera_model;
  double max_v_mps = 0.0, max_w_radps = 0.0, max_wheel_mps = 0.0;

  std::unique_ptr<link::SerialPort> serial;
  std::unique_ptr<ObjectDetector> detector;
  std::unique_ptr<internal::HwCamera> camera;
  std::unique_ptr<internal::GpioLine> gpio;

  // Everything below under `mutex` (the link thread and the controller's calls).
  mutable std::mutex mutex;
  mcu::FrameReader reader;
  DiffDriveOdometry odometry{DiffDriveParams{}, Pose2{}};
  McuTelemetry telemetry;
  HwLinkStats stats;
  Clock::time_point last_state_at = Clock::now();
  Clock::time_point recovered_at = Clock::now();
  std::optional<Clock::time_point> bad_version_at;
  bool link_lost = false;
  std::string io_problem;  ///< the last serial read/write failure
  std::optional<std::uint8_t> last_state_seq;
  // The controller's wishes.
  mcu::DriveCommand wanted;
  std::optional<Clock::time_point> command_at;
  std::optional<bool> epm_wanted;
  Clock::time_point epm_sent_at = Clock::time_point::min();
  bool gpio_epm_on = false, gpio_failed = false;
  // IR readings: each handed out once.
  std::vector<std::uint16_t> ir_mm;
  Pose2 ir_pose;
  bool ir_new = false;
  std::uint64_t ir_count_mismatches = 0;

  std::uint8_t tx_seq = 0;
  std::atomic<bool> stop{false};
  std::thread io;

  // ------------------------------------------------------------ set-up

  void take_robot(const RobotDescription& robot) {
    ir = ir_sensors_of(robot);
    for (const auto& s : ir)
      for (const auto& b : s.beams)
        ir_scan_range_m = std::max(ir_scan_range_m, b.p_BO.norm() + s.range_max_m);
    max_v_mps = robot.limits.max_velocity_mps;
    max_w_radps = robot.limits.max_yaw_rate_radps;
    max_wheel_mps = robot.wheel_speed_limit_mps.value_or(max_v_mps);
    if (config.camera.device != "none") {
      const CameraSensor& cam = robot.object_camera();  // InputError naming the URDF if none
      has_camera = true;
      p_BC = cam.X_BS.translation().head<2>();
      yaw_BC_rad = yaw_of(cam.X_BS);
      camera_hfov_rad = cam.horizontal_fov_rad;
      camera_range_m = cam.range_max_m;
      camera_model = ::ferret::camera_model(cam, robot.source);
    }
  }

  void write(const std::vector<std::uint8_t>& bytes) { serial->write(bytes); }

  void open_serial() {
    port = config.serial.port;
    std::error_code ec;
    if (!std::filesystem::exists(port, ec))
      throw HwUgvError(Kind::kSerialMissing,
                       fmt::format("miniUGV MCU serial port '{}': no such device (ls -l "
                                   "/dev/serial0 /dev/ttyAMA0 /dev/ttyUSB*; on a Pi, enable the "
                                   "UART and disable the serial console)",
                                   port));
    try {
      serial = link::open_serial_port(port, config.serial.baud);
    } catch (const link::SerialError& e) {
      throw HwUgvError(Kind::kSerialMissing,
                       fmt::format("miniUGV MCU serial port '{}': cannot open at {} baud: {}", port,
                                   config.serial.baud, e.what()));
    }
  }

  /// HELLO until INFO, then the IR count against the URDF's.
  void identify(const std::string& urdf) {
    serial->discard_input();
    const auto start = Clock::now();
    const auto deadline = start + to_duration(config.link.connect_timeout_s);
    auto next_hello = start;
    std::uint64_t bytes = 0, valid_frames = 0;
    std::optional<std::uint8_t> other_version;
    while (Clock::now() < deadline) {
      if (Clock::now() >= next_hello) {
        write(mcu::encode_hello(tx_seq++));
        next_hello += std::chrono::milliseconds(200);
      }
      bytes += reader.receive(*serial, 20);
      while (const auto ev = reader.next()) {
        if (ev->status == mcu::DecodeResult::Status::kBadVersion) {
          other_version = ev->frame.version;
          continue;
        }
        ++valid_frames;
        if (ev->frame.type != mcu::type::kInfo) continue;
        const auto info = mcu::decode_info(ev->frame.payload);
        if (!info) {
          ++stats.bad_payloads;
          continue;
        }
        telemetry.info = *info;
        if (info->ir_count != ir.size()) {
          std::string names;
          for (const auto& s : ir) names += (names.empty() ? "" : ", ") + s.name;
          throw HwUgvError(Kind::kMismatch,
                           fmt::format("the MCU on '{}' reports {} IR sensors; the URDF '{}' has "
                                       "{} with role ir ({}): the MCU sends one range a sensor, "
                                       "in the URDF's order",
                                       port, info->ir_count, urdf, ir.size(), names));
        }
        return;
      }
    }
    const double t = config.link.connect_timeout_s;
    const auto& rs = reader.stats();
    if (other_version)
      throw HwUgvError(Kind::kProtocolVersion,
                       fmt::format("the MCU on '{}' speaks protocol version {}; this host speaks "
                                   "version {} (flash the matching firmware, or update ferret)",
                                   port, *other_version, mcu::kProtocolVersion));
    if (valid_frames > 0)
      throw HwUgvError(Kind::kNoResponse,
                       fmt::format("the MCU on '{}' sends frames but gave no INFO reply to HELLO "
                                   "within {} s (firmware without HELLO support?)",
                                   port, t));
    if (bytes > 0)
      throw HwUgvError(Kind::kWrongDevice,
                       fmt::format("'{}' sent {} bytes within {} s, none of them a valid frame "
                                   "({} with a bad CRC): another device on this port, or not "
                                   "{} baud",
                                   port, bytes, t, rs.bad_crc, config.serial.baud));
    throw HwUgvError(Kind::kNoResponse,
                     fmt::format("no reply from the miniUGV MCU on '{}' within {} s (is it "
                                 "powered, TX and RX crossed, the baud rate {}?)",
                                 port, t, config.serial.baud));
  }

  // ------------------------------------------------------------ the link thread

  /// What the wheels should do now. @pre mutex held
  mcu::DriveCommand drive_now(Clock::time_point now) const {
    if (link_lost || !command_at) return {};
    // A command from before the link came back was made blind: wait for a new one.
    if (*command_at < recovered_at) return {};
    if (config.link.command_timeout_s > 0 &&
        seconds_since(*command_at, now) > config.link.command_timeout_s)
      return {};
    return wanted;
  }

  void handle_state(const mcu::Frame& frame, Clock::time_point now) {
    const auto s = mcu::decode_state(frame.payload);
    if (!s) {
      ++stats.bad_payloads;
      return;
    }
    ++stats.states;
    if (last_state_seq)
      stats.lost_states += static_cast<std::uint8_t>(frame.seq - *last_state_seq - 1);
    last_state_seq = frame.seq;
    const std::optional<mcu::McuState>& prev = telemetry.state;
    if (prev && static_cast<std::int32_t>(s->mcu_time_ms - prev->mcu_time_ms) < 0)
      ++stats.mcu_restarts;
    odometry.update(s->left_ticks, s->right_ticks, s->mcu_time_ms);
    const bool new_ir = !prev || prev->ir_seq != s->ir_seq || link_lost;
    if (s->ir_mm.size() != ir.size()) {
      ++ir_count_mismatches;
    } else if (new_ir) {
      ir_mm = s->ir_mm;
      ir_pose = odometry.pose();
      ir_new = true;
    }
    if (link_lost) {
      link_lost = false;
      recovered_at = now;
    }
    last_state_at = now;
    telemetry.state = *s;
  }

  void handle(const mcu::DecodeResult& ev, Clock::time_point now) {
    if (ev.status == mcu::DecodeResult::Status::kBadVersion) {
      bad_version_at = now;
      return;
    }
    switch (ev.frame.type) {
      case mcu::type::kState:
        handle_state(ev.frame, now);
        break;
      case mcu::type::kInfo:
        if (const auto info = mcu::decode_info(ev.frame.payload))
          telemetry.info = *info;
        else
          ++stats.bad_payloads;
        break;
      default:
        ++stats.unknown_types;
    }
  }

  void run() {
    const auto period = to_duration(1.0 / config.link.command_rate_hz);
    auto next_drive = Clock::now();
    std::array<std::uint8_t, 512> chunk{};
    while (!stop) {
      std::size_t n = 0;
      bool failed = false;
      try {
        // Outside the lock: the controller's calls go on while the port waits.
        n = serial->read_some(chunk, 5);
      } catch (const link::SerialError& e) {
        std::lock_guard lock(mutex);
        io_problem = e.what();
        failed = true;
      }
      const auto now = Clock::now();
      std::vector<std::vector<std::uint8_t>> out;
      {
        std::lock_guard lock(mutex);
        reader.push(std::span(chunk).first(n));
        while (const auto ev = reader.next()) handle(*ev, now);
        if (!link_lost && seconds_since(last_state_at, now) > config.link.telemetry_timeout_s) {
          link_lost = true;
          ++stats.link_losses;
        }
        if (now >= next_drive) {
          out.push_back(mcu::encode_drive(tx_seq++, drive_now(now)));
          ++stats.drive_frames_sent;
          next_drive = std::max(next_drive + period, now);
        }
        if (epm_wanted && config.epm.via == HwUgvConfig::Epm::Via::kMcu && !link_lost) {
          const bool reported = telemetry.state && (telemetry.state->flags & mcu::flag::kEpmOn);
          if (reported != *epm_wanted &&
              (epm_sent_at == Clock::time_point::min() ||
               seconds_since(epm_sent_at, now) >= config.link.epm_retry_s)) {
            out.push_back(mcu::encode_epm(tx_seq++, mcu::EpmCommand{*epm_wanted}));
            ++stats.epm_frames_sent;
            epm_sent_at = now;
          }
        }
      }
      for (const auto& bytes : out) {
        try {
          write(bytes);
        } catch (const link::SerialError& e) {
          std::lock_guard lock(mutex);
          io_problem = e.what();
        }
      }
      // A port that fails at once (a USB adapter pulled out) must not spin the core.
      if (failed) std::this_thread::sleep_for(std::chrono::milliseconds(20));
    }
  }

  // ------------------------------------------------------------ queries

  /// @pre mutex held
  bool lost(Clock::time_point now) const {
    return link_lost || seconds_since(last_state_at, now) > config.link.telemetry_timeout_s;
  }

  /// A reading of sensor k's beam b, from B's origin (bearing from B's x axis, range),
  /// or no return (range = the scan's maximum).
  RangeBeam beam_from_origin(const IrSensor& s, const Beam& b, std::uint16_t mm) const {
    const double r = mm / 1000.0;
    if (mm == mcu::kIrNoReturn || r < s.range_min_m || r >= s.range_max_m) {
      const Eigen::Vector2d far = b.p_BO + s.range_max_m * b.dir_B;
      return {std::atan2(far.y(), far.x()), ir_scan_range_m};
    }
    const Eigen::Vector2d p = b.p_BO + r * b.dir_B;
    return {std::atan2(p.y(), p.x()), p.norm()};
  }

  std::vector<RangeBeam> beams_of(const std::vector<std::uint16_t>& mm) const {
    std::vector<RangeBeam> out;
    for (std::size_t k = 0; k < ir.size() && k < mm.size(); ++k)
      for (const auto& b : ir[k].beams) out.push_back(beam_from_origin(ir[k], b, mm[k]));
    return out;
  }

  std::uint32_t faults(Clock::time_point now) const {
    std::uint32_t f = 0;
    const auto set = [&f](UgvFault x) { f |= static_cast<std::uint32_t>(x); };
    if (lost(now)) set(UgvFault::kLinkLost);
    if (bad_version_at && seconds_since(*bad_version_at, now) <= config.link.telemetry_timeout_s)
      set(UgvFault::kProtocolVersion);
    if (telemetry.state) {
      const std::uint16_t mf = telemetry.state->faults;
      if (mf & (mcu::fault::kMotorLeft | mcu::fault::kMotorRight | mcu::fault::kEncoder |
                mcu::fault::kBatteryCritical))
        set(UgvFault::kDrive);
      if ((mf & (mcu::fault::kImu | mcu::fault::kIr)) || telemetry.state->ir_mm.size() != ir.size())
        set(UgvFault::kSensor);
      if (config.epm.via == HwUgvConfig::Epm::Via::kMcu && (mf & mcu::fault::kEpm))
        set(UgvFault::kEpm);
    }
    if (config.epm.via == HwUgvConfig::Epm::Via::kGpio && gpio_failed) set(UgvFault::kEpm);
    if (!camera || !camera->healthy()) set(UgvFault::kCamera);
    return f;
  }

  /// A map detection from the camera re-expressed from B's origin.
  ::ferret::ObjectDetection from_origin(const ObjectDetection& d) const {
    const double a = yaw_BC_rad + d.bearing_rad;
    const Eigen::Vector2d p = p_BC + d.distance_m * Eigen::Vector2d(std::cos(a), std::sin(a));
    ::ferret::ObjectDetection out = to_map_detection(d);
    out.bearing_rad = std::atan2(p.y(), p.x());
    out.distance_m = p.norm();
    return out;
  }
};

HwUgvBase::HwUgvBase(const HwUgvConfig& config, const RobotDescription& robot,
                     const ObjectSearchParams& search, const Pose2& X_WG_start)
    : HwUgvBase(
          config, robot,
          [&]() -> std::unique_ptr<ObjectDetector> {
            ColourObjectDetector::Options o;
            o.search = search;
            if (const CameraSensor* cam = robot.find_object_camera())
              o.max_distance_m = cam->range_max_m;  // D_cam
            return std::make_unique<ColourObjectDetector>(o);
          }(),
          X_WG_start) {}

HwUgvBase::HwUgvBase(const HwUgvConfig& config, const RobotDescription& robot,
                     std::unique_ptr<ObjectDetector> detector, const Pose2& X_WG_start)
    : impl_(std::make_unique<Impl>()) {
  Impl& m = *impl_;
  config.check();
  if (!detector) throw std::invalid_argument("HwUgvBase: no object detector");
  m.config = config;
  m.detector = std::move(detector);
  m.take_robot(robot);
  m.odometry = DiffDriveOdometry(config.odometry, X_WG_start);
  m.ir_pose = X_WG_start;
  m.open_serial();
  m.identify(robot.source);
  if (m.has_camera)
    m.camera = std::make_unique<internal::HwCamera>(
        config.camera.device, m.camera_model->width_px, m.camera_model->height_px,
        config.camera.first_frame_timeout_s, config.camera.frame_timeout_s);
  if (config.epm.via == HwUgvConfig::Epm::Via::kGpio)
    m.gpio = std::make_unique<internal::GpioLine>(config.epm.chip, config.epm.line,
                                                  config.epm.active_low, "ferret-epm");
  m.last_state_at = m.recovered_at = Clock::now();
  m.io = std::thread([&m] { m.run(); });
}

HwUgvBase::~HwUgvBase() {
  Impl& m = *impl_;
  m.stop = true;
  if (m.io.joinable()) m.io.join();
  // The wheels stop now, not at the MCU's watchdog; a frame lost on the way is covered
  // by the next two.
  for (int i = 0; i < 3; ++i) {
    try {
      m.write(mcu::encode_drive(m.tx_seq++, {}));
    } catch (const link::SerialError&) {
      break;
    }
  }
}

Pose2 HwUgvBase::odometry() const {
  std::lock_guard lock(impl_->mutex);
  return impl_->odometry.pose();
}

double HwUgvBase::speed_mps() const {
  std::lock_guard lock(impl_->mutex);
  return impl_->lost(Clock::now()) ? 0.0 : impl_->odometry.speed_mps();
}

RangeScan HwUgvBase::ir_scan() {
  Impl& m = *impl_;
  std::lock_guard lock(m.mutex);
  RangeScan scan{m.odometry.pose(), m.ir_scan_range_m, {}};
  if (m.lost(Clock::now()) || !m.ir_new) return scan;
  m.ir_new = false;
  scan.X_WS = m.ir_pose;  // where the robot was when the sensors read
  scan.beams = m.beams_of(m.ir_mm);
  return scan;
}

CameraFrame HwUgvBase::camera_frame(double time_s) {
  Impl& m = *impl_;
  CameraFrame frame;
  frame.time_s = time_s;
  {
    std::lock_guard lock(m.mutex);
    frame.view = {m.odometry.pose(), m.camera_range_m, {}};
  }
  if (!m.camera) return frame;
  const std::optional<RgbImage> image = m.camera->next_frame();
  if (!image) return frame;
  // The detector runs outside the lock: the link thread keeps reading meanwhile.
  const std::vector<ObjectDetection> detections = m.detector->detect(*image, *m.camera_model);
  std::lock_guard lock(m.mutex);
  if (m.lost(Clock::now())) return frame;  // no pose to put the frame at
  frame.view.X_WS = m.odometry.pose();
  for (const auto& d : detections) frame.detections.push_back(m.from_origin(d));
  // Where the camera saw no object: along the IR beams inside its field of view, to
  // their return or D_cam. The camera alone cannot tell how far it sees.
  for (RangeBeam b : m.beams_of(m.ir_mm)) {
    const double off_axis = std::abs(wrap_angle_rad(b.bearing_rad - m.yaw_BC_rad));
    if (off_axis > m.camera_hfov_rad / 2) continue;
    b.range_m = std::min(b.range_m, m.camera_range_m);
    frame.view.beams.push_back(b);
  }
  return frame;
}

mcu::DriveCommand HwUgvBase::wheel_command(double v_mps, double w_radps) const {
  const Impl& m = *impl_;
  // A base clips, it does not refuse; NaN (a controller's bug) stops the robot.
  const double v = std::isfinite(v_mps) ? std::clamp(v_mps, -m.max_v_mps, m.max_v_mps) : 0.0;
  const double w =
      std::isfinite(w_radps) ? std::clamp(w_radps, -m.max_w_radps, m.max_w_radps) : 0.0;
  const double half_track = 0.5 * m.config.odometry.track_width_m;
  double left = v - w * half_track, right = v + w * half_track;
  // A wheel beyond its limit slows both together: the curvature stays the controller's.
  const double fastest = std::max(std::abs(left), std::abs(right));
  if (fastest > m.max_wheel_mps) {
    left *= m.max_wheel_mps / fastest;
    right *= m.max_wheel_mps / fastest;
  }
  const auto mmps = [](double mps) {
    return static_cast<std::int16_t>(std::clamp<long>(std::lround(mps * 1000.0), -32767, 32767));
  };
  return {mmps(left), mmps(right)};
}

void HwUgvBase::command_velocity(double v_mps, double w_radps) {
  const mcu::DriveCommand c = wheel_command(v_mps, w_radps);
  std::lock_guard lock(impl_->mutex);
  impl_->wanted = c;
  impl_->command_at = Clock::now();
}

void HwUgvBase::set_epm(bool on) {
  Impl& m = *impl_;
  if (m.gpio) {
    const bool ok = m.gpio->set(on);
    std::lock_guard lock(m.mutex);
    if (ok) m.gpio_epm_on = on;
    m.gpio_failed = !ok;
    return;
  }
  std::lock_guard lock(m.mutex);
  if (m.epm_wanted != on) m.epm_sent_at = Clock::time_point::min();  // send it at once
  m.epm_wanted = on;
}

UgvStatus HwUgvBase::status() const {
  const Impl& m = *impl_;
  std::lock_guard lock(m.mutex);
  UgvStatus s;
  if (m.telemetry.state) {
    s.battery_fraction = std::min<int>(m.telemetry.state->battery_percent, 100) / 100.0;
    s.contact = (m.telemetry.state->flags & mcu::flag::kContact) != 0;
    s.epm_on = (m.telemetry.state->flags & mcu::flag::kEpmOn) != 0;
  }
  if (m.gpio) s.epm_on = m.gpio_epm_on;
  s.faults = m.faults(Clock::now());
  return s;
}

McuTelemetry HwUgvBase::telemetry() const {
  std::lock_guard lock(impl_->mutex);
  return impl_->telemetry;
}

HwLinkStats HwUgvBase::link_stats() const {
  std::lock_guard lock(impl_->mutex);
  HwLinkStats s = impl_->stats;
  s.reader = impl_->reader.stats();
  return s;
}

std::string HwUgvBase::diagnosis() const {
  const Impl& m = *impl_;
  std::lock_guard lock(m.mutex);
  const auto now = Clock::now();
  std::vector<std::string> parts;
  const auto& rs = m.reader.stats();
  if (m.lost(now)) {
    std::string why = fmt::format("link lost: no STATE for {:.2f} s on '{}'",
                                  seconds_since(m.last_state_at, now), m.port);
    if (rs.bad_crc > 0 || rs.bad_length > 0)
      why += fmt::format(" ({} frames with a bad CRC, {} with a bad length so far)", rs.bad_crc,
                         rs.bad_length);
    if (!m.io_problem.empty()) why += ": " + m.io_problem;
    parts.push_back(why);
  }
  if (m.bad_version_at &&
      seconds_since(*m.bad_version_at, now) <= m.config.link.telemetry_timeout_s)
    parts.push_back(fmt::format("the MCU sends protocol version {}, this host speaks {}",
                                rs.last_bad_version, mcu::kProtocolVersion));
  if (m.telemetry.state && m.telemetry.state->faults != 0)
    parts.push_back("MCU faults: " + mcu::describe_faults(m.telemetry.state->faults));
  if (m.telemetry.state && m.telemetry.state->ir_mm.size() != m.ir.size())
    parts.push_back(fmt::format("STATE carries {} IR ranges, the URDF has {} sensors",
                                m.telemetry.state->ir_mm.size(), m.ir.size()));
  if (!m.camera)
    parts.push_back("no camera (camera.device: none)");
  else if (const std::string p = m.camera->problem(); !p.empty())
    parts.push_back("camera '" + m.config.camera.device + "': " + p);
  if (m.gpio_failed) parts.push_back("the EPM's gpio line could not be set");
  if (parts.empty()) return "ok";
  std::string out;
  for (const auto& p : parts) out += (out.empty() ? "" : "; ") + p;
  return out;
}

}  // namespace ferret::ugv
