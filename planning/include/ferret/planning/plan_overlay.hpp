#pragma once
// A plan drawn on a map picture (`ferret render --plan`): the path, start and goal,
// heading ticks, and for a miniUGV plan the tether's entry point, the wrap points it
// takes on the way and the tether at the goal, each with a legend entry.

#include <cstddef>
#include <string>

#include "ferret/mapping/map_render.hpp"
#include "ferret/mapping/occupancy_map_2d.hpp"
#include "ferret/planning/plan_file.hpp"

namespace ferret {

/// The overlay's colours (also the legend's).
struct PlanOverlayStyle {
  Rgb path{200, 0, 160};        ///< polyline and heading ticks
  Rgb start{0, 190, 0};         ///< filled dot
  Rgb goal{120, 40, 230};       ///< filled square
  Rgb tether{0, 160, 170};      ///< the taut tether at the goal
  Rgb entry{0, 110, 120};       ///< the entry point E (diamond)
  Rgb wrap{255, 190, 0};        ///< wrap points (rings)
  double tick_spacing_px = 14;  ///< heading ticks at states at least this far apart
};

struct PlanOverlaySummary {
  std::size_t states = 0;
  std::size_t outside = 0;     ///< states outside the map (clipped, not drawn)
  std::size_t wraps = 0;       ///< distinct wrap points the replayed tether took on the way
  std::size_t goal_wraps = 0;  ///< wrap points of the tether at the goal
  double tether_taut_m = 0.0;  ///< taut tether length at the goal (0 without a tether)
  double length_m = 0.0;       ///< path length in the plane
  /// "15 states, 22.3 m", the tether at the goal for a miniUGV plan ("tether 10.51 m
  /// taut at the goal, 1 wrap point (5 on the way)") and, when some states lie outside,
  /// "; 3 of 15 states outside the map".
  [[nodiscard]] std::string describe() const;
};

/// Draws `plan` on `canvas`. Parts outside the canvas's map are clipped: a plan that
/// leaves the window is drawn where it lies inside and the summary counts the rest
/// (the caller says so in the title). A miniUGV plan's tether is replayed from its
/// entry and initial wraps with the taut-tether model against the occupied cells of
/// `obstacles` (unknown cells do not wrap it): the pictured map, or when that is a
/// window, the whole slice it was cut from, so that corners outside the window
/// still hold the tether.
PlanOverlaySummary draw_plan(MapCanvas& canvas, const PlanFile& plan,
                             const OccupancyMap2D& obstacles, const PlanOverlayStyle& style = {});

}  // namespace ferret
