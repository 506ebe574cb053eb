#pragma once
// The miniUGV's mission controller (paper sect. III-IV): from the hidden space's entry,
//   explore        the object search (ExploreController) until a cell of O passes lambda2
//   track          visual servoing on the detector's bearing and distance to d_min
//   turn           180 degrees in place, the EPM (at the rear) towards the object
//   grasp          EPM on, back up to push and confirm contact (retry, then give up)
//   return         back to the entry on G's known-free cells
//   await_retract  stopped at the entry, asking the UAV's winch to lift it out
//   done           a named outcome (object_retrieved, no_object, grasp_failed, ...)
// Every state has a timeout and a defined exit; every transition goes to the
// TransitionLog with the clock's time and the reason. The battery bounds the search:
// when what is left no longer covers the way back (plus a reserve) it returns.
// The controller sees the UgvBase and the Clock only, never the simulator's truth.

#include <Eigen/Core>
#include <limits>
#include <memory>
#include <optional>
#include <string>
#include <string_view>

#include "ferret/core/clock.hpp"
#include "ferret/core/transition_log.hpp"
#include "ferret/tether_model/line_catch.hpp"
#include "ferret/ugv/explore_controller.hpp"
#include "ferret/ugv/mini_ugv_mission_options.hpp"
#include "ferret/ugv/ugv_base.hpp"

namespace ferret {

class GridPathPlanner;

class MiniUgvMission {
 public:
  /// configure: the maps are built on `geometry` (the hidden space's grid, in the
  /// robot's odometry frame); `log` may be null.
  MiniUgvMission(UgvBase& base, const Clock& clock, const GridGeometry& geometry,
                 UgvMissionOptions options, TransitionLog* log);
  ~MiniUgvMission();
  MiniUgvMission(const MiniUgvMission&) = delete;
  MiniUgvMission& operator=(const MiniUgvMission&) = delete;

  /// At the entry (the pose now is the entry): idle -> explore.
  void start();
  /// One control step at the IR rate (explore_controller().tick_s()).
  void tick();
  /// Stops the wheels and ends the mission as aborted (the EPM keeps what it holds).
  void stop(const std::string& reason);
  /// The UAV calls it back (its flight budget, say): a search, servo, turn or grasp
  /// under way gives up and returns to the entry, to be lifted out as `recalled`;
  /// a robot already on its way back or waiting is not affected.
  void recall(const std::string& reason);
  /// The winch has lifted the robot out: await_retract -> done.
  void retracted();
  /// The top speed the robot link allows from the next tick on (infinite: none): the
  /// winch follows only what it has heard (UgvLinkEndpoint sets it).
  void set_link_speed_limit_mps(double v_mps) { link_speed_mps_ = v_mps; }

  [[nodiscard]] UgvMissionState state() const { return state_; }
  [[nodiscard]] UgvMissionOutcome outcome() const { return outcome_; }
  /// The outcome the mission will end with once lifted out (set when it heads home).
  [[nodiscard]] UgvMissionOutcome return_outcome() const { return return_outcome_; }
  [[nodiscard]] bool done() const { return state_ == UgvMissionState::kDone; }
  [[nodiscard]] bool wants_retraction() const { return state_ == UgvMissionState::kAwaitRetract; }
  /// Where O confirmed the object, once it did.
  [[nodiscard]] std::optional<Eigen::Vector2d> found_W() const { return found_W_; }
  /// The search, from start() on: a mission never started (its start request lost, say)
  /// has none, and explore_controller() is only for one that has.
  [[nodiscard]] bool started() const { return explore_ != nullptr; }
  [[nodiscard]] const ExploreController& explore_controller() const { return *explore_; }
  /// How often the base stood still when told to drive forwards (bumps into G).
  [[nodiscard]] int bumps() const { return bumps_; }
  /// The top speed the line and the link allowed at the last tick (infinite: none).
  [[nodiscard]] double line_speed_limit_mps() const { return line_speed_mps_; }
  [[nodiscard]] double tick_s() const { return explore_->tick_s(); }
  /// The line from the winch as the robot's model has it: l_0 and the taut estimate
  /// from the entry (the real line is no shorter).
  [[nodiscard]] double line_length_m() const;
  [[nodiscard]] const Eigen::Vector2d& entry_W() const { return entry_W_; }
  [[nodiscard]] int grasp_attempts() const { return grasp_attempt_; }

 private:
  void enter(UgvMissionState next, const std::string& reason);
  void finish(UgvMissionOutcome outcome, const std::string& reason);
  void begin_return(UgvMissionOutcome outcome, const std::string& reason);
  [[nodiscard]] bool battery_calls_return(const Pose2& pose);
  /// Time to drive `way_m` home at the top speed (held to the line's limit, if on).
  [[nodiscard]] double drive_home_s(double way_m) const;
  [[nodiscard]] VelocityCommand servo(const Pose2& pose, const CameraFrame* frame);
  [[nodiscard]] VelocityCommand guarded(const Pose2& pose, VelocityCommand c) const;
  /// The known-free way to the entry along the tether (through its wrap points);
  /// `widen` > 0 waives the clearance further out.
  [[nodiscard]] std::vector<Eigen::Vector2d> path_home(const Pose2& pose, int widen);

  UgvBase& base_;
  const Clock& clock_;
  GridGeometry geo_;
  double line_speed_mps_ = std::numeric_limits<double>::infinity();
  double link_speed_mps_ = std::numeric_limits<double>::infinity();
  /// A bump: forwards at least this fast, yet stood still for
  /// UgvMissionOptions::bump_time_s.
  static constexpr double kBumpMinSpeed_mps = 0.02;
  double last_v_mps_ = 0.0;
  Pose2 last_pose_;
  int stalled_ticks_ = 0;
  int bumps_ = 0;
  UgvMissionOptions options_;
  TransitionLog* log_;
  std::unique_ptr<ExploreController> explore_;
  std::unique_ptr<GridPathPlanner> home_planner_;
  PathFollower follower_;

  UgvMissionState state_ = UgvMissionState::kIdle;
  UgvMissionOutcome outcome_ = UgvMissionOutcome::kNone;
  UgvMissionOutcome return_outcome_ = UgvMissionOutcome::kNone;
  double state_since_s_ = 0.0;
  double state_timeout_s_ = 0.0;
  long tick_ = 0;
  long explore_tick_ = 0;
  Eigen::Vector2d entry_W_ = Eigen::Vector2d::Zero();
  std::optional<Eigen::Vector2d> found_W_;
  Eigen::Vector2d target_W_ = Eigen::Vector2d::Zero();  ///< the object as the servo sees it
  double last_detection_s_ = 0.0;
  double turn_target_rad_ = 0.0;
  Eigen::Vector2d grasp_from_W_ = Eigen::Vector2d::Zero();
  int grasp_attempt_ = 0;
  double next_battery_check_s_ = 0.0;
  double next_replan_s_ = 0.0;
  Eigen::Vector2d progress_W_ = Eigen::Vector2d::Zero();  ///< return: last headway
  double progress_since_s_ = 0.0;
  int return_replans_ = 0;
};

}  // namespace ferret
