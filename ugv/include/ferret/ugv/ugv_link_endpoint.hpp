#pragma once
// The miniUGV's end of the robot link (docs/link.md): the UAV's requests go to the
// mission controller, the mission's state goes back to the UAV at the control rate,
// and the watchdog holds the robot while the UAV is silent. The same object serves the
// simulated mission (datagrams through a LossyChannel) and the robot (a UdpLink).

#include <cstdint>
#include <deque>
#include <functional>
#include <optional>

#include "ferret/core/clock.hpp"
#include "ferret/link/link_session.hpp"
#include "ferret/tether_model/line_catch.hpp"

namespace ferret {

class MiniUgvMission;
class UgvBase;

struct UgvLinkEndpointOptions {
  link::UgvLinkOptions link;         ///< the watchdog's timeout, the reorder window
  double telemetry_period_s = 0.05;  ///< 20 Hz, the control rate (docs/link.md)
  /// The link's speed limit (docs/link.md "Watchdogs"): the robot's line grows no faster
  /// than the winch is known to pay out, plus what the winch catches up by the tension
  /// it measures. The UAV's heartbeats echo the newest telemetry it accepted; the winch
  /// follows what it heard for `winch_follow_s`, then holds.
  bool winch_view_limit = true;
  /// How long the winch follows the newest telemetry it heard before it holds: the
  /// UAV's telemetry timeout (link::UavLinkOptions).
  double winch_follow_s = link::UavLinkOptions{}.telemetry_timeout_s;
  /// How fast the robot brakes to be within the line catch by the time the winch may
  /// hold: its path follower brakes at twice its 2 m/s^2, taken as 2 m/s^2.
  double braking_mps2 = 2.0;
  /// The most the robot's heading turns between two ticks: 2 rad/s for 0.05 s.
  double turn_per_tick_rad = 0.1;
  /// What a winch that feels the pull catches up by itself (none: the default winch's,
  /// tether::LineCatchLimit::for_winch).
  std::optional<tether::LineCatchLimit> line_catch;
};

/// The link's rule (UgvLinkEndpoint::winch_view_line_speed_mps()): how fast the line
/// may grow `age_s` after the telemetry the UAV echoed (infinite: none), `known_mps` the
/// slowest line speed the robot reported since then and `catch_mps` what the winch
/// catches up by the pull it feels. Infinite with the limit off.
[[nodiscard]] double winch_view_line_speed_mps(const UgvLinkEndpointOptions& options, double age_s,
                                               double known_mps, double catch_mps);

class UgvLinkEndpoint {
 public:
  /// The mission a search request starts, and the base it drives.
  struct Deployment {
    MiniUgvMission* mission = nullptr;
    UgvBase* base = nullptr;
  };
  /// Called when the UAV asks for a search (the request gives the entry E and the
  /// heading into the hidden space, in the UAV's world frame): the mission to start
  /// there, made for it (on the robot) or set down with the robot (in simulation). A
  /// mission of nullptr: none can be; the request is acknowledged and counted.
  using StartSearch = std::function<Deployment(const link::UavRequest& request)>;

  /// @throws std::invalid_argument for a telemetry period that is not > 0 or no
  ///         `start_search`
  UgvLinkEndpoint(const Clock& clock, StartSearch start_search,
                  UgvLinkEndpointOptions options = {});
  /// The IMU's attitude while no mission is attached: the UAV's touchdown check reads
  /// it while it lowers the robot.
  void set_attitude(double roll_rad, double pitch_rad);

  /// The mission under way (from its search request until it is told it was lifted
  /// out), nullptr when there is none.
  [[nodiscard]] MiniUgvMission* mission() const { return mission_; }

  /// Hands the requests that arrived to the mission (in order, each once), then queues
  /// telemetry when it is due. Returns holding(): while a mission is under way and the
  /// UAV has been silent past the link's timeout, the robot stops its wheels and its
  /// mission does not tick, until the UAV is heard again.
  bool tick() {
    const bool hold = handle_requests();
    report();
    return hold;
  }
  /// tick()'s halves, for a loop that moves the robot between them (the simulation:
  /// requests before the control step, the state it left after it).
  bool handle_requests();
  void report();
  [[nodiscard]] bool holding() const { return holding_; }

  /// The mission's state as the telemetry carries it (what tick() sends).
  [[nodiscard]] link::UgvTelemetry telemetry() const;
  /// The newest request acted on (0: none): the telemetry's last_request_id.
  [[nodiscard]] std::uint32_t last_request_id() const { return last_request_id_; }
  /// Requests that came with no mission to act on (a search asked of a robot that is
  /// not set down): acknowledged and counted, not acted on.
  [[nodiscard]] std::uint64_t requests_without_mission() const { return without_mission_; }
  /// Times the watchdog made the robot hold.
  [[nodiscard]] std::uint64_t holds() const { return holds_; }
  /// How old the UAV's newest view of the robot is (infinite: it has not echoed one).
  [[nodiscard]] double winch_view_age_s() const;
  /// The slowest the winch may take the line to grow (m/s, >= 0): the least outward
  /// line speed the robot reported since the telemetry the UAV echoed (whichever of
  /// them the UAV heard last, the winch follows it); 0 when none is echoed or recorded.
  [[nodiscard]] double winch_known_line_speed_mps() const;
  /// How fast the line may grow now: the line catch on the mission's line, plus the
  /// known line speed while the winch surely follows it, braking to nothing by the time
  /// it may hold (winch_follow_s after the echoed telemetry). Infinite with the limit
  /// off.
  [[nodiscard]] double winch_view_line_speed_mps() const;
  /// winch_view_line_speed_mps() as the robot's top speed: divided by the share of its
  /// speed that can grow the line by the next tick (heading and direction of travel
  /// against the line; infinite for a robot that can only shorten it).
  [[nodiscard]] double winch_view_speed_limit_mps() const;

  [[nodiscard]] link::UgvLinkSession& session() { return session_; }
  [[nodiscard]] const link::UgvLinkSession& session() const { return session_; }

 private:
  void act_on(const link::UavRequest& request);

  const Clock& clock_;
  StartSearch start_search_;
  UgvLinkEndpointOptions options_;
  link::UgvLinkSession session_;
  MiniUgvMission* mission_ = nullptr;
  UgvBase* base_ = nullptr;
  double roll_rad_ = 0.0, pitch_rad_ = 0.0;
  std::uint32_t last_request_id_ = 0;
  double next_telemetry_s_ = 0.0;
  bool holding_ = false;
  std::uint64_t without_mission_ = 0, holds_ = 0;
  tether::LineCatchLimit line_catch_;
  /// (t_s, outward line speed) of the telemetry sent lately, oldest first.
  std::deque<std::pair<double, double>> reported_;
};

}  // namespace ferret
