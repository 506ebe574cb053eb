#include "ferret/uav/flight_adapter_service.hpp"

#include <cmath>
#include <nlohmann/json.hpp>
#include <stdexcept>

#include "ferret/uav/adapter_flight_controller.hpp"

namespace ferret {
namespace {

using link::StreamMessage;
using nlohmann::json;

// A request the service refuses: the reply's "error".
struct Refusal : std::runtime_error {
  using std::runtime_error::runtime_error;
};

double number(const json& j, const char* key, double lo, double hi) {
  if (!j.contains(key) || !j[key].is_number())
    throw Refusal(std::string("'") + key + "': expected a number");
  const double v = j[key].get<double>();
  if (!std::isfinite(v) || v < lo || v > hi)
    throw Refusal(std::string("'") + key + "': expected a number in [" + json(lo).dump() + ", " +
                  json(hi).dump() + "], got " + json(v).dump());
  return v;
}

Eigen::Vector3d vec3(const json& j, const char* key, double limit) {
  if (!j.contains(key) || !j[key].is_array() || j[key].size() != 3)
    throw Refusal(std::string("'") + key + "': expected an array of 3 numbers");
  Eigen::Vector3d v;
  for (int i = 0; i < 3; ++i) {
    const json& e = j[key][static_cast<std::size_t>(i)];
    if (!e.is_number()) throw Refusal(std::string("'") + key + "': expected an array of 3 numbers");
    v[i] = e.get<double>();
    if (!std::isfinite(v[i]) || std::abs(v[i]) > limit)
      throw Refusal(std::string("'") + key + "': expected finite numbers within ±" + json(limit).dump());
  }
  return v;
}

json pose_json(const Pose3& X) {
  json m = json::array();
  for (int k = 0; k < 16; ++k) m.push_back(X.matrix()(k % 4, k / 4));  // column-major
  return m;
}

StreamMessage reply(json j) {
  j["ok"] = true;
  return {j.dump(), {}};
}

}  // namespace

FlightAdapterService::FlightAdapterService(FlightController& flight, UavCameras& cameras,
                                           std::string adapter_name, Hooks hooks)
    : flight_(flight), cameras_(cameras), adapter_name_(std::move(adapter_name)), hooks_(std::move(hooks)) {}

StreamMessage FlightAdapterService::handle(const StreamMessage& request) {
  // Positions within 100 km of the origin and speeds below 100 m/s: anything else is a
  // client bug, not a flight.
  constexpr double kMaxPositionM = 1e5, kMaxSpeedMps = 100.0;
  std::string op;
  try {
    const json r = json::parse(request.header, nullptr, false);
    if (r.is_discarded() || !r.is_object()) throw Refusal("the request is not a JSON object");
    if (!r.contains("op") || !r["op"].is_string()) throw Refusal("'op': expected a string");
    op = r["op"].get<std::string>();
    if (op == "hello") {
      const double protocol = number(r, "protocol", 0, 1e6);
      if (protocol != kFlightAdapterProtocol)
        throw Refusal("'protocol': this adapter speaks " + std::to_string(kFlightAdapterProtocol) +
                      ", got " + json(protocol).dump());
      return reply({{"protocol", kFlightAdapterProtocol}, {"adapter", adapter_name_}});
    }
    if (op == "state") {
      const FlightState s = flight_.state();
      return reply({{"p_W", {s.p_W.x(), s.p_W.y(), s.p_W.z()}},
                    {"v_W", {s.v_W.x(), s.v_W.y(), s.v_W.z()}},
                    {"yaw_rad", s.yaw_rad},
                    {"on_ground", s.on_ground},
                    {"battery", s.battery_fraction},
                    {"rc_override", s.rc_override}});
    }
    if (op == "takeoff") {
      flight_.command_takeoff(number(r, "z_m", -kMaxPositionM, kMaxPositionM));
      return reply({});
    }
    if (op == "position") {
      const Eigen::Vector3d p = vec3(r, "p_W", kMaxPositionM);
      const double yaw = number(r, "yaw_rad", -1e3, 1e3);
      flight_.command_position(p, yaw, number(r, "speed_mps", 0.0, kMaxSpeedMps));
      return reply({});
    }
    if (op == "land") {
      flight_.command_land();
      return reply({});
    }
    if (op == "velocity") {
      if (!hooks_.velocity) throw Refusal("'velocity': not supported by this adapter");
      const Eigen::Vector3d v = vec3(r, "v_W", kMaxSpeedMps);
      hooks_.velocity(v, number(r, "yaw_rate_radps", -10.0, 10.0));
      return reply({});
    }
    if (op == "marker_frame") {
      CameraShot<GrayImage> shot = cameras_.marker_frame();
      StreamMessage m = reply({{"encoding", "mono8"},
                               {"width", shot.image.width_px},
                               {"height", shot.image.height_px},
                               {"X_WC", pose_json(shot.X_WC)}});
      m.blob = std::move(shot.image.data);
      return m;
    }
    if (op == "depth_frame") {
      const CameraShot<DepthImageMm> shot = cameras_.depth_frame();
      StreamMessage m = reply({{"encoding", "mono16"},
                               {"width", shot.image.width_px},
                               {"height", shot.image.height_px},
                               {"X_WC", pose_json(shot.X_WC)}});
      m.blob.resize(2 * shot.image.data.size());
      for (std::size_t i = 0; i < shot.image.data.size(); ++i) {  // little-endian millimetres
        m.blob[2 * i] = static_cast<std::uint8_t>(shot.image.data[i] & 0xff);
        m.blob[2 * i + 1] = static_cast<std::uint8_t>(shot.image.data[i] >> 8);
      }
      return m;
    }
    if (hooks_.extension)
      if (auto m = hooks_.extension(op, request.header)) return std::move(*m);
    throw Refusal("'op': '" + op + "' is not an op of protocol " + std::to_string(kFlightAdapterProtocol));
  } catch (const std::exception& e) {
    // A refusal, or the controller's own error (a command it cannot take now).
    return {json{{"ok", false}, {"op", op}, {"error", e.what()}}.dump(), {}};
  }
}

void FlightAdapterService::serve(link::MessageStream& stream, const std::function<bool()>& keep_going) {
  while (keep_going()) {
    std::optional<StreamMessage> request;
    try {
      request = stream.receive(100);
    } catch (const link::StreamError&) {
      return;  // the client went away
    }
    if (request) stream.send(handle(*request));
  }
}

}  // namespace ferret
