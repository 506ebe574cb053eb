#include "ferret/mission/ugv_mission_log.hpp"

#include <algorithm>
#include <cmath>

namespace ferret {
namespace {

constexpr long kPoseEvery = 2;    // ticks (0.1 s at the 20 Hz IR rate)
constexpr long kPathEvery = 20;   // 1 s
constexpr long kMapsEvery = 100;  // 5 s
const RgbaColor kPathColor{0.85, 0.1, 0.75, 1.0};
const RgbaColor kFoundColor{1.0, 0.8, 0.0, 1.0};
const RgbaColor kTruthColor{0.9, 0.0, 0.0, 0.6};

}  // namespace

UgvMissionTickHook UgvMissionRecorder::hook() {
  return [this](double t_s, const MiniUgvMission& mission, const SimUgvBase& base) {
    last_t_s_ = t_s;
    const Pose2 pose = base.odometry();
    if (ticks_ % kPoseEvery == 0) {
      log_.transform(t_s, "map", "ugv", pose);
      path_.emplace_back(pose.x_m, pose.y_m, 0.0);
    }
    if (ticks_ % kPathEvery == 0) log_.line(t_s, "/ugv/path", "map", "path", path_, kPathColor);
    if (ticks_ % kMapsEvery == 0 && mission.started())
      maps(t_s, mission.explore_controller().grid(), mission.explore_controller().objects());
    ++ticks_;
  };
}

void UgvMissionRecorder::transition(const Transition& t) {
  log_.log(t.t_s, t.component, t.from + " -> " + t.to + (t.reason.empty() ? "" : ": " + t.reason));
}

void log_search_maps(FoxgloveLog& log, double t_s, const IrGrid& g, const ObjectMap& o,
                     const std::string& prefix, const std::string& frame) {
  const GridGeometry& geo = g.geometry();
  std::vector<std::uint8_t> occupancy(geo.size()), object(geo.size());
  for (int j = 0; j < geo.height; ++j)
    for (int i = 0; i < geo.width; ++i) {
      const Cell c{i, j};
      const std::size_t idx = geo.index(c);
      const GridLabel label = g.label(c);
      occupancy[idx] = label == GridLabel::kFree ? 0 : label == GridLabel::kOccupied ? 100 : 50;
      object[idx] =
          static_cast<std::uint8_t>(std::lround(std::clamp(o.probability(c), 0.0, 1.0) * 100));
    }
  log.grid(t_s, prefix + "/G", frame, geo.origin_x_m, geo.origin_y_m, geo.resolution_m, geo.width,
           geo.height, occupancy, "occupancy");
  log.grid(t_s, prefix + "/O", frame, geo.origin_x_m, geo.origin_y_m, geo.resolution_m, geo.width,
           geo.height, object, "object_probability");
}

void UgvMissionRecorder::maps(double t_s, const IrGrid& g, const ObjectMap& o) {
  log_search_maps(log_, t_s, g, o);
}

std::string UgvMissionRecorder::finish(const UgvMissionRunResult& result,
                                       const std::optional<Eigen::Vector2d>& object_W) {
  const double t = std::max(last_t_s_, result.time_s);
  log_.line(t, "/ugv/path", "map", "path", path_, kPathColor);
  if (result.grid && result.objects) maps(t, *result.grid, *result.objects);  // the final maps
  if (result.found_W)
    log_.marker(t, "/objects", "map", "found", {result.found_W->x(), result.found_W->y(), 0.1}, 0.2,
                kFoundColor, "found (O > lambda2)");
  if (object_W)
    log_.marker(t, "/objects", "map", "truth", {object_W->x(), object_W->y(), 0.1}, 0.2,
                kTruthColor, "object (simulator truth)");
  return log_.finish();
}

}  // namespace ferret
