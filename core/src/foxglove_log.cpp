#include "ferret/core/foxglove_log.hpp"

#include <cmath>
#include <nlohmann/json.hpp>
#include <stdexcept>

#include "ferret/core/mcap_writer.hpp"

namespace ferret {
namespace {

using nlohmann::json;

// JSON Schemas of the Foxglove message types this log writes (the subset of fields
// it fills; Foxglove recognises the type by the schema's name).
const json kTime = {
    {"type", "object"},
    {"properties", {{"sec", {{"type", "integer"}}}, {"nsec", {{"type", "integer"}}}}}};
const json kVector3 = {
    {"type", "object"},
    {"properties",
     {{"x", {{"type", "number"}}}, {"y", {{"type", "number"}}}, {"z", {{"type", "number"}}}}}};
const json kQuaternion = {{"type", "object"},
                          {"properties",
                           {{"x", {{"type", "number"}}},
                            {"y", {{"type", "number"}}},
                            {"z", {{"type", "number"}}},
                            {"w", {{"type", "number"}}}}}};
const json kPose = {{"type", "object"},
                    {"properties", {{"position", kVector3}, {"orientation", kQuaternion}}}};
const json kColor = {{"type", "object"},
                     {"properties",
                      {{"r", {{"type", "number"}}},
                       {"g", {{"type", "number"}}},
                       {"b", {{"type", "number"}}},
                       {"a", {{"type", "number"}}}}}};

json object_schema(const std::string& title, json properties) {
  return {{"title", title}, {"type", "object"}, {"properties", std::move(properties)}};
}
json array_of(json items) { return {{"type", "array"}, {"items", std::move(items)}}; }

std::string schema_text(const std::string& name) {
  if (name == "foxglove.FrameTransform")
    return object_schema(name, {{"timestamp", kTime},
                                {"parent_frame_id", {{"type", "string"}}},
                                {"child_frame_id", {{"type", "string"}}},
                                {"translation", kVector3},
                                {"rotation", kQuaternion}})
        .dump();
  if (name == "foxglove.Grid")
    return object_schema(
               name,
               {{"timestamp", kTime},
                {"frame_id", {{"type", "string"}}},
                {"pose", kPose},
                {"column_count", {{"type", "integer"}}},
                {"cell_size",
                 {{"type", "object"},
                  {"properties", {{"x", {{"type", "number"}}}, {"y", {{"type", "number"}}}}}}},
                {"row_stride", {{"type", "integer"}}},
                {"cell_stride", {{"type", "integer"}}},
                {"fields", array_of({{"type", "object"},
                                     {"properties",
                                      {{"name", {{"type", "string"}}},
                                       {"offset", {{"type", "integer"}}},
                                       {"type", {{"type", "integer"}}}}}})},
                {"data", {{"type", "string"}, {"contentEncoding", "base64"}}}})
        .dump();
  if (name == "foxglove.SceneUpdate") {
    const json line = {{"type", "object"},
                       {"properties",
                        {{"type", {{"type", "integer"}}},
                         {"pose", kPose},
                         {"thickness", {{"type", "number"}}},
                         {"scale_invariant", {{"type", "boolean"}}},
                         {"points", array_of(kVector3)},
                         {"color", kColor},
                         {"colors", array_of(kColor)},
                         {"indices", array_of({{"type", "integer"}})}}}};
    const json sphere = {{"type", "object"},
                         {"properties", {{"pose", kPose}, {"size", kVector3}, {"color", kColor}}}};
    const json text = {{"type", "object"},
                       {"properties",
                        {{"pose", kPose},
                         {"billboard", {{"type", "boolean"}}},
                         {"font_size", {{"type", "number"}}},
                         {"scale_invariant", {{"type", "boolean"}}},
                         {"color", kColor},
                         {"text", {{"type", "string"}}}}}};
    const json entity = {{"type", "object"},
                         {"properties",
                          {{"timestamp", kTime},
                           {"frame_id", {{"type", "string"}}},
                           {"id", {{"type", "string"}}},
                           {"lifetime", kTime},
                           {"frame_locked", {{"type", "boolean"}}},
                           {"lines", array_of(line)},
                           {"spheres", array_of(sphere)},
                           {"texts", array_of(text)}}}};
    return object_schema(name, {{"deletions", array_of({{"type", "object"}})},
                                {"entities", array_of(entity)}})
        .dump();
  }
  if (name == "foxglove.Log")
    return object_schema(name, {{"timestamp", kTime},
                                {"level", {{"type", "integer"}}},
                                {"message", {{"type", "string"}}},
                                {"name", {{"type", "string"}}},
                                {"file", {{"type", "string"}}},
                                {"line", {{"type", "integer"}}}})
        .dump();
  throw std::logic_error("FoxgloveLog: no schema " + name);
}

json stamp(double t_s) {
  const std::uint64_t ns = to_nanoseconds(t_s);
  return {{"sec", ns / 1000000000u}, {"nsec", ns % 1000000000u}};
}
json vec(const Eigen::Vector3d& v) { return {{"x", v.x()}, {"y", v.y()}, {"z", v.z()}}; }
json quat(const Eigen::Quaterniond& q) {
  return {{"x", q.x()}, {"y", q.y()}, {"z", q.z()}, {"w", q.w()}};
}
json pose_at(const Eigen::Vector3d& p) {
  return {{"position", vec(p)}, {"orientation", quat(Eigen::Quaterniond::Identity())}};
}
json color(const RgbaColor& c) { return {{"r", c.r}, {"g", c.g}, {"b", c.b}, {"a", c.a}}; }

std::string base64(const std::vector<std::uint8_t>& bytes) {
  static constexpr char kAlphabet[] =
      "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  std::string out;
  out.reserve((bytes.size() + 2) / 3 * 4);
  std::size_t i = 0;
  for (; i + 2 < bytes.size(); i += 3) {
    const std::uint32_t v = (bytes[i] << 16) | (bytes[i + 1] << 8) | bytes[i + 2];
    for (int k = 3; k >= 0; --k) out.push_back(kAlphabet[(v >> (6 * k)) & 63]);
  }
  if (i < bytes.size()) {
    const bool two = i + 1 < bytes.size();
    const std::uint32_t v = (bytes[i] << 16) | (two ? bytes[i + 1] << 8 : 0);
    out.push_back(kAlphabet[(v >> 18) & 63]);
    out.push_back(kAlphabet[(v >> 12) & 63]);
    out.push_back(two ? kAlphabet[(v >> 6) & 63] : '=');
    out.push_back('=');
  }
  return out;
}

json entity(double t_s, const std::string& frame, const std::string& id) {
  return {{"timestamp", stamp(t_s)},
          {"frame_id", frame},
          {"id", id},
          {"lifetime", {{"sec", 0}, {"nsec", 0}}},
          {"frame_locked", false},
          {"metadata", json::array()},
          {"arrows", json::array()},
          {"cubes", json::array()},
          {"spheres", json::array()},
          {"cylinders", json::array()},
          {"lines", json::array()},
          {"triangles", json::array()},
          {"texts", json::array()},
          {"models", json::array()}};
}

}  // namespace

std::uint64_t to_nanoseconds(double t_s) {
  if (!(t_s > 0) || !std::isfinite(t_s)) return 0;
  return static_cast<std::uint64_t>(std::llround(t_s * 1e9));
}

FoxgloveLog::FoxgloveLog() : writer_(std::make_unique<McapWriter>("", "ferret")) {}
FoxgloveLog::~FoxgloveLog() = default;

std::uint16_t FoxgloveLog::channel(const std::string& topic, const std::string& schema) {
  if (const auto it = channels_.find(topic); it != channels_.end()) return it->second;
  auto s = schemas_.find(schema);
  if (s == schemas_.end())
    s = schemas_.emplace(schema, writer_->add_schema(schema, "jsonschema", schema_text(schema)))
            .first;
  const std::uint16_t id = writer_->add_channel(s->second, topic, "json");
  channels_.emplace(topic, id);
  return id;
}

void FoxgloveLog::transform(double t_s, const std::string& parent, const std::string& child,
                            const Pose3& X_PC) {
  const json m = {{"timestamp", stamp(t_s)},
                  {"parent_frame_id", parent},
                  {"child_frame_id", child},
                  {"translation", vec(X_PC.translation())},
                  {"rotation", quat(Eigen::Quaterniond(X_PC.rotation()))}};
  writer_->add_message(channel("/tf", "foxglove.FrameTransform"), to_nanoseconds(t_s), m.dump());
}

void FoxgloveLog::transform(double t_s, const std::string& parent, const std::string& child,
                            const Pose2& X_PC, double z_m) {
  Pose3 X = Pose3::Identity();
  X.translation() = Eigen::Vector3d(X_PC.x_m, X_PC.y_m, z_m);
  X.linear() = Eigen::AngleAxisd(X_PC.yaw_rad, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  transform(t_s, parent, child, X);
}

void FoxgloveLog::grid(double t_s, const std::string& topic, const std::string& frame,
                       double origin_x_m, double origin_y_m, double resolution_m, int width,
                       int height, const std::vector<std::uint8_t>& values,
                       const std::string& field) {
  if (width <= 0 || height <= 0 || values.size() != static_cast<std::size_t>(width) * height)
    throw std::invalid_argument("FoxgloveLog::grid: values do not match width x height");
  const json m = {{"timestamp", stamp(t_s)},
                  {"frame_id", frame},
                  {"pose", pose_at({origin_x_m, origin_y_m, 0.0})},
                  {"column_count", width},
                  {"cell_size", {{"x", resolution_m}, {"y", resolution_m}}},
                  {"row_stride", width},
                  {"cell_stride", 1},
                  {"fields", json::array({{{"name", field}, {"offset", 0}, {"type", 1}}})},
                  {"data", base64(values)}};
  writer_->add_message(channel(topic, "foxglove.Grid"), to_nanoseconds(t_s), m.dump());
}

void FoxgloveLog::line(double t_s, const std::string& topic, const std::string& frame,
                       const std::string& id, const std::vector<Eigen::Vector3d>& points,
                       const RgbaColor& c, double thickness_m) {
  json e = entity(t_s, frame, id);
  json pts = json::array();
  for (const auto& p : points) pts.push_back(vec(p));
  e["lines"].push_back({{"type", 0},  // LINE_STRIP
                        {"pose", pose_at(Eigen::Vector3d::Zero())},
                        {"thickness", thickness_m},
                        {"scale_invariant", false},
                        {"points", std::move(pts)},
                        {"color", color(c)},
                        {"colors", json::array()},
                        {"indices", json::array()}});
  const json m = {{"deletions", json::array()}, {"entities", json::array({std::move(e)})}};
  writer_->add_message(channel(topic, "foxglove.SceneUpdate"), to_nanoseconds(t_s), m.dump());
}

void FoxgloveLog::marker(double t_s, const std::string& topic, const std::string& frame,
                         const std::string& id, const Eigen::Vector3d& p, double diameter_m,
                         const RgbaColor& c, const std::string& label) {
  json e = entity(t_s, frame, id);
  e["spheres"].push_back({{"pose", pose_at(p)},
                          {"size", vec(Eigen::Vector3d::Constant(diameter_m))},
                          {"color", color(c)}});
  if (!label.empty())
    e["texts"].push_back({{"pose", pose_at(p + Eigen::Vector3d(0, 0, diameter_m))},
                          {"billboard", true},
                          {"font_size", 14.0},
                          {"scale_invariant", true},
                          {"color", color(c)},
                          {"text", label}});
  const json m = {{"deletions", json::array()}, {"entities", json::array({std::move(e)})}};
  writer_->add_message(channel(topic, "foxglove.SceneUpdate"), to_nanoseconds(t_s), m.dump());
}

void FoxgloveLog::log(double t_s, const std::string& name, const std::string& text, int level) {
  const json m = {{"timestamp", stamp(t_s)},
                  {"level", level},
                  {"message", text},
                  {"name", name},
                  {"file", ""},
                  {"line", 0}};
  writer_->add_message(channel("/log", "foxglove.Log"), to_nanoseconds(t_s), m.dump());
}

std::uint64_t FoxgloveLog::message_count() const { return writer_->message_count(); }

std::string FoxgloveLog::finish() { return writer_->finish(); }

}  // namespace ferret
