#include "ferret/mission/mission_run.hpp"

#include <algorithm>
#include <cmath>
#include <map>

#include "ferret/core/clock.hpp"
#include "ferret/core/error.hpp"
#include "ferret/mission/mission_assembly.hpp"
#include "ferret/sim/mission_world.hpp"
#include "ferret/uav/linked_ugv.hpp"
#include "ferret/ugv/ugv_link_endpoint.hpp"

namespace ferret {

namespace {

using internal::SimHiddenSpaces;

// The miniUGV over the robot link when both controllers run in this process: its
// mission controller runs on the simulated base the world put down at the entry.
class InProcessUgvLink final : public UgvLink {
 public:
  explicit InProcessUgvLink(SimHiddenSpaces& spaces) : spaces_(spaces) {}
  [[nodiscard]] static const char* kind() { return "in-process"; }

  void deploy(const Eigen::Vector3d& p_WE, double /*entry_yaw_rad*/) override {
    spaces_.put_down(p_WE, true);
    if (UgvMissionSim* s = spaces_.active()) s->start();
  }
  void retracted() override {
    if (UgvMissionSim* s = spaces_.active()) {
      MiniUgvMission& m = ugv_mission_of(*s);
      if (m.wants_retraction()) m.retracted();
      if (!m.done()) m.stop("lifted out");
    }
    spaces_.lift();
  }
  void release_object() override { spaces_.release_object(); }
  void abort(const std::string& reason) override {
    if (UgvMissionSim* s = spaces_.active(); s && !ugv_mission_of(*s).done())
      ugv_mission_of(*s).stop(reason);
  }
  void recall(const std::string& reason) override {
    if (UgvMissionSim* s = spaces_.active()) ugv_mission_of(*s).recall(reason);
  }
  [[nodiscard]] UgvReport report() const override {
    UgvReport r;
    const UgvMissionSim* s = spaces_.active();
    if (spaces_.lonely() && !s) return UgvReport::nothing_to_search();
    if (!s) {  // hanging or aboard: its IMU sees where it would touch down
      r.object_held = spaces_.holding();
      r.roll_rad = spaces_.touchdown().roll_rad;
      r.pitch_rad = spaces_.touchdown().pitch_rad;
      return r;
    }
    const MiniUgvMission& m = ugv_mission_of(*s);
    r.running = !m.done();
    r.done = m.done();
    r.wants_retraction = m.wants_retraction();
    if (m.done()) r.outcome = std::string(to_string(m.outcome()));
    if (m.wants_retraction()) r.outcome = std::string(to_string(m.return_outcome()));
    r.object_held = s->base().status().epm_on && s->base().status().contact;
    const Pose2 p = s->base().odometry();
    r.p_WG = {p.x_m, p.y_m};
    r.v_WG = s->base().speed_mps() * Eigen::Vector2d(std::cos(p.yaw_rad), std::sin(p.yaw_rad));
    if (const auto a = m.started() ? m.explore_controller().tether_anchor() : std::nullopt) {
      r.tether_anchor_W = a->first;
      r.tether_to_anchor_m = a->second;
      r.tether_uncertainty_m = std::max(
          0.0, m.explore_controller().reach_length_m() - m.explore_controller().tether_length_m());
    } else {
      r.tether_anchor_W = spaces_.entry_W();
    }
    r.battery_fraction = s->base().status().battery_fraction;
    return r;
  }

 private:
  SimHiddenSpaces& spaces_;
};

// The miniUGV over the robot link's messages, both ends in this process. What the
// UAV's calls do to the world happens at once, as the winch does it (the robot set
// down at the entry, lifted out, the object let go); what they ask of the miniUGV's
// controller travels as requests through a simulated network, and the UAV reads the
// miniUGV from its telemetry, as it would from the robot.
class SimLinkedUgv final : public UgvLink {
 public:
  SimLinkedUgv(SimHiddenSpaces& spaces, const Clock& clock,
               const link::LossyChannelOptions& channel, std::uint64_t seed,
               const FaultSchedule* faults, double delivery_s)
      : faults_(faults),
        delivery_s_(delivery_s),
        spaces_(spaces),
        uav_(clock),
        ugv_(clock, [this](const link::UavRequest&) { return set_down(); }),
        up_(seeded(channel, seed, 1)),
        down_(seeded(channel, seed, 2)) {}
  [[nodiscard]] static const char* kind() { return "messages"; }

