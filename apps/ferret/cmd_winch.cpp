// `ferret winch`: bring-up and checks of the Dynamixel winch (docs/tether.md).
//   ferret winch ping  --port /dev/ttyUSB0 [--id 1] [--baud 57600]
//   ferret winch state --port /dev/ttyUSB0            (velocity mode, torque on, speed 0)
//   ferret winch spin  --port /dev/ttyUSB0 --speed 0.1 --seconds 1
// A port that cannot be opened is bad input (exit 2); a servo that does not answer,
// answers with an error or is the wrong model is a failed check (exit 1).

#include <chrono>
#include <cstdio>
#include <functional>
#include <memory>
#include <string>
#include <thread>

#include "command.hpp"
#include "ferret/core/error.hpp"
#include "ferret/tether_model/dynamixel_winch.hpp"

namespace ferret::cli {
namespace {

struct WinchOptions {
  std::string port;
  int baud = 57600;
  int id = 1;
  int timeout_ms = 30;
  int retries = 2;
  double spool_radius_m = 0.09;
  double speed_mps = 0.0;
  double seconds = 1.0;
};

// Runs `body` and turns driver errors into the CLI's exit codes.
void guarded(const WinchOptions& o, const std::function<void()>& body) {
  if (o.id < 0 || o.id > 252)
    throw InputError("--id", "", "a Dynamixel id in [0, 252]", std::to_string(o.id));
  if (o.timeout_ms <= 0 || o.retries < 0)
    throw InputError("--timeout-ms/--retries", "", "a timeout > 0 and retries >= 0");
  try {
    body();
  } catch (const tether::DynamixelError& e) {
    throw CheckFailed(e.what());
  } catch (const tether::SerialError& e) {
    throw InputError("--port", "", "a serial port that can be opened", e.what());
  }
}

tether::DynamixelWinch::Options winch_options(const WinchOptions& o) {
  tether::DynamixelWinch::Options w;
  w.port = o.port;
  w.baud_rate = o.baud;
  w.id = static_cast<std::uint8_t>(o.id);
  w.spool_radius_m = o.spool_radius_m;
  w.bus.timeout_ms = o.timeout_ms;
  w.bus.retries = o.retries;
  return w;
}

void print_state(const tether::WinchState& s) {
  std::printf("released_m: %.4f\nspeed_mps: %.4f\ntension_n: %.2f\n", s.released_m, s.speed_mps,
              s.tension_n);
}

void add_common(CLI::App* sub, WinchOptions& o) {
  sub->add_option("--port", o.port, "serial port of the Dynamixel adapter")->required();
  sub->add_option("--baud", o.baud, "baud rate")->capture_default_str();
  sub->add_option("--id", o.id, "servo id")->capture_default_str();
  sub->add_option("--timeout-ms", o.timeout_ms, "reply timeout per attempt")->capture_default_str();
  sub->add_option("--retries", o.retries, "attempts after a timeout or corrupt reply")
      ->capture_default_str();
  sub->add_option("--spool-radius", o.spool_radius_m, "spool radius, metres")
      ->capture_default_str();
}

const CommandRegistration kWinch{
    "winch", [](CLI::App& app) {
      auto o = std::make_shared<WinchOptions>();
      auto* winch = app.add_subcommand("winch", "Check and drive the Dynamixel winch");
      winch->require_subcommand(1);

      auto* ping = winch->add_subcommand("ping", "Ping the servo and print its model and firmware");
      add_common(ping, *o);
      ping->callback([o] {
        guarded(*o, [&] {
          tether::DynamixelBus bus(tether::open_serial_port(o->port, o->baud),
                                   {o->timeout_ms, o->retries});
          const auto r = bus.ping(static_cast<std::uint8_t>(o->id));
          std::printf("id %d on %s: %s (model number %u), firmware %u\n", o->id, o->port.c_str(),
                      tether::dynamixel_model_name(r.model_number).c_str(), r.model_number,
                      r.firmware_version);
        });
      });

      auto* state = winch->add_subcommand(
          "state", "Connect (velocity mode, speed 0) and print l_t, speed and tension");
      add_common(state, *o);
      state->callback([o] {
        guarded(*o, [&] {
          tether::DynamixelWinch w(winch_options(*o));
          (void)w.connect();
          print_state(w.read_state());
        });
      });

      auto* spin = winch->add_subcommand("spin", "Run the spool at a speed for a while, then stop");
      add_common(spin, *o);
      spin->add_option("--speed", o->speed_mps, "spool speed, m/s (positive pays out)")->required();
      spin->add_option("--seconds", o->seconds, "how long")->capture_default_str();
      spin->callback([o] {
        if (!(o->seconds > 0.0 && o->seconds <= 60.0))
          throw InputError("ferret winch spin", "--seconds", "a duration in (0, 60]",
                           std::to_string(o->seconds));
        guarded(*o, [&] {
          tether::DynamixelWinch w(winch_options(*o));
          (void)w.connect();
          w.command_velocity_mps(o->speed_mps);
          std::this_thread::sleep_for(std::chrono::duration<double>(o->seconds));
          const auto s = w.read_state();
          w.command_velocity_mps(0.0);
          print_state(s);
        });
      });
    }};

}  // namespace
}  // namespace ferret::cli
