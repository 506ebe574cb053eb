// The settings of a tether simulation run: options sized for a tether, and a run
// config YAML (control, mpc, baseline, sim) mapped onto the controllers' and the
// simulator's options, each value checked against its range.

#include "ferret/core/yaml_config.hpp"
#include "ferret/sim/tether_sim.hpp"
#include "ferret/tether_model/winch_controllers.hpp"

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
                   "ugv_tracking_time_s", "identify_ugv_response", "tension_fusion",
                   "observer_pose_noise_m", "observer_tension_noise_n", "observer_speed_noise_mps",
                   "observer_model_offset_decay_mps", "servo_time_constant_s"});
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
    obs.model_offset_decay_mps = r->get_in_range_or("observer_model_offset_decay_mps", 0.0, 10.0,
                                                    obs.model_offset_decay_mps);
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
  // Each controller's own section, read beside its options (winch_controllers.hpp).
  if (const auto r = root.optional_child("mpc")) tether::read_mpc_options(*r, c.mpc);
  if (const auto r = root.optional_child("baseline")) tether::read_baseline_options(*r, c.baseline);
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
