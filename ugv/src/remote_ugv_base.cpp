#include "ferret/ugv/remote_ugv_base.hpp"

#include <cmath>
#include <limits>
#include <nlohmann/json.hpp>
#include <stdexcept>

#include "ferret/core/error.hpp"
#include "ferret/link/json_dispatcher.hpp"

namespace ferret {
namespace {

using link::StreamMessage;
using nlohmann::json;

using link::dump_json;

// --- the server's half -------------------------------------------------------------

using link::JsonReply;
using link::JsonRequest;
using link::request_number;
using link::RequestError;

json pose_json(const Pose2& p) { return json::array({p.x_m, p.y_m, p.yaw_rad}); }

// A range beyond every return ("no return" may be +inf) travels as null.
json range_json(double r) { return std::isfinite(r) ? json(r) : json(nullptr); }

json scan_json(const RangeScan& s) {
  json beams = json::array();
  for (const RangeBeam& b : s.beams) {
    beams.push_back(b.bearing_rad);
    beams.push_back(range_json(b.range_m));
  }
  return {{"X_WS", pose_json(s.X_WS)}, {"max_range_m", s.max_range_m}, {"beams", std::move(beams)}};
}

// --- the client's half -------------------------------------------------------------

[[noreturn]] void broken(const std::string& op, const std::string& what) {
  throw UgvBaseProtocolError("miniUGV base: the reply to '" + op + "' " + what);
}

json parse_reply(const StreamMessage& m, const std::string& op) {
  json j = json::parse(m.header, nullptr, false);
  if (j.is_discarded() || !j.is_object()) broken(op, "is not a JSON object");
  if (!j.contains("ok") || !j["ok"].is_boolean()) broken(op, "has no boolean 'ok'");
  if (!j["ok"].get<bool>()) {
    const std::string why = j.contains("error") && j["error"].is_string()
                                ? j["error"].get<std::string>()
                                : "no reason given";
    throw UgvBaseProtocolError("miniUGV base: '" + op + "' refused: " + printable(why));
  }
  return j;
}

double finite(const json& v, const std::string& op, const std::string& key) {
  if (!v.is_number()) broken(op, "has no number '" + key + "'");
  const double x = v.get<double>();
  if (!std::isfinite(x)) broken(op, "has '" + key + "' not finite");
  return x;
}

double field(const json& j, const char* key, const std::string& op) {
  if (!j.contains(key)) broken(op, std::string("has no number '") + key + "'");
  return finite(j[key], op, key);
}

bool flag(const json& j, const char* key, const std::string& op) {
  if (!j.contains(key) || !j[key].is_boolean())
    broken(op, std::string("has no boolean '") + key + "'");
  return j[key].get<bool>();
}

const json& array(const json& j, const char* key, const std::string& op) {
  if (!j.is_object() || !j.contains(key) || !j[key].is_array())
    broken(op, std::string("has no array '") + key + "'");
  return j[key];
}

Pose2 pose_of(const json& j, const char* key, const std::string& op) {
  const json& a = array(j, key, op);
  if (a.size() != 3) broken(op, std::string("has '") + key + "' not [x, y, yaw]");
  return {finite(a[0], op, key), finite(a[1], op, key), finite(a[2], op, key)};
}

RangeScan scan_of(const json& j, const std::string& op) {
  RangeScan s;
  s.X_WS = pose_of(j, "X_WS", op);
  s.max_range_m = field(j, "max_range_m", op);
  if (!(s.max_range_m > 0.0)) broken(op, "has 'max_range_m' not > 0");
  const json& beams = array(j, "beams", op);
  if (beams.size() % 2 != 0 || beams.size() / 2 > kMaxRemoteBeams)
    broken(op,
           "has 'beams' not pairs of (bearing, range), at most " + std::to_string(kMaxRemoteBeams));
  s.beams.reserve(beams.size() / 2);
  for (std::size_t k = 0; k < beams.size(); k += 2) {
    RangeBeam b;
    b.bearing_rad = finite(beams[k], op, "beams");
    b.range_m = beams[k + 1].is_null() ? std::numeric_limits<double>::infinity()
                                       : finite(beams[k + 1], op, "beams");
    if (b.range_m < 0.0) broken(op, "has a negative range");
    s.beams.push_back(b);
  }
  return s;
}

}  // namespace

UgvBaseService::UgvBaseService(UgvBase& base, std::string server_name)
    : base_(base),
      name_(std::move(server_name)),
      dispatcher_(std::make_unique<link::JsonDispatcher>("the miniUGV base protocol " +
                                                         std::to_string(kUgvBaseProtocol))) {
  // Set-points within what any miniUGV could mean: anything else is a client bug.
  constexpr double kMaxSpeedMps = 100.0, kMaxYawRateRadps = 100.0, kMaxTimeS = 1e9;
  link::JsonDispatcher& d = *dispatcher_;
  d.add("hello", [this](const JsonRequest& r) -> JsonReply {
    if (!r.fields.contains("protocol") || !r.fields["protocol"].is_number_integer())
      throw RequestError("'protocol': expected an integer");
    if (r.fields["protocol"].get<long long>() != kUgvBaseProtocol)
      throw RequestError("'protocol': this server speaks " + std::to_string(kUgvBaseProtocol));
    return json{{"protocol", kUgvBaseProtocol}, {"server", name_}, {"backend", base_.backend()}};
  });
  d.add("odometry", [this](const JsonRequest&) -> JsonReply {
    return json{{"pose", pose_json(base_.odometry())}};
  });
  d.add("speed", [this](const JsonRequest&) -> JsonReply {
    return json{{"speed_mps", base_.speed_mps()}};
  });
  d.add("ir_scan", [this](const JsonRequest&) -> JsonReply {
    return json{{"scan", scan_json(base_.ir_scan())}};
  });
  d.add("camera_frame", [this](const JsonRequest& r) -> JsonReply {
    const CameraFrame f =
        base_.camera_frame(request_number(r.fields, "time_s", -kMaxTimeS, kMaxTimeS));
    json detections = json::array();
    for (const ObjectDetection& o : f.detections)
      detections.push_back(json::array({o.bearing_rad, o.distance_m, o.confidence}));
    return json{
        {"frame", {{"time_s", f.time_s}, {"view", scan_json(f.view)}, {"detections", detections}}}};
  });
  d.add("velocity", [this](const JsonRequest& r) -> JsonReply {
    const double v = request_number(r.fields, "v_mps", -kMaxSpeedMps, kMaxSpeedMps);
    const double w = request_number(r.fields, "w_radps", -kMaxYawRateRadps, kMaxYawRateRadps);
    base_.command_velocity(v, w);
    return {};
  });
  d.add("epm", [this](const JsonRequest& r) -> JsonReply {
    base_.set_epm(link::request_bool(r.fields, "on"));
    return {};
  });
  d.add("status", [this](const JsonRequest&) -> JsonReply {
    const UgvStatus s = base_.status();
    return json{{"battery_fraction", s.battery_fraction},
                {"epm_on", s.epm_on},
                {"contact", s.contact},
                {"faults", s.faults}};
  });
}

UgvBaseService::~UgvBaseService() = default;

StreamMessage UgvBaseService::handle(const StreamMessage& request) const {
  return dispatcher_->handle(request);
}

RemoteUgvBase::RemoteUgvBase(link::RpcChannel& channel, std::string backend)
    : channel_(channel), backend_(std::move(backend)) {
  const json j = parse_reply(
      channel_.call(dump_json({{"op", "hello"}, {"protocol", kUgvBaseProtocol}})), "hello");
  if (!j.contains("protocol") || !j["protocol"].is_number_integer() ||
      j["protocol"].get<long long>() != kUgvBaseProtocol)
    throw UgvBaseProtocolError("miniUGV base: the server does not speak protocol " +
                               std::to_string(kUgvBaseProtocol));
  if (j.contains("server") && j["server"].is_string())
    server_ = printable(j["server"].get<std::string>());
}

Pose2 RemoteUgvBase::odometry() const {
  return pose_of(parse_reply(channel_.call(R"({"op":"odometry"})"), "odometry"), "pose",
                 "odometry");
}

double RemoteUgvBase::speed_mps() const {
  return field(parse_reply(channel_.call(R"({"op":"speed"})"), "speed"), "speed_mps", "speed");
}

RangeScan RemoteUgvBase::ir_scan() {
  const json j = parse_reply(channel_.call(R"({"op":"ir_scan"})"), "ir_scan");
  if (!j.contains("scan") || !j["scan"].is_object()) broken("ir_scan", "has no object 'scan'");
  return scan_of(j["scan"], "ir_scan");
}

CameraFrame RemoteUgvBase::camera_frame(double time_s) {
  const std::string op = "camera_frame";
  const json j = parse_reply(channel_.call(dump_json({{"op", op}, {"time_s", time_s}})), op);
  if (!j.contains("frame") || !j["frame"].is_object()) broken(op, "has no object 'frame'");
  const json& f = j["frame"];
  CameraFrame frame;
  frame.time_s = field(f, "time_s", op);
  if (!f.contains("view") || !f["view"].is_object()) broken(op, "has no object 'view'");
  frame.view = scan_of(f["view"], op);
  const json& detections = array(f, "detections", op);
  if (detections.size() > kMaxRemoteDetections)
    broken(op, "has more than " + std::to_string(kMaxRemoteDetections) + " detections");
  for (const json& d : detections) {
    if (!d.is_array() || d.size() != 3)
      broken(op, "has a detection not [bearing, distance, confidence]");
    ObjectDetection o{finite(d[0], op, "detections"), finite(d[1], op, "detections"),
                      finite(d[2], op, "detections")};
    if (!(o.distance_m > 0.0)) broken(op, "has a detection whose distance is not > 0");
    frame.detections.push_back(o);
  }
  return frame;
}

void RemoteUgvBase::command_velocity(double v_mps, double w_radps) {
  (void)parse_reply(
      channel_.call(dump_json({{"op", "velocity"}, {"v_mps", v_mps}, {"w_radps", w_radps}})),
      "velocity");
}

void RemoteUgvBase::set_epm(bool on) {
  (void)parse_reply(channel_.call(dump_json({{"op", "epm"}, {"on", on}})), "epm");
}

UgvStatus RemoteUgvBase::status() const {
  const std::string op = "status";
  const json j = parse_reply(channel_.call(R"({"op":"status"})"), op);
  UgvStatus s;
  s.battery_fraction = field(j, "battery_fraction", op);
  s.epm_on = flag(j, "epm_on", op);
  s.contact = flag(j, "contact", op);
  if (!j.contains("faults") || !j["faults"].is_number_unsigned() ||
      j["faults"].get<std::uint64_t>() > std::numeric_limits<std::uint32_t>::max())
    broken(op, "has no 32-bit unsigned 'faults'");
  s.faults = static_cast<std::uint32_t>(j["faults"].get<std::uint64_t>());
  return s;
}

}  // namespace ferret
