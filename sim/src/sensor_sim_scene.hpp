#pragma once
// Private to sensor_sim*.cpp: the world's geometry as ray-castable primitives, the
// per-camera ray tables and the frame cast shared by the camera and depth renderers.

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <array>
#include <cstdint>
#include <functional>
#include <limits>
#include <memory>
#include <mutex>
#include <vector>

#include "ferret/mapping/world_spec.hpp"
#include "ferret/perception/camera_model.hpp"
#include "ferret/perception/marker_family.hpp"

namespace ferret::internal {

inline constexpr double kInf = std::numeric_limits<double>::infinity();
/// Hits nearer than this along a ray are ignored (the ray's own surface).
inline constexpr double kMinHitT = 1e-6;

enum class Material : std::uint8_t { kGround, kStructure, kEnclosure, kRubble, kObject, kCylinder };

struct BoxPrim {
  Eigen::Vector3d center = Eigen::Vector3d::Zero();
  Eigen::Vector3d half = Eigen::Vector3d::Zero();
  double cos_yaw = 1.0, sin_yaw = 0.0;
  Material material = Material::kStructure;
};

struct CylinderPrim {
  Eigen::Vector2d center = Eigen::Vector2d::Zero();
  double z0 = 0.0, z1 = 0.0, radius = 0.0;
};

/// A marker: its bitmap with a white quiet zone of one cell around it, on the plane
/// z_M = 0, seen from its front (+z_M) only.
struct MarkerPrim {
  int hidden_space = -1;
  FiducialMarker marker;
  MarkerBitmap bitmap;
  Pose3 X_MW = Pose3::Identity();
  Eigen::Vector3d p_W = Eigen::Vector3d::Zero(), n_W = Eigen::Vector3d::UnitZ();
  double cell_m = 0.0;         ///< side of one bitmap cell
  double bitmap_half_m = 0.0;  ///< half side of the bitmap
  double quad_half_m = 0.0;    ///< half side with the quiet zone
  /// Reflectance at (x, y) in M (inside the quad): the cell's, or the quiet zone's white.
  [[nodiscard]] float reflectance(double x_m, double y_m) const;
};

/// The convex hull of a primitive as a (possibly flat) box: centre, axes, half sizes.
struct Hull {
  Eigen::Vector3d center = Eigen::Vector3d::Zero();
  Eigen::Matrix3d axes = Eigen::Matrix3d::Identity();  ///< columns
  Eigen::Vector3d half = Eigen::Vector3d::Zero();
};

/// Hit codes: -1 nothing; otherwise kind << 28 | index << 3 | face.
enum class PrimKind : std::int32_t { kGround = 0, kBox = 1, kCylinder = 2, kMarker = 3 };
[[nodiscard]] inline std::int32_t hit_code(PrimKind kind, std::size_t index, int face) {
  return (static_cast<std::int32_t>(kind) << 28) | (static_cast<std::int32_t>(index) << 3) | face;
}
[[nodiscard]] inline PrimKind code_kind(std::int32_t code) { return PrimKind(code >> 28); }
[[nodiscard]] inline std::size_t code_index(std::int32_t code) {
  return static_cast<std::size_t>((code >> 3) & ((1 << 25) - 1));
}
[[nodiscard]] inline int code_face(std::int32_t code) { return code & 7; }

/// The rays of every pixel of one camera (undistorted, normalised: z = 1), and the
/// bounds of 16 x 16 pixel tiles in normalised coordinates.
struct RayTable {
  static constexpr int kTile = 16;
  int width = 0, height = 0, tiles_x = 0, tiles_y = 0;
  std::vector<float> x, y;                      ///< per pixel
  std::vector<std::array<float, 4>> tile_rect;  ///< x0, x1, y0, y1 per tile
  /// The x range of each column of tiles and the y range of each row: a primitive's
  /// tiles are looked for only in the columns and rows its projection meets.
  std::vector<std::array<float, 2>> column_x, row_y;
};

/// What a frame cast leaves per pixel: the ray parameter (= z in C, rays have z = 1)
/// and the hit code.
/// Runs body(k) for k in [0, n), spread over up to `hardware_concurrency` (at most 4)
/// threads, item k on thread k mod T: each item's work must be independent of the
/// others' (a frame's tile rows, its pixel rows), so the result is the same bytes for
/// any number of threads.
void for_each_interleaved(int n, const std::function<void(int)>& body);

struct CastBuffers {
  std::vector<float> t;
  std::vector<std::int32_t> code;
};

/// Pixel i's ray in the world (z = 1 in C): one expression, so that the cast and the
/// shading see the same bits.
[[nodiscard]] inline Eigen::Vector3d ray_direction(const Eigen::Matrix3d& R_WC,
                                                   const RayTable& rays, std::size_t i) {
  return R_WC * Eigen::Vector3d(rays.x[i], rays.y[i], 1.0);
}

struct Scene {
  GroundSpec ground;
  Eigen::Vector3d ground_normal = Eigen::Vector3d::UnitZ();
  Eigen::Vector2d xy_min = Eigen::Vector2d::Zero(), xy_max = Eigen::Vector2d::Zero();
  double z_min = 0.0;
  std::vector<BoxPrim> boxes;
  std::vector<CylinderPrim> cylinders;
  std::vector<MarkerPrim> markers;

  mutable std::mutex cache_mutex;
  mutable std::vector<std::pair<CameraModel, std::shared_ptr<const RayTable>>> ray_cache;

  explicit Scene(const WorldSpec& world);

  /// The camera's ray table, computed once per distinct model (a small cache).
  [[nodiscard]] std::shared_ptr<const RayTable> rays(const CameraModel& camera) const;
  /// Casts every pixel's ray from X_WC; markers only when `with_markers`.
  void cast_frame(const RayTable& rays, const Pose3& X_WC, bool with_markers,
                  CastBuffers& out) const;
  /// Whether a marker could cover a pixel of the frame from X_WC: exactly when
  /// cast_frame with markers would test one at all (some tile's marker bin is not empty).
  [[nodiscard]] bool markers_in_frame(const RayTable& rays, const Pose3& X_WC) const;
  /// The nearest hit of one ray (any direction scale) among ground, boxes, cylinders.
  [[nodiscard]] double cast(const Eigen::Vector3d& o, const Eigen::Vector3d& d,
                            std::int32_t* code) const;
  /// The surface normal at a hit, facing against `d`.
  [[nodiscard]] Eigen::Vector3d normal(std::int32_t code, const Eigen::Vector3d& p_W,
                                       const Eigen::Vector3d& d) const;
};

}  // namespace ferret::internal
