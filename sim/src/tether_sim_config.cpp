// The settings of a tether simulation run: options sized for a tether, and a run
// config YAML (control, mpc, baseline, sim) mapped onto the controllers' and the
// simulator's options, each value checked against its range.

#include "ferret/core/yaml_config.hpp"
#include "ferret/sim/tether_sim.hpp"

namespace ferret::sim {

TetherSimOptions TetherSimOptions::for_tether(double total_length_m, double entry_offset_m) {
  TetherSimOptions o;
  o.entry_offset_m = entry_offset_m;
  o.control.limits.total_length_m = total_length_m;
  o.winch.total_length_m = total_length_m;
  o.winch.max_speed_mps = o.control.limits.max_speed_mps;
  o.winch.max_acceleration_mps2 = o.control.limits.max_acceleration_mps2;
  return o;
}

TetherRunConfig TetherRunConfig::for_tether(double total_length_m, double entry_offset_m) {
  TetherRunConfig c;
  c.sim = TetherSimOptions::for_tether(total_length_m, entry_offset_m);
  c.mpc.control = c.sim.control;
  c.baseline.control = c.sim.control;
  return c;
}

void apply_tether_run_config(const std::filesystem::path& path, TetherRunConfig& c) {
  const yaml::MapReader root(yaml::load_file(path), path.string());
  root.allow_only({"control", "mpc", "baseline", "sim"});
  auto& ctl = c.sim.control;
  if (const auto r = root.optional_child("control")) {
    r->allow_only({"slack_reference_m", "max_slack_m", "pose_filter_gain", "guard_n",
                   "max_tension_n", "max_speed_mps", "max_acceleration_mps2", "ugv_velocity_lag_s",
                   "ugv_tracking_time_s", "identify_ugv_response",
                   "tension_fusion", "observer_pose_noise_m", "observer_tension_noise_n",
                   "observer_speed_noise_mps", "observer_model_offset_decay_mps",
                   "servo_time_constant_s"});
    ctl.slack_reference_m =
        r->get_in_range_or("slack_reference_m", -0.1, 1.0, ctl.slack_reference_m);
    ctl.max_slack_m = r->get_in_range_or("max_slack_m", 0.0, 10.0, ctl.max_slack_m);
    ctl.pose_filter_gain = r->get_in_range_or("pose_filter_gain", 1e-3, 1.0, ctl.pose_filter_gain);
    ctl.ugv_velocity_lag_s =
        r->get_in_range_or("ugv_velocity_lag_s", 0.0, 5.0, ctl.ugv_velocity_lag_s);
    ctl.ugv_tracking_time_s =
        r->get_in_range_or("ugv_tracking_time_s", 0.0, 100.0, ctl.ugv_tracking_time_s);
    ctl.ugv_response_identification.enabled =
        r->get_or<bool>("identify_ugv_response", ctl.ugv_response_identification.enabled);
    ctl.limits.velocity_time_constant_s =
        r->get_in_range_or("servo_time_constant_s", 1e-4, 1.0, ctl.limits.velocity_time_constant_s);
    auto& obs = ctl.slack_observer;
    obs.tension_fusion = r->get_or<bool>("tension_fusion", obs.tension_fusion);
    obs.pose_noise_m = r->get_in_range_or("observer_pose_noise_m", 0.0, 1.0, obs.pose_noise_m);
    obs.tension_noise_n =
        r->get_in_range_or("observer_tension_noise_n", 1e-3, 100.0, obs.tension_noise_n);
    obs.ugv_speed_noise_mps =
        r->get_in_range_or("observer_speed_noise_mps", 0.0, 10.0, obs.ugv_speed_noise_mps);
    obs.model_offset_decay_mps =
        r->get_in_range_or("observer_model_offset_decay_mps", 0.0, 10.0, obs.model_offset_decay_mps);
    ctl.slack_estimator.guard_n =
        r->get_in_range_or("guard_n", 0.0, 1e3, ctl.slack_estimator.guard_n);
    ctl.slack_estimator.tension.max_tension_n =
        r->get_in_range_or("max_tension_n", 0.1, 1e4, ctl.slack_estimator.tension.max_tension_n);
    ctl.limits.max_speed_mps =
        r->get_in_range_or("max_speed_mps", 1e-3, 10.0, ctl.limits.max_speed_mps);
    ctl.limits.max_acceleration_mps2 =
        r->get_in_range_or("max_acceleration_mps2", 1e-3, 100.0, ctl.limits.max_acceleration_mps2);
    c.sim.winch.max_speed_mps = ctl.limits.max_speed_mps;
    c.sim.winch.max_acceleration_mps2 = ctl.limits.max_acceleration_mps2;
  }
  if (const auto r = root.optional_child("mpc")) {
    r->allow_only({"horizon", "prediction_dt_s", "acceleration_time_s", "use_preview",
                   "weight_slack", "weight_command_rate", "rate_penalty_about_tracking_command",
                   "weight_feedforward", "weight_terminal",
                   "weight_soft_linear", "weight_stretch_linear", "weight_soft_quadratic",
                   "ugv_velocity_error_mps", "ugv_velocity_error_time_s",
                   "ugv_velocity_error_window_s", "ugv_velocity_error_prior_log_odds",
                   "ugv_velocity_error_prior_log_odds_with_lag", "ugv_velocity_error_long_window_s",
                   "identify_ugv_response", "ugv_response_window_s",
                   "ugv_response_prior_log_odds", "give_back_at_stopping_speed",
                   "give_back_stiffness_factor"});
    auto& m = c.mpc;
    m.horizon = static_cast<int>(r->get_in_range_or("horizon", 2, 200, m.horizon));
    if (r->has("horizon") && r->get<double>("horizon") != m.horizon)
      r->fail("horizon", "an integer in [2, 200]");
    m.prediction_dt_s = r->get_in_range_or("prediction_dt_s", 1e-3, 1.0, m.prediction_dt_s);
    m.acceleration_time_s =
        r->get_in_range_or("acceleration_time_s", 0.0, 10.0, m.acceleration_time_s);
    m.use_preview = r->get_or<bool>("use_preview", m.use_preview);
    m.rate_penalty_about_tracking_command =
        r->get_or<bool>("rate_penalty_about_tracking_command", m.rate_penalty_about_tracking_command);
    m.give_back_at_stopping_speed =
        r->get_or<bool>("give_back_at_stopping_speed", m.give_back_at_stopping_speed);
    m.give_back_stiffness_factor =
        r->get_in_range_or("give_back_stiffness_factor", 1.0, 100.0, m.give_back_stiffness_factor);
    m.weight_slack = r->get_in_range_or("weight_slack", 0.0, 1e6, m.weight_slack);
    m.weight_command_rate =
        r->get_in_range_or("weight_command_rate", 0.0, 1e6, m.weight_command_rate);
    m.weight_feedforward =
        r->get_in_range_or("weight_feedforward", 1e-6, 1e6, m.weight_feedforward);
    m.weight_terminal = r->get_in_range_or("weight_terminal", 0.0, 1e6, m.weight_terminal);
    m.soft_linear_weight = r->get_in_range_or("weight_soft_linear", 0.0, 1e8, m.soft_linear_weight);
    m.stretch_linear_weight =
        r->get_in_range_or("weight_stretch_linear", 0.0, 1e8, m.stretch_linear_weight);
    m.soft_quadratic_weight =
        r->get_in_range_or("weight_soft_quadratic", 1e-6, 1e8, m.soft_quadratic_weight);
    auto& e = m.ugv_velocity_error;
    e.sigma_mps = r->get_in_range_or("ugv_velocity_error_mps", 0.0, 10.0, e.sigma_mps);
    e.time_s = r->get_in_range_or("ugv_velocity_error_time_s", 1e-3, 100.0, e.time_s);
    e.window_s = r->get_in_range_or("ugv_velocity_error_window_s", 1e-3, 100.0, e.window_s);
    e.prior_log_odds =
        r->get_in_range_or("ugv_velocity_error_prior_log_odds", 0.0, 100.0, e.prior_log_odds);
    e.prior_log_odds_with_lag = r->get_in_range_or("ugv_velocity_error_prior_log_odds_with_lag", 0.0,
                                                   100.0, e.prior_log_odds_with_lag);
    e.long_window_s =
        r->get_in_range_or("ugv_velocity_error_long_window_s", 1e-3, 1e4, e.long_window_s);
    auto& id = m.ugv_response_identification;
    id.enabled = r->get_or<bool>("identify_ugv_response", id.enabled);
    id.window_s = r->get_in_range_or("ugv_response_window_s", 1e-3, 1e4, id.window_s);
    id.prior_log_odds =
        r->get_in_range_or("ugv_response_prior_log_odds", 0.0, 1e4, id.prior_log_odds);
  }
  if (const auto r = root.optional_child("baseline")) {
    r->allow_only({"kp_per_s", "ki_per_s2", "kd", "feedforward_gain", "use_preview"});
    auto& b = c.baseline;
    b.kp_per_s = r->get_in_range_or("kp_per_s", 0.0, 1e3, b.kp_per_s);
    b.ki_per_s2 = r->get_in_range_or("ki_per_s2", 0.0, 1e4, b.ki_per_s2);
    b.kd = r->get_in_range_or("kd", 0.0, 1e2, b.kd);
    b.feedforward_gain = r->get_in_range_or("feedforward_gain", 0.0, 2.0, b.feedforward_gain);
    b.use_preview = r->get_or<bool>("use_preview", b.use_preview);
  }
  if (const auto r = root.optional_child("sim")) {
    r->allow_only({"link_latency_s", "pose_noise_m", "tension_noise_n", "ugv_preview_s",
                   "ugv_preview_step_s", "ugv_velocity_lag_s", "ugv_slip_noise_mps",
                   "ugv_slip_time_s", "ugv_tracking_time_s"});
    c.sim.link_latency_s = r->get_in_range_or("link_latency_s", 0.0, 1.0, c.sim.link_latency_s);
    c.sim.pose_noise_m = r->get_in_range_or("pose_noise_m", 0.0, 1.0, c.sim.pose_noise_m);
    c.sim.tension_noise_n =
        r->get_in_range_or("tension_noise_n", 0.0, 100.0, c.sim.tension_noise_n);
    c.sim.ugv_preview_s = r->get_in_range_or("ugv_preview_s", 0.0, 10.0, c.sim.ugv_preview_s);
    c.sim.ugv_preview_step_s =
        r->get_in_range_or("ugv_preview_step_s", 1e-3, 1.0, c.sim.ugv_preview_step_s);
    c.sim.ugv_velocity_lag_s =
        r->get_in_range_or("ugv_velocity_lag_s", 0.0, 5.0, c.sim.ugv_velocity_lag_s);
    c.sim.ugv_slip_noise_mps =
        r->get_in_range_or("ugv_slip_noise_mps", 0.0, 1.0, c.sim.ugv_slip_noise_mps);
    c.sim.ugv_slip_time_s =
        r->get_in_range_or("ugv_slip_time_s", 1e-3, 100.0, c.sim.ugv_slip_time_s);
    c.sim.ugv_tracking_time_s =
        r->get_in_range_or("ugv_tracking_time_s", 0.0, 100.0, c.sim.ugv_tracking_time_s);
  }
  c.mpc.control = ctl;
  c.baseline.control = ctl;
}

}  // namespace ferret::sim
