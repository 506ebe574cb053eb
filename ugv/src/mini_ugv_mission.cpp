#include "ferret/ugv/mini_ugv_mission.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "ferret/core/error.hpp"
#include "ferret/core/number.hpp"
#include "ferret/planning/grid_path_planner.hpp"

namespace ferret {
namespace {

constexpr double kTurnTolerance_rad = 0.05;
constexpr double kServoBearingTolerance_rad = 0.1;
constexpr double kServoDistanceTolerance_m = 0.03;
constexpr double kBatteryCheckPeriod_s = 1.0;
constexpr double kReplanPeriod_s = 1.0;
constexpr double kReturnStuck_s = 3.0;
constexpr double kWayHomeNodeSpacing_m = 0.3;  ///< wrap points closer than this share a node
constexpr double kWayHomeSnap_m = 0.3;         ///< how far from a wrap point a node may move

}  // namespace

std::string_view to_string(UgvMissionState state) {
  switch (state) {
    case UgvMissionState::kIdle:
      return "idle";
    case UgvMissionState::kExplore:
      return "explore";
    case UgvMissionState::kTrack:
      return "track";
    case UgvMissionState::kTurn:
      return "turn";
    case UgvMissionState::kGrasp:
      return "grasp";
    case UgvMissionState::kReturn:
      return "return";
    case UgvMissionState::kAwaitRetract:
      return "await_retract";
    case UgvMissionState::kDone:
      return "done";
  }
  return "?";
}

std::string_view to_string(UgvMissionOutcome outcome) {
  switch (outcome) {
    case UgvMissionOutcome::kNone:
      return "none";
    case UgvMissionOutcome::kObjectRetrieved:
      return "object_retrieved";
    case UgvMissionOutcome::kNoObject:
      return "no_object";
    case UgvMissionOutcome::kGraspFailed:
      return "grasp_failed";
    case UgvMissionOutcome::kTrackLost:
      return "track_lost";
    case UgvMissionOutcome::kBatteryLow:
      return "battery_low";
    case UgvMissionOutcome::kSearchTimeout:
      return "search_timeout";
    case UgvMissionOutcome::kReturnFailed:
      return "return_failed";
    case UgvMissionOutcome::kRetractTimeout:
      return "retract_timeout";
    case UgvMissionOutcome::kAborted:
      return "aborted";
    case UgvMissionOutcome::kRecalled:
      return "recalled";
  }
  return "?";
}

std::optional<double> UgvMissionOptions::state_timeout_s(UgvMissionState state) const {
  using S = UgvMissionState;
  switch (state) {
    case S::kExplore:
      return explore_timeout_s;
    case S::kTrack:
      return track_timeout_s;
    case S::kTurn:
      return turn_timeout_s;
    case S::kGrasp:
      return grasp_timeout_s;
    case S::kAwaitRetract:
      return retract_timeout_s;
    case S::kIdle:
    case S::kReturn:
    case S::kDone:
      return std::nullopt;
  }
  return std::nullopt;
}

void UgvMissionOptions::validate(const std::string& source) const {
  const auto positive = [&](double v, const char* field, std::string_view unit) {
    check_number(v, NumberRange::positive(1e6, unit), source, field);
  };
  positive(standoff_m, "ugv.standoff_m", "m");
  positive(servo_max_speed_mps, "ugv.servo_max_speed_mps", "m/s");
  positive(servo_gain_per_s, "ugv.servo_gain_per_s", "1/s");
  positive(servo_yaw_gain_per_s, "ugv.servo_yaw_gain_per_s", "1/s");
  positive(track_lost_s, "ugv.track_lost_s", "s");
  positive(track_timeout_s, "ugv.track_timeout_s", "s");
  positive(turn_timeout_s, "ugv.turn_timeout_s", "s");
  check_number(rear_offset_m, NumberRange::non_negative(10.0, "m"), source, "ugv.rear_offset_m");
  positive(grasp_speed_mps, "ugv.grasp_speed_mps", "m/s");
  check_number(grasp_overshoot_m, NumberRange::non_negative(10.0, "m"), source,
               "ugv.grasp_overshoot_m");
  if (grasp_attempts < 1 || grasp_attempts > 100)
    throw InputError(source, "ugv.grasp_attempts", "an integer in [1, 100]",
                     std::to_string(grasp_attempts));
  positive(grasp_timeout_s, "ugv.grasp_timeout_s", "s");
  positive(explore_timeout_s, "ugv.explore_timeout_s", "s");
  positive(entry_tolerance_m, "ugv.entry_tolerance_m", "m");
  positive(return_timeout_min_s, "ugv.return_timeout_min_s", "s");
  positive(retract_timeout_s, "ugv.retract_timeout_s", "s");
  positive(battery_endurance_s, "ugv.battery_endurance_s", "s");
  check_number(bump_time_s, NumberRange::closed(0.05, 10.0, "s"), source, "ugv.base.stall_time_s");
  check_number(battery_reserve_fraction, NumberRange::closed(0.0, 0.9), source,
               "ugv.battery_reserve_fraction");
  check_number(line_catch.pull_budget_n, NumberRange::non_negative(1e4, "N"), source,
               "ugv line_catch.pull_budget_n");
  if (line_catch.on()) {
    positive(line_catch.axial_stiffness_n, "ugv line_catch.axial_stiffness_n", "N");
    check_number(line_catch.reaction_s, NumberRange::non_negative(10.0, "s"), source,
                 "ugv line_catch.reaction_s");
    positive(line_catch.spool_acceleration_mps2, "ugv line_catch.spool_acceleration_mps2", "m/s^2");
  }
  if (explore.tether_budget_m)
    check_number(*explore.tether_budget_m, NumberRange::positive(1000.0, "m"), source,
                 "tether budget (tether.total_length_m - tether.entry_offset_m)");
  if (standoff_m <= rear_offset_m + explore.sensors.object_radius_m)
    throw InputError(source, "ugv.standoff_m",
                     "more than ugv.rear_offset_m + the object's radius (room to turn)",
                     std::to_string(standoff_m));
}

MiniUgvMission::MiniUgvMission(UgvBase& base, const Clock& clock, const GridGeometry& geometry,
                               UgvMissionOptions options, TransitionLog* log)
    : base_(base),
      clock_(clock),
      geo_(geometry),
      options_(std::move(options)),
      log_(log),
      follower_(options_.explore.robot) {
  if (options_.tether_aware && !options_.explore.tether_budget_m) {
    const TetherParams& tether = options_.explore.mission.tether;
    options_.explore.tether_budget_m = tether.total_length_m - tether.entry_offset_m;
  }
  options_.validate("ugv mission options");
  home_planner_ = std::make_unique<GridPathPlanner>(geo_, options_.explore.robot.body_radius_m);
}

MiniUgvMission::~MiniUgvMission() = default;

void MiniUgvMission::enter(UgvMissionState next, const std::string& reason) {
  if (log_)
    log_->add({clock_.now_s(), "ugv", std::string(to_string(state_)), std::string(to_string(next)),
               reason});
  state_ = next;
  state_since_s_ = clock_.now_s();
  follower_.clear();
}

void MiniUgvMission::finish(UgvMissionOutcome outcome, const std::string& reason) {
  base_.command_velocity(0.0, 0.0);
  outcome_ = outcome;
  enter(UgvMissionState::kDone, std::string(to_string(outcome)) + ": " + reason);
}

void MiniUgvMission::start() {
  if (state_ != UgvMissionState::kIdle) return;
  const Pose2 pose = base_.odometry();
  entry_W_ = pose.position();
  explore_ = std::make_unique<ExploreController>(geo_, pose, options_.explore);
  tick_ = explore_tick_ = 0;
  last_pose_ = pose;
  last_v_mps_ = 0.0;
  stalled_ticks_ = 0;
  next_battery_check_s_ = clock_.now_s();
  enter(UgvMissionState::kExplore, "started at the entry");
  state_timeout_s_ = options_.explore_timeout_s;
}

void MiniUgvMission::stop(const std::string& reason) {
  if (state_ == UgvMissionState::kDone) return;
  finish(UgvMissionOutcome::kAborted, reason);
}

void MiniUgvMission::recall(const std::string& reason) {
  switch (state_) {
    case UgvMissionState::kExplore:
    case UgvMissionState::kTrack:
    case UgvMissionState::kTurn:
    case UgvMissionState::kGrasp:
      base_.set_epm(false);  // nothing held yet (a contact would have started the return)
      begin_return(UgvMissionOutcome::kRecalled, "recalled: " + reason);
      return;
    case UgvMissionState::kIdle:
    case UgvMissionState::kReturn:
    case UgvMissionState::kAwaitRetract:
    case UgvMissionState::kDone:
      return;
  }
}

void MiniUgvMission::retracted() {
  if (state_ != UgvMissionState::kAwaitRetract) return;
  const UgvStatus status = base_.status();
  const bool held = status.epm_on && status.contact;
  if (held) {
    finish(UgvMissionOutcome::kObjectRetrieved, "lifted out with the object");
  } else if (return_outcome_ == UgvMissionOutcome::kObjectRetrieved) {
    finish(UgvMissionOutcome::kGraspFailed, "lifted out, but the object was lost on the way");
  } else {
    finish(return_outcome_, "lifted out");
  }
}

std::vector<Eigen::Vector2d> MiniUgvMission::path_home(const Pose2& pose, int widen) {
  const double escape_m = options_.explore.robot.escape_radius_m * (1 + widen);
  // Home along the tether: through its wrap points (pushed off their corners by the
  // clearance and a cell), each leg G's shortest known-free way. The shortest way home
  // by G alone can pass an obstacle on the other side and wind the tether round it.
  std::vector<Eigen::Vector2d> nodes =
      explore_->way_home_along_tether(options_.explore.robot.clearance_m + 2.0 * geo_.resolution_m);
  nodes.push_back(entry_W_);
  Cell from = geo_.cell_at(pose.x_m, pose.y_m);
  std::vector<Eigen::Vector2d> path{geo_.center(from)};  // as path_to: the follower skips it
  for (std::size_t k = 0; k < nodes.size(); ++k) {
    const bool last = k + 1 == nodes.size();
    // Wrap points of a slanted wall lie a cell apart: one node in a stretch will do.
    if (!last && (nodes[k] - path.back()).norm() < kWayHomeNodeSpacing_m) continue;
    home_planner_->compute(explore_->grid(), from, GridPathPlanner::Traversal::kKnownFree,
                           escape_m);
    // The node itself, or the nearest cell G can reach near it: a wrap point's offset
    // may lie in a wall's clearance band, and the entry's own cell may never have been
    // seen by the IR (the robot starts on it); within entry_tolerance_m is home.
    std::optional<Cell> goal;
    const Cell c = geo_.cell_at(nodes[k].x(), nodes[k].y());
    // (Half the tolerance for the entry: the follower stops within 0.1 m of its goal.)
    const double snap_m = last ? 0.5 * options_.entry_tolerance_m : kWayHomeSnap_m;
    const int r = static_cast<int>(std::ceil(snap_m / geo_.resolution_m));
    double best = std::numeric_limits<double>::infinity();
    for (int dj = -r; dj <= r; ++dj)
      for (int di = -r; di <= r; ++di) {
        const Cell q{c.i + di, c.j + dj};
        if (!home_planner_->reachable(q)) continue;
        const double d = (geo_.center(q) - nodes[k]).norm();
        if (d <= snap_m + 0.5 * geo_.resolution_m && d < best) best = d, goal = q;
      }
    if (!goal) {
      if (last) return {};  // the entry is out of G's reach from here
      continue;
    }
    const auto leg = home_planner_->path_to(*goal);
    if (!leg.empty()) path.insert(path.end(), leg.begin() + 1, leg.end());
    from = *goal;
  }
  if (path.size() < 2) return {};
  // The entry itself, not its cell's centre, when its cell was reached.
  if (from == geo_.cell_at(entry_W_.x(), entry_W_.y())) path.back() = entry_W_;
  return path;
}

double MiniUgvMission::drive_home_s(double way_m) const {
  const double top_mps = options_.explore.robot.max_velocity_mps;
  if (!options_.explore.tether_budget_m || !options_.line_catch.on()) return way_m / top_mps;
  // On the line's limit the last metres, on the shortest line, are the slowest; the
  // line is l_0 and (about) the way still to go.
  const double l0_m = options_.explore.mission.tether.entry_offset_m;
  const int n = std::max(1, static_cast<int>(std::ceil(way_m / 0.05)));
  const double dx_m = way_m / n;
  double t_s = 0.0;
  for (int k = 0; k < n; ++k)
    t_s += dx_m / std::min(top_mps, options_.line_catch.speed_mps(l0_m + (k + 0.5) * dx_m));
  return t_s;
}

bool MiniUgvMission::battery_calls_return(const Pose2& pose) {
  const double now = clock_.now_s();
  if (now < next_battery_check_s_) return false;
  next_battery_check_s_ = now + kBatteryCheckPeriod_s;
  const Cell robot = geo_.cell_at(pose.x_m, pose.y_m);
  const Cell entry = geo_.cell_at(entry_W_.x(), entry_W_.y());
  home_planner_->compute(explore_->grid(), robot, GridPathPlanner::Traversal::kKnownFree,
                         options_.explore.robot.escape_radius_m);
  // The way back as driven (known free) or, if the map cannot say, as the crow flies
  // (a floor for it: a robot that came in got here somehow).
  double way_m = home_planner_->reachable(entry)
                     ? static_cast<double>(home_planner_->distance_m(entry))
                     : (pose.position() - entry_W_).norm();
  // The return follows the tether (path_home): at least the tether's length.
  if (explore_->tether_budget_m()) way_m = std::max(way_m, explore_->reach_length_m());
  const double return_s = 2.0 * drive_home_s(way_m);
  const double needed = return_s / options_.battery_endurance_s + options_.battery_reserve_fraction;
  return base_.status().battery_fraction <= needed;
}

void MiniUgvMission::begin_return(UgvMissionOutcome outcome, const std::string& reason) {
  return_outcome_ = outcome;
  enter(UgvMissionState::kReturn, reason);
  const Pose2 pose = base_.odometry();
  return_replans_ = 0;
  progress_W_ = pose.position();
  progress_since_s_ = clock_.now_s();
  auto path = path_home(pose, 0);
  double length_m = (pose.position() - entry_W_).norm();
  const std::size_t corners = path.size();
  if (!path.empty()) {
    length_m = 0.0;
    Eigen::Vector2d prev = pose.position();
    for (const auto& p : path) {
      length_m += (p - prev).norm();
      prev = p;
    }
    follower_.set_path(std::move(path), std::nullopt);
  }
  // Four times the drive at full speed, and a half turn on the spot at every corner
  // (a way home along the tether turns at each wrap point).
  state_timeout_s_ =
      std::max(options_.return_timeout_min_s,
               4.0 * drive_home_s(length_m) + static_cast<double>(corners) * std::numbers::pi /
                                                  options_.explore.robot.max_yaw_rate_radps);
  next_replan_s_ = clock_.now_s() + kReplanPeriod_s;
}

VelocityCommand MiniUgvMission::guarded(const Pose2& pose, VelocityCommand c) const {
  // Forward only into cells G knows to be free (as the path follower): the servo must
  // not drive the robot into a wall it has not seen.
  const Pose2 next = integrate_unicycle(pose, c, explore_->tick_s());
  const Cell to = geo_.cell_at(next.x_m, next.y_m);
  const bool same = to == geo_.cell_at(pose.x_m, pose.y_m);
  if (c.v_mps > 0 && !same &&
      (!geo_.contains(to) || explore_->grid().label(to) != GridLabel::kFree))
    c.v_mps = 0.0;
  // Nor further out on a tether at its budget (turning and backing up stay allowed).
  // The servo's last metres are priced by the estimate and at most the reach margin of
  // the bound's doubt: the bound wraps every unknown patch the robot drove round, and
  // stopping short of a confirmed object for that (metres, once it circled one) would
  // end the mission for an obstacle that is most likely not there.
  const auto budget = explore_->tether_budget_m();
  if (c.v_mps > 0 && budget) {
    const double estimate = explore_->tether_length_m();
    const double doubt = std::max(0.0, explore_->reach_length_m() - estimate);
    const double margin = options_.explore.tether_margin_m;
    if (estimate + std::min(doubt, margin) + 0.5 * margin >= *budget) c.v_mps = 0.0;
  }
  return c;
}

VelocityCommand MiniUgvMission::servo(const Pose2& pose, const CameraFrame* frame) {
  const double now = clock_.now_s();
  if (frame && !frame->detections.empty()) {
    // The detection nearest to where the object is expected (one object, but a
    // detector may report a spurious second).
    const ObjectDetection* best = nullptr;
    double best_err = std::numeric_limits<double>::infinity();
    for (const auto& d : frame->detections) {
      if (!(d.distance_m > 0) || !std::isfinite(d.bearing_rad)) continue;
      const double a = pose.yaw_rad + d.bearing_rad;
      const Eigen::Vector2d p =
          pose.position() + d.distance_m * Eigen::Vector2d(std::cos(a), std::sin(a));
      const double err = (p - target_W_).norm();
      if (err < best_err) {
        best_err = err;
        best = &d;
      }
    }
    if (best) {
      const double a = pose.yaw_rad + best->bearing_rad;
      target_W_ = pose.position() + best->distance_m * Eigen::Vector2d(std::cos(a), std::sin(a));
      last_detection_s_ = now;
    }
  }
  const Eigen::Vector2d to = target_W_ - pose.position();
  const double bearing = wrap_angle_rad(std::atan2(to.y(), to.x()) - pose.yaw_rad);
  const double distance = to.norm();
  const RobotOptions& r = options_.explore.robot;
  VelocityCommand c;
  c.w_radps = std::clamp(options_.servo_yaw_gain_per_s * bearing, -r.max_yaw_rate_radps,
                         r.max_yaw_rate_radps);
  if (std::abs(bearing) < 0.3)
    c.v_mps = std::clamp(options_.servo_gain_per_s * (distance - options_.standoff_m),
                         -0.5 * options_.servo_max_speed_mps, options_.servo_max_speed_mps);
  return guarded(pose, c);
}

double MiniUgvMission::line_length_m() const {
  return options_.explore.mission.tether.entry_offset_m + explore_->tether_length_m();
}

void MiniUgvMission::tick() {
  if (state_ == UgvMissionState::kIdle || state_ == UgvMissionState::kDone) return;
  const double now = clock_.now_s();
  const Pose2 pose = base_.odometry();
  // The maps keep growing in every state: the way home is planned on them.
  explore_->observe_scan(base_.ir_scan());
  // A bump: told to drive forwards, the base has not moved for a while. What holds the
  // body goes into G (the IR may never have seen it: a low edge, a corner of the body's
  // side, or a wall it saw a cell off), or the follower, which trusts G, drives into it
  // again and again.
  if (last_v_mps_ > kBumpMinSpeed_mps &&
      (pose.position() - last_pose_.position()).norm() < 0.2 * last_v_mps_ * explore_->tick_s()) {
    if (++stalled_ticks_ * explore_->tick_s() >= options_.bump_time_s - 1e-9) {
      if (explore_->mark_bumped(pose) > 0) follower_.clear();
      stalled_ticks_ = 0;
      ++bumps_;
    }
  } else {
    stalled_ticks_ = 0;
  }
  last_pose_ = pose;
  if (state_ != UgvMissionState::kExplore) explore_->follow_tether(pose, now);
  // On its line, the robot drives no faster than the winch can follow a catch
  // (tether::LineCatchLimit); the line is l_0 and the taut estimate from the entry. A
  // line that can be longer than the estimate only by less than the stretch the limit
  // allows (the bound, with unknown space, less the estimate) cannot pull more.
  const double line_m = line_length_m();
  const double doubt_m = explore_->reach_length_m() - explore_->tether_length_m();
  line_speed_mps_ =
      std::min(link_speed_mps_,
               options_.explore.tether_budget_m && doubt_m > options_.line_catch.stretch_m(line_m)
                   ? options_.line_catch.speed_mps(line_m)
                   : std::numeric_limits<double>::infinity());
  explore_->set_speed_limit_mps(line_speed_mps_);
  follower_.set_speed_limit_mps(line_speed_mps_);
  std::optional<CameraFrame> frame;
  if (explore_->frame_due(tick_)) frame = base_.camera_frame(now);
  ++tick_;
  const bool timed_out = now - state_since_s_ > state_timeout_s_;
  VelocityCommand command;

  switch (state_) {
    case UgvMissionState::kExplore: {
      if (frame) {
        if (const auto cell = explore_->observe_frame(*frame)) {
          found_W_ = geo_.center(*cell);
          target_W_ = *found_W_;
          last_detection_s_ = now;
          enter(UgvMissionState::kTrack, "the object's probability passed lambda2");
          state_timeout_s_ = options_.track_timeout_s;
          command = servo(pose, nullptr);
          break;
        }
      }
      if (timed_out) {
        begin_return(UgvMissionOutcome::kSearchTimeout, "the search's time limit");
        break;
      }
      if (battery_calls_return(pose)) {
        begin_return(UgvMissionOutcome::kBatteryLow, "the battery left covers only the way back");
        break;
      }
      const ExploreController::Command c = explore_->decide(explore_tick_++, pose);
      if (c.explored) {
        begin_return(UgvMissionOutcome::kNoObject,
                     explore_->reach_rejections() > 0
                         ? "explored everything within the tether's reach, no object"
                         : "explored everything reachable, no object");
        break;
      }
      command = c.velocity;
      break;
    }
    case UgvMissionState::kTrack: {
      if (frame) explore_->observe_frame(*frame);
      if (timed_out) {
        begin_return(UgvMissionOutcome::kTrackLost, "could not close in on the object in time");
        break;
      }
      if (now - last_detection_s_ > options_.track_lost_s) {
        begin_return(UgvMissionOutcome::kTrackLost, "the object out of sight too long");
        break;
      }
      if (battery_calls_return(pose)) {
        begin_return(UgvMissionOutcome::kBatteryLow, "the battery left covers only the way back");
        break;
      }
      command = servo(pose, frame ? &*frame : nullptr);
      const Eigen::Vector2d to = target_W_ - pose.position();
      const double bearing = wrap_angle_rad(std::atan2(to.y(), to.x()) - pose.yaw_rad);
      if (std::abs(to.norm() - options_.standoff_m) < kServoDistanceTolerance_m &&
          std::abs(bearing) < kServoBearingTolerance_rad) {
        turn_target_rad_ = wrap_angle_rad(pose.yaw_rad + std::numbers::pi);
        enter(UgvMissionState::kTurn, "at d_min facing the object");
        state_timeout_s_ = options_.turn_timeout_s;
        command = {};
      }
      break;
    }
    case UgvMissionState::kTurn: {
      if (timed_out) {
        begin_return(UgvMissionOutcome::kGraspFailed, "could not turn in place");
        break;
      }
      const double e = wrap_angle_rad(turn_target_rad_ - pose.yaw_rad);
      if (std::abs(e) < kTurnTolerance_rad) {
        base_.set_epm(true);
        grasp_from_W_ = pose.position();
        ++grasp_attempt_;
        enter(UgvMissionState::kGrasp,
              "EPM on, backing onto the object (attempt " + std::to_string(grasp_attempt_) + ")");
        state_timeout_s_ = options_.grasp_timeout_s;
        break;
      }
      const double w_max = options_.explore.robot.max_yaw_rate_radps;
      command = {0.0, std::clamp(3.0 * e, -w_max, w_max)};
      break;
    }
    case UgvMissionState::kGrasp: {
      const UgvStatus status = base_.status();
      if (status.epm_on && status.contact) {
        begin_return(UgvMissionOutcome::kObjectRetrieved, "contact: the object is on the magnet");
        break;
      }
      const double backed_m = (pose.position() - grasp_from_W_).norm();
      const double gap_m =
          options_.standoff_m - options_.rear_offset_m - options_.explore.sensors.object_radius_m;
      if (backed_m >= gap_m + options_.grasp_overshoot_m || timed_out) {
        base_.set_epm(false);
        if (grasp_attempt_ >= options_.grasp_attempts) {
          begin_return(UgvMissionOutcome::kGraspFailed,
                       "no contact after " + std::to_string(grasp_attempt_) + " attempts");
          break;
        }
        // Again from the start: find the object, close in, turn, back up.
        last_detection_s_ = now;
        enter(UgvMissionState::kTrack, "no contact: servo onto the object again");
        state_timeout_s_ = options_.track_timeout_s;
        break;
      }
      command = {-options_.grasp_speed_mps, 0.0};
      break;
    }
    case UgvMissionState::kReturn: {
      if ((pose.position() - entry_W_).norm() <= options_.entry_tolerance_m) {
        enter(UgvMissionState::kAwaitRetract, "at the entry, asking for retraction");
        state_timeout_s_ = options_.retract_timeout_s;
        break;
      }
      if (timed_out) {
        finish(UgvMissionOutcome::kReturnFailed, "did not reach the entry in time");
        return;
      }
      // No headway for kReturnStuck_s (a path cut into the clearance band of a wall, a
      // blocked step the follower cannot recover from): plan again from here, the
      // clearance waived further out each time.
      if ((pose.position() - progress_W_).norm() > 0.05) {
        progress_W_ = pose.position();
        progress_since_s_ = now;
      } else if (now - progress_since_s_ > kReturnStuck_s) {
        ++return_replans_;
        follower_.clear();
        next_replan_s_ = now;
        progress_since_s_ = now;
      }
      if (!follower_.has_path() && now >= next_replan_s_) {
        next_replan_s_ = now + kReplanPeriod_s;
        auto path = path_home(pose, return_replans_);
        if (!path.empty()) follower_.set_path(std::move(path), std::nullopt);
      }
      bool reached = false;
      command = follower_.step(pose, explore_->grid(), explore_->tick_s(), reached);
      if (reached) follower_.clear();  // near the entry cell; the tolerance check decides
      break;
    }
    case UgvMissionState::kAwaitRetract:
      if (timed_out) {
        finish(UgvMissionOutcome::kRetractTimeout, "nobody lifted the robot out");
        return;
      }
      break;
    case UgvMissionState::kIdle:
    case UgvMissionState::kDone:
      break;
  }
  // The servo's and the grasp's speeds too.
  command.v_mps = std::clamp(command.v_mps, -line_speed_mps_, line_speed_mps_);
  last_v_mps_ = state_ == UgvMissionState::kDone ? 0.0 : command.v_mps;
  if (state_ != UgvMissionState::kDone) base_.command_velocity(command.v_mps, command.w_radps);
}

}  // namespace ferret
