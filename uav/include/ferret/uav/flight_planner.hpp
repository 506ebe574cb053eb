#pragma once
// The UAV's onboard flight planner for its mission controller: OMPL (RRT-Connect) in the
// world's OctoMap with FCL against the UAV's shape, alone or with the miniUGV hanging
// below; a leg whose straight segment the planner's own motion check passes is flown as
// it is. One home for it, so the in-process mission and a
// robot process plan alike.

#include <cstdint>
#include <memory>

#include "ferret/planning/collision_map.hpp"
#include "ferret/planning/mission_config.hpp"
#include "ferret/planning/planning_world.hpp"
#include "ferret/uav/flight_path_follower.hpp"
#include "ferret/uav/uav_mission_options.hpp"
#include "ferret/urdf/robot_description.hpp"

namespace ferret {

/// Builds the planner (both shapes from the UAV's URDF) on `map`, or on the collision
/// map of `world` when `map` is null. `max_velocity_mps` times the plans; OMPL is seeded
/// once a process with `seed`. The planner keeps what it needs; `world` must outlive it.
[[nodiscard]] FlightPlanner make_flight_planner(const PlanningWorld& world,
                                                const RobotDescription& uav_robot,
                                                const MissionConfig& mission,
                                                double max_velocity_mps, std::uint64_t seed,
                                                std::shared_ptr<const CollisionMap> map = nullptr);

/// The UAV mission's options that come from the world the team describes: the markers
/// it placed and their openings, the marker detector for them (unless the mission YAML
/// set `uav.marker`), the drop zone, and the mission's tether (the openings and the drop
/// zone only where the options have none).
void fill_uav_mission_from_world(UavMissionOptions& options, const WorldSpec& world,
                                 const MissionConfig& mission);

}  // namespace ferret
