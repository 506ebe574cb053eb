#include "ferret/uav/coverage_pattern.hpp"

#include <algorithm>
#include <cmath>

#include "ferret/perception/marker_family.hpp"

namespace ferret {
namespace {

// The cells across the black square of the marker min_marker_side_px was set for
// (ArUco 4x4 with its border), which the search's range scales from.
constexpr double kSearchMarkerCells = 6.0;

// Legs of a boustrophedon over the area at height z: along x (legs stepping in y),
// or along y; consecutive legs run opposite ways, so each way of a pass is flown on
// every other leg.
void add_pass(std::vector<Eigen::Vector3d>& out, const Eigen::Vector4d& a, double spacing, double z,
              bool along_x) {
  const double lo = along_x ? a[1] : a[0], hi = along_x ? a[3] : a[2];
  const double from = along_x ? a[0] : a[1], to = along_x ? a[2] : a[3];
  const int legs = std::max(1, static_cast<int>(std::ceil((hi - lo) / spacing)));
  const double step = (hi - lo) / legs;
  for (int i = 0; i < legs; ++i) {
    const double c = lo + (i + 0.5) * step;
    const double s = (i % 2 == 0) ? from : to, e = (i % 2 == 0) ? to : from;
    out.emplace_back(along_x ? s : c, along_x ? c : s, z);
    out.emplace_back(along_x ? e : c, along_x ? c : e, z);
  }
}

}  // namespace

CoveragePattern::CoveragePattern(const Eigen::Vector4d& area_m, double altitude_m, int passes,
                                 double leg_spacing_m)
    : leg_spacing_m_(leg_spacing_m) {
  add_pass(waypoints_, area_m, leg_spacing_m_, altitude_m, true);
  first_pass_end_ = waypoints_.size();
  if (passes > 1) add_pass(waypoints_, area_m, leg_spacing_m_, altitude_m, false);
}

double CoveragePattern::camera_leg_spacing_m(const MarkerDetectorOptions& marker,
                                             const CameraModel& marker_camera) {
  // A 4x4 marker (6 cells across its black square) spans min_marker_side_px at
  // d_max; it is decoded reliably up to about two thirds of that. What the decoder
  // needs is pixels a cell, so a marker of more cells is read nearer: d_max is where
  // the cells span min_marker_side_px / 6 px each (tag36h11's 8 cells: 3/4 of a 4x4
  // marker's range; docs/mission.md). Seen from a leg flying at it, it must lie within
  // the camera's half-width at about half that range (a wall marker near the ground
  // leaves the pitched camera's view when the UAV comes closer); every other leg flies
  // each way, so legs are one reach apart.
  const int cells = marker_bitmap(marker.dictionary, 0).black_square_cells;
  const double d_max_m =
      marker_camera.fx_px * marker.marker_size_m /
      (std::max(1.0, marker.min_marker_side_px) * std::max(1, cells) / kSearchMarkerCells);
  const double half_fov = std::atan2(0.5 * marker_camera.width_px, marker_camera.fx_px);
  return std::clamp(0.5 * d_max_m * std::tan(half_fov), 1.0, 50.0);
}

}  // namespace ferret