  void deploy(const Eigen::Vector3d& p_WE, double entry_yaw_rad) override {
    spaces_.put_down(p_WE, true);
    uav_.deploy(p_WE, entry_yaw_rad);
  }
  void retracted() override {
    uav_.retracted();
    if (const auto index = spaces_.lift())
      pending_results_.emplace_back(uav_.last_request(), *index);
  }
  void release_object() override {
    spaces_.release_object();
    uav_.release_object();
  }
  void abort(const std::string& reason) override { uav_.abort(reason); }
  void recall(const std::string& reason) override { uav_.recall(reason); }
  [[nodiscard]] UgvReport report() const override {
    // Set down where no hidden space is: nothing to search.
    if (spaces_.lonely() && !spaces_.active()) return UgvReport::nothing_to_search();
    return uav_.report();
  }

  // At the miniUGV's control rate, before its step: the requests that arrived are acted
  // on. True while the miniUGV holds (its link silent).
  bool receive() {
    if (faults_) {  // the link's faults acting now, each way
      up_.set_impairment(faults_->link_impairment(FaultTarget::kUavToUgv, delivery_s_));
      down_.set_impairment(faults_->link_impairment(FaultTarget::kUgvToUav, delivery_s_));
    }
    for (const auto& d : up_.deliver()) ugv_.session().receive(d);
    const ImuReading& hanging = spaces_.touchdown();
    if (spaces_.active())
      ugv_.set_attitude(0.0, 0.0);
    else
      ugv_.set_attitude(hanging.roll_rad, hanging.pitch_rad);
    const bool hold = ugv_.handle_requests();
    // A deployment's controller heard it was lifted out: its result is final now.
    std::erase_if(pending_results_, [&](const auto& p) {
      if (ugv_.last_request_id() < p.first) return false;
      spaces_.update_result(p.second);
      return true;
    });
    return hold;
  }
  // After its step: the state it left goes to the UAV, and the UAV's messages go out.
  void send() {
    ugv_.report();
    down_.send(ugv_.session().take_outgoing());
    for (const auto& d : down_.deliver()) uav_.session().receive(d);
    up_.send(uav_.session().take_outgoing());
  }
  [[nodiscard]] std::string summary() const {
    return "UAV end: " + uav_.session().counters().summary() +
           "; miniUGV end: " + ugv_.session().counters().summary();
  }

 private:
  static link::LossyChannelOptions seeded(link::LossyChannelOptions o, std::uint64_t seed,
                                          std::uint64_t way) {
    o.seed = seed * 1000003u + way;
    return o;
  }
  UgvLinkEndpoint::Deployment set_down() {
    UgvMissionSim* s = spaces_.active();
    if (!s) return {};
    return {&ugv_mission_of(*s), &s->base()};
  }

