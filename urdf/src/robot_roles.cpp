// The roles of a robot's sensors and links (camera for objects, IR array, EPM, winch
// spool, ...): from the URDF's <ferret role> markers, replaced role by role by the
// mission's, each checked for the kind of sensor it needs; the frames of the link roles.

#include <algorithm>

#include "loader_passes.hpp"

namespace ferret::internal {

namespace {

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

}  // namespace

/// Roles from the <ferret role> markers, replaced role by role by the mission's
/// `roles: {ROBOT: {...}}` entries; every role checked for the kind of sensor it needs.
void assign_roles(const XmlSource& src, const std::vector<SensorSpec>& specs,
                  const Structure& structure, const std::vector<std::string>& links,
                  const RobotMissionSettings& mission, RobotDescription& out) {
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

}  // namespace ferret::internal
