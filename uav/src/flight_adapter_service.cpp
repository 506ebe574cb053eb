#include "ferret/uav/flight_adapter_service.hpp"

#include <cmath>
#include <nlohmann/json.hpp>
#include <stdexcept>

#include "ferret/link/json_dispatcher.hpp"
#include "ferret/uav/adapter_flight_controller.hpp"

namespace ferret {
namespace {

using link::JsonReply;
using link::JsonRequest;
using link::request_number;
using link::RequestError;
using link::StreamMessage;
using nlohmann::json;

Eigen::Vector3d vec3(const json& j, const char* key, double limit) {
  if (!j.contains(key) || !j[key].is_array() || j[key].size() != 3)
    throw RequestError(std::string("'") + key + "': expected an array of 3 numbers");
  Eigen::Vector3d v;
  for (int i = 0; i < 3; ++i) {
    const json& e = j[key][static_cast<std::size_t>(i)];
    if (!e.is_number())
      throw RequestError(std::string("'") + key + "': expected an array of 3 numbers");
    v[i] = e.get<double>();
    if (!std::isfinite(v[i]) || std::abs(v[i]) > limit)
      throw RequestError(std::string("'") + key + "': expected finite numbers within ±" +
                         json(limit).dump());
  }
  return v;
}

json pose_json(const Pose3& X) {
  json m = json::array();
  for (int k = 0; k < 16; ++k) m.push_back(X.matrix()(k % 4, k / 4));  // column-major
  return m;
}

}  // namespace

FlightAdapterService::FlightAdapterService(FlightController& flight, UavCameras& cameras,
                                           std::string adapter_name, Hooks hooks)
    : flight_(flight),
      cameras_(cameras),
      adapter_name_(std::move(adapter_name)),
      hooks_(std::move(hooks)),
      dispatcher_(std::make_unique<link::JsonDispatcher>("the flight adapter protocol " +
                                                         std::to_string(kFlightAdapterProtocol))) {
  // Positions within 100 km of the origin and speeds below 100 m/s: anything else is a
  // client bug, not a flight.
  constexpr double kMaxPositionM = 1e5, kMaxSpeedMps = 100.0;
  dispatcher_->add("hello", [this](const JsonRequest& r) -> JsonReply {
    const double protocol = request_number(r.fields, "protocol", 0, 1e6);
    if (protocol != kFlightAdapterProtocol)
      throw RequestError("'protocol': this adapter speaks " +
                         std::to_string(kFlightAdapterProtocol) + ", got " + json(protocol).dump());
    return json{{"protocol", kFlightAdapterProtocol}, {"adapter", adapter_name_}};
  });
  dispatcher_->add("state", [this](const JsonRequest&) -> JsonReply {
    const FlightState s = flight_.state();
    return json{{"p_W", {s.p_W.x(), s.p_W.y(), s.p_W.z()}},
                {"v_W", {s.v_W.x(), s.v_W.y(), s.v_W.z()}},
                {"yaw_rad", s.yaw_rad},
                {"on_ground", s.on_ground},
                {"battery", s.battery_fraction},
                {"rc_override", s.rc_override}};
  });
  dispatcher_->add("takeoff", [this](const JsonRequest& r) -> JsonReply {
    flight_.command_takeoff(request_number(r.fields, "z_m", -kMaxPositionM, kMaxPositionM));
    return {};
  });
  dispatcher_->add("position", [this](const JsonRequest& r) -> JsonReply {
    const Eigen::Vector3d p = vec3(r.fields, "p_W", kMaxPositionM);
    const double yaw = request_number(r.fields, "yaw_rad", -1e3, 1e3);
    flight_.command_position(p, yaw, request_number(r.fields, "speed_mps", 0.0, kMaxSpeedMps));
    return {};
  });
  dispatcher_->add("land", [this](const JsonRequest&) -> JsonReply {
    flight_.command_land();
    return {};
  });
  dispatcher_->add("velocity", [this](const JsonRequest& r) -> JsonReply {
    if (!hooks_.velocity) throw RequestError("'velocity': not supported by this adapter");
    const Eigen::Vector3d v = vec3(r.fields, "v_W", kMaxSpeedMps);
    hooks_.velocity(v, request_number(r.fields, "yaw_rate_radps", -10.0, 10.0));
    return {};
  });
  dispatcher_->add("marker_frame", [this](const JsonRequest&) -> JsonReply {
    CameraShot<GrayImage> shot = cameras_.marker_frame();
    return {json{{"encoding", "mono8"},
                 {"width", shot.image.width_px},
                 {"height", shot.image.height_px},
                 {"X_WC", pose_json(shot.X_WC)}},
            std::move(shot.image.data)};
  });
  dispatcher_->add("depth_frame", [this](const JsonRequest&) -> JsonReply {
    const CameraShot<DepthImageMm> shot = cameras_.depth_frame();
    std::vector<std::uint8_t> blob(2 * shot.image.data.size());
    for (std::size_t i = 0; i < shot.image.data.size(); ++i) {  // little-endian millimetres
      blob[2 * i] = static_cast<std::uint8_t>(shot.image.data[i] & 0xff);
      blob[2 * i + 1] = static_cast<std::uint8_t>(shot.image.data[i] >> 8);
    }
    return {json{{"encoding", "mono16"},
                 {"width", shot.image.width_px},
                 {"height", shot.image.height_px},
                 {"X_WC", pose_json(shot.X_WC)}},
            std::move(blob)};
  });
}

FlightAdapterService::~FlightAdapterService() = default;

StreamMessage FlightAdapterService::handle(const StreamMessage& request) {
  return dispatcher_->handle(request);
}

void FlightAdapterService::serve(link::MessageStream& stream,
                                 const std::function<bool()>& keep_going) {
  dispatcher_->serve(stream, keep_going);
}

}  // namespace ferret