  const FaultSchedule* faults_;
  double delivery_s_;
  SimHiddenSpaces& spaces_;
  LinkedUgv uav_;
  UgvLinkEndpoint ugv_;
  link::LossyChannel up_, down_;  // UAV -> miniUGV, miniUGV -> UAV
  std::vector<std::pair<std::uint32_t, std::size_t>>
      pending_results_;  // (retracted request, deployment)
};

// Why the mission left the miniUGV where it is, as the UAV recorded it for the visit it
// lowered it at and never lifted it from (empty: no reason recorded).
std::string ugv_left_reason(const UavMission& mission) {
  const auto& visits = mission.visits();
  for (auto v = visits.rbegin(); v != visits.rend(); ++v)
    if (v->deployed_s >= 0.0 && v->retracted_s < 0.0) return v->note;
  return {};
}

}  // namespace

class MissionSimImpl {
 public:
  UavMission* uav = nullptr;
  internal::MissionWorld* world = nullptr;
};

const UavMission& MissionSim::uav() const { return *impl_.uav; }
FlightState MissionSim::uav_truth() const { return impl_.world->flight().state(); }
const UgvMissionSim* MissionSim::ugv() const { return impl_.world->spaces().active(); }
double MissionSim::released_m() const { return impl_.world->winch().released_m(); }

MissionRunResult run_mission(const PlanningWorld& world, const RobotDescription& uav_robot,
                             const MissionRunSettings& settings, std::uint64_t seed,
                             TransitionLog* log) {
  TransitionLog own_log;
  TransitionLog& transitions = log ? *log : own_log;
  internal::MissionWorld sim(world, uav_robot, settings, seed, transitions);
  const MissionAssembly assembly(world, uav_robot, settings, seed, "mission");
  sim.spaces().set_ugv_controllers(
      MissionAssembly::ugv_controllers(sim.settings().ugv, sim.clock(), &transitions));
  InProcessUgvLink in_process(sim.spaces());
  std::unique_ptr<SimLinkedUgv> linked;
  // Link faults act on the link's messages: without a channel of its own, a clean one.
  if (settings.link_channel || breaks_link(settings.faults))
    linked = std::make_unique<SimLinkedUgv>(
        sim.spaces(), sim.clock(), settings.link_channel.value_or(link::LossyChannelOptions{}),
        seed, sim.faults(), 1.0 / settings.ugv.exploration.sensors.ir_rate_hz);
  UgvLink& link = linked ? static_cast<UgvLink&>(*linked) : in_process;
  const std::unique_ptr<UavMission> uav = assembly.uav_mission(
      {sim.flight(), sim.cameras(), sim.winch(), link}, sim.clock(), &transitions);
  UavMission& mission = *uav;
  MissionSimImpl impl{&mission, &sim};
  const MissionSim view(impl);
  mission.start();
  internal::MissionControllers controllers;
  controllers.uav_tick = [&] { mission.tick(); };
  controllers.uav_done = [&] { return mission.done(); };
  controllers.uav_state = [&] { return std::string(to_string(mission.state())); };
  // The base-only world step moves the robot; in this process the controller ticks first.
  controllers.ugv_tick = [] {};
  if (linked) {
    controllers.link_receive = [&] { return linked->receive(); };
    controllers.link_send = [&] { linked->send(); };
  }
  sim.run(controllers, [&](double t_s) {
    if (settings.on_sample) settings.on_sample(t_s, view);
  });
  const bool ended = mission.done();
  if (!ended) mission.stop("the simulation's time limit");
  sim.finish_invariants(ended, ugv_left_reason(mission));
  sim.spaces().close();
  MissionRunResult result = std::move(sim.result());
  result.outcome = mission.outcome();
  result.visits = mission.visits();
  result.deployments = std::move(sim.spaces().deployments());
  result.time_in_state = mission.time_in_state();
  result.leg_spacing_m = mission.leg_spacing_m();
  result.pattern_waypoints = mission.pattern().size();
  result.pattern_done = mission.pattern_done();
  result.first_pass_waypoints = mission.first_pass_waypoints();
  result.frames = mission.frames_processed();
  result.marker_frames_rendered = static_cast<int>(sim.cameras().marker_frames_rendered());
  result.transitions = transitions.all();
  result.backends = {{"uav.flight_controller", sim.flight().backend()},
                     {"uav.cameras", "sim"},  // rendered frames (SimUavCameras)
                     {"uav.winch", "sim"},    // tether::SimulatedWinch
                     {"ugv.base", "sim"},     // SimUgvBase in each hidden space
                     {"link", linked ? SimLinkedUgv::kind() : InProcessUgvLink::kind()}};
  if (linked) result.link_counters = linked->summary();
  return result;
}

}  // namespace ferret
