// Collision queries per second in the default world: ferret's checker (distance
// field fast path, FCL near obstacles) against plain FCL octree collide on the same
// queries, and the number of disagreements between the two (must be 0).
//
//   build/<dir>/bench/ferret_bench_collision [--benchmark_filter=...]
//
// Query sets: the UAV, the UAV with the miniUGV on 1.5 m of tether, both at random
// poses over the whole site below 4 m (where the rubble and the structures are); the
// miniUGV at random poses on the floor of the house_void hidden space; and the poses
// the planners actually ask about: the UAV planner on 20 approaches in the default
// world, the miniUGV planner on 20 problems in the 12 x 8 m cellar of
// examples/scenarios/tether_detour.yaml; both again with the robots' URDF shapes
// (urdf/models/m100.urdf, 14 parts; miniugv.urdf, 6 parts), as `ferret plan` uses them.

#include <benchmark/benchmark.h>
#include <fcl/geometry/octree/octree.h>
#include <fcl/geometry/shape/box.h>
#include <fcl/geometry/shape/capsule.h>
#include <fcl/geometry/shape/cylinder.h>
#include <fcl/geometry/shape/sphere.h>
#include <fcl/narrowphase/collision.h>
#include <fcl/narrowphase/collision_object.h>

#include <cstdio>
#include <map>

#include "ferret/core/random.hpp"
#include "ferret/mapping/world_octree.hpp"
#include "ferret/planning/benchmark_problems.hpp"
#include "ferret/planning/collision_checker.hpp"
#include "ferret/planning/ompl_setup.hpp"
#include "ferret/planning/planning_world.hpp"
#include "ferret/planning/uav_planner.hpp"
#include "ferret/urdf/robot_description.hpp"

namespace ferret {
namespace {

constexpr int kQueries = 20000;

struct World {
  WorldSpec spec;
  std::shared_ptr<const octomap::OcTree> tree;
  std::shared_ptr<const CollisionMap> map;
  std::shared_ptr<const CollisionMap> ugv_map;
  HiddenSpaceFrame house;
};

const World& world() {
  static const World w = [] {
    World w;
    w.spec = load_world(std::string(FERRET_SOURCE_DIR) + "/examples/worlds/default.yaml");
    w.tree = build_world_octree(w.spec);
    w.map = CollisionMap::build(*w.tree, uav_map_options(w.spec));
    w.house = hidden_space_frame(w.spec.hidden_spaces.at(0));
    w.ugv_map = ugv_collision_map(*w.tree, w.house);
    return w;
  }();
  return w;
}

// Plain FCL: the source OcTree wrapped as FCL geometry, one object per shape part.
class PlainFcl {
 public:
  PlainFcl(const std::shared_ptr<const octomap::OcTree>& tree, const RobotShape& shape)
      : map_(std::make_shared<fcl::OcTreed>(tree)) {
    map_.computeAABB();
    for (const ShapePart& p : shape.parts) {
      std::shared_ptr<fcl::CollisionGeometryd> g;
      switch (p.kind) {
        case ShapePart::Kind::kBox:
          g = std::make_shared<fcl::Boxd>(p.box_size_m);
          break;
        case ShapePart::Kind::kCylinder:
          g = std::make_shared<fcl::Cylinderd>(p.radius_m, p.length_m);
          break;
        case ShapePart::Kind::kCapsule:
          g = std::make_shared<fcl::Capsuled>(p.radius_m, p.length_m);
          break;
        case ShapePart::Kind::kSphere:
          g = std::make_shared<fcl::Sphered>(p.radius_m);
          break;
      }
      parts_.push_back({p.X_BS, std::make_unique<fcl::CollisionObjectd>(g)});
    }
  }
  bool collides(const Pose3& X_WB) {
    for (auto& [X_BS, obj] : parts_) {
      obj->setTransform(X_WB * X_BS);
      obj->computeAABB();
      fcl::CollisionRequestd req;
      fcl::CollisionResultd res;
      fcl::collide(&map_, obj.get(), req, res);
      if (res.isCollision()) return true;
    }
    return false;
  }

