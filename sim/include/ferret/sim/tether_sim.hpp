#pragma once
// Tether simulation for evaluating the winch controllers: a scripted or recorded
// miniUGV trajectory, the taut-tether geometry (entry, wrap points), the spool
// (tether::SimulatedWinch), an elastic tether with its taut/slack state and tension,
// snags (a wrap point that holds the line for a while), link latency and sensor
// noise. docs/tether.md describes the trajectory files and the model.

#include <Eigen/Core>
#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include "ferret/tether_model/feedforward_pid.hpp"
#include "ferret/tether_model/required_length.hpp"
#include "ferret/tether_model/simulated_winch.hpp"
#include "ferret/tether_model/taut_mpc.hpp"
#include "ferret/tether_model/tether_controller.hpp"

namespace ferret::sim {

struct TrajectorySample {
  double t_s = 0.0;
  Eigen::Vector2d p_WG = Eigen::Vector2d::Zero();
  double yaw_rad = 0.0;
  Eigen::Vector2d v_WG = Eigen::Vector2d::Zero();  ///< desired velocity
  Eigen::Vector2d a_WG = Eigen::Vector2d::Zero();  ///< desired acceleration
};

/// A wrap point that stops sliding: the line is pinched there from start_s for duration_s.
struct TetherSnag {
  std::size_t wrap_point = 0;
  double start_s = 0.0;
  double duration_s = 0.0;
};

struct TetherScenario {
  std::string name;
  Eigen::Vector2d p_WE = Eigen::Vector2d::Zero();  ///< hidden-space entry point
  std::vector<tether::WrapPoint> wrap_points;
  std::vector<TetherSnag> snags;
  std::vector<TrajectorySample> samples;  ///< strictly increasing t_s, at least two

  [[nodiscard]] double start_s() const { return samples.front().t_s; }
  [[nodiscard]] double end_s() const { return samples.back().t_s; }
  /// Linear interpolation (clamped to the ends).
  [[nodiscard]] TrajectorySample at(double t_s) const;
};

/// Reads a trajectory: CSV (header `t,x,y,yaw` or `t,x,y,yaw,vx,vy,ax,ay`; '#'
/// comments) or YAML (entry, wrap points, snags and the samples inline or from a
/// CSV beside it), chosen by the extension (.csv, .yaml/.yml). Missing velocities and
/// accelerations come from central differences. Throws InputError naming the file,
/// the line or field and what was expected.
[[nodiscard]] TetherScenario load_tether_scenario(const std::filesystem::path& path);

/// Fills v_WG and a_WG by central differences of the positions (one-sided at the ends).
void differentiate_trajectory(std::vector<TrajectorySample>& samples);

/// Straight segments through `waypoints`, each driven from rest to rest with a
/// trapezoidal speed profile (cruise speed, acceleration), sampled every dt_s, with
/// `dwell_s` standing still at every waypoint. Yaw follows the segment.
[[nodiscard]] std::vector<TrajectorySample> scripted_trajectory(
    const std::vector<Eigen::Vector2d>& waypoints, double cruise_mps, double accel_mps2,
    double dwell_s, double dt_s = 0.02);

/// How the miniUGV really moves (TetherSimOptions::ugv_*).
struct UgvObedience {
  double velocity_lag_s = 0.0;
  double slip_mps = 0.0;
  double slip_time_s = 0.5;
  double tracking_time_s = 0.0;
};

/// The miniUGV's actual motion, sampled every dt_s over the scenario: its velocity
/// loop (first-order lag) follows the desired velocity plus, with a tracking time,
/// the position error over that time; a Gauss-Markov slip velocity drawn from `seed`
/// adds to it. v_WG is the actual velocity, a_WG the desired acceleration.
[[nodiscard]] std::vector<TrajectorySample> actual_ugv_motion(const TetherScenario& scenario,
                                                              const UgvObedience& ugv, double dt_s,
                                                              std::uint64_t seed);

/// The built-in scenario `ferret tether-sim` runs without --trajectory: out from the
/// entry, round an obstacle corner (the tether wraps), behind it, and back.
[[nodiscard]] TetherScenario default_tether_scenario();

struct TetherSimOptions {
  tether::TautControlOptions control;  ///< also the limits and the tension model
  tether::SimulatedWinch::Options winch;
  double entry_offset_m = 1.0;  ///< l_0 (from MissionConfig)
  double physics_dt_s = 0.001;
  double link_latency_s = 0.06;  ///< age of the miniUGV's pose when it reaches the winch
  double pose_noise_m = 0.01;    ///< standard deviation of the reported position
  double tension_noise_n = 0.2;  ///< standard deviation of the current-based tension
  /// How far ahead each message carries the miniUGV's planned motion (its desired
  /// trajectory), in knots `ugv_preview_step_s` apart; 0: no preview.
  double ugv_preview_s = 0.0;
  double ugv_preview_step_s = 0.05;
  /// A less obedient miniUGV (an extra scenario; lag and slip 0 = it follows its
  /// desired motion exactly, the shipped setting): its own velocity loop lags the
  /// desired velocity with this time constant, wheel slip adds a random velocity
  /// error (Gauss-Markov: standard deviation per axis, correlation time), and its
  /// path tracking steers back to the desired position with this time constant
  /// (0: none, the error accumulates).
  double ugv_velocity_lag_s = 0.0;
  double ugv_slip_noise_mps = 0.0;
  double ugv_slip_time_s = 0.5;
  double ugv_tracking_time_s = 1.0;
  std::uint64_t seed = 1;

