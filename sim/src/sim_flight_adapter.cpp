#include "ferret/sim/sim_flight_adapter.hpp"

#include <cmath>
#include <nlohmann/json.hpp>

#include "ferret/core/clock.hpp"
#include "ferret/core/transition_log.hpp"
#include "ferret/link/json_dispatcher.hpp"
#include "ferret/sim/mission_world.hpp"
#include "ferret/uav/flight_adapter_service.hpp"

namespace ferret {

struct SimFlightAdapter::Impl {
  Impl(const PlanningWorld& world, const RobotDescription& uav_robot,
       const MissionRunSettings& settings, std::uint64_t seed)
      : mission_world(world, uav_robot, every_frame(settings), seed, log),
        service(
            mission_world.flight(), mission_world.cameras(), "sim",
            FlightAdapterService::Hooks{[this](const Eigen::Vector3d& v_W, double yaw_rate_radps) {
              mission_world.flight().command_velocity(v_W, yaw_rate_radps);
            }}) {
    // Beyond protocol 1: the simulator's clock.
    service.dispatcher().add("sim_advance", [this](const link::JsonRequest& r) -> link::JsonReply {
      const nlohmann::json& j = r.fields;
      const double seconds =
          j.contains("seconds") && j["seconds"].is_number() ? j["seconds"].get<double>() : -1.0;
      if (!(seconds >= 0.0 && seconds <= 3600.0))
        throw link::RequestError("'seconds': expected a number in [0, 3600]");
      const long steps = std::lround(seconds / internal::kDt);
      for (long k = 0; k < steps; ++k) step_once();
      return nlohmann::json{{"t_s", mission_world.clock().now_s()}};
    });
  }

  // A camera on a vehicle delivers every frame; so does the reference adapter.
  static MissionRunSettings every_frame(MissionRunSettings s) {
    s.render_markerless_frames = true;
    return s;
  }

  void step_once() {
    ++step;
    mission_world.clock().set(static_cast<double>(step) * internal::kDt);
    mission_world.flight().step(internal::kDt);
  }
  void advance_to(double t_s) {
    while (static_cast<double>(step + 1) * internal::kDt <= t_s) step_once();
  }

  TransitionLog log;
  internal::MissionWorld mission_world;
  FlightAdapterService service;
  long step = 0;
};

SimFlightAdapter::SimFlightAdapter(const PlanningWorld& world, const RobotDescription& uav_robot,
                                   const MissionRunSettings& settings, std::uint64_t seed)
    : impl_(std::make_unique<Impl>(world, uav_robot, settings, seed)) {}
SimFlightAdapter::~SimFlightAdapter() = default;

link::StreamMessage SimFlightAdapter::handle(const link::StreamMessage& request) {
  return impl_->service.handle(request);
}
void SimFlightAdapter::serve(link::MessageStream& stream, const std::function<bool()>& keep_going) {
  impl_->service.serve(stream, keep_going);
}
void SimFlightAdapter::serve_in_real_time(link::MessageStream& stream,
                                          const std::function<bool()>& keep_going) {
  const SteadyClock wall;
  const double t0_s = now_s();
  while (keep_going()) {
    std::optional<link::StreamMessage> request;
    try {
      request = stream.receive(10);
    } catch (const link::StreamError&) {
      return;  // the client went away
    }
    impl_->advance_to(t0_s + wall.now_s());
    if (request) stream.send(handle(*request));
  }
}
double SimFlightAdapter::now_s() const { return impl_->mission_world.clock().now_s(); }

}  // namespace ferret
