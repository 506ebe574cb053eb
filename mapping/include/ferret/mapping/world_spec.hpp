#pragma once
// The parsed world description (docs/maps_and_worlds.md): solid geometry as
// primitives, hidden spaces (closed cavities with one small opening) with their
// markers and entry points, the objects inside them, and the drop zone. Free of
// OctoMap types: the UAV search, the planners and the simulator read it directly;
// world_octree.hpp turns it into voxels.

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "ferret/core/pose.hpp"
#include "ferret/perception/marker_family.hpp"

namespace ferret {

/// A box rotated about the vertical axis only.
struct OrientedBox {
  Eigen::Vector3d center_m = Eigen::Vector3d::Zero();
  Eigen::Vector3d size_m = Eigen::Vector3d::Ones();  ///< full edge lengths along the box's own axes
  double yaw_rad = 0.0;

  /// True when the point lies inside or on the box.
  [[nodiscard]] bool contains(const Eigen::Vector3d& p_W) const;
};

/// An upright cylinder standing on `base_z_m`.
struct VerticalCylinder {
  Eigen::Vector2d center_m = Eigen::Vector2d::Zero();
  double base_z_m = 0.0;
  double radius_m = 0.5;
  double height_m = 1.0;

  [[nodiscard]] bool contains(const Eigen::Vector3d& p_W) const;
};

/// The ground: a plane z = height_m + slope_x * x + slope_y * y; solid below.
struct GroundSpec {
  double height_m = 0.0;
  double slope_x = 0.0;  ///< dz/dx
  double slope_y = 0.0;  ///< dz/dy

  [[nodiscard]] double height_at(double x_m, double y_m) const {
    return height_m + slope_x * x_m + slope_y * y_m;
  }
};

/// Which wall of a hidden space holds the opening, in the space's own frame
/// (+x is the wall facing the space's local x direction).
enum class WallSide : std::uint8_t { kPlusX, kMinusX, kPlusY, kMinusY };

/// A fiducial marker (ArUco or AprilTag): a black square of side `size_m` whose frame
/// M has z out of the printed face, x to the right and y up in the image of the marker
/// (OpenCV's convention).
struct FiducialMarker {
  int id = 0;
  double size_m = 0.15;
  MarkerDictionary dictionary;  ///< default: ArUco DICT_4X4_50
  Pose3 X_WM = Pose3::Identity();
};

/// A closed cavity: a box-shaped enclosure (walls and roof of `wall_thickness_m`)
/// around a free interior, entered only through an opening of
/// `opening_width_m` x `opening_height_m` at floor level in one wall. The frame H
/// is centred on the interior in plan, at floor height, x along the space.
struct HiddenSpace {
  std::string name;
  Pose2 X_WH;              ///< interior centre and heading in plan
  double floor_z_m = 0.0;  ///< interior floor height (world z)
  Eigen::Vector3d interior_size_m{12.0, 8.0, 0.4};
  double wall_thickness_m = 0.1;
  WallSide opening_wall = WallSide::kMinusX;
  double opening_width_m = 0.15;
  double opening_height_m = 0.07;
  double opening_offset_m = 0.0;  ///< along the wall from its centre (towards +y or +x of H)
  FiducialMarker marker;
  Eigen::Vector3d p_WE =
      Eigen::Vector3d::Zero();  ///< entry: bottom centre of the opening, outer face
  double entry_yaw_rad = 0.0;   ///< heading that drives from E into the interior

  /// The solids of the enclosure (roof, walls with the opening cut out), as boxes.
  [[nodiscard]] std::vector<OrientedBox> solids() const;
  /// True for a point of the free interior (including the opening's tunnel through the wall).
  [[nodiscard]] bool interior_contains(const Eigen::Vector3d& p_W) const;
  /// Axis-aligned world box around the whole enclosure (walls, roof, floor slab).
  [[nodiscard]] Eigen::AlignedBox3d outer_bounds_m() const;
  /// Position of a point given in H (x, y in the interior frame, z above the floor).
  [[nodiscard]] Eigen::Vector3d to_world(const Eigen::Vector3d& p_H) const;
};

/// An object to be found; a solid box resting on the floor of its hidden space.
struct WorldObject {
  std::string name;
  int hidden_space = -1;  ///< index into WorldSpec::hidden_spaces, -1 when lying outside
  OrientedBox box;        ///< in world coordinates
  [[nodiscard]] Eigen::Vector3d p_WO() const { return box.center_m; }
};

/// Where the UAV drops a retrieved object: a disc on the ground.
struct DropZone {
  Eigen::Vector2d center_m = Eigen::Vector2d::Zero();
  double radius_m = 1.0;
};

/// Seeded random boxes on the ground of a region (debris around the structures).
struct RubbleSpec {
  std::uint64_t seed = 1;
  int count = 0;
  Eigen::Vector2d region_min_m = Eigen::Vector2d::Zero(), region_max_m = Eigen::Vector2d::Zero();
  Eigen::Vector3d size_min_m{0.2, 0.2, 0.1}, size_max_m{1.0, 1.0, 0.6};
  double clearance_m = 1.0;  ///< kept free around hidden spaces and the drop zone
};

struct WorldSpec {
  std::filesystem::path source;  ///< the YAML it came from (for messages)
  std::string name;
  double resolution_m = 0.05;
  Eigen::Vector3d bounds_min_m{-10.0, -10.0, -0.5};
  Eigen::Vector3d bounds_max_m{10.0, 10.0, 3.0};  ///< z: the ceiling of known free space
  GroundSpec ground;
  std::vector<OrientedBox> boxes;
  std::vector<VerticalCylinder> cylinders;
  std::vector<HiddenSpace> hidden_spaces;
  std::vector<WorldObject> objects;
  std::optional<DropZone> drop_zone;
  std::vector<RubbleSpec> rubble_specs;
  std::vector<OrientedBox> rubble;  ///< generated from rubble_specs (deterministic)

  /// Every solid box: boxes, rubble, objects and the hidden spaces' enclosures.
  [[nodiscard]] std::vector<OrientedBox> solid_boxes() const;
  /// Ground truth: is the point solid (ground, a box, a cylinder, an enclosure,
  /// rubble or an object)? Points outside the bounds are not solid.
  [[nodiscard]] bool is_solid(const Eigen::Vector3d& p_W) const;
  [[nodiscard]] bool in_bounds(const Eigen::Vector3d& p_W) const;
  /// Index of the hidden space by name, or -1.
  [[nodiscard]] int find_hidden_space(const std::string& name) const;
};

/// Loads and checks a world YAML. Throws InputError naming the file and dotted
/// field for a wrong type, an unknown key, a non-positive size, coordinates outside
/// OctoMap's key range, an object outside its hidden space, and so on.
[[nodiscard]] WorldSpec load_world(const std::filesystem::path& yaml_path);

/// Same, from YAML text; `source` names it in errors.
[[nodiscard]] WorldSpec parse_world(const std::string& yaml_text, const std::string& source);

}  // namespace ferret
