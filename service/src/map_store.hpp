#pragma once
// The planner service's map store: maps as immutable snapshots, each with the setups
// its plans need cached, and the one thread every map is built on. No HTTP types here.

#include <chrono>
#include <condition_variable>
#include <cstddef>
#include <deque>
#include <functional>
#include <future>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <thread>
#include <unordered_map>
#include <vector>

#include "ferret/planning/collision_map.hpp"
#include "ferret/planning/planning_world.hpp"
#include "ferret/planning/uav_approach.hpp"
#include "ferret/planning/ugv_path.hpp"

namespace ferret::internal {

// Maps: immutable snapshots. A PUT swaps the pointer; a plan running on the old map
// keeps it alive until it finishes. Each map keeps the setups its plans need (the
// distance field and tether corners of a hidden space, a UAV geofence's snapshot),
// built once by the first request that needs one; later ones wait for it.

struct MapEntry {
  MapEntry() = default;
  MapEntry(const MapEntry&) = delete;
  MapEntry& operator=(const MapEntry&) = delete;
  ~MapEntry();  // map_store.cpp says why it trims
  std::string name, format;
  std::size_t bytes = 0;
  PlanningWorld world;
  std::string loaded_at;  // ISO 8601, UTC

  template <typename Setup>
  struct Cache {
    std::mutex mutex;
    std::deque<std::string> order;
    std::unordered_map<std::string, std::shared_future<std::shared_ptr<const Setup>>> setups;
  };
  Cache<UgvPathSetup> ugv;
  Cache<UavApproachSetup> uav;
  // The collision maps validations built, by their options: building one is most of a
  // validation (0.76 s of 0.77 for a UAV plan on the default world).
  struct ValidationMap {
    std::shared_ptr<const CollisionMap> map;
  };
  Cache<ValidationMap> validation;
};

constexpr std::size_t kSetupsPerMap = 16;

// Keeps `future` under `key` (the cache's mutex held), the oldest setup making room.
template <typename Setup>
void keep_setup(MapEntry::Cache<Setup>& cache, const std::string& key,
                std::shared_future<std::shared_ptr<const Setup>> future) {
  if (cache.order.size() >= kSetupsPerMap) {
    cache.setups.erase(cache.order.front());
    cache.order.pop_front();
  }
  cache.setups.emplace(key, std::move(future));
  cache.order.push_back(key);
}

template <typename Setup, typename Make>
std::shared_ptr<const Setup> cached_setup(MapEntry::Cache<Setup>& cache, const std::string& key,
                                          Make make) {
  std::promise<std::shared_ptr<const Setup>> promise;
  std::shared_future<std::shared_ptr<const Setup>> future;
  bool build = false;
  {
    const std::lock_guard lock(cache.mutex);
    const auto it = cache.setups.find(key);
    if (it != cache.setups.end()) {
      future = it->second;
    } else {
      future = promise.get_future().share();
      keep_setup(cache, key, future);
      build = true;
    }
  }
  if (build) {
    try {
      promise.set_value(std::make_shared<const Setup>(make()));
    } catch (...) {
      promise.set_exception(std::current_exception());
      const std::lock_guard lock(cache.mutex);  // a bad request is not kept
      cache.setups.erase(key);
      cache.order.erase(std::find(cache.order.begin(), cache.order.end(), key));
    }
  }
  return future.get();
}

// Puts a setup another request built into `cache` (unless one is there already).
template <typename Setup>
void offer_setup(MapEntry::Cache<Setup>& cache, const std::string& key, Setup setup) {
  std::promise<std::shared_ptr<const Setup>> promise;
  promise.set_value(std::make_shared<const Setup>(std::move(setup)));
  const std::lock_guard lock(cache.mutex);
  if (!cache.setups.count(key)) keep_setup(cache, key, promise.get_future().share());
}

/// Now as ISO 8601, UTC ("2024-05-01T12:00:00Z").
std::string utc_now();
/// 1 to 64 letters, digits, '_', '-' or '.'.
bool valid_map_name(const std::string& name);

// Every map is built on this one thread, which also hands freed memory back to the
// system every few seconds. A map is millions of small blocks that live as
// long as it does; built on whichever HTTP thread took the PUT, they land in the malloc
// arenas where plans make their short-lived blocks, and a replaced map's holes there stay
// partly in use: over a 10-minute soak with the map replaced every 3 s the resident
// memory crept by 5 %. On one thread (with an arena of its own, ferret-plannerd's main
// allows one a thread), each new map fills the holes the last but one left.
class MapBuilder {
 public:
  MapBuilder() : thread_([this] { run(); }) {
    std::unique_lock lock(mutex_);
    cv_.wait(lock, [&] { return ready_; });  // its arena is taken before the HTTP threads start
  }
  ~MapBuilder() {
    {
      const std::lock_guard lock(mutex_);
      stop_ = true;
    }
    cv_.notify_all();
    thread_.join();
  }
  MapBuilder(const MapBuilder&) = delete;
  MapBuilder& operator=(const MapBuilder&) = delete;

  /// Runs `work` on the builder's thread and returns what it returns (or throws what it threw).
  template <typename Work>
  auto run_here(Work work) -> decltype(work()) {
    auto task = std::make_shared<std::packaged_task<decltype(work())()>>(std::move(work));
    auto result = task->get_future();
    {
      const std::lock_guard lock(mutex_);
      tasks_.emplace_back([task] { (*task)(); });
    }
    cv_.notify_all();
    return result.get();
  }

 private:
  void run();  // the builder thread: tasks, and a trim when idle

  static constexpr std::chrono::seconds kTrimEvery{5};
  std::mutex mutex_;
  std::condition_variable cv_;
  std::vector<std::function<void()>> tasks_;
  bool ready_ = false, stop_ = false;
  std::thread thread_;  // last: started once the members above exist
};

// The map in a body: an OctoMap file (by its header line) or a world YAML; or a
// map_server map as its YAML's text and its image's bytes (`map_2d`), the YAML's
// `image` key never opened (a request must not make the service read its files).
// InputError naming `source` (for a map_server map: "yaml" or "image") when the
// bytes are not a map.
struct Map2DUpload {
  std::string yaml, image;                                   // the YAML's text, the image's bytes
  std::string yaml_source = "yaml", image_source = "image";  // what errors name
};
struct MapUpload {
  std::string body;
  std::optional<Map2DUpload> map_2d;
};

}  // namespace ferret::internal
