#pragma once
// A run's log as Foxglove reads it: an MCAP file (mcap_writer.hpp) whose channels
// carry Foxglove's well-known message types, JSON-encoded with their JSON schemas —
// poses as foxglove.FrameTransform, maps as foxglove.Grid, paths and markers as
// foxglove.SceneUpdate, state transitions as foxglove.Log. Open the file in Foxglove
// and the 3D panel shows the robots moving over the maps; the Log panel the
// transitions. Times are simulated (or robot) seconds from the run's start.

#include <Eigen/Core>
#include <cstdint>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "ferret/core/pose.hpp"

namespace ferret {

class McapWriter;

struct RgbaColor {
  double r = 1.0, g = 1.0, b = 1.0, a = 1.0;
};

class FoxgloveLog {
 public:
  FoxgloveLog();
  ~FoxgloveLog();
  FoxgloveLog(const FoxgloveLog&) = delete;
  FoxgloveLog& operator=(const FoxgloveLog&) = delete;

  /// The pose of `child` in `parent` (topic /tf).
  void transform(double t_s, const std::string& parent, const std::string& child,
                 const Pose3& X_PC);
  /// A planar pose at height z.
  void transform(double t_s, const std::string& parent, const std::string& child, const Pose2& X_PC,
                 double z_m = 0.0);
  /// A 2D grid of one uint8 field `field` (row-major from the origin corner, x fastest)
  /// in `frame`, its corner at (origin_x, origin_y).
  void grid(double t_s, const std::string& topic, const std::string& frame, double origin_x_m,
            double origin_y_m, double resolution_m, int width, int height,
            const std::vector<std::uint8_t>& values, const std::string& field);
  /// A polyline (scene entity `id` on `topic`, replacing its earlier version).
  void line(double t_s, const std::string& topic, const std::string& frame, const std::string& id,
            const std::vector<Eigen::Vector3d>& points, const RgbaColor& color,
            double thickness_m = 0.03);
  /// A sphere with a text label above it.
  void marker(double t_s, const std::string& topic, const std::string& frame, const std::string& id,
              const Eigen::Vector3d& p, double diameter_m, const RgbaColor& color,
              const std::string& label);
  /// One log line (topic /log): level 1 debug, 2 info, 3 warning, 4 error.
  void log(double t_s, const std::string& name, const std::string& text, int level = 2);

  [[nodiscard]] std::uint64_t message_count() const;
  /// The MCAP file's bytes; the log is spent afterwards.
  [[nodiscard]] std::string finish();

 private:
  std::uint16_t channel(const std::string& topic, const std::string& schema);

  std::unique_ptr<McapWriter> writer_;
  std::map<std::string, std::uint16_t> schemas_, channels_;
};

/// Seconds to MCAP nanoseconds (negative and non-finite times clamp to 0).
[[nodiscard]] std::uint64_t to_nanoseconds(double t_s);

}  // namespace ferret
