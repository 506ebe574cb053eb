// URDF + mission YAML -> RobotDescription.
//
// A strict pre-check and three passes over one document:
//  0. libxml2's iterative reader (xml_check.cpp) refuses malformed XML, DOCTYPEs and
//     documents past the size, depth and element limits before TinyXML's recursive
//     parser sees them; every number in <link>, <joint> and <material> is checked
//     (checked_number.cpp) and the links and joints are counted and checked to form
//     one tree before urdfdom builds its own.
//  1. TinyXML (the XML library urdfdom itself is built on) checks what urdfdom
//     accepts silently or reports only on the console: shape sizes <= 0, joints
//     naming missing links; it reads the meshes (their bounding boxes, with assimp)
//     and the links' <ferret role> markers. Errors carry file:line.
//  2. urdfdom builds the kinematic tree and the collision geometry; its console
//     messages are captured (console_bridge) and folded into one InputError.
//  3. TinyXML reads the sensors, both urdfdom's <sensor> elements and Gazebo's
//     <gazebo reference=...><sensor> blocks, which urdfdom ignores. urdfdom 3.0's own
//     sensor parser is not used: it drops every <ray> sensor (parseRay returns false)
//     and has no range for rays.

#include <console_bridge/console.h>
#include <fmt/format.h>
#include <tinyxml.h>
#include <urdf_parser/urdf_parser.h>

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <fstream>
#include <map>
#include <mutex>
#include <numbers>
#include <set>
#include <sstream>

#include "checked_number.hpp"
#include "ferret/core/error.hpp"
#include "ferret/urdf/robot_description.hpp"
#include "mesh_bounds.hpp"
#include "xml_check.hpp"

namespace ferret {
namespace {

using internal::kInf;
constexpr double kPi = std::numbers::pi;

/// Where an element sits, for errors: "file:line".
class XmlSource {
 public:
  explicit XmlSource(std::string source) : source_(std::move(source)) {}
  [[nodiscard]] std::string at(const TiXmlNode* node) const {
    return node != nullptr ? source_ + ":" + std::to_string(node->Row()) : source_;
  }
  [[noreturn]] void fail(const TiXmlNode* node, const std::string& field,
                         const std::string& expected, const std::string& got = {}) const {
    throw InputError(at(node), field, expected, got);
  }
  [[nodiscard]] const std::string& source() const { return source_; }

