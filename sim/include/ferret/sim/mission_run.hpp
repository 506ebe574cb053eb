#pragma once
// The settings and the result of a whole mission in one simulated world (docs/mission.md),
// the world's side (sim/mission_world.hpp) and the controllers' (mission/mission_run.hpp,
// which runs them). Only the simulation reads the truth: the world's geometry, where
// the hidden spaces and objects are, the true taut tether.

#include <Eigen/Core>
#include <cstdint>
#include <functional>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "ferret/core/transition_log.hpp"
#include "ferret/link/lossy_channel.hpp"
#include "ferret/planning/planning_world.hpp"
#include "ferret/sim/fault_plan.hpp"
#include "ferret/sim/invariant_monitor.hpp"
#include "ferret/sim/ugv_mission_run.hpp"
#include "ferret/uav/uav_mission_options.hpp"
#include "ferret/urdf/robot_description.hpp"

namespace ferret {

struct MissionRunSettings {
  /// The UAV's mission. Its openings, search area, drop zone and tether are filled
  /// from the world and the mission config where they are left empty / at defaults.
  UavMissionOptions uav;
  /// The miniUGV's mission, search and simulated base (as `ferret explore --retrieve`).
  UgvMissionRunSettings ugv;
  double uav_max_speed_mps = 5.0;  ///< the M100's limits (the UAV URDF's)
  double uav_max_accel_mps2 = 2.0;
  double uav_max_yaw_rate_radps = 1.0;
  double landed_height_m = 0.25;     ///< base_link above the ground when landed
  double time_limit_s = 4 * 3600.0;  ///< the simulation's own bound
  /// Render the marker camera's frames also when no marker's quad lies in the image.
  /// Off: such a frame reaches the mission empty, as a dropped frame, and the detector
  /// does not run on it. The rendered frame would hold only the scene without markers;
  /// off changes an outcome only if the detector found a marker there (docs/mission.md
  /// says what was measured). Most survey frames are such frames.
  bool render_markerless_frames = false;
  /// The robot link. nullopt: the two controllers call each other (one process, no
  /// messages). Set: every call is a message of the link's wire format through its
  /// sessions (docs/link.md), through a simulated network with these faults each way
  /// (its seed drawn from the run's), and the UAV reads the miniUGV from telemetry.
  std::optional<link::LossyChannelOptions> link_channel;
  /// What breaks on purpose (docs/safety.md): the simulated backends and the link's
  /// network apply it on the simulation's clock. A plan with link faults runs the robot
  /// link's messages (a clean network where link_channel is unset).
  FaultPlan faults;
  /// Called every 0.1 s of simulated time (the MCAP recorder's hook).
  std::function<void(double t_s, const class MissionSim&)> on_sample;
};

/// What the miniUGV did in one hidden space.
struct UgvDeployment {
  std::string hidden_space;  ///< the world's name for it ("" when the UAV's estimate hit none)
  UgvMissionRunResult result;
  OccupancyMap2D truth;  ///< the slice it searched (for the figures)
  std::optional<Eigen::Vector2d> object_W;
  double max_true_tether_m = 0.0;  ///< l_0 + the true taut tether, longest
  double deployed_s = 0.0;
};

struct MissionSample {
  double t_s = 0.0;
  Eigen::Vector3d p_W = Eigen::Vector3d::Zero();
  double yaw_rad = 0.0;
  std::string state;
  double battery = 1.0;
  double released_m = 0.0;  ///< l_t
  double required_m = 0.0;  ///< l_0 + true taut tether while the miniUGV works, else 0
  double tension_n = 0.0;
  double ugv_battery = 1.0;
};

struct MissionRunResult {
  /// What drove each interface (the mission YAML's names, "uav.flight_controller",
  /// "uav.winch", "ugv.base", and "uav.cameras": sim or hw; "link": in-process), read
  /// from the objects the run used.
  std::map<std::string, std::string> backends;
  /// With the robot link's messages (MissionRunSettings::link_channel): what each end's
  /// session counted (received, accepted, corrupted, duplicates, stale, resent, ...).
  std::string link_counters;
  UavMissionOutcome outcome = UavMissionOutcome::kNone;
  double time_s = 0.0;
  std::vector<HiddenSpaceVisit> visits;
  std::vector<UgvDeployment> deployments;
  std::map<std::string, double> time_in_state;
  double flown_m = 0.0;
  double battery_left = 1.0;
  int objects_in_world = 0;  ///< objects inside hidden spaces
  int objects_dropped = 0;   ///< released inside the drop zone (truth)
  int hidden_spaces_in_world = 0;
  int uav_collisions = 0;  ///< checks (every 0.1 s) with the UAV's shape in an occupied voxel
  std::map<std::string, int> collisions_in;                     ///< the same by the UAV's state
  Eigen::Vector3d first_collision_W = Eigen::Vector3d::Zero();  ///< where the first was
  double max_released_m = 0.0;                                  ///< l_t, longest
  int required_over_length = 0;  ///< steps where the true taut tether needed more than L
  int over_tension_events = 0;   ///< rising edges of tension above the limit
  double max_tension_n = 0.0;
  double leg_spacing_m = 0.0;
  std::size_t pattern_waypoints = 0, pattern_done = 0, first_pass_waypoints = 0;
  int frames = 0;                      ///< marker frames the mission asked for
  int marker_frames_rendered = 0;      ///< of which rendered (render_markerless_frames)
  std::vector<MissionSample> samples;  ///< every 0.5 s
  std::vector<Transition> transitions;
  /// The safety invariants, checked at every step from the truth (docs/safety.md): each
  /// episode of a violation. Any makes the run unsafe.
  std::vector<InvariantViolation> invariant_violations;
  [[nodiscard]] bool safe() const { return invariant_violations.empty(); }
};

}  // namespace ferret
