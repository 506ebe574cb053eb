// ferret as a library (docs/library.md): load the shipped default world, plan the
// UAV's approach to the hidden space house_void, plan a tether-aware miniUGV path
// inside it, check both plans with the validation API, and run one curiosity-driven
// object search with the shipped miniUGV's sensors in a shipped hidden-space map.
//
//   ferret_library_example [OUT_DIR]   (OUT_DIR: also write approach.json, ugv.json)
//
// Exit 0 when both plans are found and valid, 1 when not, 2 for bad input.

#include <cstdio>
#include <ferret/core/data_path.hpp>
#include <ferret/core/error.hpp>
#include <ferret/mapping/occupancy_map_2d.hpp>
#include <ferret/mission/search_robot.hpp>
#include <ferret/planning/plan_validation.hpp>
#include <ferret/planning/planning_world.hpp>
#include <ferret/planning/uav_approach.hpp>
#include <ferret/planning/ugv_path.hpp>
#include <ferret/urdf/robot_description.hpp>
#include <filesystem>
#include <string>

namespace {

double path_length_m(const ferret::PlanFile& plan) {
  double length_m = 0.0;
  for (std::size_t k = 1; k < plan.states.size(); ++k)
    length_m += (plan.states[k].position() - plan.states[k - 1].position()).norm();
  return length_m;
}

// Checks a plan as `ferret validate` does (docs/validate.md): the robot and limits the
// plan was made with, its bounds, the tether replayed, FCL alone; every violation.
bool report_check(const char* what, const ferret::PlanningWorld& world,
                  const ferret::PlanFile& plan) {
  const ferret::ValidationReport report = ferret::validate_plan(plan, world, {}, what);
  if (!report.valid()) {
    std::printf("%s check: invalid, %zu violations, first: %s\n", what, report.violations.size(),
                report.violations.front().describe().c_str());
    return false;
  }
  std::printf("%s check: valid, clearance >= %.2f m, peak %.2f m/s, %.2f m/s^2\n", what,
              report.margins.min_clearance_m, report.margins.peak_speed_mps,
              report.margins.peak_acceleration_mps2);
  return true;
}

}  // namespace

int main(int argc, char** argv) {
  if (argc > 2) {
    std::fprintf(stderr, "usage: %s [OUT_DIR]\n", argv[0]);
    return 2;
  }
  try {
    // The world ships with ferret: data_path() finds it beside the installed library.
    const std::filesystem::path world_file = ferret::data_path("worlds/default.yaml");
    const ferret::PlanningWorld world = ferret::load_planning_world(world_file);
    std::printf("world: %s\n", std::filesystem::absolute(world_file).c_str());

    // 1. The UAV from the site's south-west corner to the hover pose in front of
    //    house_void's opening, with the shipped M100 model (its shapes and limits).
    ferret::UavApproachRequest approach;
    approach.start = {.t_s = 0.0, .x_m = -20.0, .y_m = -20.0, .z_m = 3.0, .yaw_rad = 0.0};
    approach.hidden_space = "house_void";
    approach.seed = 7;
    const ferret::PlanResult uav = ferret::plan_uav_approach(world, approach);
    if (!uav.solved) {
      std::printf("approach: not solved: %s\n", uav.status.c_str());
      return 1;
    }
    std::printf("model: %s\n", std::filesystem::absolute(uav.plan.robot_model).c_str());
    std::printf("approach: solved, %zu states, %.2f m, %.2f s to house_void\n",
                uav.plan.states.size(), path_length_m(uav.plan), uav.plan.states.back().t_s);

    // 2. The miniUGV, lowered at the opening, from just inside the entry to the far side
    //    of the rubble, its tether held within the mission's budget (15 m - 1 m).
    ferret::UgvPathRequest path;
    path.start = {-7.3, 7.0, 3.14159};
    path.goal = {-14.8, 6.665, 2.92};
    path.seed = 7;
    const ferret::UgvPathResult ugv = ferret::plan_ugv_path(world, path);
    if (!ugv.solved) {
      std::printf("ugv: not solved: %s\n", ugv.status.c_str());
      return 1;
    }
    std::printf("ugv: solved, %zu states, %.2f m, tether %.2f m taut of %.2f m, %zu wrap points\n",
                ugv.plan.states.size(), path_length_m(ugv.plan),
                ugv.plan.states.back().tether_length_m, ugv.tether_budget_m,
                ugv.final_wraps.size());

    // 3. Both plans checked as `ferret validate` checks them.
    const bool valid =
        report_check("approach", world, uav.plan) & report_check("ugv", world, ugv.plan);

    // 4. One object search (CDOS) in the sparse hidden space, with the miniUGV's own
    //    camera and IR sensors and speed limit from its URDF.
    const ferret::RobotDescription miniugv = ferret::load_robot("miniugv");
    const ferret::OccupancyMap2D hidden =
        ferret::load_map_server(ferret::data_path("maps/sparse.yaml"));
    const ferret::EpisodeResult search = ferret::run_search(
        hidden, ferret::Pose2{1.0, 4.0, 0.0}, {9.0, 6.0}, "cdos", miniugv, /*seed=*/1);
    std::printf("search: cdos %s in %.1f s, %.1f m, %d decisions (%s)\n",
                search.found ? "found the object" : "did not find the object", search.time_s,
                search.path_m, search.decisions, search.end_reason.c_str());
    if (argc == 2) {
      ferret::save_plan(uav.plan, std::filesystem::path(argv[1]) / "approach.json");
      ferret::save_plan(ugv.plan, std::filesystem::path(argv[1]) / "ugv.json");
    }
    return valid && search.found ? 0 : 1;
  } catch (const ferret::InputError& e) {
    std::fprintf(stderr, "error: %s\n", e.what());
    return 2;
  }
}
