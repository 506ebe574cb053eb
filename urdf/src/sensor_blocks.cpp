// Pass 3 of the URDF loader, reading the sensors as declared: urdfdom's <sensor>
// elements and Gazebo's <gazebo reference=...><sensor> blocks, which urdfdom ignores,
// one SensorSpec each, a sensor declared in both merged into one. urdfdom 3.0's own
// sensor parser is not used: it drops every <ray> sensor (parseRay returns false) and
// has no range for rays.

#include <algorithm>
#include <cmath>

#include "loader_passes.hpp"
#include "xml_check.hpp"

// GCC 12 reports -Wrestrict falsely on inlined std::string concatenation such as
// "'" + printable(text) (GCC PR 105329); this file's messages are built that way.
// Clang has no such warning (and would refuse the pragma under -Werror).
#if defined(__GNUC__) && !defined(__clang__)
#pragma GCC diagnostic ignored "-Wrestrict"
#endif

namespace ferret::internal {

namespace {

Pose3 pose_from_xyz_rpy(const std::vector<double>& xyz, const std::vector<double>& rpy) {
  // URDF and SDF: fixed-axis roll about x, then pitch about y, then yaw about z.
  Pose3 X = Pose3::Identity();
  X.translation() = Eigen::Vector3d(xyz[0], xyz[1], xyz[2]);
  X.linear() = (Eigen::AngleAxisd(rpy[2], Eigen::Vector3d::UnitZ()) *
                Eigen::AngleAxisd(rpy[1], Eigen::Vector3d::UnitY()) *
                Eigen::AngleAxisd(rpy[0], Eigen::Vector3d::UnitX()))
                   .toRotationMatrix();
  return X;
}

/// <origin xyz=".." rpy=".."/>, both optional; |xyz| <= 1000 m, rpy finite.
Pose3 read_origin(const XmlSource& src, const TiXmlElement* origin, const std::string& field) {
  if (origin == nullptr) return Pose3::Identity();
  const auto xyz = internal::checked_numbers(src.at(origin), field + "@xyz",
                                             origin->Attribute("xyz"), 3, kPosition, false);
  const auto rpy = internal::checked_numbers(src.at(origin), field + "@rpy",
                                             origin->Attribute("rpy"), 3, kAngle, false);
  return pose_from_xyz_rpy(xyz.value_or(std::vector<double>{0, 0, 0}),
                           rpy.value_or(std::vector<double>{0, 0, 0}));
}

std::vector<RoleMark> sensor_role_marks(const XmlSource& src, const TiXmlElement* e,
                                        const std::string& field) {
  return read_role_marks(src, e, field, sensor_role_names(), " (frame roles go inside the <link>)");
}

void set_value(const XmlSource& src, SensorSpec& s, const std::string& key, const TiXmlElement* e,
               const char* text, const std::string& field) {
  const auto v = parse_number(text);
  if (!v) src.fail(e, field, "a finite number", "'" + internal::printable(text ? text : "") + "'");
  s.values[key] = SensorValue{*v, src.at(e), field};
}

void attr_value(const XmlSource& src, SensorSpec& s, const std::string& key, const TiXmlElement* e,
                const char* attr, const std::string& field) {
  if (e == nullptr) return;
  if (const char* text = e->Attribute(attr)) set_value(src, s, key, e, text, field + "@" + attr);
}

/// Gazebo style: the number is the element's text, <parent><child>1.0</child></parent>.
void text_value(const XmlSource& src, SensorSpec& s, const std::string& key,
                const TiXmlElement* parent, const char* child, const std::string& field) {
  if (parent == nullptr) return;
  const TiXmlElement* e = parent->FirstChildElement(child);
  if (e == nullptr) return;
  set_value(src, s, key, e, e->GetText() != nullptr ? e->GetText() : "", field + "/" + child);
}

}  // namespace

/// urdfdom's sensor format (ROS wiki urdf/XML/sensor):
///   <sensor name="cam" update_rate="30"> <parent link="L"/> <origin .../>
///     <camera><image width=".." height=".." hfov=".." near=".." far=".."/></camera>
///     or <ray><horizontal samples=".." min_angle=".." max_angle=".."/><range min max/></ray>
///   </sensor>
/// urdfdom 3.0's parser wants the parent as attribute parent_link_name: both are read.
SensorSpec read_urdf_sensor(const XmlSource& src, const TiXmlElement* e) {
  SensorSpec s;
  s.name = attr_or_empty(e, "name");
  if (s.name.empty()) src.fail(e, "sensor@name", "a sensor name");
  s.at = src.at(e);
  s.field = "sensor[" + s.name + "]";
  s.from_urdf = true;
  s.link = attr_or_empty(e, "parent_link_name");
  if (const TiXmlElement* parent = e->FirstChildElement("parent"))
    s.link = attr_or_empty(parent, "link");
  if (s.link.empty()) src.fail(e, s.field + "/parent@link", "the link the sensor is attached to");
  if (const TiXmlElement* origin = e->FirstChildElement("origin")) {
    s.X_LS = read_origin(src, origin, s.field + "/origin");
    s.pose_at = src.at(origin);
    s.pose_field = s.field + "/origin";
  }
  attr_value(src, s, "update_rate", e, "update_rate", s.field);
  s.roles = sensor_role_marks(src, e, s.field);
  if (const TiXmlElement* camera = e->FirstChildElement("camera")) {
    s.kind = SensorSpec::Kind::kCamera;
    const TiXmlElement* image = camera->FirstChildElement("image");
    if (image == nullptr) src.fail(camera, s.field + "/camera/image", "an <image> element");
    const std::string f = s.field + "/camera/image";
    for (const char* key : {"hfov", "width", "height", "near", "far"})
      attr_value(src, s, key, image, key, f);
  } else if (const TiXmlElement* ray = e->FirstChildElement("ray")) {
    s.kind = SensorSpec::Kind::kRay;
    const TiXmlElement* h = ray->FirstChildElement("horizontal");
    const std::string f = s.field + "/ray/horizontal";
    for (const char* key : {"samples", "min_angle", "max_angle"})
      attr_value(src, s, key, h, key, f);
    const TiXmlElement* range = ray->FirstChildElement("range");
    attr_value(src, s, "range_min", range, "min", s.field + "/ray/range");
    attr_value(src, s, "range_max", range, "max", s.field + "/ray/range");
  } else {
    src.fail(e, s.field, "a <camera> or <ray> element");
  }
  return s;
}

namespace {

SensorSpec::Kind gazebo_kind(const std::string& type) {
  if (type == "camera" || type == "wideanglecamera" || type == "multicamera")
    return SensorSpec::Kind::kCamera;
  if (type == "depth" || type == "depth_camera" || type == "rgbd_camera" || type == "rgbd")
    return SensorSpec::Kind::kDepth;
  if (type == "ray" || type == "gpu_ray" || type == "lidar" || type == "gpu_lidar")
    return SensorSpec::Kind::kRay;
  return SensorSpec::Kind::kOther;
}

/// Gazebo's optional calibration of a camera: <distortion> (k1 k2 k3 p1 p2, each
/// optional and 0 when absent, and <center>, two normalised coordinates) and
/// <lens><intrinsics> (fx fy cx cy, all four, and an optional skew <s>).
void read_lens_blocks(const XmlSource& src, SensorSpec& s, const TiXmlElement* camera,
                      const std::string& f) {
  if (const TiXmlElement* d = camera->FirstChildElement("distortion")) {
    s.distortion_at = src.at(d);
    s.distortion_field = f + "/distortion";
    for (const char* key : {"k1", "k2", "k3", "p1", "p2"})
      text_value(src, s, std::string("distortion_") + key, d, key, s.distortion_field);
    if (const TiXmlElement* c = d->FirstChildElement("center")) {
      const std::string field = s.distortion_field + "/center";
      const internal::NumberRange normalised{0.0, 1.0, false, false, "of the image size"};
      const auto xy = internal::checked_numbers(
          src.at(c), field, c->GetText() != nullptr ? c->GetText() : "", 2, normalised, true);
      s.values["distortion_center_x"] = SensorValue{(*xy)[0], src.at(c), field};
      s.values["distortion_center_y"] = SensorValue{(*xy)[1], src.at(c), field};
    }
  }
  const TiXmlElement* lens = camera->FirstChildElement("lens");
  if (const TiXmlElement* in = lens != nullptr ? lens->FirstChildElement("intrinsics") : nullptr) {
    s.intrinsics_at = src.at(in);
    s.intrinsics_field = f + "/lens/intrinsics";
    for (const char* key : {"fx", "fy", "cx", "cy", "s"})
      text_value(src, s, std::string("intrinsics_") + key, in, key, s.intrinsics_field);
  }
}

}  // namespace

/// Gazebo style: <gazebo reference="L"><sensor type="camera|depth|ray" name="..">.
SensorSpec read_gazebo_sensor(const XmlSource& src, const TiXmlElement* e,
                              const std::string& link) {
  SensorSpec s;
  s.name = attr_or_empty(e, "name");
  const std::string type = attr_or_empty(e, "type");
  s.field = "gazebo[" + link + "]/sensor[" + s.name + "]";
  if (s.name.empty()) src.fail(e, "gazebo[" + link + "]/sensor@name", "a sensor name");
  if (type.empty()) src.fail(e, s.field + "@type", "a sensor type (camera, depth, ray, imu, ...)");
  s.at = src.at(e);
  s.link = link;
  s.from_gazebo = true;
  s.kind = gazebo_kind(type);
  if (const TiXmlElement* pose = e->FirstChildElement("pose")) {
    auto values = parse_numbers(pose->GetText() != nullptr ? pose->GetText() : "");
    bool ok = values && values->size() == 6;
    for (int i = 0; ok && i < 3; ++i) ok = std::abs((*values)[i]) <= 1e3;
    if (!ok)
      src.fail(pose, s.field + "/pose",
               "six numbers: x y z (within 1000 metres) roll pitch yaw (radians)",
               "'" + internal::printable(pose->GetText() ? pose->GetText() : "") + "'");
    s.X_LS = pose_from_xyz_rpy({(*values)[0], (*values)[1], (*values)[2]},
                               {(*values)[3], (*values)[4], (*values)[5]});
    s.pose_at = src.at(pose);
    s.pose_field = s.field + "/pose";
  }
  text_value(src, s, "update_rate", e, "update_rate", s.field);
  s.roles = sensor_role_marks(src, e, s.field);
  if (s.kind == SensorSpec::Kind::kCamera || s.kind == SensorSpec::Kind::kDepth) {
    const TiXmlElement* camera = e->FirstChildElement("camera");
    if (camera == nullptr) src.fail(e, s.field + "/camera", "a <camera> element");
    const std::string f = s.field + "/camera";
    text_value(src, s, "hfov", camera, "horizontal_fov", f);
    const TiXmlElement* image = camera->FirstChildElement("image");
    text_value(src, s, "width", image, "width", f + "/image");
    text_value(src, s, "height", image, "height", f + "/image");
    const TiXmlElement* clip = camera->FirstChildElement("clip");
    text_value(src, s, "near", clip, "near", f + "/clip");
    text_value(src, s, "far", clip, "far", f + "/clip");
    read_lens_blocks(src, s, camera, f);
  } else if (s.kind == SensorSpec::Kind::kRay) {
    const char* tag = e->FirstChildElement("ray") != nullptr ? "ray" : "lidar";
    const TiXmlElement* ray = e->FirstChildElement(tag);
    if (ray == nullptr) src.fail(e, s.field + "/ray", "a <ray> element");
    const std::string f = s.field + "/" + tag;
    const TiXmlElement* scan = ray->FirstChildElement("scan");
    const TiXmlElement* h = scan != nullptr ? scan->FirstChildElement("horizontal") : nullptr;
    text_value(src, s, "samples", h, "samples", f + "/scan/horizontal");
    text_value(src, s, "min_angle", h, "min_angle", f + "/scan/horizontal");
    text_value(src, s, "max_angle", h, "max_angle", f + "/scan/horizontal");
    const TiXmlElement* range = ray->FirstChildElement("range");
    text_value(src, s, "range_min", range, "min", f + "/range");
    text_value(src, s, "range_max", range, "max", f + "/range");
  }
  return s;
}

namespace {

bool same_value(double a, double b) { return std::abs(a - b) <= 1e-9 * std::max(1.0, std::abs(a)); }

}  // namespace

/// A sensor declared both as urdfdom <sensor> and in a Gazebo block: one sensor, as
/// long as the two agree wherever both say something.
void merge_into(SensorSpec& into, const SensorSpec& from) {
  auto conflict = [&](const std::string& at, const std::string& field, const std::string& what,
                      const std::string& other_at, const std::string& got = "a conflicting value") {
    throw InputError(at, field, what + " as declared at " + other_at, got);
  };
  if (into.link != from.link)
    conflict(from.at, from.field, "the same link ('" + into.link + "')", into.at);
  const bool into_camera =
      into.kind == SensorSpec::Kind::kCamera || into.kind == SensorSpec::Kind::kDepth;
  const bool from_camera =
      from.kind == SensorSpec::Kind::kCamera || from.kind == SensorSpec::Kind::kDepth;
  if (into_camera != from_camera ||
      (into.kind == SensorSpec::Kind::kRay) != (from.kind == SensorSpec::Kind::kRay))
    conflict(from.at, from.field + "@type", "the same sensor type", into.at);
  if (from.kind == SensorSpec::Kind::kDepth)
    into.kind = SensorSpec::Kind::kDepth;  // only Gazebo knows depth
  if (from.X_LS) {
    if (into.X_LS && !into.X_LS->isApprox(*from.X_LS, 1e-9))
      conflict(from.pose_at, from.pose_field, "the same pose", into.pose_at);
    into.X_LS = from.X_LS;
  }
  for (const auto& [key, v] : from.values) {
    const auto it = into.values.find(key);
    if (it != into.values.end() && !same_value(it->second.value, v.value))
      conflict(v.at, v.field, "the value " + num(it->second.value),
               it->second.at + " (" + it->second.field + ")", "'" + num(v.value) + "'");
    into.values[key] = v;
  }
  into.roles.insert(into.roles.end(), from.roles.begin(), from.roles.end());
  if (!from.distortion_at.empty()) {
    into.distortion_at = from.distortion_at;
    into.distortion_field = from.distortion_field;
  }
  if (!from.intrinsics_at.empty()) {
    into.intrinsics_at = from.intrinsics_at;
    into.intrinsics_field = from.intrinsics_field;
  }
}

}  // namespace ferret::internal