 private:
  std::string source_;
};

/// Shortest round-trip form of a number, for messages.
std::string num(double v) { return fmt::format("{}", v); }

std::string quoted(const char* text) {
  return text == nullptr ? "nothing" : "'" + internal::printable(text) + "'";
}

/// Whitespace-separated finite decimal numbers; nullopt when any token is not one.
std::optional<std::vector<double>> parse_numbers(const char* text) {
  if (text == nullptr) return std::nullopt;
  std::vector<double> out;
  std::istringstream tokens{std::string(text)};
  std::string token;
  while (tokens >> token) {
    const auto v = internal::parse_decimal(token);
    if (!v) return std::nullopt;
    out.push_back(*v);
  }
  return out;
}

std::optional<double> parse_number(const char* text) {
  auto values = parse_numbers(text);
  if (!values || values->size() != 1) return std::nullopt;
  return values->front();
}

std::string attr_or_empty(const TiXmlElement* e, const char* name) {
  const char* v = e->Attribute(name);
  return v == nullptr ? std::string() : std::string(v);
}

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

/// Where a URDF's positions may lie and how its angles are written.
const internal::NumberRange kPosition{-1e3, 1e3, false, false, "metres"};
const internal::NumberRange kAngle{-kInf, kInf, false, false, "radians"};

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

// ---------------------------------------------------------------- pass 0: numbers

/// One numeric attribute of a URDF element: its count and range, and whether urdfdom
/// requires it (so its absence is named here, not in urdfdom's console message).
struct NumericAttribute {
  const char* name;
  std::size_t count;
  internal::NumberRange range;
  bool required;
};

/// The numeric attributes of `element` (a descendant of a <link>, <joint> or
/// top-level <material>), by the URDF specification (wiki.ros.org/urdf/XML).
std::vector<NumericAttribute> numeric_attributes(const std::string& element,
                                                 const std::string& parent) {
  using R = internal::NumberRange;
  const R size{0.0, 1e3, true, false, "metres"};
  const R finite{};
  const R non_negative{0.0, kInf, false, false};
  if (element == "origin") return {{"xyz", 3, kPosition, false}, {"rpy", 3, kAngle, false}};
  if (parent == "geometry") {
    if (element == "box") return {{"size", 3, size, true}};
    if (element == "cylinder") return {{"radius", 1, size, true}, {"length", 1, size, true}};
    if (element == "sphere") return {{"radius", 1, size, true}};
    if (element == "mesh") {
      R scale{-1e3, 1e3, false, false};
      scale.nonzero = true;  // a negative factor mirrors the mesh
      return {{"scale", 3, scale, false}};
    }
    return {};
  }
  if (element == "limit")
    return {{"lower", 1, R{-kInf, kInf, false, false, "radians or metres"}, false},
            {"upper", 1, R{-kInf, kInf, false, false, "radians or metres"}, false},
            {"effort", 1, R{0.0, kInf, false, false, "N m or N"}, true},
            {"velocity", 1, R{0.0, kInf, false, false, "rad/s or m/s"}, true}};
  if (element == "dynamics")
    return {{"damping", 1, non_negative, false}, {"friction", 1, non_negative, false}};
  if (element == "safety_controller")
    return {{"soft_lower_limit", 1, finite, false},
            {"soft_upper_limit", 1, finite, false},
            {"k_position", 1, finite, false},
            {"k_velocity", 1, finite, true}};
  if (element == "calibration")
    return {{"rising", 1, finite, false}, {"falling", 1, finite, false}};
  if (element == "mimic") return {{"multiplier", 1, finite, false}, {"offset", 1, finite, false}};
  if (element == "axis") {
    R axis = finite;
    axis.nonzero_vector = true;
    return {{"xyz", 3, axis, false}};
  }
  if (element == "mass") return {{"value", 1, R{0.0, kInf, false, false, "kg"}, true}};
  if (element == "inertia") {
    const R inertia{-kInf, kInf, false, false, "kg m^2"};
    return {{"ixx", 1, inertia, true}, {"ixy", 1, inertia, true}, {"ixz", 1, inertia, true},
            {"iyy", 1, inertia, true}, {"iyz", 1, inertia, true}, {"izz", 1, inertia, true}};
  }
  if (element == "color") return {{"rgba", 4, R{0.0, 1.0, false, false}, true}};
  return {};
}

/// Every number under the <link>, <joint> and <material> children of <robot>, walked
/// with an explicit stack (depth is bounded by the pre-check, but nothing here relies
/// on it). Fields read "link[NAME]/collision[0]/geometry/box@size".
void check_numbers(const XmlSource& src, const TiXmlElement* robot) {
  struct Item {
    const TiXmlElement* e;
    std::string field;
  };
  std::vector<Item> stack;
  for (const TiXmlElement* top = robot->FirstChildElement(); top != nullptr;
       top = top->NextSiblingElement()) {
    const std::string tag = top->Value();
    if (tag != "link" && tag != "joint" && tag != "material") continue;
    stack.push_back({top, tag + "[" + attr_or_empty(top, "name") + "]"});
  }
  std::reverse(stack.begin(), stack.end());  // errors in file order
  while (!stack.empty()) {
    const Item item = std::move(stack.back());
    stack.pop_back();
    std::vector<Item> children;
    std::map<std::string, int> index;
    for (const TiXmlElement* c = item.e->FirstChildElement(); c != nullptr;
         c = c->NextSiblingElement()) {
      const std::string tag = c->Value();
      std::string field = item.field + "/" + tag;
      if (tag == "collision" || tag == "visual") {
        // Appended piece by piece: GCC 12 sees a false -Wrestrict in "[" + n + "]".
        field += '[';
        field += std::to_string(index[tag]++);
        field += ']';
      }
      for (const auto& a : numeric_attributes(tag, item.e->Value()))
        (void)internal::checked_numbers(src.at(c), field + "@" + a.name, c->Attribute(a.name),
                                        a.count, a.range, a.required);
      children.push_back({c, std::move(field)});
    }
    for (auto it = children.rbegin(); it != children.rend(); ++it) stack.push_back(std::move(*it));
  }
}

// ---------------------------------------------------------------- pass 1: structure

/// A <ferret role=".."/> marker: the role and where it was written.
struct RoleMark {
  std::string role;
  std::string at;  ///< file:line
};

/// A mesh collision element, read in pass 1 (urdfdom knows no line numbers).
struct MeshBox {
  Eigen::AlignedBox3d box_C;  ///< the scaled vertices' bounds in the collision frame C
  std::string path;           ///< the resolved file
};

struct Structure {
  std::map<std::pair<std::string, int>, MeshBox> meshes;     ///< (link, collision index)
  std::vector<std::pair<std::string, RoleMark>> link_roles;  ///< (link, marker), URDF order
  std::map<std::string, std::string> joint_at;               ///< joint name -> file:line
  std::map<std::string, std::string> link_at;                ///< link name -> file:line
  std::map<std::string, std::size_t> collisions;             ///< link -> <collision> count
};

bool contains(const std::vector<std::string>& list, const std::string& item) {
  return std::find(list.begin(), list.end(), item) != list.end();
}

std::string join(const std::vector<std::string>& list) {
  std::string out;
  for (const auto& item : list) out += (out.empty() ? "" : ", ") + item;
  return out;
}

/// The <ferret role=".."/> children of a sensor or link; roles outside `allowed` fail
/// with `hint` (where such a role goes instead).
std::vector<RoleMark> read_role_marks(const XmlSource& src, const TiXmlElement* e,
                                      const std::string& field,
                                      const std::vector<std::string>& allowed,
                                      const std::string& hint) {
  std::vector<RoleMark> marks;
  for (const TiXmlElement* m = e->FirstChildElement("ferret"); m != nullptr;
       m = m->NextSiblingElement("ferret")) {
    const std::string role = attr_or_empty(m, "role");
    if (!contains(allowed, role))
      src.fail(m, field + "/ferret@role", "a role: one of " + join(allowed) + hint,
               quoted(m->Attribute("role")));
    marks.push_back({role, src.at(m)});
  }
  return marks;
}

/// Meshes larger than this are refused before assimp reads them (about 1.3 million
/// triangles of binary STL; robot collision meshes are far smaller).
constexpr std::uintmax_t kMaxMeshBytes = std::uintmax_t{64} << 20;

/// Raw vertex bounds of each mesh file read so far: a URDF naming one file in many
/// collisions reads it once.
using MeshCache = std::map<std::string, Eigen::AlignedBox3d>;

MeshBox read_mesh(const XmlSource& src, const TiXmlElement* mesh, const std::string& field,
                  const std::filesystem::path& urdf_dir, MeshCache& cache) {
  const std::string filename = attr_or_empty(mesh, "filename");
  if (filename.empty())
    src.fail(mesh, field + "@filename", "a mesh file (package://, file:// or a path)");
  Eigen::Vector3d scale = Eigen::Vector3d::Ones();
  if (const char* text = mesh->Attribute("scale")) {
    const auto values = parse_numbers(text);
    bool ok = values && values->size() == 3;
    if (ok)
      for (const double v : *values) ok = ok && v != 0.0;
    if (!ok) src.fail(mesh, field + "@scale", "three non-zero numbers", quoted(text));
    scale = Eigen::Vector3d((*values)[0], (*values)[1], (*values)[2]);
  }
  std::vector<std::string> tried;
  const auto path = internal::resolve_mesh_path(filename, urdf_dir, tried);
  if (path.empty())
    src.fail(mesh, field + "@filename", "a mesh file that exists (tried " + join(tried) + ")",
             quoted(filename.c_str()));
  std::error_code ec;
  if (const auto bytes = std::filesystem::file_size(path, ec); !ec && bytes > kMaxMeshBytes)
    src.fail(mesh, field + "@filename", "a mesh file of at most 64 MiB",
             "'" + internal::printable(path.string()) + "': " + std::to_string(bytes) + " bytes");
  Eigen::AlignedBox3d raw;
  try {
    const auto known = cache.find(path.string());
    raw = known != cache.end()
              ? known->second
              : cache.emplace(path.string(), internal::mesh_vertex_bounds(path)).first->second;
  } catch (const std::exception& e) {
    std::string why = e.what();
    for (char& c : why)
      if (c == '\n' || c == '\r') c = ' ';
    src.fail(mesh, field + "@filename",
             "a mesh file assimp can read (STL, OBJ, DAE, ...) with vertices",
             "'" + path.string() + "': " + why);
  }
  // Scaling is per axis about C's origin; a negative factor mirrors, so take both corners.
  MeshBox out;
  out.path = path.string();
  out.box_C.setEmpty();
  out.box_C.extend(raw.min().cwiseProduct(scale));
  out.box_C.extend(raw.max().cwiseProduct(scale));
  const Eigen::Vector3d size = out.box_C.sizes();
  if ((size.array() <= 0.0).any())
    src.fail(mesh, field + "@filename", "a mesh with extent along x, y and z",
             "'" + path.string() + "': bounding box " + num(size.x()) + " x " + num(size.y()) +
                 " x " + num(size.z()) + " m");
  return out;
}

/// More links or joints than this are refused before urdfdom builds its tree (whose
/// shared_ptr links are freed recursively); a chain is thus at most 1000 links deep.
constexpr std::size_t kMaxLinks = 1000;
constexpr std::size_t kMaxJoints = 1000;

const std::vector<std::string>& joint_types() {
  static const std::vector<std::string> types{"revolute", "continuous", "prismatic",
                                              "fixed",    "floating",   "planar"};
  return types;
}

/// Sensors are matched by name pairwise (urdfdom and Gazebo declarations): bounded so
/// the matching stays small.
constexpr std::size_t kMaxSensors = 1000;

/// Counts the <link>, <joint> and sensor elements of <robot> against their limits.
void check_counts(const XmlSource& src, const TiXmlElement* robot) {
  std::size_t sensors = 0;
  auto count_sensor = [&](const TiXmlElement* e) {
    if (++sensors > kMaxSensors)
      src.fail(e, "sensor[" + attr_or_empty(e, "name") + "]",
               "a robot of at most " + std::to_string(kMaxSensors) + " sensors",
               "<sensor> number " + std::to_string(sensors));
  };
  for (const TiXmlElement* e = robot->FirstChildElement("sensor"); e != nullptr;
       e = e->NextSiblingElement("sensor"))
    count_sensor(e);
  for (const TiXmlElement* g = robot->FirstChildElement("gazebo"); g != nullptr;
       g = g->NextSiblingElement("gazebo"))
    for (const TiXmlElement* e = g->FirstChildElement("sensor"); e != nullptr;
         e = e->NextSiblingElement("sensor"))
      count_sensor(e);
  for (const auto& [tag, limit] : {std::pair<std::string, std::size_t>{"link", kMaxLinks},
                                   std::pair<std::string, std::size_t>{"joint", kMaxJoints}}) {
    std::size_t count = 0;
    for (const TiXmlElement* e = robot->FirstChildElement(tag); e != nullptr;
         e = e->NextSiblingElement(tag))
      if (++count > limit)
        src.fail(e, tag + "[" + attr_or_empty(e, "name") + "]",
                 "a robot of at most " + std::to_string(limit) + " " + tag + "s",
                 "<" + tag + "> number " + std::to_string(count));
  }
}

/// <robot name=".." version="1.0">, and unique top-level <material> names: urdfdom's
/// checks, named at their element.
void check_robot_element(const XmlSource& src, const TiXmlElement* robot) {
  if (attr_or_empty(robot, "name").empty())
    src.fail(robot, "robot@name", "a robot name", "nothing");
  if (const char* version = robot->Attribute("version")) {
    // urdfdom 3.0 reads "MAJOR.MINOR" and supports only 1.0.
    const std::string v = version;
    const auto dot = v.find('.');
    auto digits = [](const std::string& t) {
      return !t.empty() && t.size() < 9 &&
             std::all_of(t.begin(), t.end(), [](char c) { return c >= '0' && c <= '9'; });
    };
    const bool ok = dot != std::string::npos && digits(v.substr(0, dot)) &&
                    digits(v.substr(dot + 1)) && std::stoi(v.substr(0, dot)) == 1 &&
                    std::stoi(v.substr(dot + 1)) == 0;
    if (!ok)
      src.fail(robot, "robot@version", "version 1.0 (the only one urdfdom reads)", quoted(version));
  }
  std::map<std::string, std::string> materials;
  for (const TiXmlElement* m = robot->FirstChildElement("material"); m != nullptr;
       m = m->NextSiblingElement("material")) {
    const std::string name = attr_or_empty(m, "name");
    if (name.empty()) src.fail(m, "material@name", "a material name", "nothing");
    if (const auto [it, fresh] = materials.emplace(name, src.at(m)); !fresh)
      src.fail(m, "material[" + name + "]", "a unique material name (first at " + it->second + ")",
               "a duplicate");
  }
}

/// The joints' checks urdfdom would otherwise report only on its console.
void check_joint(const XmlSource& src, const TiXmlElement* joint, const std::string& field) {
  const char* type = joint->Attribute("type");
  if (type == nullptr || !contains(joint_types(), type))
    src.fail(joint, field + "@type", "a joint type: one of " + join(joint_types()),
             type == nullptr ? "nothing" : "'" + internal::printable(type) + "'");
  const TiXmlElement* limit = joint->FirstChildElement("limit");
  const std::string t = type;
  if (limit == nullptr && (t == "revolute" || t == "prismatic"))
    src.fail(joint, field + "/limit",
             "a <limit effort=\"..\" velocity=\"..\"/> (a " + t + " joint needs one)", "none");
  if (limit != nullptr) {
    const auto lower = parse_number(limit->Attribute("lower"));
    const auto upper = parse_number(limit->Attribute("upper"));
    if (lower && upper && *upper < *lower)
      src.fail(limit, field + "/limit@upper", "a number >= lower (" + num(*lower) + ")",
               quoted(limit->Attribute("upper")));
  }
}

Structure check_structure(const XmlSource& src, const TiXmlElement* robot,
                          const std::filesystem::path& urdf_dir) {
  Structure out;
  MeshCache mesh_cache;
  std::set<std::string> links;
  std::vector<std::string> link_names;  // file order
  std::map<std::string, const TiXmlElement*> link_element;
  for (const TiXmlElement* link = robot->FirstChildElement("link"); link != nullptr;
       link = link->NextSiblingElement("link")) {
    const std::string name = attr_or_empty(link, "name");
    if (name.empty()) src.fail(link, "link@name", "a link name");
    if (!links.insert(name).second)
      src.fail(link, "link[" + name + "]", "a unique link name", "a duplicate");
    link_names.push_back(name);
    link_element[name] = link;
    out.link_at[name] = src.at(link);
    // urdfdom drops what it cannot parse in a link (a <visual> without geometry takes
    // the link's collisions with it): name it here instead.
    int visual = 0;
    for (const TiXmlElement* vis = link->FirstChildElement("visual"); vis != nullptr;
         vis = vis->NextSiblingElement("visual"), ++visual) {
      const std::string field = "link[" + name + "]/visual[" + std::to_string(visual) + "]";
      const TiXmlElement* geometry = vis->FirstChildElement("geometry");
      const TiXmlElement* shape = geometry != nullptr ? geometry->FirstChildElement() : nullptr;
      const std::string type = shape != nullptr ? shape->Value() : "";
      if (type != "box" && type != "cylinder" && type != "sphere" && type != "mesh")
        src.fail(vis, field + "/geometry", "a <geometry> with a box, cylinder, sphere or mesh",
                 shape == nullptr ? "none" : "<" + internal::printable(type) + ">");
    }
    if (const TiXmlElement* inertial = link->FirstChildElement("inertial")) {
      for (const char* child : {"mass", "inertia"})
        if (inertial->FirstChildElement(child) == nullptr)
          src.fail(inertial, "link[" + name + "]/inertial/" + child,
                   std::string("a <") + child + "> in the <inertial>", "none");
    }
    for (auto& mark : read_role_marks(src, link, "link[" + name + "]", frame_role_names(),
                                      " (sensor roles go inside the <sensor>)"))
      out.link_roles.emplace_back(name, std::move(mark));
    int index = 0;
    for (const TiXmlElement* col = link->FirstChildElement("collision"); col != nullptr;
         col = col->NextSiblingElement("collision"), ++index) {
      const std::string field = "link[" + name + "]/collision[" + std::to_string(index) + "]";
      const TiXmlElement* geometry = col->FirstChildElement("geometry");
      const TiXmlElement* shape = geometry != nullptr ? geometry->FirstChildElement() : nullptr;
      if (shape == nullptr)
        src.fail(col, field + "/geometry", "a <geometry> with a box, cylinder, sphere or mesh");
      const std::string type = shape->Value();
      const std::string shape_field = field + "/geometry/" + type;
      // Box, cylinder and sphere sizes were checked with every other number.
      ++out.collisions[name];
      if (type == "mesh") {
        out.meshes[{name, index}] = read_mesh(src, shape, shape_field, urdf_dir, mesh_cache);
      } else if (type != "box" && type != "cylinder" && type != "sphere") {
        src.fail(shape, field + "/geometry", "a box, cylinder, sphere or mesh", "<" + type + ">");
      }
    }
  }
  if (links.empty()) src.fail(robot, "robot", "at least one <link>");

  // One tree: every link the child of at most one joint, one root, no cycle.
  std::map<std::string, std::string> parent_of;  // child link -> parent link
  std::map<std::string, std::string> joint_of;   // child link -> its joint
  std::map<std::string, const TiXmlElement*> joint_element;
  std::map<std::string, std::vector<std::string>> children_of;
  for (const TiXmlElement* joint = robot->FirstChildElement("joint"); joint != nullptr;
       joint = joint->NextSiblingElement("joint")) {
    const std::string name = attr_or_empty(joint, "name");
    if (name.empty()) src.fail(joint, "joint@name", "a joint name");
    const std::string field = "joint[" + name + "]";
    if (out.joint_at.count(name) > 0)
      src.fail(joint, field, "a unique joint name (first at " + out.joint_at[name] + ")",
               "a duplicate");
    out.joint_at[name] = src.at(joint);
    joint_element[name] = joint;
    check_joint(src, joint, field);
    std::string ends[2];
    for (int i = 0; i < 2; ++i) {
      const char* role = i == 0 ? "parent" : "child";
      const TiXmlElement* e = joint->FirstChildElement(role);
      const std::string link = e != nullptr ? attr_or_empty(e, "link") : std::string();
      if (link.empty())
        src.fail(e != nullptr ? e : joint, field + "/" + role + "@link", "the name of a link");
      if (links.count(link) == 0)
        src.fail(e, field + "/" + role + "@link", "the name of a <link> in this file",
                 "'" + link + "'");
      ends[i] = link;
    }
    const auto& [parent, child] = ends;
    if (parent == child)
      src.fail(joint, field + "/child@link", "a link other than the parent (a joint cycle)",
               "'" + child + "'");
    if (const auto first = joint_of.find(child); first != joint_of.end())
      src.fail(joint->FirstChildElement("child"), field + "/child@link",
               "a link that is the child of one joint only (it is the child of joint '" +
                   first->second + "' at " + out.joint_at[first->second] + ")",
               "'" + child + "'");
    parent_of[child] = parent;
    joint_of[child] = name;
    children_of[parent].push_back(child);
  }

  std::vector<std::string> roots;
  for (const auto& name : link_names)
    if (parent_of.count(name) == 0) roots.push_back(name);
  if (roots.size() > 1)
    src.fail(link_element[roots[1]], "link[" + roots[1] + "]",
             "one root link: every other link the child of a joint (the root is '" + roots[0] +
                 "' at " + src.at(link_element[roots[0]]) + ")",
             "a second link without a parent joint");
  // Links a walk from the root does not reach hang below a cycle of joints.
  std::set<std::string> reached;
  std::vector<std::string> stack(roots.begin(), roots.end());
  while (!stack.empty()) {
    const std::string link = stack.back();
    stack.pop_back();
    if (!reached.insert(link).second) continue;
    if (const auto it = children_of.find(link); it != children_of.end())
      stack.insert(stack.end(), it->second.begin(), it->second.end());
  }
  for (const auto& name : link_names) {
    if (reached.count(name) > 0) continue;
    // Parents from here repeat within links.size() steps: that is the cycle.
    std::vector<std::string> path{name};
    std::set<std::string> seen{name};
    for (std::string at = parent_of.at(name); seen.insert(at).second; at = parent_of.at(at))
      path.push_back(at);
    // parent_of(path.back()) is on the path: the cycle, written parent -> child.
    const std::string start = parent_of.at(path.back());
    std::string shown = start;
    for (auto it = path.rbegin(); *it != start; ++it) shown += " -> " + *it;
    shown += " -> " + start;
    const std::string joint = joint_of.at(start);
    src.fail(joint_element.at(joint), "joint[" + joint + "]",
             "a kinematic tree (no cycle of joints)", "the cycle " + internal::printable(shown));
  }
  return out;
}

// ---------------------------------------------------------------- pass 2: urdfdom

/// Collects console_bridge messages instead of printing them.
class CapturingOutput : public console_bridge::OutputHandler {
 public:
  void log(const std::string& text, console_bridge::LogLevel level, const char* /*filename*/,
           int /*line*/) override {
    if (level >= console_bridge::CONSOLE_BRIDGE_LOG_WARN) messages.push_back(text);
  }
  std::vector<std::string> messages;
};

std::mutex& console_mutex() {
  static std::mutex m;
  return m;
}

urdf::ModelInterfaceSharedPtr parse_with_urdfdom(const XmlSource& src, const std::string& xml) {
  CapturingOutput output;
  urdf::ModelInterfaceSharedPtr model;
  std::string exception;
  {
    // console_bridge's handler is process-wide: one parse at a time swaps it.
    const std::lock_guard lock(console_mutex());
    console_bridge::useOutputHandler(&output);
    try {
      model = urdf::parseURDF(xml);
    } catch (const std::exception& e) {
      exception = e.what();
    }
    console_bridge::restorePreviousOutputHandler();
  }
  if (model) return model;
  std::string why = !exception.empty()        ? exception
                    : output.messages.empty() ? ""
                                              : output.messages.front();
  for (char& c : why)
    if (c == '\n' || c == '\r') c = ' ';
  throw InputError(src.source(), "robot", "a URDF that urdfdom accepts",
                   why.empty() ? "urdfdom rejected it" : "urdfdom: " + why);
}

Pose3 to_pose(const urdf::Pose& p) {
  Pose3 X = Pose3::Identity();
  X.translation() = Eigen::Vector3d(p.position.x, p.position.y, p.position.z);
  X.linear() = Eigen::Quaterniond(p.rotation.w, p.rotation.x, p.rotation.y, p.rotation.z)
                   .normalized()
                   .toRotationMatrix();
  return X;
}

/// X_BL of every link at zero joint positions, walking the tree from the root with an
/// explicit stack (a chain is as deep as it has links).
void place_links(const urdf::ModelInterface& model, const urdf::LinkConstSharedPtr& root,
                 std::map<std::string, Pose3>& X_B) {
  std::vector<std::pair<urdf::LinkConstSharedPtr, Pose3>> stack{{root, Pose3::Identity()}};
  while (!stack.empty()) {
    const auto [link, X_BL] = stack.back();
    stack.pop_back();
    if (!X_B.emplace(link->name, X_BL).second) continue;  // urdfdom made it a tree; be sure
    for (const auto& joint : link->child_joints) {
      const auto child = model.getLink(joint->child_link_name);
      if (child) stack.emplace_back(child, X_BL * to_pose(joint->parent_to_joint_origin_transform));
    }
  }
}

// ---------------------------------------------------------------- pass 3: sensors

/// One value of a sensor, with where it was read (for errors and conflicts).
struct SensorValue {
  double value = 0.0;
  std::string at;     ///< file:line
  std::string field;  ///< element path
};

/// A sensor as declared in one or two places (urdfdom <sensor>, Gazebo block).
struct SensorSpec {
  enum class Kind { kCamera, kDepth, kRay, kOther };
  std::string name;
  std::string link;
  Kind kind = Kind::kOther;
  std::string at, field;  ///< the first declaration
  std::optional<Pose3> X_LS;
  std::string pose_at, pose_field;
  std::map<std::string, SensorValue> values;  ///< keys: see value_names()
  bool from_urdf = false, from_gazebo = false;
  std::vector<RoleMark> roles;  ///< its <ferret role> markers
  /// Gazebo <camera><distortion> / <lens><intrinsics>: where, when given.
  std::string distortion_at, distortion_field, intrinsics_at, intrinsics_field;
};

std::vector<RoleMark> sensor_role_marks(const XmlSource& src, const TiXmlElement* e,
                                        const std::string& field) {
  return read_role_marks(src, e, field, sensor_role_names(), " (frame roles go inside the <link>)");
}

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

bool same_value(double a, double b) { return std::abs(a - b) <= 1e-9 * std::max(1.0, std::abs(a)); }

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

// ---------------------------------------------------------------- roles, provenance

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

const char* kind_name(SensorSpec::Kind kind) {
  switch (kind) {
    case SensorSpec::Kind::kCamera:
      return "a colour camera";
    case SensorSpec::Kind::kDepth:
      return "a depth camera";
    case SensorSpec::Kind::kRay:
      return "a range (ray) sensor";
    case SensorSpec::Kind::kOther:
      break;
  }
  return "a sensor that is no camera or range sensor";
}

/// The sensor kind a role needs.
SensorSpec::Kind role_kind(const std::string& role) {
  if (role == kRoleDepthCamera) return SensorSpec::Kind::kDepth;
  if (role == kRoleIr) return SensorSpec::Kind::kRay;
  return SensorSpec::Kind::kCamera;  // object_camera, marker_camera
}

bool single_role(const std::string& role) {
  return role != kRoleIr && role != kRoleTetherAttachment;
}

/// Roles from the <ferret role> markers, replaced role by role by the mission's
/// `roles: {ROBOT: {...}}` entries; every role checked for the kind of sensor it needs.
void assign_roles(const XmlSource& src, const std::vector<SensorSpec>& specs,
                  const Structure& structure, const std::vector<std::string>& links,
                  const MissionConfig& mission, RobotDescription& out) {
  struct Holder {
    std::string name;
    std::string at;  ///< where the role was given: file:line, or the mission file
  };
  std::map<std::string, std::vector<Holder>> holders;
  for (const auto& s : specs)
    for (const auto& m : s.roles) holders[m.role].push_back({s.name, m.at});
  for (const auto& [link, m] : structure.link_roles) holders[m.role].push_back({link, m.at});
  std::map<std::string, std::string> from;  // role -> provenance
  for (const auto& [role, list] : holders) from[role] = "urdf:" + list.front().at;

  const auto mission_roles = mission.roles.find(out.name);
  if (mission_roles != mission.roles.end()) {
    const std::string source = mission.source.empty() ? "mission" : mission.source;
    for (const auto& [role, names] : mission_roles->second) {
      const std::string field = "roles." + out.name + "." + role;
      const bool sensor_role = contains(sensor_role_names(), role);
      std::vector<std::string> choices;
      if (sensor_role)
        for (const auto& s : specs) choices.push_back(s.name);
      else
        choices = links;
      auto& list = holders[role];
      list.clear();
      for (const auto& name : names) {
        if (!contains(choices, name))
          throw InputError(source, field,
                           std::string("the name of a ") + (sensor_role ? "sensor" : "link") +
                               " of " + src.source() + ": one of " + join(choices),
                           "'" + name + "'");
        list.push_back({name, source});
      }
      from[role] = "mission:" + source;
    }
  }

  for (const auto& [role, list] : holders) {
    if (list.empty()) continue;
    if (single_role(role) && list.size() > 1)
      throw InputError(list[1].at, "role[" + role + "]",
                       "one sensor or link with the role " + role + " (given to '" + list[0].name +
                           "' at " + list[0].at + ")",
                       "also '" + list[1].name + "'");
    if (contains(sensor_role_names(), role)) {
      for (const auto& h : list) {
        const auto spec = std::find_if(specs.begin(), specs.end(),
                                       [&](const SensorSpec& s) { return s.name == h.name; });
        if (spec->kind != role_kind(role))
          throw InputError(h.at, "sensor[" + h.name + "]/role[" + role + "]",
                           std::string(kind_name(role_kind(role))) + " for the role " + role,
                           std::string(kind_name(spec->kind)) + " '" + h.name + "'");
      }
    }
    auto& names = out.roles[role];
    for (const auto& h : list) names.push_back(h.name);
    out.provenance["roles." + role] = from[role];
  }

  // Frames of the link roles, in URDF link order for tether attachments.
  auto frame_of = [&](const std::string& name) { return Frame{name, out.frames.at(name)}; };
  auto one = [&](std::string_view role, std::optional<Frame>& slot) {
    const auto it = out.roles.find(std::string(role));
    if (it != out.roles.end()) slot = frame_of(it->second.front());
  };
  one(kRoleEpm, out.epm);
  one(kRoleImu, out.imu);
  one(kRoleWinchSpool, out.winch_spool);
  if (const auto it = out.roles.find(std::string(kRoleTetherAttachment)); it != out.roles.end())
    for (const auto& name : it->second) out.tether_attachments.push_back(frame_of(name));

  // The IR array's values follow from its sensors'.
  if (const auto it = out.roles.find(std::string(kRoleIr)); it != out.roles.end()) {
    std::string range, fov;
    for (const auto& name : it->second) {
      const auto r = out.provenance.find("range_sensors." + name + ".range_max_m");
      const auto f = out.provenance.find("range_sensors." + name + ".fov");
      if (r != out.provenance.end()) range += (range.empty() ? "" : ", ") + r->second;
      if (f != out.provenance.end()) fov += (fov.empty() ? "" : ", ") + f->second;
    }
    out.provenance["ir_array.range_max_m"] = range + " (the smallest)";
    out.provenance["ir_array.fov"] = fov + " (spans and poses together)";
  }
}

// ---------------------------------------------------------------- geometry, roles

void read_collision_shapes(const urdf::ModelInterface& model,
                           const std::map<std::string, Pose3>& X_BL, const Structure& structure,
                           RobotDescription& out) {
  for (const auto& [name, link] : model.links_) {
    const auto pose = X_BL.find(name);
    if (pose == X_BL.end()) continue;
    // A collision urdfdom dropped without a word would silently shrink the robot.
    const auto expected = structure.collisions.find(name);
    const std::size_t declared = expected == structure.collisions.end() ? 0 : expected->second;
    if (link->collision_array.size() != declared)
      throw InputError(structure.link_at.at(name), "link[" + name + "]/collision",
                       std::to_string(declared) + " <collision> elements urdfdom reads",
                       "urdfdom read " + std::to_string(link->collision_array.size()));
    int index = -1;
    for (const auto& col : link->collision_array) {
      ++index;  // urdfdom keeps a link's <collision> elements in file order
      if (!col || !col->geometry) continue;
      CollisionShape s;
      s.link = name;
      s.X_BS = pose->second * to_pose(col->origin);
      switch (col->geometry->type) {
        case urdf::Geometry::MESH: {
          const auto mesh = structure.meshes.find({name, index});
          if (mesh == structure.meshes.end()) continue;
          // The box around the mesh, centred on S: X_BS = X_BC * translation(centre in C).
          s.type = CollisionShape::Type::kBox;
          s.box_size_m = mesh->second.box_C.sizes();
          s.X_BS = s.X_BS * Eigen::Translation3d(mesh->second.box_C.center());
          s.mesh = mesh->second.path;
          break;
        }
        case urdf::Geometry::BOX: {
          const auto& d = static_cast<const urdf::Box&>(*col->geometry).dim;
          s.type = CollisionShape::Type::kBox;
          s.box_size_m = Eigen::Vector3d(d.x, d.y, d.z);
          break;
        }
        case urdf::Geometry::CYLINDER: {
          const auto& c = static_cast<const urdf::Cylinder&>(*col->geometry);
          s.type = CollisionShape::Type::kCylinder;
          s.radius_m = c.radius;
          s.length_m = c.length;
          break;
        }
        case urdf::Geometry::SPHERE:
          s.type = CollisionShape::Type::kSphere;
          s.radius_m = static_cast<const urdf::Sphere&>(*col->geometry).radius;
          break;
        default:
          continue;  // rejected in check_structure
      }
      out.collision_shapes.push_back(s);
    }
  }
}

/// Links are kept in URDF order for shapes and roles, so dumps are stable.
std::vector<std::string> link_order(const TiXmlElement* robot) {
  std::vector<std::string> names;
  for (const TiXmlElement* l = robot->FirstChildElement("link"); l != nullptr;
       l = l->NextSiblingElement("link"))
    names.push_back(attr_or_empty(l, "name"));
  return names;
}

bool is_wheel_joint(const urdf::Joint& j) {
  return (j.type == urdf::Joint::CONTINUOUS || j.type == urdf::Joint::REVOLUTE) &&
         j.child_link_name.find("wheel") != std::string::npos;
}

void read_limits(const urdf::ModelInterface& model, const MissionConfig& mission,
                 const Structure& structure, RobotDescription& out) {
  bool has_wheels = false;
  std::string wheel_note;
  for (const auto& [name, joint] : model.joints_) {
    if (!joint || !is_wheel_joint(*joint)) continue;
    has_wheels = true;
    if (!joint->limits || joint->limits->velocity <= 0.0) continue;
    const auto link = model.getLink(joint->child_link_name);
    for (const auto& col : link->collision_array) {
      if (!col || !col->geometry || col->geometry->type != urdf::Geometry::CYLINDER) continue;
      const double r = static_cast<const urdf::Cylinder&>(*col->geometry).radius;
      const double v = joint->limits->velocity * r;
      if (!out.wheel_speed_limit_mps || v < *out.wheel_speed_limit_mps) {
        out.wheel_speed_limit_mps = v;
        wheel_note = "urdf:" + structure.joint_at.at(name) + " (joint " + name + ": " +
                     num(joint->limits->velocity) + " rad/s x wheel radius " + num(r) + " m)";
      }
      break;
    }
  }
  out.kind = has_wheels ? RobotKind::kUgv : RobotKind::kUav;
  out.limits = has_wheels ? mission.ugv_limits : mission.uav_limits;
  const std::string section = has_wheels ? "ugv_limits." : "uav_limits.";
  for (const char* key : {"max_velocity_mps", "max_acceleration_mps2", "max_yaw_rate_radps"})
    out.provenance[std::string("motion_limits.") + key] = mission.provenance(section + key);
  if (out.wheel_speed_limit_mps) {
    out.provenance["motion_limits.wheel_speed_limit_mps"] = wheel_note;
    if (*out.wheel_speed_limit_mps < out.limits.max_velocity_mps) {
      out.limits.max_velocity_mps = *out.wheel_speed_limit_mps;
      out.provenance["motion_limits.max_velocity_mps"] = wheel_note;
    }
  }
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
                                const MissionConfig& mission) {
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
                                               const MissionConfig& mission) {
  try {
    return describe_robot(urdf_xml, source, mission);
  } catch (const InputError& e) {
    rethrow_printable(e);
  }
}

RobotDescription load_robot(const std::string& urdf_or_name, const MissionConfig& mission) {
  for (const char* name : {"miniugv", "m100"})
    if (urdf_or_name == name || urdf_or_name == std::string(name) + ".urdf")
      return load_robot_description(find_model(std::string(name) + ".urdf"), mission);
  return load_robot_description(urdf_or_name, mission);
}

RobotDescription load_robot_description(const std::filesystem::path& urdf_path,
                                        const MissionConfig& mission) {
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
