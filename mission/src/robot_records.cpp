#include "ferret/mission/robot_records.hpp"

#include <algorithm>
#include <cstdio>
#include <nlohmann/json.hpp>
#include <utility>

#include "ferret/core/output_set.hpp"
#include "ferret/link/message_stream.hpp"

namespace ferret {

// The flight controller as the mission reads it, remembering its last state.
class UavRunRecorder::RecordedFlight final : public FlightController {
 public:
  explicit RecordedFlight(FlightController& inner) : inner_(inner) {}
  [[nodiscard]] std::string backend() const override { return inner_.backend(); }
  [[nodiscard]] FlightState state() const override {
    last_ = inner_.state();
    return *last_;
  }
  void command_takeoff(double z_m) override { inner_.command_takeoff(z_m); }
  void command_position(const Eigen::Vector3d& p_W, double yaw_rad, double speed_mps) override {
    inner_.command_position(p_W, yaw_rad, speed_mps);
  }
  void command_land() override { inner_.command_land(); }
  [[nodiscard]] const std::optional<FlightState>& last() const { return last_; }

 private:
  FlightController& inner_;
  mutable std::optional<FlightState> last_;
};

// The winch as the mission reads it, remembering its last reading.
class UavRunRecorder::RecordedWinch final : public tether::Winch {
 public:
  explicit RecordedWinch(tether::Winch& inner) : inner_(inner) {}
  void set_torque_enabled(bool enabled) override { inner_.set_torque_enabled(enabled); }
  void command_velocity_mps(double speed_mps) override { inner_.command_velocity_mps(speed_mps); }
  [[nodiscard]] tether::WinchState read_state() override {
    last_ = inner_.read_state();
    return last_;
  }
  [[nodiscard]] const tether::WinchState& last() const { return last_; }

 private:
  tether::Winch& inner_;
  tether::WinchState last_;
};

UavRunRecorder::UavRunRecorder(FlightController& flight, tether::Winch& winch)
    : flight_(std::make_unique<RecordedFlight>(flight)),
      winch_(std::make_unique<RecordedWinch>(winch)) {}

UavRunRecorder::~UavRunRecorder() = default;

FlightController& UavRunRecorder::flight() { return *flight_; }
tether::Winch& UavRunRecorder::winch() { return *winch_; }

void UavRunRecorder::after_tick(double t_s, const UavMission& mission) {
  const tether::WinchState& w = winch_->last();
  max_released_m_ = std::max(max_released_m_, w.released_m);
  max_tension_n_ = std::max(max_tension_n_, w.tension_n);
  const std::optional<FlightState>& f = flight_->last();
  if (!f) return;
  if (last_p_W_) flown_m_ += (f->p_W - *last_p_W_).norm();
  last_p_W_ = f->p_W;
  if (t_s + 1e-9 < next_sample_s_) return;
  next_sample_s_ = t_s + 0.5;
  MissionSample s;
  s.t_s = t_s;
  s.p_W = f->p_W;
  s.yaw_rad = f->yaw_rad;
  s.state = std::string(to_string(mission.state()));
  s.battery = f->battery_fraction;
  s.released_m = w.released_m;
  s.tension_n = w.tension_n;
  samples_.push_back(s);
}

MissionRunResult UavRunRecorder::result(const UavMission* mission, double t_s,
                                        const TransitionLog& log) const {
  MissionRunResult r;
  r.time_s = t_s;
  r.flown_m = flown_m_;
  r.battery_left = flight_->last() ? flight_->last()->battery_fraction : 1.0;
  r.max_released_m = max_released_m_;
  r.max_tension_n = max_tension_n_;
  r.samples = samples_;
  r.transitions = log.all();
  if (mission) {
    r.outcome = mission->outcome();
    r.visits = mission->visits();
    r.time_in_state = mission->time_in_state();
    r.leg_spacing_m = mission->leg_spacing_m();
    r.pattern_waypoints = mission->pattern().size();
    r.pattern_done = mission->pattern_done();
    r.first_pass_waypoints = mission->first_pass_waypoints();
    r.frames = mission->frames_processed();
  }
  return r;
}

void UgvRunRecorder::started(double t_s, const MiniUgvMission& mission) {
  searches_.push_back({&mission, t_s, std::nullopt, 0.0});
}

void UgvRunRecorder::after_tick(double t_s) {
  for (Search& s : searches_) {
    if (s.ended_s || !s.mission->started()) continue;
    s.max_tether_m = std::max(s.max_tether_m, s.mission->explore_controller().tether_length_m());
    if (s.mission->done() || s.mission->wants_retraction()) s.ended_s = t_s;
  }
}

MissionRunResult UgvRunRecorder::result(double t_s, const TransitionLog& log) const {
  MissionRunResult r;
  r.time_s = t_s;
  r.transitions = log.all();
  for (const Search& s : searches_) {
    UgvDeployment d;
    d.deployed_s = s.started_s;
    report_ugv_controller(*s.mission, d.result);
    d.result.time_s = s.ended_s.value_or(t_s) - s.started_s;
    d.result.max_tether_m = s.max_tether_m;
    r.deployments.push_back(std::move(d));
  }
  return r;
}

void recording_failures(const std::function<void()>& run,
                        const std::function<void(const std::string& why)>& record) {
  try {
    run();
  } catch (const link::StreamError& e) {
    record(e.what());
    throw;
  } catch (const nlohmann::json::exception& e) {
    record(std::string("a lockstep message without the fields it needs: ") + e.what());
    throw;
  }
}

void check_record_target(const std::string& out) {
  if (!out.empty()) (void)check_output_target(out, OutputKind::kDirectory, "--out");
}

RunOutputsInput robot_side(RunSide side, std::uint64_t seed, std::string ended_early) {
  RunOutputsInput in;
  in.side = side;
  in.seed = seed;
  in.ended_early = std::move(ended_early);
  return in;
}

void write_robot_record(const std::string& out, RunOutputsInput in, const MissionSetup& setup,
                        const MissionRunResult& r) {
  if (out.empty()) return;
  in.world_path = setup.world_path;
  in.uav = &setup.settings.uav;
  in.tether_total_length_m = setup.mission.tether.total_length_m;
  write_run_outputs(out, in, r);
  std::printf("wrote: %s\n", out.c_str());
  std::fflush(stdout);
}

void report_ugv_controller(const MiniUgvMission& m, UgvMissionRunResult& result) {
  result.outcome = m.outcome();
  result.final_state = m.state();
  result.found_W = m.found_W();
  result.grasp_attempts = m.grasp_attempts();
  if (!m.started()) return;  // set down, never told to search: no maps, no decisions
  result.decisions = m.explore_controller().decisions();
  result.grid = m.explore_controller().grid_ptr();
  result.objects = m.explore_controller().objects_ptr();
}

}  // namespace ferret
