#pragma once
// Generated hidden spaces for the object search (docs/object_search.md, "Generated
// hidden spaces"): a walled floor plan with rooms behind partitions with doors,
// pillars, boxes and debris, the miniUGV's start by the left wall facing +x, and the
// five zones defined the paper's way relative to the start. Deterministic in the seed
// on every machine (ferret's own random numbers).
//
// The zones assume the paper's sensors (camera 90 deg, IR 30 deg, both 4 m):
//   1: ahead, x 1.2-3.8 m, |y| <= 0.3 m: inside both cones;
//   2, 4: left / right, x 2.0-3.2 m, |y| 1.0-1.8 m: outside the IR cone, inside the
//         camera's cone and range;
//   3, 5: left / right of the heading beyond x 4.5 m: out of both sensors' reach.
// (x, y relative to the start, x along its heading.) Nothing is placed in zones 1, 2
// and 4 or between them and the start but, in dense spaces, a few thin pillars, as
// in the paper's cluttered map.

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "ferret/core/pose.hpp"
#include "ferret/mapping/occupancy_map_2d.hpp"

namespace ferret {

/// A zone of a hidden space's map, where the experiment samples objects (an axis-aligned
/// rectangle in the map's frame, m).
struct ZoneSpec {
  int id = 0;
  double xmin_m = 0, ymin_m = 0, xmax_m = 0, ymax_m = 0;
};

enum class HiddenSpaceClutter { kSparse, kDense };

[[nodiscard]] const char* to_string(HiddenSpaceClutter clutter);
/// "sparse" or "dense"; nullopt for anything else.
[[nodiscard]] std::optional<HiddenSpaceClutter> parse_hidden_space_clutter(const std::string& text);

struct HiddenSpaceGeneratorOptions {
  std::uint64_t seed = 1;
  double width_m = 12.0;       ///< along the start's heading, [8, 64]
  double height_m = 8.0;       ///< across it, [5, 64]
  double resolution_m = 0.05;  ///< [0.02, 0.2]
  HiddenSpaceClutter clutter = HiddenSpaceClutter::kSparse;
  /// Every place a robot of this radius can stand on stays reachable from the start, so
  /// no passage is narrower than twice it (plus a cell). The search keeps its paths
  /// 0.15 m from what its IR grid holds (ugv/path_follower.hpp) and sees walls a cell
  /// or two thick: with 0.1 m (the miniUGV's half diagonal) rooms behind a 0.3 m gap
  /// were found by no method, the oracle included.
  double robot_radius_m = 0.25;
};

struct GeneratedHiddenSpace {
  OccupancyMap2D map;
  Pose2 start;
  std::vector<ZoneSpec> zones;  ///< ids 1..5
  HiddenSpaceGeneratorOptions options;
  /// The map YAML's `search` section: start, zones and the generator's settings.
  [[nodiscard]] std::string search_yaml() const;
};

/// Throws InputError (source "generate-hidden", the option as field) for sizes or a
/// resolution outside the ranges above or not finite.
[[nodiscard]] GeneratedHiddenSpace generate_hidden_space(
    const HiddenSpaceGeneratorOptions& options);

}  // namespace ferret
