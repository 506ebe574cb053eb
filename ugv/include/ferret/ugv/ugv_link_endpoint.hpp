#pragma once
// The miniUGV's end of the robot link (docs/link.md): the UAV's requests go to the
// mission controller, the mission's state goes back to the UAV at the control rate,
// and the watchdog holds the robot while the UAV is silent. The same object serves the
// simulated mission (datagrams through a LossyChannel) and the robot (a UdpLink).

#include <cstdint>
#include <deque>
#include <functional>

#include "ferret/core/clock.hpp"
#include "ferret/link/link_session.hpp"

namespace ferret {

class MiniUgvMission;
class UgvBase;

struct UgvLinkEndpointOptions {
  link::UgvLinkOptions link;         ///< the watchdog's timeout, the reorder window
  double telemetry_period_s = 0.05;  ///< 20 Hz, the control rate (docs/link.md)
  /// How fresh the UAV's view of the robot must be for it to drive as it likes: the
  /// UAV's heartbeats echo the newest telemetry it accepted, and the winch follows only
  /// what it heard. Up to `winch_view_fresh_s` old the robot may speed up beyond the
  /// speed the UAV knows by what the spool can catch up in the rest of that time; older,
  /// it keeps below that known speed, down to standing at `winch_view_stale_s` (the
  /// winch holds its length after 0.3 s without telemetry). 0 turns the limit off.
  double winch_view_fresh_s = 0.1;
  double winch_view_stale_s = 0.35;
  double winch_acceleration_mps2 = 2.0;  ///< the spool's (WinchLimits)
};

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
  /// How old the UAV's newest view of the robot is (infinite: it has not heard it), and
  /// the top speed that allows (winch_view_fresh_s).
  [[nodiscard]] double winch_view_age_s() const;
  [[nodiscard]] double winch_view_speed_limit_mps() const;

  [[nodiscard]] link::UgvLinkSession& session() { return session_; }
  [[nodiscard]] const link::UgvLinkSession& session() const { return session_; }

 private:
  void act_on(const link::UavRequest& request);
  /// The speed the robot reported in its telemetry stamped `t_s` (0 when forgotten).
  [[nodiscard]] double reported_speed_mps(double t_s) const;

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
  std::deque<std::pair<double, double>> reported_;  ///< (t_s, speed) of recent telemetry
};

}  // namespace ferret
