#pragma once
// The reference flight adapter: the flight adapter protocol (docs/flight_adapter.md)
// served over the simulated M100 of a mission world, with the point-mass position loop
// and the rendered marker and depth cameras of `ferret mission`. ferret's client talks
// to it as to a DJI adapter on the vehicle (`ferret flight-adapter serve`).
//
// One op beyond protocol 1: {"op": "sim_advance", "seconds": s} steps the simulated
// vehicle by s (in 10 ms steps) and answers the simulated time; a real adapter's
// vehicle moves by itself, and answers the op as unknown.

#include <cstdint>
#include <functional>
#include <memory>

#include "ferret/link/message_stream.hpp"
#include "ferret/sim/mission_run.hpp"

namespace ferret {

struct PlanningWorld;
struct RobotDescription;

class SimFlightAdapter {
 public:
  /// The vehicle starts landed at the mission's home (as in `ferret mission`). Throws
  /// InputError for a world without a world YAML or a robot without its cameras.
  SimFlightAdapter(const PlanningWorld& world, const RobotDescription& uav_robot,
                   const MissionRunSettings& settings, std::uint64_t seed);
  ~SimFlightAdapter();
  SimFlightAdapter(const SimFlightAdapter&) = delete;
  SimFlightAdapter& operator=(const SimFlightAdapter&) = delete;

  [[nodiscard]] link::StreamMessage handle(const link::StreamMessage& request);
  /// Answers requests on `stream` until the client closes it or `keep_going()` is false.
  void serve(link::MessageStream& stream, const std::function<bool()>& keep_going);
  /// The same with the vehicle moving by itself, as a real one does: before each request
  /// (and every 10 ms without one) the simulation is stepped up to the wall time since
  /// this call (`ferret flight-adapter serve --real-time`, for a `ferret uav` on its own
  /// steady clock).
  void serve_in_real_time(link::MessageStream& stream, const std::function<bool()>& keep_going);
  [[nodiscard]] double now_s() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace ferret
