// Pass 1 of the URDF loader, structure: with TinyXML, what urdfdom accepts silently or
// reports only on its console: element counts past their limits, the <robot> element,
// joints, links (their visuals, inertials, collisions and role markers) and one
// kinematic tree. Errors carry file:line.

#include <algorithm>
#include <map>
#include <set>

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

}  // namespace

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

namespace {

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

}  // namespace

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

}  // namespace ferret::internal
