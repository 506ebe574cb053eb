// The tether simulation's physics: a winch paying out and reeling in over wrap points
// and snags while the miniUGV drives, its controller stepped at the control period and
// the tether at the physics step, with the run's log and metrics.

#include "ferret/sim/tether_sim.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <memory>

#include "ferret/core/random.hpp"

namespace ferret::sim {

namespace {

// The tether between the winch and the miniUGV, sliding freely over its wrap points
// except while a snag pins it at one.
class TetherState {
 public:
  TetherState(const TetherScenario& scn, const TetherSimOptions& opt)
      : scn_(scn), opt_(opt), geometry_(opt.entry_offset_m, scn.p_WE, scn.wrap_points) {}

  struct Forces {
    double required_m = 0.0, ugv_n = 0.0, winch_n = 0.0;
    /// Slack on the winch's side of a pinned corner (the whole slack when nothing pins).
    double reachable_slack_m = 0.0;
    bool snagged = false;
  };

  Forces update(double t_s, double released_m, const Eigen::Vector2d& p_WG) {
    Forces f;
    f.required_m = geometry_.required_length_m(p_WG);
    const auto& tension = opt_.control.slack_estimator.tension;
    const TetherSnag* snag = nullptr;
    for (const auto& s : scn_.snags)
      if (t_s >= s.start_s && t_s < s.start_s + s.duration_s) snag = &s;
    if (snag != current_snag_) {
      current_snag_ = snag;
      pinned_ = false;
      // A snag only holds a corner the tether is actually bent round.
      if (snag && geometry_.engaged_count(p_WG) > snag->wrap_point) {
        pinned_ = true;
        const double to_pin = geometry_.length_to_wrap_point_m(snag->wrap_point);
        const double beyond = f.required_m - to_pin;
        // The slack at the moment of the snag is shared in proportion to length.
        beyond_material_m_ = beyond + (released_m - f.required_m) * beyond / f.required_m;
        beyond_geometry_ = std::make_unique<tether::FixedWrapTether>(
            0.0, scn_.wrap_points[snag->wrap_point].p_W,
            std::vector<tether::WrapPoint>(
                scn_.wrap_points.begin() + static_cast<long>(snag->wrap_point) + 1,
                scn_.wrap_points.end()));
        winch_side_m_ = to_pin;
      }
    }
    if (pinned_) {
      f.snagged = true;
      const double beyond_geom = beyond_geometry_->required_length_m(p_WG);
      f.ugv_n = tension.tension_n(beyond_material_m_, beyond_material_m_ - beyond_geom);
      f.reachable_slack_m = (released_m - beyond_material_m_) - winch_side_m_;
      f.winch_n = tension.tension_n(released_m - beyond_material_m_, f.reachable_slack_m);
    } else {
      f.reachable_slack_m = released_m - f.required_m;
      f.ugv_n = f.winch_n = tension.tension_n(released_m, f.reachable_slack_m);
    }
    return f;
  }

