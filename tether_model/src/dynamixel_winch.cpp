#include "ferret/tether_model/dynamixel_winch.hpp"

#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include <algorithm>
#include <cmath>
#include <numbers>

namespace ferret::tether {

std::string dynamixel_model_name(std::uint16_t model) {
  switch (model) {
    case mx2::kModelMx28:
      return "MX-28";
    case mx2::kModelMx64:
      return "MX-64";
    case mx2::kModelMx106:
      return "MX-106";
    case 1020:
      return "XM430-W350";
    case 1030:
      return "XM430-W210";
    case 1060:
      return "XL430-W250";
    default:
      return "model " + std::to_string(model);
  }
}

DynamixelWinch::DynamixelWinch(Options options)
    : DynamixelWinch(options, open_serial_port(options.port, options.baud_rate)) {}

DynamixelWinch::DynamixelWinch(Options options, std::unique_ptr<link::SerialPort> port)
    : options_(std::move(options)), bus_(std::move(port), options_.bus) {
  if (!(options_.spool_radius_m > 0.0) ||
      (options_.payout_direction != 1 && options_.payout_direction != -1))
    throw SerialError("Dynamixel winch: spool radius must be > 0 and payout direction +1 or -1");
}

PingReply DynamixelWinch::connect() {
  const std::uint8_t id = options_.id;
  const PingReply reply = bus_.ping(id);
  if (std::find(options_.accepted_models.begin(), options_.accepted_models.end(),
                reply.model_number) == options_.accepted_models.end()) {
    std::string accepted;
    for (const auto m : options_.accepted_models)
      accepted +=
          (accepted.empty() ? "" : ", ") + fmt::format("{} ({})", dynamixel_model_name(m), m);
    throw DynamixelError(
        DynamixelError::Kind::kWrongDevice, 0,
        fmt::format("Dynamixel id {} on '{}' is a {} (model number {}); the winch needs one of: {}",
                    id, bus_.port(), dynamixel_model_name(reply.model_number), reply.model_number,
                    accepted));
  }
  // The operating mode and profile can only be written with torque off (else: access error).
  bus_.write_u8(id, mx2::kTorqueEnable, 0);
  bus_.write_u8(id, mx2::kOperatingMode, mx2::kVelocityMode);
  const double rev_per_min2 =
      options_.max_acceleration_mps2 / (2.0 * std::numbers::pi * options_.spool_radius_m) * 3600.0;
  bus_.write_u32(id, mx2::kProfileAcceleration,
                 static_cast<std::uint32_t>(
                     std::max(1.0, std::round(rev_per_min2 / mx2::kRevPerMin2PerUnit))));
  bus_.write_u32(id, mx2::kGoalVelocity, 0);
  zero_ticks_ = static_cast<std::int32_t>(bus_.read_u32(id, mx2::kPresentPosition));
  bus_.write_u8(id, mx2::kTorqueEnable, 1);
  connected_ = true;
  spdlog::info("winch: {} firmware {} on '{}' id {} in velocity mode",
               dynamixel_model_name(reply.model_number), reply.firmware_version, bus_.port(), id);
  return reply;
}

void DynamixelWinch::set_torque_enabled(bool enabled) {
  bus_.write_u8(options_.id, mx2::kTorqueEnable, enabled ? 1 : 0);
}

std::int32_t DynamixelWinch::velocity_units(double speed_mps) const {
  const double v = std::clamp(speed_mps, -options_.max_speed_mps, options_.max_speed_mps);
  const double rpm = v / (2.0 * std::numbers::pi * options_.spool_radius_m) * 60.0;
  return static_cast<std::int32_t>(std::lround(options_.payout_direction * rpm / mx2::kRpmPerUnit));
}

void DynamixelWinch::command_velocity_mps(double speed_mps) {
  if (!connected_) throw SerialError("Dynamixel winch: connect() first");
  bus_.write_u32(options_.id, mx2::kGoalVelocity,
                 static_cast<std::uint32_t>(velocity_units(speed_mps)));
}

WinchState DynamixelWinch::read_state() {
  if (!connected_) throw SerialError("Dynamixel winch: connect() first");
  // One read of 126..135 covers current, velocity and position.
  const auto bytes = bus_.read(options_.id, mx2::kPresentCurrent, 10);
  const auto current = static_cast<std::int16_t>(dxl::from_le(std::span(bytes).subspan(0, 2)));
  const auto velocity = static_cast<std::int32_t>(dxl::from_le(std::span(bytes).subspan(2, 4)));
  const auto position = static_cast<std::int32_t>(dxl::from_le(std::span(bytes).subspan(6, 4)));
  const double metres_per_tick =
      2.0 * std::numbers::pi * options_.spool_radius_m / mx2::kTicksPerRev;
  WinchState s;
  s.released_m = options_.initial_released_m + options_.payout_direction *
                                                   static_cast<double>(position - zero_ticks_) *
                                                   metres_per_tick;
  s.speed_mps = options_.payout_direction * velocity * mx2::kRpmPerUnit / 60.0 * 2.0 *
                std::numbers::pi * options_.spool_radius_m;
  // The motor holds the line against the tension: the current opposes paying out.
  s.tension_n = std::abs(current * options_.tension_n_per_current_unit);
  return s;
}

}  // namespace ferret::tether
