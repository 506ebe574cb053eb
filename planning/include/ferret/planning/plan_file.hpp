#pragma once
// Plans on disk: the JSON written by `ferret plan` (docs/planning.md has the
// format) and, for plans written by other tools, a CSV of t,x,y,z,yaw.

#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "ferret/planning/collision_map.hpp"
#include "ferret/planning/motion_check.hpp"
#include "ferret/tether_model/taut_tether.hpp"

namespace ferret {

enum class PlanRobot { kUav, kUavWithUgv, kUgv };
[[nodiscard]] const char* to_string(PlanRobot robot);

/// The tether of a miniUGV plan: where it enters, how it lay at the start, the budget.
struct PlanTether {
  Eigen::Vector2d p_WE = Eigen::Vector2d::Zero();
  std::vector<WrapPoint> initial_wraps;
  double total_length_m = 15.0;  ///< L
  double entry_offset_m = 1.0;   ///< l_0
};

struct PlanFile {
  PlanRobot robot = PlanRobot::kUav;
  bool robot_known =
      true;  ///< false for a CSV or a JSON of states only (the robot comes from the command line)
  std::string frame = "world";
  std::vector<Waypoint> states;
  double released_length_m = 0.0;    ///< kUavWithUgv: tether from the winch to the miniUGV
  std::optional<PlanTether> tether;  ///< kUgv
  std::optional<UnknownPolicy> unknown_policy;
  std::optional<Aabb3> bounds;  ///< the geofence (UAV) or hidden-space bounds (miniUGV)
  std::optional<double> max_velocity_mps, max_acceleration_mps2, max_yaw_rate_radps;
  /// The URDF whose collision shapes the plan was made with; empty: ferret's
  /// built-in shapes (robot_shape.hpp). `ferret validate` checks with the same.
  std::string robot_model;
  // What made it (informational).
  std::string planner;
  double planning_time_s =
      0.0;  ///< read from older files; not written (wall time would make runs differ)
  std::uint64_t seed = 0;
  std::string world;
};

[[nodiscard]] std::string plan_to_json(const PlanFile& plan);
/// Writes the JSON atomically.
void save_plan(const PlanFile& plan, const std::filesystem::path& path);
/// Reads a plan: JSON (by content: a leading '{') or CSV of t,x,y,z,yaw with an
/// optional header line. A JSON object without "format" is a plan of another tool:
/// only "states" is required (and read), and the robot comes from the command line. Throws
/// InputError naming the file, the field (or line) and what was expected for anything malformed:
/// syntax, missing or mistyped fields, non-finite numbers, an unknown robot, fewer than one state.
[[nodiscard]] PlanFile load_plan(const std::filesystem::path& path);
[[nodiscard]] PlanFile parse_plan(const std::string& text, const std::string& source);

}  // namespace ferret
