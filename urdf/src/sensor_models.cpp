// Pass 3 of the URDF loader, checking the sensors: each declared sensor (sensor_blocks.cpp)
// becomes a CameraSensor or a RangeSensor with its values checked, errors at the
// value's own element; and where each value came from.

#include <cmath>
#include <numbers>

#include "loader_passes.hpp"

namespace ferret::internal {

namespace {

constexpr double kPi = std::numbers::pi;

/// How a missing sensor value is named in errors, and where a user can write it.
struct ValueName {
  const char* field;  ///< appended to the sensor's path
  const char* where;  ///< the urdfdom and Gazebo places
};
const std::map<std::string, ValueName>& value_names() {
  static const std::map<std::string, ValueName> names{
      {"hfov", {"horizontal_fov", "<image hfov=..> or Gazebo <camera><horizontal_fov>"}},
      {"width", {"image_width", "<image width=..> or Gazebo <image><width>"}},
      {"height", {"image_height", "<image height=..> or Gazebo <image><height>"}},
      {"near", {"clip_near", "<image near=..> or Gazebo <clip><near>"}},
      {"far", {"clip_far", "<image far=..> or Gazebo <clip><far>"}},
      {"samples", {"samples", "<horizontal samples=..> or Gazebo <scan><horizontal><samples>"}},
      {"min_angle",
       {"min_angle", "<horizontal min_angle=..> or Gazebo <scan><horizontal><min_angle>"}},
      {"max_angle",
       {"max_angle", "<horizontal max_angle=..> or Gazebo <scan><horizontal><max_angle>"}},
      {"range_min", {"range_min", "<ray><range min=..> or Gazebo <ray><range><min>"}},
      {"range_max", {"range_max", "<ray><range max=..> or Gazebo <ray><range><max>"}},
      {"intrinsics_fx", {"lens/intrinsics/fx", "Gazebo <camera><lens><intrinsics><fx>"}},
      {"intrinsics_fy", {"lens/intrinsics/fy", "Gazebo <camera><lens><intrinsics><fy>"}},
      {"intrinsics_cx", {"lens/intrinsics/cx", "Gazebo <camera><lens><intrinsics><cx>"}},
      {"intrinsics_cy", {"lens/intrinsics/cy", "Gazebo <camera><lens><intrinsics><cy>"}},
  };
  return names;
}

/// A required value checked against a predicate; errors point at the value's own
/// element, or at the sensor when the value is missing.
double need(const SensorSpec& s, const std::string& key, bool (*ok)(double),
            const std::string& expected) {
  const auto it = s.values.find(key);
  if (it == s.values.end())
    throw InputError(s.at, s.field + "/" + value_names().at(key).field,
                     expected + ", required: " + value_names().at(key).where, "nothing");
  if (!ok(it->second.value))
    throw InputError(it->second.at, it->second.field, expected, "'" + num(it->second.value) + "'");
  return it->second.value;
}

double optional_rate(const SensorSpec& s) {
  const auto it = s.values.find("update_rate");
  if (it == s.values.end()) return 0.0;
  if (!(it->second.value > 0.0))
    throw InputError(it->second.at, it->second.field, "a rate > 0 (Hz)");
  return it->second.value;
}

/// An optional value checked against a predicate, `fallback` when absent.
double optional_value(const SensorSpec& s, const std::string& key, bool (*ok)(double),
                      const std::string& expected, double fallback) {
  const auto it = s.values.find(key);
  if (it == s.values.end()) return fallback;
  if (!ok(it->second.value))
    throw InputError(it->second.at, it->second.field, expected, "'" + num(it->second.value) + "'");
  return it->second.value;
}

bool is_count(double v) { return v >= 1.0 && v <= 1e6 && std::floor(v) == v; }
bool is_pixels(double v) { return v >= 1.0 && v <= 1e5 && std::floor(v) == v; }

/// The distortion and intrinsics blocks into `c` (its size already read).
void read_calibration(const SensorSpec& s, CameraSensor& c) {
  if (!s.intrinsics_at.empty()) {
    const auto focal_ok = [](double v) { return v > 0.0 && v <= 1e7; };
    const std::string focal = "a focal length in (0, 1e7] px";
    CameraIntrinsics in;
    in.fx_px = need(s, "intrinsics_fx", focal_ok, focal);
    in.fy_px = need(s, "intrinsics_fy", focal_ok, focal);
    // The principal point in camera_info's pixels (0 at the first pixel's centre).
    const auto inside = [&](const char* key, int size_px) {
      const auto it = s.values.find(key);
      const double v = need(
          s, key, [](double x) { return std::isfinite(x); }, "a principal point in px");
      if (!(v >= -0.5 && v <= size_px - 0.5))
        throw InputError(
            it->second.at, it->second.field,
            "a principal point inside the image, -0.5 to " + num(size_px - 0.5) + " px",
            "'" + num(v) + "'");
      return v;
    };
    in.cx_px = inside("intrinsics_cx", c.image_width_px);
    in.cy_px = inside("intrinsics_cy", c.image_height_px);
    in.skew = optional_value(
        s, "intrinsics_s", [](double v) { return std::abs(v) <= 1e7; }, "a skew in [-1e7, 1e7] px",
        0.0);
    c.intrinsics = in;
  }
  if (!s.distortion_at.empty()) {
    const auto coefficient_ok = [](double v) { return std::abs(v) <= 1e3; };
    const std::string coefficient = "a distortion coefficient in [-1000, 1000]";
    CameraDistortion d;
    d.k1 = optional_value(s, "distortion_k1", coefficient_ok, coefficient, 0.0);
    d.k2 = optional_value(s, "distortion_k2", coefficient_ok, coefficient, 0.0);
    d.k3 = optional_value(s, "distortion_k3", coefficient_ok, coefficient, 0.0);
    d.p1 = optional_value(s, "distortion_p1", coefficient_ok, coefficient, 0.0);
    d.p2 = optional_value(s, "distortion_p2", coefficient_ok, coefficient, 0.0);
    const auto centre = s.values.find("distortion_center_x");
    if (centre != s.values.end()) {
      d.center_x = centre->second.value;
      d.center_y = s.values.at("distortion_center_y").value;
      // plumb_bob distorts about the principal point; Gazebo may distort about another
      // point, which no camera_info can describe: refuse it rather than model it wrong.
      const double cx = c.intrinsics ? c.intrinsics->cx_px : 0.5 * (c.image_width_px - 1);
      const double cy = c.intrinsics ? c.intrinsics->cy_px : 0.5 * (c.image_height_px - 1);
      const double ux = d.center_x * c.image_width_px - 0.5;
      const double uy = d.center_y * c.image_height_px - 0.5;
      if (std::abs(ux - cx) > 1.0 || std::abs(uy - cy) > 1.0)
        throw InputError(centre->second.at, centre->second.field,
                         "the principal point (" + num(cx) + ", " + num(cy) +
                             " px; plumb_bob distorts about it), i.e. a center of " +
                             num((cx + 0.5) / c.image_width_px) + " " +
                             num((cy + 0.5) / c.image_height_px),
                         "'" + num(d.center_x) + " " + num(d.center_y) + "'");
    }
    c.distortion = d;
  }
}

CameraSensor make_camera(const SensorSpec& s, const Pose3& X_BS) {
  CameraSensor c;
  c.name = s.name;
  c.link = s.link;
  c.X_BS = X_BS;
  c.depth = s.kind == SensorSpec::Kind::kDepth;
  c.horizontal_fov_rad = need(
      s, "hfov", [](double v) { return v > 0.0 && v < kPi; },
      "a horizontal fov in (0, pi) radians");
  c.image_width_px = static_cast<int>(
      need(s, "width", is_pixels, "an image width in pixels, an integer in [1, 100000]"));
  c.image_height_px = static_cast<int>(
      need(s, "height", is_pixels, "an image height in pixels, an integer in [1, 100000]"));
  c.range_min_m = need(
      s, "near", [](double v) { return v >= 0.0; }, "a clip near >= 0 (metres)");
  const auto far = s.values.find("far");
  c.range_max_m = need(
      s, "far", [](double v) { return v > 0.0; }, "a clip far > 0 (metres)");
  if (c.range_max_m <= c.range_min_m)
    throw InputError(far->second.at, far->second.field,
                     "a clip far > clip near (" + num(c.range_min_m) + " m)",
                     "'" + num(c.range_max_m) + "'");
  // Square pixels: tan(v/2) / tan(h/2) = height / width.
  c.vertical_fov_rad =
      2.0 * std::atan(std::tan(c.horizontal_fov_rad / 2.0) * c.image_height_px / c.image_width_px);
  c.update_rate_hz = optional_rate(s);
  read_calibration(s, c);
  return c;
}

RangeSensor make_range_sensor(const SensorSpec& s, const Pose3& X_BS) {
  RangeSensor r;
  r.name = s.name;
  r.link = s.link;
  r.X_BS = X_BS;
  auto angle_ok = [](double v) { return v >= -kPi && v <= kPi; };
  r.samples = static_cast<int>(
      need(s, "samples", is_count, "a number of samples, an integer in [1, 1000000]"));
  r.min_angle_rad = need(s, "min_angle", angle_ok, "an angle in [-pi, pi] radians");
  r.max_angle_rad = need(s, "max_angle", angle_ok, "an angle in [-pi, pi] radians");
  const auto& max_angle = s.values.at("max_angle");
  if (r.max_angle_rad < r.min_angle_rad || (r.samples > 1 && r.max_angle_rad == r.min_angle_rad))
    throw InputError(
        max_angle.at, max_angle.field,
        std::string("an angle ") + (r.samples > 1 ? ">" : ">=") + " min_angle (a fov > 0)",
        "'" + num(r.max_angle_rad) + "'");
  r.range_min_m = need(
      s, "range_min", [](double v) { return v >= 0.0; }, "a range min >= 0 (metres)");
  r.range_max_m = need(
      s, "range_max", [](double v) { return v > 0.0; }, "a range max > 0 (metres)");
  if (r.range_max_m <= r.range_min_m) {
    const auto& v = s.values.at("range_max");
    throw InputError(v.at, v.field, "a range max > range min (" + num(r.range_min_m) + " m)",
                     "'" + num(r.range_max_m) + "'");
  }
  r.update_rate_hz = optional_rate(s);
  return r;
}

}  // namespace

std::vector<SensorSpec> read_sensors(const XmlSource& src, const TiXmlElement* robot,
                                     const std::map<std::string, Pose3>& X_BL,
                                     RobotDescription& out) {
  std::vector<SensorSpec> specs;
  auto add = [&](SensorSpec s, const TiXmlElement* e) {
    if (X_BL.count(s.link) == 0)
      src.fail(e, s.field, "a sensor on a <link> of this file", "link '" + s.link + "'");
    for (auto& existing : specs) {
      if (existing.name != s.name) continue;
      // One urdfdom <sensor> and one Gazebo <sensor> may describe the same sensor.
      if ((s.from_gazebo && existing.from_gazebo) || (!s.from_gazebo && existing.from_urdf))
        src.fail(e, s.field, "a unique sensor name", "a second sensor named '" + s.name + "'");
      merge_into(existing, s);
      existing.from_gazebo = existing.from_gazebo || s.from_gazebo;
      existing.from_urdf = existing.from_urdf || s.from_urdf;
      return;
    }
    specs.push_back(std::move(s));
  };
  for (const TiXmlElement* e = robot->FirstChildElement("sensor"); e != nullptr;
       e = e->NextSiblingElement("sensor"))
    add(read_urdf_sensor(src, e), e);
  for (const TiXmlElement* g = robot->FirstChildElement("gazebo"); g != nullptr;
       g = g->NextSiblingElement("gazebo")) {
    const std::string link = attr_or_empty(g, "reference");
    const TiXmlElement* first = g->FirstChildElement("sensor");
    if (first == nullptr) continue;  // materials, plugins: not ours
    if (link.empty()) src.fail(g, "gazebo@reference", "the link a <sensor> is attached to");
    for (const TiXmlElement* e = first; e != nullptr; e = e->NextSiblingElement("sensor"))
      add(read_gazebo_sensor(src, e, link), e);
  }

  for (const auto& s : specs) {
    if (X_BL.count(s.name) > 0)
      throw InputError(s.at, s.field, "a sensor name that is not also a link name",
                       "'" + s.name + "'");
    const Pose3 X_BS = X_BL.at(s.link) * s.X_LS.value_or(Pose3::Identity());
    out.frames[s.name] = X_BS;
    switch (s.kind) {
      case SensorSpec::Kind::kCamera:
      case SensorSpec::Kind::kDepth:
        out.cameras.push_back(make_camera(s, X_BS));
        break;
      case SensorSpec::Kind::kRay:
        out.range_sensors.push_back(make_range_sensor(s, X_BS));
        break;
      case SensorSpec::Kind::kOther:
        break;  // an IMU or the like: a frame, nothing more
    }
  }
  return specs;
}

/// Where each value of the sensors came from ("urdf:FILE:LINE").
void sensor_provenance(const std::vector<SensorSpec>& specs, RobotDescription& out) {
  for (const auto& s : specs) {
    auto put = [&](const std::string& key, const char* value) {
      const auto it = s.values.find(value);
      if (it != s.values.end()) out.provenance[key] = "urdf:" + it->second.at;
    };
    if (s.kind == SensorSpec::Kind::kCamera || s.kind == SensorSpec::Kind::kDepth) {
      const std::string k = "cameras." + s.name + ".";
      put(k + "horizontal_fov", "hfov");
      put(k + "image_width_px", "width");
      put(k + "image_height_px", "height");
      put(k + "range_max_m", "far");
      if (!s.distortion_at.empty()) out.provenance[k + "distortion"] = "urdf:" + s.distortion_at;
      if (!s.intrinsics_at.empty()) out.provenance[k + "intrinsics"] = "urdf:" + s.intrinsics_at;
    } else if (s.kind == SensorSpec::Kind::kRay) {
      const std::string k = "range_sensors." + s.name + ".";
      put(k + "fov", "max_angle");
      put(k + "samples", "samples");
      put(k + "range_max_m", "range_max");
    }
  }
}

}  // namespace ferret::internal