  /// Consistent options for a tether of total length L and entry offset l_0.
  [[nodiscard]] static TetherSimOptions for_tether(double total_length_m, double entry_offset_m);
};

/// Everything `ferret tether-sim --config FILE` can set: the simulation and both
/// controllers, starting from the defaults for a tether (L, l_0).
struct TetherRunConfig {
  TetherSimOptions sim;
  tether::TautTetherMpc::Options mpc;
  tether::FeedForwardPid::Options baseline;

  /// Defaults for a tether of total length L and entry offset l_0 (controllers share sim.control).
  [[nodiscard]] static TetherRunConfig for_tether(double total_length_m, double entry_offset_m);
};

/// Applies a YAML file with optional sections `control` (slack_reference_m,
/// max_slack_m, pose_filter_gain, guard_n, max_tension_n, max_speed_mps,
/// max_acceleration_mps2, ugv_velocity_lag_s, tension_fusion, observer_pose_noise_m,
/// observer_tension_noise_n, observer_speed_noise_mps), `mpc` (horizon,
/// prediction_dt_s, acceleration_time_s, use_preview, weight_*), `baseline`
/// (kp_per_s, ki_per_s2, kd, feedforward_gain, use_preview) and `sim` (link_latency_s,
/// pose_noise_m, tension_noise_n, ugv_preview_s, ugv_preview_step_s,
/// ugv_velocity_lag_s, ugv_slip_noise_mps, ugv_slip_time_s, ugv_tracking_time_s)
/// on top of `config`. Unknown keys and values out of
/// range are InputErrors naming the file and field.
void apply_tether_run_config(const std::filesystem::path& path, TetherRunConfig& config);

struct TetherSimSample {
  double t_s = 0.0;
  double released_m = 0.0;  ///< l_t
  double required_m = 0.0;  ///< taut length to the miniUGV (ground truth)
  double slack_m = 0.0;     ///< l_t - required
  double ugv_tension_n = 0.0;
  double winch_tension_n = 0.0;  ///< true, without the hanging weight
  double command_mps = 0.0;
  double speed_mps = 0.0;
  bool snagged = false;
  /// The slack a winch can act on: while a snag pins the line at a corner, only the
  /// winch's side of the pin (its material less its taut length to the pin); the
  /// slack beyond the pin is out of any winch's reach. Otherwise slack_m.
  double reachable_slack_m = 0.0;
};

struct TetherSimMetrics {
  double slack_rms_m = 0.0;
  /// RMS of TetherSimSample::reachable_slack_m over all control cycles.
  double reachable_slack_rms_m = 0.0;
  double max_slack_m = 0.0;
  double min_slack_m = 0.0;
  double max_tension_n = 0.0;
  int over_tension_events = 0;  ///< rising edges of tension > max_tension_n (either end)
  double over_tension_time_s = 0.0;
  double limit_active_s = 0.0;  ///< time with l_t within 1 mm of L
  double max_released_m = 0.0;
  int released_over_limit = 0;  ///< control cycles with l_t > L (+1 mm)
  double duration_s = 0.0;
  int control_cycles = 0;
  /// Wall-clock time of controller.step(): the only non-deterministic figures.
  double step_time_median_us = 0.0;
  double step_time_max_us = 0.0;
};

struct TetherSimResult {
  std::string scenario;
  std::string controller;
  /// The plot's first words (empty: "tether-sim SCENARIO trajectory") and the name of
  /// its slack band (empty: "allowed [0, s_max = ... mm]").
  std::string plot_title, band_label;
  std::vector<TetherSimSample> log;  ///< one row a control cycle
  TetherSimMetrics metrics;
};

/// Runs the scenario in closed loop with the controller. Deterministic for a seed.
/// Throws std::invalid_argument if the scenario is unusable (too few samples, a
/// snag on a wrap point that does not exist).
[[nodiscard]] TetherSimResult run_tether_sim(const TetherScenario& scenario,
                                             const TetherSimOptions& options,
                                             tether::TetherController& controller);

/// CSV:
/// t_s,released_m,required_m,slack_m,ugv_tension_n,winch_tension_n,command_mps,speed_mps,snagged,
/// reachable_slack_m.
void write_tether_sim_csv(const TetherSimResult& result, const std::filesystem::path& path);
/// PNG plot: l_t and the required length (top), slack with the [0, s_max] band and
/// snag intervals (bottom). Written atomically.
void write_tether_sim_plot(const TetherSimResult& result, double max_slack_m, double total_length_m,
                           const std::filesystem::path& path);

}  // namespace ferret::sim
