#pragma once
// The winch while the miniUGV is out (paper sect. III): lowering it with the IMU
// touchdown check, the taut-tether control that keeps l_t on the length the miniUGV's
// pose asks for while it works, and the reel-in. The mission's states say when; this
// class says what the winch is commanded.

#include <memory>
#include <string>

#include "ferret/tether_model/taut_control_options.hpp"
#include "ferret/tether_model/tether_controller.hpp"
#include "ferret/tether_model/tether_modes.hpp"
#include "ferret/tether_model/winch.hpp"
#include "ferret/tether_model/winch_controllers.hpp"
#include "ferret/uav/flight_controller.hpp"

namespace ferret {

class WinchSupervision {
 public:
  struct Options {
    double entry_offset_m = 1.0;  ///< l_0
    tether::TouchdownGuard::Options touchdown;
    std::string controller = "mpc";  ///< a name of tether::tether_controllers()
    tether::TautControlOptions control;
    /// Each controller's own options (the mission YAML's uav.winch_control).
    tether::WinchControllerOptions controllers;
    double retract_speed_mps = 0.4;
  };
  WinchSupervision(tether::Winch& winch, Options options);
  ~WinchSupervision();
  WinchSupervision(const WinchSupervision&) = delete;
  WinchSupervision& operator=(const WinchSupervision&) = delete;

  /// Torque on, the spool stopped (the mission starts).
  void switch_on();
  /// Holds the line: the spool stopped.
  void idle();

  /// A fresh touchdown check (the UAV landed beside the opening).
  void arm_touchdown_guard();
  /// A touchdown check unless one is armed (a hover release keeps the one it has).
  void keep_touchdown_guard();
  /// The miniUGV is at the entry: l_0 and the slack reference paid out.
  [[nodiscard]] bool ugv_at_entry(const tether::WinchState& w) const;
  /// One step of lowering towards the entry, slowed by the touchdown check.
  /// @pre a touchdown guard is armed
  void lower(double now_s, const UgvReport& r, const tether::WinchState& w);

  /// The miniUGV starts its mission: the spool stopped, the touchdown check dropped,
  /// the taut-tether control started afresh.
  void start_taut_control();
  /// One step of the taut-tether control on the miniUGV's last report; without word
  /// from it, the winch holds its length.
  void follow_ugv(double now_s, const UgvReport& r, const tether::WinchState& w);

  /// The miniUGV is aboard.
  [[nodiscard]] bool reeled_in(const tether::WinchState& w) const { return w.released_m <= 0.01; }
  /// One step of the reel-in at retract_speed_mps.
  void reel_in();

 private:
  /// What the miniUGV is lowered to: l_0 and the slack reference.
  [[nodiscard]] double release_length_m() const;
  /// The spool's speed while it holds without word from the miniUGV: 0, or paying out
  /// against a pull it measures above the guard.
  [[nodiscard]] double yield_to_tension_mps(const tether::WinchState& w) const;

  tether::Winch& winch_;
  Options options_;
  std::unique_ptr<tether::TouchdownGuard> guard_;
  std::shared_ptr<class ReportedTetherLength> required_;
  std::unique_ptr<tether::TetherController> controller_;
};

}  // namespace ferret