 private:
  fcl::CollisionObjectd map_;
  std::vector<std::pair<Pose3, std::unique_ptr<fcl::CollisionObjectd>>> parts_;
};

struct QuerySet {
  std::string name;
  RobotShape shape;
  std::shared_ptr<const CollisionMap> map;
  std::shared_ptr<const octomap::OcTree> plain_tree;
  std::vector<Pose3> poses;
};

// The shipped URDFs' collision shapes (14 parts for the M100, 6 for the miniUGV).
RobotShape urdf_shape(const char* model, PlanRobot robot) {
  const RobotShape s = robot_shape_from_description(load_robot_description(find_model(model)));
  return plan_robot_shape(robot, 0.0, &s);
}

QuerySet make_set(const std::string& name) {
  const World& w = world();
  QuerySet q;
  q.name = name;
  Rng rng(stable_hash(name.c_str()));
  auto pose = [](double x, double y, double z, double yaw, double tilt) {
    Pose3 X = Pose3::Identity();
    X.translation() = Eigen::Vector3d(x, y, z);
    X.linear() = (Eigen::AngleAxisd(yaw, Eigen::Vector3d::UnitZ()) *
                  Eigen::AngleAxisd(tilt, Eigen::Vector3d::UnitX()))
                     .toRotationMatrix();
    return X;
  };
  if (name == "uav_planner" || name == "uav_urdf_planner") {
    q.shape = name == "uav_planner" ? uav_shape() : urdf_shape("m100.urdf", PlanRobot::kUav);
    q.map = w.map;
    q.plain_tree = w.tree;
    seed_ompl_once(1);
    UavPlannerOptions opt;
    opt.geofence = {{-29.5, -29.5, 0.5}, {29.5, 29.5, 7.5}};
    UavPlanner planner(w.map, q.shape, opt);
    planner.checker().record_queries(&q.poses);
    const auto problems = uav_approach_problems(w.spec, planner.checker(), opt.geofence, 20, 1);
    q.poses.clear();
    for (const auto& p : problems) (void)planner.plan(p.start, p.goal);
    return q;
  }
  if (name == "ugv_planner" || name == "ugv_urdf_planner") {
    static const PlanningWorld cellar = load_planning_world(
        std::string(FERRET_SOURCE_DIR) + "/examples/scenarios/tether_detour.yaml");
    const HiddenSpaceFrame f = hidden_space_frame(cellar.spec->hidden_spaces.at(0));
    q.shape = name == "ugv_planner" ? ugv_shape() : urdf_shape("miniugv.urdf", PlanRobot::kUgv);
    q.map = ugv_collision_map(*cellar.tree, f);
    q.plain_tree = std::shared_ptr<const octomap::OcTree>(q.map, &q.map->tree());
    UgvPlannerOptions opt;
    opt.shape = q.shape;
    UgvPlanner planner(q.map, f, {}, opt);
    const auto problems = ugv_problems(planner, 20, 1);
    planner.checker().record_queries(&q.poses);
    for (const auto& p : problems) {
      UgvPlanRequest req;
      req.start = {p.start.x_m, p.start.y_m, p.start.yaw_rad};
      req.goal = {p.goal.x_m, p.goal.y_m, p.goal.yaw_rad};
      (void)planner.plan(req);
    }
    return q;
  }
  if (name == "ugv") {
    q.shape = ugv_shape();
    q.map = w.ugv_map;
    q.plain_tree = std::shared_ptr<const octomap::OcTree>(w.ugv_map, &w.ugv_map->tree());
    for (int k = 0; k < kQueries; ++k)
      q.poses.push_back(pose(rng.uniform(w.house.lo_m.x(), w.house.hi_m.x()),
                             rng.uniform(w.house.lo_m.y(), w.house.hi_m.y()), w.house.floor_z_m,
                             rng.uniform(-3.1416, 3.1416), 0.0));
  } else {
    q.shape = name == "uav" ? uav_shape() : uav_with_suspended_ugv_shape(1.5);
    q.map = w.map;
    q.plain_tree = w.tree;
    for (int k = 0; k < kQueries; ++k)
      q.poses.push_back(pose(rng.uniform(-29.0, 29.0), rng.uniform(-29.0, 29.0),
                             rng.uniform(0.0, 4.0), rng.uniform(-3.1416, 3.1416),
                             rng.uniform(-0.2, 0.2)));
  }
  return q;
}

const QuerySet& query_set(const std::string& name) {
  static std::map<std::string, QuerySet> sets;
  auto it = sets.find(name);
  if (it == sets.end()) it = sets.emplace(name, make_set(name)).first;
  return it->second;
}

void BM_Ferret(benchmark::State& state, const std::string& name) {
  const QuerySet& q = query_set(name);
  CollisionChecker checker(q.map, q.shape);
  PlainFcl plain(q.plain_tree, q.shape);
  // Agreement over the whole set (outside the timed loop).
  int disagreements = 0, collisions = 0;
  for (const Pose3& X : q.poses) {
    const bool ours = checker.in_collision(X);
    disagreements += ours != plain.collides(X);
    collisions += ours;
  }
  const CollisionChecker::Stats before = checker.stats();
  std::size_t k = 0;
  for (auto _ : state) {
    benchmark::DoNotOptimize(checker.in_collision(q.poses[k]));
    k = (k + 1) % q.poses.size();
  }
  const auto& s = checker.stats();
  const double parts = static_cast<double>(s.fast_free + s.fast_hit + s.fcl_calls -
                                           before.fast_free - before.fast_hit - before.fcl_calls);
  state.counters["queries_per_s"] =
      benchmark::Counter(static_cast<double>(state.iterations()), benchmark::Counter::kIsRate);
  state.counters["disagreements"] = disagreements;
  state.counters["collision_share"] = static_cast<double>(collisions) / q.poses.size();
  state.counters["fcl_share_of_parts"] = (s.fcl_calls - before.fcl_calls) / std::max(parts, 1.0);
  state.counters["field_cell_m"] = q.map->field_cell_m();
  state.counters["query_set_size"] = static_cast<double>(q.poses.size());
}

void BM_PlainFcl(benchmark::State& state, const std::string& name) {
  const QuerySet& q = query_set(name);
  PlainFcl plain(q.plain_tree, q.shape);
  std::size_t k = 0;
  for (auto _ : state) {
    benchmark::DoNotOptimize(plain.collides(q.poses[k]));
    k = (k + 1) % q.poses.size();
  }
  state.counters["queries_per_s"] =
      benchmark::Counter(static_cast<double>(state.iterations()), benchmark::Counter::kIsRate);
}

}  // namespace
}  // namespace ferret

int main(int argc, char** argv) {
  for (const std::string name : {"uav", "uav_with_ugv", "ugv", "uav_planner", "ugv_planner",
                                 "uav_urdf_planner", "ugv_urdf_planner"}) {
    benchmark::RegisterBenchmark(("ferret/" + name).c_str(), ferret::BM_Ferret, name);
    benchmark::RegisterBenchmark(("plain_fcl/" + name).c_str(), ferret::BM_PlainFcl, name);
  }
  benchmark::Initialize(&argc, argv);
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}
