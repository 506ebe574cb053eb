// The helpers every pass of the URDF loader uses (loader_passes.hpp).

#include "loader_passes.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <sstream>

#include "xml_check.hpp"

// GCC 12 reports -Wrestrict falsely on inlined std::string concatenation such as
// "'" + printable(text) (GCC PR 105329); this file's messages are built that way.
// Clang has no such warning (and would refuse the pragma under -Werror).
#if defined(__GNUC__) && !defined(__clang__)
#pragma GCC diagnostic ignored "-Wrestrict"
#endif

namespace ferret::internal {

std::string num(double v) { return fmt::format("{}", v); }

std::string quoted(const char* text) {
  return text == nullptr ? "nothing" : "'" + internal::printable(text) + "'";
}

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

bool contains(const std::vector<std::string>& list, const std::string& item) {
  return std::find(list.begin(), list.end(), item) != list.end();
}

std::string join(const std::vector<std::string>& list) {
  std::string out;
  for (const auto& item : list) out += (out.empty() ? "" : ", ") + item;
  return out;
}

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

Pose3 to_pose(const urdf::Pose& p) {
  Pose3 X = Pose3::Identity();
  X.translation() = Eigen::Vector3d(p.position.x, p.position.y, p.position.z);
  X.linear() = Eigen::Quaterniond(p.rotation.w, p.rotation.x, p.rotation.y, p.rotation.z)
                   .normalized()
                   .toRotationMatrix();
  return X;
}

}  // namespace ferret::internal
