#include "ferret/ugv/hw_ugv_config.hpp"

#include <fmt/format.h>

#include <cmath>

#include "ferret/core/backend.hpp"
#include "ferret/core/error.hpp"
#include "ferret/core/number.hpp"
#include "ferret/core/yaml_config.hpp"
#include "ferret/core/yaml_emit.hpp"
#include "ferret/ugv/ugv_base_factory.hpp"

namespace ferret::ugv {
namespace {

constexpr const char* kRoot = "ugv.base";

std::string field(const char* section, const char* key) {
  return fmt::format("{}.{}.{}", kRoot, section, key);
}

void check_range(double v, const NumberRange& range, const std::string& source,
                 const std::string& name) {
  (void)check_number(v, range, source, name);
}

}  // namespace

const char* to_string(HwUgvConfig::Epm::Via via) {
  return via == HwUgvConfig::Epm::Via::kGpio ? "gpio" : "mcu";
}

void HwUgvConfig::check() const {
  if (serial.port.empty())
    throw InputError(source, field("serial", "port"), "the MCU's serial device (e.g. /dev/ttyAMA0)",
                     "nothing");
  if (serial.baud < 1200 || serial.baud > 4000000)
    throw InputError(source, field("serial", "baud"), "an integer in [1200, 4000000] baud",
                     std::to_string(serial.baud));
  check_range(link.connect_timeout_s, NumberRange::positive(600.0, "s"), source,
              field("link", "connect_timeout_s"));
  check_range(link.telemetry_timeout_s, NumberRange::positive(60.0, "s"), source,
              field("link", "telemetry_timeout_s"));
  check_range(link.command_rate_hz, NumberRange::closed(1.0, 1000.0, "Hz"), source,
              field("link", "command_rate_hz"));
  check_range(link.command_timeout_s, NumberRange::non_negative(3600.0, "s"), source,
              field("link", "command_timeout_s"));
  check_range(link.epm_retry_s, NumberRange::positive(60.0, "s"), source,
              field("link", "epm_retry_s"));
  if (camera.device.empty())
    throw InputError(source, field("camera", "device"),
                     "a camera: an index, a /dev/video path, a video file, or none", "nothing");
  check_range(camera.first_frame_timeout_s, NumberRange::positive(600.0, "s"), source,
              field("camera", "first_frame_timeout_s"));
  check_range(camera.frame_timeout_s, NumberRange::positive(600.0, "s"), source,
              field("camera", "frame_timeout_s"));
  if (epm.via == Epm::Via::kGpio && epm.chip.empty())
    throw InputError(source, field("epm", "chip"),
                     "a gpio chip (gpiochip0 or /dev/gpiochip0) with via: gpio", "nothing");
  if (epm.line > 1023)
    throw InputError(source, field("epm", "line"), "a line offset in [0, 1023]",
                     std::to_string(epm.line));
  check_range(odometry.wheel_radius_m, NumberRange::positive(1.0, "m"), source,
              field("odometry", "wheel_radius_m"));
  check_range(odometry.ticks_per_rev, NumberRange::closed(1.0, 1e7), source,
              field("odometry", "ticks_per_rev"));
  check_range(odometry.track_width_m, NumberRange::positive(10.0, "m"), source,
              field("odometry", "track_width_m"));
  check_range(odometry.speed_window_s, NumberRange::positive(10.0, "s"), source,
              field("odometry", "speed_window_s"));
  check_range(odometry.max_plausible_wheel_speed_mps, NumberRange::positive(1000.0, "m/s"), source,
              field("odometry", "max_plausible_wheel_speed_mps"));
}

HwUgvConfig hw_ugv_config_from_yaml(const YAML::Node& node, const std::string& source,
                                    const std::string& path) {
  HwUgvConfig c;
  c.source = source;
  const yaml::MapReader root(node, source, path);
  // stall_time_s is the mission's (ugv_base_factory.hpp), read for every backend.
  root.allow_only({"backend", "stall_time_s", "serial", "link", "camera", "epm", "odometry"});
  // Checked here too; which one runs is ugv_base_config's choice.
  (void)read_backend(root, ugv_base_backends().names());

  // Required sections are asked for by name, so a missing one says which.
  const yaml::MapReader serial = root.child("serial");
  serial.allow_only({"port", "baud"});
  c.serial.port = serial.get<std::string>("port");
  if (c.serial.port.empty())
    serial.fail("port", "the MCU's serial device (e.g. /dev/ttyAMA0)", "''");
  c.serial.baud = serial.get_or<int>("baud", c.serial.baud);
  if (c.serial.baud < 1200 || c.serial.baud > 4000000)
    serial.fail("baud", "an integer in [1200, 4000000] baud", std::to_string(c.serial.baud));

  if (const auto link = root.optional_child("link")) {
    link->allow_only({"connect_timeout_s", "telemetry_timeout_s", "command_rate_hz",
                      "command_timeout_s", "epm_retry_s"});
    auto& l = c.link;
    l.connect_timeout_s =
        link->get_in_range_or("connect_timeout_s", 1e-3, 600.0, l.connect_timeout_s);
    l.telemetry_timeout_s =
        link->get_in_range_or("telemetry_timeout_s", 1e-3, 60.0, l.telemetry_timeout_s);
    l.command_rate_hz = link->get_in_range_or("command_rate_hz", 1.0, 1000.0, l.command_rate_hz);
    l.command_timeout_s =
        link->get_in_range_or("command_timeout_s", 0.0, 3600.0, l.command_timeout_s);
    l.epm_retry_s = link->get_in_range_or("epm_retry_s", 1e-3, 60.0, l.epm_retry_s);
  }

  const yaml::MapReader camera = root.child("camera");
  camera.allow_only({"device", "first_frame_timeout_s", "frame_timeout_s"});
  c.camera.device = camera.get<std::string>("device");
  if (c.camera.device.empty())
    camera.fail("device", "a camera: an index, a /dev/video path, a video file, or none", "''");
  c.camera.first_frame_timeout_s =
      camera.get_in_range_or("first_frame_timeout_s", 1e-3, 600.0, c.camera.first_frame_timeout_s);
  c.camera.frame_timeout_s =
      camera.get_in_range_or("frame_timeout_s", 1e-3, 600.0, c.camera.frame_timeout_s);

  if (const auto epm = root.optional_child("epm")) {
    epm->allow_only({"via", "chip", "line", "active_low"});
    const std::string via = epm->get_or<std::string>("via", "mcu");
    if (via == "mcu") {
      c.epm.via = HwUgvConfig::Epm::Via::kMcu;
      for (const char* k : {"chip", "line", "active_low"})
        if (epm->has(k) || epm->given_empty(k))
          epm->fail(k, "no gpio setting with via: mcu (the MCU drives the EPM)", "a value");
    } else if (via == "gpio") {
      c.epm.via = HwUgvConfig::Epm::Via::kGpio;
      c.epm.chip = epm->get<std::string>("chip");
      if (c.epm.chip.empty()) epm->fail("chip", "a gpio chip (gpiochip0 or /dev/gpiochip0)", "''");
      c.epm.line = epm->get<unsigned>("line");
      if (c.epm.line > 1023)
        epm->fail("line", "a line offset in [0, 1023]", std::to_string(c.epm.line));
      c.epm.active_low = epm->get_or("active_low", c.epm.active_low);
    } else {
      epm->fail("via", "one of mcu, gpio", via);
    }
  }

  if (const auto odo = root.optional_child("odometry")) {
    odo->allow_only({"wheel_radius_m", "ticks_per_rev", "track_width_m", "speed_window_s",
                     "max_plausible_wheel_speed_mps"});
    auto& o = c.odometry;
    o.wheel_radius_m = odo->get_in_range_or("wheel_radius_m", 1e-4, 1.0, o.wheel_radius_m);
    const int ticks = odo->get_or<int>("ticks_per_rev", static_cast<int>(o.ticks_per_rev));
    if (ticks < 1 || ticks > 10000000)
      odo->fail("ticks_per_rev", "an integer in [1, 10000000]", std::to_string(ticks));
    o.ticks_per_rev = ticks;
    o.track_width_m = odo->get_in_range_or("track_width_m", 1e-3, 10.0, o.track_width_m);
    o.speed_window_s = odo->get_in_range_or("speed_window_s", 1e-3, 10.0, o.speed_window_s);
    o.max_plausible_wheel_speed_mps = odo->get_in_range_or("max_plausible_wheel_speed_mps", 1e-3,
                                                           1000.0, o.max_plausible_wheel_speed_mps);
  }
  c.check();
  return c;
}

void emit_hw_ugv_config(YAML::Emitter& e, const HwUgvConfig& c) {
  using internal::emit_key_number;
  e << YAML::Key << "serial" << YAML::Value << YAML::BeginMap;
  e << YAML::Key << "port" << YAML::Value << c.serial.port;
  e << YAML::Key << "baud" << YAML::Value << c.serial.baud << YAML::EndMap;
  internal::emit_key_number_map(e, "link",
                                {{"connect_timeout_s", c.link.connect_timeout_s},
                                 {"telemetry_timeout_s", c.link.telemetry_timeout_s},
                                 {"command_rate_hz", c.link.command_rate_hz},
                                 {"command_timeout_s", c.link.command_timeout_s},
                                 {"epm_retry_s", c.link.epm_retry_s}});
  e << YAML::Key << "camera" << YAML::Value << YAML::BeginMap;
  e << YAML::Key << "device" << YAML::Value << c.camera.device;
  emit_key_number(e, "first_frame_timeout_s", c.camera.first_frame_timeout_s);
  emit_key_number(e, "frame_timeout_s", c.camera.frame_timeout_s);
  e << YAML::EndMap;
  e << YAML::Key << "epm" << YAML::Value << YAML::BeginMap;
  e << YAML::Key << "via" << YAML::Value << to_string(c.epm.via);
  if (c.epm.via == HwUgvConfig::Epm::Via::kGpio) {
    e << YAML::Key << "chip" << YAML::Value << c.epm.chip;
    e << YAML::Key << "line" << YAML::Value << c.epm.line;
    e << YAML::Key << "active_low" << YAML::Value << c.epm.active_low;
  }
  e << YAML::EndMap;
  const DiffDriveParams& o = c.odometry;
  internal::emit_key_number_map(
      e, "odometry",
      {{"wheel_radius_m", o.wheel_radius_m},
       {"ticks_per_rev", o.ticks_per_rev},
       {"track_width_m", o.track_width_m},
       {"speed_window_s", o.speed_window_s},
       {"max_plausible_wheel_speed_mps", o.max_plausible_wheel_speed_mps}});
}

}  // namespace ferret::ugv
