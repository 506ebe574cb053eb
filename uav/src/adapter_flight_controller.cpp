#include "ferret/uav/adapter_flight_controller.hpp"

#include <cmath>
#include <filesystem>
#include <nlohmann/json.hpp>

#include "ferret/core/error.hpp"

namespace ferret {
namespace {

using link::StreamMessage;
using nlohmann::json;

// Optional fields of a given type: a field of another type is the adapter's error, not
// the default (nlohmann's value() would throw its own type_error; found by the fuzzer).
bool flag(const json& j, const char* key, const std::string& op) {
  if (!j.contains(key)) return false;
  if (!j[key].is_boolean())
    throw FlightAdapterError(std::string("flight adapter: '") + key + "' in the reply to '" + op +
                             "' is not a boolean");
  return j[key].get<bool>();
}
std::string text(const json& j, const char* key, const std::string& fallback,
                 const std::string& op) {
  if (!j.contains(key)) return fallback;
  if (!j[key].is_string())
    throw FlightAdapterError(std::string("flight adapter: '") + key + "' in the reply to '" + op +
                             "' is not a string");
  return j[key].get<std::string>();
}

json parse_reply(const StreamMessage& m, const std::string& op) {
  json j = json::parse(m.header, nullptr, false);
  if (j.is_discarded() || !j.is_object())
    throw FlightAdapterError("flight adapter: the reply to '" + op + "' is not a JSON object");
  if (!flag(j, "ok", op))
    throw FlightAdapterError("flight adapter: '" + op +
                             "' refused: " + printable(text(j, "error", "no reason given", op)));
  return j;
}

double number(const json& j, const char* key, const std::string& op) {
  if (!j.contains(key) || !j[key].is_number())
    throw FlightAdapterError(std::string("flight adapter: the reply to '") + op +
                             "' has no number '" + key + "'");
  const double v = j[key].get<double>();
  if (!std::isfinite(v))
    throw FlightAdapterError(std::string("flight adapter: '") + key + "' in the reply to '" + op +
                             "' is not finite");
  return v;
}

Eigen::Vector3d vec3(const json& j, const char* key, const std::string& op) {
  if (!j.contains(key) || !j[key].is_array() || j[key].size() != 3)
    throw FlightAdapterError(std::string("flight adapter: the reply to '") + op +
                             "' has no 3-vector '" + key + "'");
  Eigen::Vector3d v;
  for (int i = 0; i < 3; ++i) {
    if (!j[key][i].is_number())
      throw FlightAdapterError(std::string("flight adapter: '") + key + "' is not numeric");
    v[i] = j[key][i].get<double>();
  }
  if (!v.allFinite())
    throw FlightAdapterError(std::string("flight adapter: '") + key + "' is not finite");
  return v;
}

Pose3 pose(const json& j, const std::string& op) {
  if (!j.contains("X_WC") || !j["X_WC"].is_array() || j["X_WC"].size() != 16)
    throw FlightAdapterError("flight adapter: the reply to '" + op +
                             "' has no 4x4 'X_WC' (16 numbers, column-major)");
  Eigen::Matrix4d m;
  for (int k = 0; k < 16; ++k) {
    if (!j["X_WC"][k].is_number())
      throw FlightAdapterError("flight adapter: 'X_WC' is not numeric");
    m(k % 4, k / 4) = j["X_WC"][k].get<double>();
  }
  if (!m.allFinite()) throw FlightAdapterError("flight adapter: 'X_WC' is not finite");
  Pose3 X = Pose3::Identity();
  X.matrix() = m;
  return X;
}

// A frame arrives as a blob of raw pixels, or as a path to an image file the adapter
// wrote (a DJI adapter may prefer to drop frames into /dev/shm).
template <class Image>
Image frame_image(const json& j, const StreamMessage& m, const std::string& op,
                  const char* encoding, std::size_t bytes_per_px) {
  if (j.contains("path")) {
    if (!j["path"].is_string()) throw FlightAdapterError("flight adapter: 'path' is not a string");
    const std::string path = j["path"].get<std::string>();
    // A regular file only: a device or FIFO named by a broken adapter would never end.
    std::error_code ec;
    if (!std::filesystem::is_regular_file(path, ec))
      throw FlightAdapterError("flight adapter: the frame file '" + printable(path) + "' of '" +
                               op + "' is not a regular file");
    if constexpr (std::is_same_v<Image, GrayImage>)
      return read_gray_image(path);
    else
      return read_depth_png(path);
  }
  if (text(j, "encoding", "", op) != encoding)
    throw FlightAdapterError("flight adapter: the reply to '" + op + "' must be encoded " +
                             encoding);
  const double w = number(j, "width", op), h = number(j, "height", op);
  if (w == 0 && h == 0 && m.blob.empty()) return Image{};  // no frame this time (dropped)
  if (!(w >= 1 && h >= 1 && w <= 16384 && h <= 16384 && w == std::floor(w) && h == std::floor(h)))
    throw FlightAdapterError("flight adapter: a frame of " + std::to_string(w) + " x " +
                             std::to_string(h) + " px");
  Image image(static_cast<int>(w), static_cast<int>(h));
  if (m.blob.size() != image.data.size() * bytes_per_px)
    throw FlightAdapterError("flight adapter: the frame's blob has " +
                             std::to_string(m.blob.size()) + " bytes, expected " +
                             std::to_string(image.data.size() * bytes_per_px));
  if constexpr (std::is_same_v<Image, GrayImage>) {
    std::copy(m.blob.begin(), m.blob.end(), image.data.begin());
  } else {
    for (std::size_t i = 0; i < image.data.size(); ++i)  // little-endian millimetres
      image.data[i] = static_cast<std::uint16_t>(m.blob[2 * i] | (m.blob[2 * i + 1] << 8));
  }
  return image;
}

}  // namespace

AdapterFlightController::AdapterFlightController(link::RpcChannel& channel, std::string backend)
    : channel_(channel), backend_(std::move(backend)) {
  const json hello{{"op", "hello"}, {"protocol", kFlightAdapterProtocol}, {"client", "ferret uav"}};
  const json r = parse_reply(channel_.call(hello.dump()), "hello");
  const double protocol = number(r, "protocol", "hello");
  if (protocol != kFlightAdapterProtocol)
    throw FlightAdapterError("flight adapter speaks protocol " + json(protocol).dump() +
                             ", this client " + std::to_string(kFlightAdapterProtocol));
  adapter_ = printable(text(r, "adapter", "unnamed", "hello"));
}

FlightState AdapterFlightController::state() const {
  const json r = parse_reply(channel_.call(R"({"op":"state"})"), "state");
  FlightState s;
  s.p_W = vec3(r, "p_W", "state");
  s.v_W = vec3(r, "v_W", "state");
  s.yaw_rad = number(r, "yaw_rad", "state");
  s.on_ground = flag(r, "on_ground", "state");
  s.battery_fraction = number(r, "battery", "state");
  s.rc_override = flag(r, "rc_override", "state");
  return s;
}

void AdapterFlightController::command_takeoff(double z_m) {
  (void)parse_reply(channel_.call(json{{"op", "takeoff"}, {"z_m", z_m}}.dump()), "takeoff");
}

void AdapterFlightController::command_position(const Eigen::Vector3d& p_W, double yaw_rad,
                                               double speed_mps) {
  const json req{{"op", "position"},
                 {"p_W", {p_W.x(), p_W.y(), p_W.z()}},
                 {"yaw_rad", yaw_rad},
                 {"speed_mps", speed_mps}};
  (void)parse_reply(channel_.call(req.dump()), "position");
}

void AdapterFlightController::command_land() {
  (void)parse_reply(channel_.call(R"({"op":"land"})"), "land");
}

void AdapterFlightController::command_velocity(const Eigen::Vector3d& v_W, double yaw_rate_radps) {
  const json req{
      {"op", "velocity"}, {"v_W", {v_W.x(), v_W.y(), v_W.z()}}, {"yaw_rate_radps", yaw_rate_radps}};
  (void)parse_reply(channel_.call(req.dump()), "velocity");
}

CameraShot<GrayImage> AdapterFlightController::marker_frame() {
  const StreamMessage m = channel_.call(R"({"op":"marker_frame"})");
  const json r = parse_reply(m, "marker_frame");
  return {frame_image<GrayImage>(r, m, "marker_frame", "mono8", 1), pose(r, "marker_frame")};
}

CameraShot<DepthImageMm> AdapterFlightController::depth_frame() {
  const StreamMessage m = channel_.call(R"({"op":"depth_frame"})");
  const json r = parse_reply(m, "depth_frame");
  return {frame_image<DepthImageMm>(r, m, "depth_frame", "mono16", 2), pose(r, "depth_frame")};
}

}  // namespace ferret
