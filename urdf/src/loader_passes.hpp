#pragma once
// What the passes of the URDF loader share (urdf_loader.cpp runs them in order, its
// opening comment says what each does): where an element sits, numbers read from text,
// <ferret role> markers, what the structure pass found, and a sensor as declared.
// Private to ferret::urdf: TinyXML and urdfdom stay behind it.

#include <tinyxml.h>
#include <urdf_model/model.h>
#include <urdf_world/types.h>

#include <Eigen/Geometry>
#include <cstddef>
#include <filesystem>
#include <map>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "checked_number.hpp"
#include "ferret/core/error.hpp"
#include "ferret/urdf/robot_description.hpp"

namespace ferret::internal {

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
std::string num(double v);
/// 'text' made printable, or "nothing".
std::string quoted(const char* text);
/// Whitespace-separated finite decimal numbers; nullopt when any token is not one.
std::optional<std::vector<double>> parse_numbers(const char* text);
/// Exactly one number, or nullopt.
std::optional<double> parse_number(const char* text);
std::string attr_or_empty(const TiXmlElement* e, const char* name);
bool contains(const std::vector<std::string>& list, const std::string& item);
/// "a, b, c".
std::string join(const std::vector<std::string>& list);

/// Where a URDF's positions may lie and how its angles are written.
inline const internal::NumberRange kPosition{-1e3, 1e3, false, false, "metres"};
inline const internal::NumberRange kAngle{-kInf, kInf, false, false, "radians"};

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

/// The <ferret role=".."/> children of a sensor or link; roles outside `allowed` fail
/// with `hint` (where such a role goes instead).
std::vector<RoleMark> read_role_marks(const XmlSource& src, const TiXmlElement* e,
                                      const std::string& field,
                                      const std::vector<std::string>& allowed,
                                      const std::string& hint);

/// Raw vertex bounds of each mesh file read so far: a URDF naming one file in many
/// collisions reads it once.
using MeshCache = std::map<std::string, Eigen::AlignedBox3d>;

/// A urdfdom pose as a Pose3.
Pose3 to_pose(const urdf::Pose& p);

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

// Pass 0, numbers (urdf_numbers.cpp).
void check_numbers(const XmlSource& src, const TiXmlElement* robot);

// Pass 1, structure (urdf_structure.cpp; meshes in collision_shapes.cpp).
void check_counts(const XmlSource& src, const TiXmlElement* robot);
void check_robot_element(const XmlSource& src, const TiXmlElement* robot);
Structure check_structure(const XmlSource& src, const TiXmlElement* robot,
                          const std::filesystem::path& urdf_dir);
MeshBox read_mesh(const XmlSource& src, const TiXmlElement* mesh, const std::string& field,
                  const std::filesystem::path& urdf_dir, MeshCache& cache);

// Pass 2, urdfdom (kinematic_tree.cpp; its collisions in collision_shapes.cpp).
urdf::ModelInterfaceSharedPtr parse_with_urdfdom(const XmlSource& src, const std::string& xml);
void place_links(const urdf::ModelInterface& model, const urdf::LinkConstSharedPtr& root,
                 std::map<std::string, Pose3>& X_B);
void read_collision_shapes(const urdf::ModelInterface& model,
                           const std::map<std::string, Pose3>& X_BL, const Structure& structure,
                           RobotDescription& out);

// Pass 3, sensors: as declared (sensor_blocks.cpp), as cameras and range sensors
// (sensor_models.cpp).
SensorSpec read_urdf_sensor(const XmlSource& src, const TiXmlElement* e);
SensorSpec read_gazebo_sensor(const XmlSource& src, const TiXmlElement* e, const std::string& link);
void merge_into(SensorSpec& into, const SensorSpec& from);
std::vector<SensorSpec> read_sensors(const XmlSource& src, const TiXmlElement* robot,
                                     const std::map<std::string, Pose3>& X_BL,
                                     RobotDescription& out);
void sensor_provenance(const std::vector<SensorSpec>& specs, RobotDescription& out);

// Motion limits and wheels (motion_limits.cpp), roles (robot_roles.cpp).
void read_limits(const urdf::ModelInterface& model, const RobotMissionSettings& mission,
                 const Structure& structure, RobotDescription& out);
void assign_roles(const XmlSource& src, const std::vector<SensorSpec>& specs,
                  const Structure& structure, const std::vector<std::string>& links,
                  const RobotMissionSettings& mission, RobotDescription& out);

}  // namespace ferret::internal
