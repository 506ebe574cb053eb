#pragma once
// Why a plan was not found, as a value a program can branch on (the status string is
// for people). The planner service maps these onto its error codes (docs/service.md).

namespace ferret {

enum class PlanFailure {
  kNone,            ///< solved
  kStartInvalid,    ///< the start is in collision
  kGoalInvalid,     ///< the goal is in collision
  kStartOutside,    ///< the start is outside the geofence / hidden space
  kGoalOutside,     ///< the goal is outside the geofence / hidden space
  kTetherTooShort,  ///< the tether cannot reach (already over L - l_0, or the goal beyond it)
  kTimeout,         ///< the time limit passed before a path was found
  kCancelled,       ///< the caller's cancel flag stopped the search
  kNoPath,          ///< a path was found but failed its final checks
};

[[nodiscard]] inline const char* to_string(PlanFailure f) {
  switch (f) {
    case PlanFailure::kNone:
      return "none";
    case PlanFailure::kStartInvalid:
      return "start_occupied";
    case PlanFailure::kGoalInvalid:
      return "goal_occupied";
    case PlanFailure::kStartOutside:
      return "start_outside_bounds";
    case PlanFailure::kGoalOutside:
      return "goal_outside_bounds";
    case PlanFailure::kTetherTooShort:
      return "tether_too_short";
    case PlanFailure::kTimeout:
      return "timeout";
    case PlanFailure::kCancelled:
      return "cancelled";
    case PlanFailure::kNoPath:
      return "no_valid_path";
  }
  return "none";
}

}  // namespace ferret
