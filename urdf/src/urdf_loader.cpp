// URDF + mission YAML -> RobotDescription.
//
// A strict pre-check and three passes over one document, each in a file named after
// it (what they share: loader_passes.hpp):
//  0. libxml2's iterative reader (xml_check.cpp) refuses malformed XML, DOCTYPEs and
//     documents past the size, depth and element limits before TinyXML's recursive
//     parser sees them; every number in <link>, <joint> and <material> is checked
//     (urdf_numbers.cpp, checked_number.cpp) and the links and joints are counted and
//     checked to form one tree before urdfdom builds its own (urdf_structure.cpp).
//  1. TinyXML (the XML library urdfdom itself is built on) checks what urdfdom
//     accepts silently or reports only on the console: shape sizes <= 0, joints
//     naming missing links (urdf_structure.cpp); it reads the meshes (their bounding
//     boxes, with assimp: collision_shapes.cpp) and the links' <ferret role> markers.
//     Errors carry file:line.
//  2. urdfdom builds the kinematic tree (kinematic_tree.cpp) and the collision
//     geometry (collision_shapes.cpp); its console messages are captured
//     (console_bridge) and folded into one InputError.
//  3. TinyXML reads the sensors, both urdfdom's <sensor> elements and Gazebo's
//     <gazebo reference=...><sensor> blocks, which urdfdom ignores (sensor_blocks.cpp),
//     and checks them as cameras and range sensors (sensor_models.cpp).
// Then the motion limits follow from the mission and the wheels (motion_limits.cpp),
// and the roles from the <ferret role> markers and the mission (robot_roles.cpp).

#include <tinyxml.h>

#include <algorithm>
#include <fstream>
#include <map>

#include "ferret/core/error.hpp"
#include "ferret/urdf/robot_description.hpp"
#include "loader_passes.hpp"
#include "xml_check.hpp"

// GCC 12 reports -Wrestrict falsely on inlined std::string concatenation such as
// "'" + printable(text) (GCC PR 105329); this file's messages are built that way.
// Clang has no such warning (and would refuse the pragma under -Werror).
#if defined(__GNUC__) && !defined(__clang__)
#pragma GCC diagnostic ignored "-Wrestrict"
#endif