 private:
  const TetherScenario& scn_;
  const TetherSimOptions& opt_;
  tether::FixedWrapTether geometry_;
  const TetherSnag* current_snag_ = nullptr;
  bool pinned_ = false;
  double beyond_material_m_ = 0.0, winch_side_m_ = 0.0;
  std::unique_ptr<tether::FixedWrapTether> beyond_geometry_;
};

}  // namespace

TetherSimResult run_tether_sim(const TetherScenario& scn, const TetherSimOptions& opt,
                               tether::TetherController& controller) {
  if (scn.samples.size() < 2)
    throw std::invalid_argument("tether sim: the trajectory needs two samples or more");
  for (const auto& s : scn.snags)
    if (s.wrap_point >= scn.wrap_points.size())
      throw std::invalid_argument("tether sim: snag on a missing wrap point");
  if (!(opt.physics_dt_s > 0.0) || !(opt.control.control_period_s >= opt.physics_dt_s))
    throw std::invalid_argument("tether sim: need 0 < physics dt <= control period");
  if (opt.ugv_preview_s > 0.0 && !(opt.ugv_preview_step_s > 0.0))
    throw std::invalid_argument("tether sim: a preview needs a step > 0");

  const tether::FixedWrapTether geometry(opt.entry_offset_m, scn.p_WE, scn.wrap_points);
  const auto& tension_model = opt.control.slack_estimator.tension;
  const double L = opt.control.limits.total_length_m;
  Rng rng(opt.seed);
  controller.reset();
  tether::SimulatedWinch::Options winch_options = opt.winch;
  winch_options.total_length_m = L;
  winch_options.initial_released_m = std::clamp(
      geometry.required_length_m(scn.samples.front().p_WG) + opt.control.slack_reference_m, 0.0, L);
  tether::SimulatedWinch winch(winch_options);
  TetherState tether_state(scn, opt);
  // Where the miniUGV really is: its desired motion, unless it lags or slips.
  TetherScenario actual_storage;
  const bool obedient = opt.ugv_velocity_lag_s == 0.0 && opt.ugv_slip_noise_mps == 0.0;
  if (!obedient) {
    actual_storage.samples = actual_ugv_motion(scn,
                                               {opt.ugv_velocity_lag_s, opt.ugv_slip_noise_mps,
                                                opt.ugv_slip_time_s, opt.ugv_tracking_time_s},
                                               opt.physics_dt_s, derive_seed(opt.seed, {1}));
  }
  const TetherScenario& actual = obedient ? scn : actual_storage;

  TetherSimResult result;
  result.scenario = scn.name;
  result.controller = std::string(controller.name());
  auto& m = result.metrics;
  const int substeps =
      std::max(1, static_cast<int>(std::lround(opt.control.control_period_s / opt.physics_dt_s)));
  const double dt = opt.control.control_period_s / substeps;
  double t = scn.start_s();
  bool over = false;
  double sum_sq = 0.0, reachable_sum_sq = 0.0;
  std::vector<double> step_times_us;
  m.min_slack_m = std::numeric_limits<double>::infinity();
  m.max_slack_m = -std::numeric_limits<double>::infinity();
  auto forces = tether_state.update(t, winch.released_m(), actual.at(t).p_WG);
  while (t <= scn.end_s() + 1e-9) {
    // The miniUGV's message left latency seconds ago, with its localisation error.
    const double t_msg = std::max(scn.start_s(), t - opt.link_latency_s);
    const TrajectorySample msg = scn.at(t_msg);  // the desired motion it reports
    tether::TetherObservation obs;
    obs.t_s = t;
    obs.released_m = winch.released_m();
    obs.spool_speed_mps = winch.speed_mps();
    obs.winch_tension_n =
        tension_model.hanging_weight_n + forces.winch_n + rng.normal(0.0, opt.tension_noise_n);
    obs.ugv.p_WG = actual.at(t_msg).p_WG + Eigen::Vector2d(rng.normal(0.0, opt.pose_noise_m),
                                                           rng.normal(0.0, opt.pose_noise_m));
    obs.ugv.v_WG = msg.v_WG;
    obs.ugv.a_WG = msg.a_WG;
    obs.ugv_age_s = t - t_msg;
    // Its plan ahead, relative to where the plan has it at the message.
    const int preview_knots =
        static_cast<int>(std::ceil(opt.ugv_preview_s / opt.ugv_preview_step_s - 1e-9));
    if (preview_knots > 0) {
      auto& preview = obs.ugv_preview;
      preview.step_s = opt.ugv_preview_step_s;
      for (int i = 0; i <= preview_knots; ++i) {
        const TrajectorySample planned = scn.at(t_msg + i * opt.ugv_preview_step_s);
        preview.displacement_m.push_back(planned.p_WG - msg.p_WG);
        // The plan stands still once it has ended.
        preview.velocity_mps.push_back(t_msg + i * opt.ugv_preview_step_s >= scn.end_s()
                                           ? Eigen::Vector2d::Zero()
                                           : planned.v_WG);
      }
    }
    const auto tick = std::chrono::steady_clock::now();
    const double command = controller.step(obs);
    step_times_us.push_back(
        std::chrono::duration<double, std::micro>(std::chrono::steady_clock::now() - tick).count());
    winch.command_velocity_mps(command);

    TetherSimSample row;
    row.t_s = t;
    row.released_m = winch.released_m();
    row.required_m = forces.required_m;
    row.slack_m = row.released_m - row.required_m;
    row.reachable_slack_m = forces.reachable_slack_m;  // = slack_m unless a corner pins the line
    row.ugv_tension_n = forces.ugv_n;
    row.winch_tension_n = forces.winch_n;
    row.command_mps = command;
    row.speed_mps = winch.speed_mps();
    row.snagged = forces.snagged;
    result.log.push_back(row);
    sum_sq += row.slack_m * row.slack_m;
    reachable_sum_sq += row.reachable_slack_m * row.reachable_slack_m;
    m.min_slack_m = std::min(m.min_slack_m, row.slack_m);
    m.max_slack_m = std::max(m.max_slack_m, row.slack_m);
    if (row.released_m > L + 1e-3) ++m.released_over_limit;

    for (int i = 0; i < substeps; ++i) {
      winch.advance(dt, tension_model.hanging_weight_n + forces.winch_n);
      t += dt;
      forces = tether_state.update(t, winch.released_m(), actual.at(t).p_WG);
      const double peak = std::max(forces.ugv_n, forces.winch_n);
      m.max_tension_n = std::max(m.max_tension_n, peak);
      const bool now_over = peak > tension_model.max_tension_n;
      if (now_over && !over) ++m.over_tension_events;
      if (now_over) m.over_tension_time_s += dt;
      over = now_over;
      if (winch.released_m() >= L - 1e-3) m.limit_active_s += dt;
      m.max_released_m = std::max(m.max_released_m, winch.released_m());
    }
  }
  m.slack_rms_m = std::sqrt(sum_sq / static_cast<double>(result.log.size()));
  m.reachable_slack_rms_m = std::sqrt(reachable_sum_sq / static_cast<double>(result.log.size()));
  m.duration_s = scn.end_s() - scn.start_s();
  m.control_cycles = static_cast<int>(result.log.size());
  std::sort(step_times_us.begin(), step_times_us.end());
  m.step_time_median_us = step_times_us[step_times_us.size() / 2];
  m.step_time_max_us = step_times_us.back();
  return result;
}

}  // namespace ferret::sim
