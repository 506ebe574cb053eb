// Pass 0 of the URDF loader, numbers: every number under the <link>, <joint> and
// <material> children of <robot>, checked by the URDF specification's count and range
// for its attribute (checked_number.cpp does the check).

#include <algorithm>
#include <map>

#include "loader_passes.hpp"

namespace ferret::internal {

namespace {

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

}  // namespace

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

}  // namespace ferret::internal