namespace ferret {
namespace {

// The passes describe_robot() runs (loader_passes.hpp).
using internal::assign_roles;
using internal::attr_or_empty;
using internal::check_counts;
using internal::check_numbers;
using internal::check_robot_element;
using internal::check_structure;
using internal::parse_with_urdfdom;
using internal::place_links;
using internal::read_collision_shapes;
using internal::read_limits;
using internal::read_sensors;
using internal::sensor_provenance;
using internal::Structure;
using internal::XmlSource;

/// Links are kept in URDF order for shapes and roles, so dumps are stable.
std::vector<std::string> link_order(const TiXmlElement* robot) {
  std::vector<std::string> names;
  for (const TiXmlElement* l = robot->FirstChildElement("link"); l != nullptr;
       l = l->NextSiblingElement("link"))
    names.push_back(attr_or_empty(l, "name"));
  return names;
}

/// Names and values in a message come from the file (a link name may hold a newline
/// as &#10;): every part is made one printable line. InputError keeps no "got", so it
/// is recovered from the message, whose layout core/src/error.cpp fixes.
[[noreturn]] void rethrow_printable(const InputError& e) {
  const std::string prefix = InputError(e.source(), e.field(), e.expected()).what();
  const std::string what = e.what();
  std::string got;
  if (what.size() > prefix.size() + 7 && what.compare(0, prefix.size(), prefix) == 0)
    got = what.substr(prefix.size() + 6, what.size() - prefix.size() - 7);  // " (got " ... ")"
  throw InputError(internal::printable(e.source()), internal::printable(e.field()),
                   internal::printable(e.expected()), internal::printable(got));
}

RobotDescription describe_robot(const std::string& urdf_xml, const std::string& source,
                                const RobotMissionSettings& mission) {
  const XmlSource src(source);
  // Before any recursive parser: well-formed, and within the size and depth limits.
  internal::check_well_formed_xml(urdf_xml, source);
  TiXmlDocument doc;
  doc.Parse(urdf_xml.c_str(), nullptr, TIXML_ENCODING_UTF8);
  if (doc.Error())  // libxml2 accepted it: a TinyXML limitation, still the file's fault
    throw InputError(source, "line " + std::to_string(doc.ErrorRow()), "XML that TinyXML reads",
                     internal::printable(doc.ErrorDesc()));
  const TiXmlElement* robot = doc.RootElement();
  if (robot == nullptr || std::string(robot->Value()) != "robot")
    src.fail(robot, "(document)", "a <robot> root element",
             robot == nullptr ? "nothing" : "<" + internal::printable(robot->Value()) + ">");
  check_counts(src, robot);
  check_robot_element(src, robot);
  check_numbers(src, robot);
  const Structure structure =
      check_structure(src, robot, std::filesystem::path(source).parent_path());
  const auto model = parse_with_urdfdom(src, urdf_xml);

  RobotDescription out;
  out.name = model->getName();
  out.source = source;
  const auto root = model->getRoot();
  out.base_link = root->name;
  place_links(*model, root, out.frames);
  const std::map<std::string, Pose3> X_BL = out.frames;

  read_collision_shapes(*model, X_BL, structure, out);
  // Shapes in URDF link order (urdfdom keeps links in a map).
  const auto order = link_order(robot);
  std::map<std::string, std::size_t> rank;
  for (std::size_t i = 0; i < order.size(); ++i) rank.emplace(order[i], i);
  std::stable_sort(out.collision_shapes.begin(), out.collision_shapes.end(),
                   [&](const auto& a, const auto& b) { return rank.at(a.link) < rank.at(b.link); });
  if (out.collision_shapes.empty())
    src.fail(robot, "robot", "at least one <collision> with a box, cylinder, sphere or mesh");
  out.bounding_box_B.setEmpty();
  for (const auto& s : out.collision_shapes) out.bounding_box_B.extend(s.aabb_B());
  out.circumscribed_radius_m = 0.0;
  for (const auto& s : out.collision_shapes)
    out.circumscribed_radius_m = std::max(out.circumscribed_radius_m, s.xy_reach_m());
  // Bounded sizes and origins over at most 1000 links keep this finite; say so if not.
  if (!out.bounding_box_B.min().allFinite() || !out.bounding_box_B.max().allFinite())
    src.fail(robot, "robot", "collision geometry with a finite extent",
             "a bounding box that is not finite");
  out.ground_offset_m = -out.bounding_box_B.min().z();
  out.provenance["ground_offset_m"] = "urdf:" + source + " (lowest collision point)";
  out.provenance["bounding_box_m"] = "urdf:" + source + " (collision geometry)";

  const auto specs = read_sensors(src, robot, X_BL, out);
  sensor_provenance(specs, out);
  read_limits(*model, mission, structure, out);
  assign_roles(src, specs, structure, order, mission, out);
  return out;
}

}  // namespace

RobotDescription robot_description_from_string(const std::string& urdf_xml,
                                               const std::string& source,
                                               const RobotMissionSettings& mission) {
  try {
    return describe_robot(urdf_xml, source, mission);
  } catch (const InputError& e) {
    rethrow_printable(e);
  }
}

RobotDescription load_robot(const std::string& urdf_or_name, const RobotMissionSettings& mission) {
  for (const char* name : {"miniugv", "m100"})
    if (urdf_or_name == name || urdf_or_name == std::string(name) + ".urdf")
      return load_robot_description(find_model(std::string(name) + ".urdf"), mission);
  return load_robot_description(urdf_or_name, mission);
}

RobotDescription load_robot_description(const std::filesystem::path& urdf_path,
                                        const RobotMissionSettings& mission) {
  std::ifstream in(urdf_path, std::ios::binary);
  std::error_code ec;
  if (!in || std::filesystem::is_directory(urdf_path, ec))
    throw InputError(urdf_path.string(), "", "a readable URDF file", "cannot open");
  // Read at most one byte past the limit: a huge file (or a device) is refused
  // without being read whole.
  std::string text;
  std::vector<char> chunk(1 << 16);
  while (text.size() <= internal::kMaxUrdfBytes &&
         in.read(chunk.data(), static_cast<std::streamsize>(chunk.size())).gcount() > 0)
    text.append(chunk.data(), static_cast<std::size_t>(in.gcount()));
  if (text.size() > internal::kMaxUrdfBytes)
    throw InputError(urdf_path.string(), "", "a URDF of at most 16 MiB (16777216 bytes)",
                     "more than 16777216 bytes");
  return robot_description_from_string(text, urdf_path.string(), mission);
}

}  // namespace ferret
