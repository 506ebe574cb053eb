// The planner service's map store (map_store.hpp): maps loaded, looked up, described.

#include <fmt/format.h>
#include <malloc.h>
#include <octomap/OcTree.h>

#include <algorithm>
#include <cctype>
#include <ctime>

#include "ferret/core/error.hpp"
#include "ferret/mapping/occupancy_map_2d.hpp"
#include "ferret/mapping/world_octree.hpp"
#include "ferret/mapping/world_spec.hpp"
#include "planner_service_impl.hpp"

namespace ferret {
namespace internal {

// A map is millions of small nodes, built on whichever HTTP thread took the PUT, so
// in whichever malloc arena that thread uses. glibc keeps a freed map's pages in its
// arena; over many replacements every arena holds one and the service's memory grows
// with the number of threads. Trimming returns them to the system.
MapEntry::~MapEntry() {
  world = {};
  ugv.setups.clear();
  uav.setups.clear();
  validation.setups.clear();
  malloc_trim(0);
}

std::string utc_now() {
  const std::time_t t = std::time(nullptr);
  std::tm tm{};
  gmtime_r(&t, &tm);
  char buf[32];
  std::strftime(buf, sizeof buf, "%Y-%m-%dT%H:%M:%SZ", &tm);
  return buf;
}

bool valid_map_name(const std::string& name) {
  if (name.empty() || name.size() > 64) return false;
  return std::all_of(name.begin(), name.end(), [](unsigned char c) {
    return std::isalnum(c) || c == '_' || c == '-' || c == '.';
  });
}

void MapBuilder::run() {
  std::unique_lock lock(mutex_);
  tasks_.reserve(4);  // a first allocation: this thread's arena, now
  ready_ = true;
  cv_.notify_all();
  auto next_trim = std::chrono::steady_clock::now() + kTrimEvery;
  for (;;) {
    cv_.wait_until(lock, next_trim, [&] { return stop_ || !tasks_.empty(); });
    if (stop_ && tasks_.empty()) return;
    if (tasks_.empty()) {
      // Plans free all they take, but the pages stay with the arena of the thread that
      // freed them: without a trim the resident memory grew 374 -> 576 MiB in two
      // minutes at 2500 plans/s on one map while the heap in use stayed at 190 MiB.
      lock.unlock();
      malloc_trim(0);
      lock.lock();
      next_trim = std::chrono::steady_clock::now() + kTrimEvery;
      continue;
    }
    auto task = std::move(tasks_.front());
    tasks_.erase(tasks_.begin());
    lock.unlock();
    task();
    lock.lock();
  }
}

}  // namespace internal

namespace {

using internal::ApiError;
using internal::cached_setup;
using internal::json;
using internal::MapEntry;
using internal::utc_now;

}  // namespace

std::shared_ptr<MapEntry> PlannerService::Impl::find_map(const std::string& name) const {
  const std::lock_guard lock(maps_mutex);
  const auto it = maps.find(name);
  if (it == maps.end())
    throw ApiError{
        404, "UNKNOWN_MAP",
        fmt::format("map: no map called '{}' (PUT /v1/maps/{{name}} first)", printable(name, 64)),
        "map"};
  return it->second;
}

std::size_t PlannerService::Impl::map_count() const {
  const std::lock_guard lock(maps_mutex);
  return maps.size();
}

std::shared_ptr<MapEntry> PlannerService::Impl::load_map(const std::string& name,
                                                         const MapUpload& upload,
                                                         const std::string& source) {
  auto entry = std::make_shared<MapEntry>();
  entry->name = name;
  entry->loaded_at = utc_now();
  const std::string& body = upload.body;
  const bool bt = body.rfind("# Octomap OcTree binary file", 0) == 0;
  const bool ot = !bt && body.rfind("# Octomap OcTree file", 0) == 0;
  if (upload.map_2d) {
    const Map2DUpload& u = *upload.map_2d;
    entry->bytes = u.yaml.size() + u.image.size();
    entry->format = "map_server";
    const MapServerMeta meta = parse_map_server_meta(u.yaml, u.yaml_source);
    Map2DExtrusion extrusion;
    extrusion.max_voxels = options.max_map_nodes;
    entry->world = planning_world_from_map_2d(
        map_from_image(meta, decode_map_image(u.image, u.image_source)), u.yaml_source, extrusion);
  } else if (bt || ot) {
    entry->bytes = body.size();
    entry->format = bt ? "octomap_bt" : "octomap_ot";
    entry->world.tree = parse_octree(body, bt, source);
  } else {
    entry->bytes = body.size();
    if (first_invalid_utf8(body) != std::string::npos)
      throw InputError(
          source, "",
          "an OctoMap file (it starts '# Octomap OcTree') or a world YAML (UTF-8 text)");
    entry->format = "world_yaml";
    WorldSpec spec = parse_world(body, source);
    WorldBuildOptions build;
    build.max_nodes = options.max_map_nodes;
    entry->world.tree = build_world_octree(spec, build);
    entry->world.spec = std::move(spec);
  }
  entry->world.source = "maps/" + name;
  // Each hidden space's setup now, so the first plans there are as quick as the rest.
  if (entry->world.spec)
    for (const HiddenSpace& h : entry->world.spec->hidden_spaces) {
      UgvPathRequest r = ugv_defaults();
      r.hidden_space = h.name;
      const HiddenSpaceFrame space = ugv_request_space(entry->world, r);
      (void)cached_setup(entry->ugv, ugv_key(space), [&] {
        metrics.record_setup_built("ugv");
        return prepare_ugv_path(entry->world, r, space);
      });
    }
  return entry;
}

json PlannerService::Impl::map_metadata(const MapEntry& m) const {
  const octomap::OcTree& t = *m.world.tree;
  json j{{"name", m.name},
         {"format", m.format},
         {"bytes", m.bytes},
         {"loaded_at", m.loaded_at},
         {"resolution_m", t.getResolution()},
         {"nodes", t.size()}};
  if (t.size() > 0) {
    double x0, y0, z0, x1, y1, z1;
    t.getMetricMin(x0, y0, z0);
    t.getMetricMax(x1, y1, z1);
    j["known_bounds_m"] = {x0, y0, z0, x1, y1, z1};
  }
  json spaces = json::array();
  if (m.world.spec)
    for (const HiddenSpace& h : m.world.spec->hidden_spaces) {
      const HiddenSpaceFrame f = hidden_space_frame(h);
      spaces.push_back({{"name", h.name},
                        {"floor_z_m", f.floor_z_m},
                        {"bounds_xy_m", {f.lo_m.x(), f.lo_m.y(), f.hi_m.x(), f.hi_m.y()}},
                        {"entry_m", {f.p_WE.x(), f.p_WE.y()}}});
    }
  j["hidden_spaces"] = spaces;
  if (m.world.map_2d) {
    const GridGeometry& g = *m.world.map_2d;
    const HiddenSpaceFrame f = map_2d_frame(g);
    j["map_2d"] = {{"origin_m", {g.origin_x_m, g.origin_y_m}},
                   {"resolution_m", g.resolution_m},
                   {"width", g.width},
                   {"height", g.height},
                   {"bounds_xy_m", {f.lo_m.x(), f.lo_m.y(), f.hi_m.x(), f.hi_m.y()}},
                   {"floor_z_m", f.floor_z_m}};
  }
  return j;
}

}  // namespace ferret
