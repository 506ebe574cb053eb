#include "ferret/uav/flight_planner.hpp"

#include <ompl/base/SpaceInformation.h>

#include <algorithm>
#include <cmath>

#include "ferret/core/error.hpp"
#include "ferret/planning/ompl_setup.hpp"
#include "ferret/planning/uav_planner.hpp"
#include "ferret/uav/opening_locator.hpp"

namespace ferret {
namespace {

struct PlannerState {
  Aabb3 fence;
  std::shared_ptr<const CollisionMap> map;
  std::unique_ptr<UavPlanner> alone, loaded;
  ompl::base::SpaceInformationPtr si_alone, si_loaded;
};

}  // namespace

FlightPlanner make_flight_planner(const PlanningWorld& world, const RobotDescription& uav_robot,
                                  const MissionConfig& mission, double max_velocity_mps,
                                  std::uint64_t seed, std::shared_ptr<const CollisionMap> map) {
  auto st = std::make_shared<PlannerState>();
  st->fence = default_uav_bounds(world);
  st->map = map ? std::move(map)
                : CollisionMap::build(*world.tree,
                                      uav_map_options(world.spec, UnknownPolicy::kFree, st->fence));
  UavPlannerOptions po;
  po.geofence = st->fence;
  po.seed = seed;
  po.max_velocity_mps = max_velocity_mps;
  seed_ompl_once(seed);
  const LoadedPlanRobot alone = load_plan_robot(
      PlanRobot::kUav, PlanRobotModel{uav_robot.source, false}, mission, 0.0, "UAV");
  const LoadedPlanRobot loaded =
      load_plan_robot(PlanRobot::kUavWithUgv, PlanRobotModel{uav_robot.source, false}, mission, 0.3,
                      "UAV with miniUGV");
  st->alone = std::make_unique<UavPlanner>(st->map, alone.shape, po);
  st->loaded = std::make_unique<UavPlanner>(st->map, loaded.shape, po);
  st->si_alone = st->alone->space_information();
  st->si_loaded = st->loaded->space_information();
  return [st](const Eigen::Vector3d& from, const Eigen::Vector3d& to,
              bool carrying) -> std::optional<std::vector<Eigen::Vector3d>> {
    UavPlanner& p = carrying ? *st->loaded : *st->alone;
    auto& si = carrying ? st->si_loaded : st->si_alone;
    const Aabb3& fence = st->fence;
    Waypoint a, b;
    a.x_m = from.x(), a.y_m = from.y(), a.z_m = std::clamp(from.z(), fence.lo.z(), fence.hi.z());
    b.x_m = to.x(), b.y_m = to.y(), b.z_m = std::clamp(to.z(), fence.lo.z(), fence.hi.z());
    a.yaw_rad = b.yaw_rad = std::atan2(to.y() - from.y(), to.x() - from.x());
    ompl::base::State* sa = si->allocState();
    ompl::base::State* sb = si->allocState();
    p.to_ompl_state(a, sa);
    p.to_ompl_state(b, sb);
    const bool straight = si->isValid(sa) && si->isValid(sb) && si->checkMotion(sa, sb);
    si->freeState(sa);
    si->freeState(sb);
    if (straight) return std::vector<Eigen::Vector3d>{from, to};
    const UavPlan plan = p.plan(a, b);
    if (!plan.solved) return std::nullopt;
    std::vector<Eigen::Vector3d> out;
    for (const Waypoint& w : plan.states) out.push_back(w.position());
    out.back() = to;
    return out;
  };
}

void fill_uav_mission_from_world(UavMissionOptions& uo, const WorldSpec& spec,
                                 const MissionConfig& mission) {
  if (uo.openings.empty())
    for (const HiddenSpace& h : spec.hidden_spaces) uo.openings.push_back(opening_in_marker(h));
  if (!uo.marker_from_mission && !spec.hidden_spaces.empty())
    uo.marker = marker_detector_options(spec.hidden_spaces.front().marker);
  if (spec.drop_zone) uo.drop_zone_W = spec.drop_zone->center_m;
  uo.tether = mission.tether;
}

}  // namespace ferret
