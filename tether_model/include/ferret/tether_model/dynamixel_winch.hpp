#pragma once
// The winch on a Dynamixel MX-28 / MX-64 / MX-106 with Protocol 2.0 firmware, in
// velocity mode: the spool speed becomes Goal Velocity, l_t comes from the
// multi-turn Present Position, the tension from Present Current (Present Load on
// the MX-28, which has no current sensor).

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "ferret/tether_model/dynamixel_bus.hpp"
#include "ferret/tether_model/winch.hpp"

namespace ferret::tether {

/// Control-table addresses of the MX series with Protocol 2.0 firmware.
namespace mx2 {
inline constexpr std::uint16_t kModelNumber = 0;  // 2 bytes
inline constexpr std::uint16_t kOperatingMode =
    11;  // 1: velocity, 3: position, 4: extended position
inline constexpr std::uint16_t kVelocityLimit = 44;  // 4 bytes, 0.229 rpm
inline constexpr std::uint16_t kTorqueEnable = 64;
inline constexpr std::uint16_t kHardwareErrorStatus = 70;
inline constexpr std::uint16_t kGoalVelocity = 104;         // 4 bytes, 0.229 rpm, signed
inline constexpr std::uint16_t kProfileAcceleration = 108;  // 4 bytes, 214.577 rev/min^2
inline constexpr std::uint16_t kPresentCurrent =
    126;  // 2 bytes signed (MX-28: Present Load, 0.1 %)
inline constexpr std::uint16_t kPresentVelocity = 128;  // 4 bytes signed, 0.229 rpm
inline constexpr std::uint16_t kPresentPosition = 132;  // 4 bytes signed, 4096 a revolution
inline constexpr std::uint8_t kVelocityMode = 1;
inline constexpr std::uint16_t kModelMx28 = 30, kModelMx64 = 311, kModelMx106 = 321;
inline constexpr double kRpmPerUnit = 0.229;
inline constexpr double kRevPerMin2PerUnit = 214.577;
inline constexpr double kTicksPerRev = 4096.0;
}  // namespace mx2

[[nodiscard]] std::string dynamixel_model_name(std::uint16_t model_number);

class DynamixelWinch final : public Winch {
 public:
  struct Options {
    std::string port = "/dev/ttyUSB0";
    int baud_rate = 57600;  ///< factory default of the MX series (Protocol 2.0)
    std::uint8_t id = 1;
    std::vector<std::uint16_t> accepted_models = {mx2::kModelMx28, mx2::kModelMx64,
                                                  mx2::kModelMx106};
    double spool_radius_m = 0.09;
    int payout_direction = +1;  ///< +1: positive servo velocity pays line out
    double max_speed_mps = 0.6;
    double max_acceleration_mps2 = 2.0;
    double initial_released_m = 0.0;  ///< l_t at connect()
    /// Tension from the current register: N per unit (MX-64: 3.36 mA a unit times the
    /// torque constant over the spool radius; calibrate on the real winch).
    double tension_n_per_current_unit = 0.018;
    DynamixelBus::Options bus;
  };

  /// Opens the port (throws SerialError if it is missing). Call connect() next.
  explicit DynamixelWinch(Options options);
  /// For tests and emulators: an already-open port.
  DynamixelWinch(Options options, std::unique_ptr<link::SerialPort> port);

  /// Pings the servo, checks its model, switches it to velocity mode with the profile
  /// acceleration and enables torque; l_t is initial_released_m from here. Throws
  /// DynamixelError with a clear message for no reply or a model not accepted.
  PingReply connect();

  void set_torque_enabled(bool enabled) override;
  void command_velocity_mps(double speed_mps) override;
  [[nodiscard]] WinchState read_state() override;

  [[nodiscard]] DynamixelBus& bus() { return bus_; }
  /// Goal Velocity register value for a spool speed (after clamping to max_speed_mps).
  [[nodiscard]] std::int32_t velocity_units(double speed_mps) const;

 private:
  Options options_;
  DynamixelBus bus_;
  std::int32_t zero_ticks_ = 0;
  bool connected_ = false;
};

}  // namespace ferret::tether
