#include "ferret/planning/frontier_sampler.hpp"

#include <gtest/gtest.h>
#include <ompl/base/ProblemDefinition.h>
#include <ompl/base/ScopedState.h>
#include <ompl/base/SpaceInformation.h>
#include <ompl/base/spaces/SE2StateSpace.h>
#include <ompl/geometric/PathGeometric.h>
#include <ompl/geometric/planners/prm/PRM.h>
#include <ompl/geometric/planners/rrt/RRTConnect.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <thread>

#include "exploration_room.hpp"
#include "ferret/core/error.hpp"
#include "ferret/planning/ompl_setup.hpp"

namespace ferret {
namespace {

namespace ob = ompl::base;

// Three frontier cells of a 10 x 10 m grid at 0.5 m, weighted 1 : 2 : 7.
std::shared_ptr<FrontierCandidates> three_frontiers() {
  auto c = std::make_shared<FrontierCandidates>();
  c->geometry = {0.0, 0.0, 0.5, 20, 20};
  c->cells = {{2, 17}, {17, 17}, {17, 2}};
  c->weights = {1.0, 2.0, 7.0};
  c->rule = GoalRule::kNearest;
  c->finalize();
  return c;
}

ob::SpaceInformationPtr open_plane(const std::function<bool(double, double)>& valid) {
  auto space = std::make_shared<ob::SE2StateSpace>();
  ob::RealVectorBounds b(2);
  b.setLow(0.0);
  b.setHigh(10.0);
  space->setBounds(b);
  auto si = std::make_shared<ob::SpaceInformation>(space);
  si->setStateValidityChecker([valid](const ob::State* s) {
    const auto* se2 = s->as<ob::SE2StateSpace::StateType>();
    return valid(se2->getX(), se2->getY());
  });
  si->setup();
  return si;
}

TEST(FrontierCandidates, DrawsInProportionToTheWeights) {
  const auto c = three_frontiers();
  Rng rng(4);
  int counts[3] = {0, 0, 0};
  for (int k = 0; k < 20000; ++k) ++counts[c->draw(rng)];
  EXPECT_NEAR(counts[0] / 20000.0, 0.1, 0.01);
  EXPECT_NEAR(counts[1] / 20000.0, 0.2, 0.01);
  EXPECT_NEAR(counts[2] / 20000.0, 0.7, 0.015);
  EXPECT_EQ(c->find(8.7, 1.2), 2);
  EXPECT_EQ(c->find(5.0, 5.0), -1);
}

TEST(FrontierSampler, StatesLieOnFrontierCellsAndSampleNearKeepsItsDistance) {
  const auto c = three_frontiers();
  auto si = open_plane([](double, double) { return true; });
  auto counter = std::make_shared<std::atomic<std::size_t>>(0);
  FrontierValidStateSampler sampler(si.get(), c, 3, counter);
  ob::ScopedState<ob::SE2StateSpace> s(si->getStateSpace()), near(si->getStateSpace());
  for (int k = 0; k < 200; ++k) {
    ASSERT_TRUE(sampler.sample(s.get()));
    EXPECT_GE(c->find(s->getX(), s->getY()), 0);
  }
  EXPECT_EQ(counter->load(), 200u);
  near->setXY(1.0, 8.0);
  near->setYaw(0);
  for (int k = 0; k < 50; ++k) {
    ASSERT_TRUE(sampler.sampleNear(s.get(), near.get(), 1.0));
    EXPECT_EQ(c->find(s->getX(), s->getY()), 0);  // the only frontier within 1 m
  }
  // Frontier cells that are all invalid: the sampler gives up.
  auto blocked = open_plane([](double, double) { return false; });
  FrontierValidStateSampler none(blocked.get(), c, 3);
  EXPECT_FALSE(none.sample(s.get()));
}

// Pitfall (ompl#810): only planners that allocate a valid-state sampler use ours.
// PRM does, and finds its way to a frontier; RRTConnect never calls it.
TEST(FrontierSampler, PrmCallsItRrtConnectDoesNot) {
  seed_ompl_once(7);
  const auto c = three_frontiers();
  // A wall across y = 5 with a gap at x > 8, and one across x = 5 with a gap at 4 < y < 4.8:
  // the start sees no frontier cell, so no plan exists before PRM adds roadmap states.
  // (With a goal in plain sight, PRM's goal thread could connect start and goal before
  // the roadmap grew once: the test failed about 1 run in 100 on a loaded machine.)
  auto si = open_plane([](double x, double y) {
    const bool wall_y5 = y > 4.8 && y < 5.2 && x < 8.0;
    const bool wall_x5 = x > 4.8 && x < 5.2 && y < 4.0;
    return !wall_y5 && !wall_x5;
  });
  auto counter = std::make_shared<std::atomic<std::size_t>>(0);
  si->setValidStateSamplerAllocator(frontier_sampler_allocator(c, 11, counter));
  auto run = [&](ob::Planner& planner) {
    auto pdef = std::make_shared<ob::ProblemDefinition>(si);
    ob::ScopedState<ob::SE2StateSpace> start(si->getStateSpace());
    start->setXY(1.0, 1.0);
    start->setYaw(0.0);
    pdef->addStartState(start);
    pdef->setGoal(std::make_shared<FrontierGoal>(si, c));
    planner.setProblemDefinition(pdef);
    planner.setup();
    // Until the first exact solution, with a generous wall-clock cap: a fixed 1 s budget
    // made PRM fail on a loaded machine (the test is about which sampler is called).
    const auto status = planner.solve(
        ob::plannerOrTerminationCondition(ob::timedPlannerTerminationCondition(60.0),
                                          ob::exactSolnPlannerTerminationCondition(pdef)));
    return std::pair{status == ob::PlannerStatus::EXACT_SOLUTION, pdef};
  };
  ompl::geometric::RRTConnect rrt(si);
  const auto [rrt_solved, rrt_pdef] = run(rrt);
  EXPECT_TRUE(rrt_solved);
  EXPECT_EQ(counter->load(), 0u);  // the trap: the sampler was never asked

  ompl::geometric::PRM prm(si);
  const auto [solved, pdef] = run(prm);
  ASSERT_TRUE(solved);
  EXPECT_GT(counter->load(), 0u);
  auto& path = *pdef->getSolutionPath()->as<ompl::geometric::PathGeometric>();
  const auto* last = path.getStates().back()->as<ob::SE2StateSpace::StateType>();
  EXPECT_GE(c->find(last->getX(), last->getY()), 0);
}

using Room = test::HalfSeenRoom;

std::size_t heaviest(const FrontierCandidates& c) {
  return static_cast<std::size_t>(std::max_element(c.weights.begin(), c.weights.end()) -
                                  c.weights.begin());
}

// A weak detection of `object` from the robot's pose, folded into O.
void see_weakly(Room& r, const Eigen::Vector2d& object) {
  CameraFrame frame;
  frame.view = {r.pose, 4.0, {}};
  const Eigen::Vector2d to = object - r.pose.position();
  frame.detections = {{std::atan2(to.y(), to.x()), to.norm(), 1.0 / to.norm()}};
  r.objects.integrate_frame(frame);
}

TEST(FrontierWeights, RapidAndCdosWeighTheFrontier) {
  Room r;
  const auto options = PolicyOptions::from(MissionConfig{}, 4.0, 2.0);
  ASSERT_FALSE(r.sets.visible.empty());
  // At rest, facing +x: the rapid weight peaks straight ahead (y = 1).
  const FrontierCandidates rapid = rapid_candidates(r.state(), 2.0);
  EXPECT_EQ(rapid.rule, GoalRule::kRapid);
  EXPECT_EQ(rapid.cells.size(), r.sets.visible.size());
  EXPECT_NEAR(r.geo.center(rapid.cells[heaviest(rapid)]).y(), 1.0, 0.05);
  // Without object evidence CDOS weighs as rapid does.
  const FrontierCandidates same = cdos_candidates(r.state(), options.curiosity);
  EXPECT_EQ(same.rule, GoalRule::kRapid);
  EXPECT_EQ(same.weights, rapid.weights);
  // A weak detection at (3, 1.8): the curiosity weights peak level with it.
  const Eigen::Vector2d object{3.0, 1.8};
  see_weakly(r, object);
  const FrontierCandidates curious = cdos_candidates(r.state(), options.curiosity);
  EXPECT_EQ(curious.rule, GoalRule::kCuriosity);
  const std::size_t best = heaviest(curious);
  EXPECT_DOUBLE_EQ(curious.weights[best], 1.0);  // exp(0): the largest loss
  EXPECT_NEAR(r.geo.center(curious.cells[best]).y(), object.y(), 0.03);
  // The loss ranks the cells: the far end of the visible frontier weighs less.
  EXPECT_LT(curious.weights.front(), 1.0);
}

TEST(FrontierWeights, PrmPlansFromTheRobotToAFrontier) {
  Room r;
  auto c = std::make_shared<FrontierCandidates>(rapid_candidates(r.state(), 2.0));
  FrontierPlanBudget unseeded;
  unseeded.seed_grid_paths = false;
  for (const FrontierPlanBudget& budget : {FrontierPlanBudget{}, unseeded}) {
    const FrontierPlan plan = plan_to_frontier(r.state(), c, budget, 3);
    ASSERT_TRUE(plan.solved);
    EXPECT_GT(plan.samples_drawn, 0u);  // the frontier sampler grew the roadmap
    EXPECT_TRUE(plan.path_W.front().isApprox(r.pose.position()));
    // The best-weighted frontier (straight ahead), not the first one PRM connected.
    EXPECT_EQ(plan.goal, c->cells[heaviest(*c)]);
    EXPECT_EQ(plan.path_W.size(), 2u);  // in the open, shortened to a straight line
  }
}

TEST(FrontierCandidates, OrderIsHeaviestFirstTiesInCellOrder) {
  auto c = std::make_shared<FrontierCandidates>();
  c->geometry = {0.0, 0.0, 0.5, 20, 20};
  c->cells = {{1, 1}, {2, 2}, {3, 3}, {4, 4}};
  c->weights = {1.0, 3.0, 1.0, 3.0};
  c->finalize();
  EXPECT_EQ(c->order, (std::vector<std::size_t>{1, 3, 0, 2}));
}

// The tether as goal validity: a connected goal whose path the reach check refuses is
// never the plan's goal; the plan takes the best-weighted goal within reach instead.
TEST(FrontierWeights, AGoalOutOfTheTethersReachIsNeverChosen) {
  Room r;
  auto c = std::make_shared<FrontierCandidates>(rapid_candidates(r.state(), 2.0));
  // "Out of reach": the frontier within 0.3 m of the robot's line of sight (y = 1).
  const auto out_of_reach = [&](Cell cell) { return std::abs(r.geo.center(cell).y() - 1.0) < 0.3; };
  std::vector<Cell> asked;
  auto state = r.state();
  state.within_reach = [&](Cell cell, const std::vector<Eigen::Vector2d>& path) {
    EXPECT_TRUE(path.front().isApprox(r.pose.position()));
    EXPECT_EQ(r.geo.cell_at(path.back().x(), path.back().y()), cell);
    asked.push_back(cell);
    return !out_of_reach(cell);
  };
  const FrontierPlan plan = plan_to_frontier(state, c, FrontierPlanBudget{}, 3);
  ASSERT_TRUE(plan.solved);
  EXPECT_FALSE(out_of_reach(plan.goal));
  EXPECT_GT(plan.out_of_reach, 0u);
  ASSERT_FALSE(asked.empty());
  EXPECT_EQ(asked.back(), plan.goal);  // the chosen path was asked, and passed
  // The best of the rest: no candidate within reach outweighs it.
  const double w = c->weights[static_cast<std::size_t>(
      c->find(r.geo.center(plan.goal).x(), r.geo.center(plan.goal).y()))];
  for (std::size_t k = 0; k < c->cells.size(); ++k)
    if (!out_of_reach(c->cells[k])) {
      EXPECT_LE(c->weights[k], w);
    }
}

// The OMPL policies decide as the grid ones do, PRM only plans the way: with object
// evidence cdos+ompl heads for the cell cdos heads for, and faces the same way.
TEST(FrontierWeights, CdosOmplChoosesTheGoalCdosChooses) {
  Room r;
  const Eigen::Vector2d object{3.0, 1.8};
  see_weakly(r, object);
  auto options = PolicyOptions::from(MissionConfig{}, 4.0, 2.0);
  options.seed = 5;
  const auto grid = make_exploration_policy("cdos", options)->choose(r.state());
  const auto ompl = make_exploration_policy("cdos+ompl", options)->choose(r.state());
  ASSERT_TRUE(grid && ompl);
  EXPECT_EQ(ompl->cell, grid->cell);
  EXPECT_EQ(to_string(ompl->reason), "curiosity+ompl");
  ASSERT_TRUE(ompl->heading_rad && grid->heading_rad);
  EXPECT_NEAR(*ompl->heading_rad, *grid->heading_rad, 1e-9);
  EXPECT_FALSE(ompl->path_W.empty());
}

TEST(FrontierSampler, OnePlaceDecidesThePolicyOfAMethodAndAPlanner) {
  EXPECT_EQ(exploration_policy_for("cdos", FrontierPlanner::kGrid), "cdos");
  EXPECT_EQ(exploration_policy_for("nearest", FrontierPlanner::kGrid), "nearest");
  EXPECT_EQ(exploration_policy_for("cdos", FrontierPlanner::kOmpl), "cdos+ompl");
  EXPECT_EQ(exploration_policy_for("rapid", FrontierPlanner::kOmpl), "rapid+ompl");
  // A variant named as it is keeps its planner (the experiment's methods after --planner).
  EXPECT_EQ(exploration_policy_for("cdos+ompl", FrontierPlanner::kGrid), "cdos+ompl");
  // The sampler serves cdos and rapid: any other method with it is an error saying so.
  for (const char* method : {"nearest", "oracle", "cdos-literal", "bayes"}) {
    try {
      (void)exploration_policy_for(method, FrontierPlanner::kOmpl);
      ADD_FAILURE() << method;
    } catch (const InputError& e) {
      EXPECT_EQ(e.source(), "--planner");
      EXPECT_NE(e.expected().find("(cdos, rapid); " + std::string(method) + " has none"),
                std::string::npos)
          << e.what();
    }
  }
  try {
    (void)exploration_policy_for("random", FrontierPlanner::kOmpl);
    ADD_FAILURE() << "random";
  } catch (const InputError& e) {
    EXPECT_EQ(e.source(), "--method");
    EXPECT_NE(e.expected().find("cdos, cdos-literal"), std::string::npos) << e.what();
    EXPECT_EQ(e.expected().find("cdos+ompl"), std::string::npos) << e.what();
  }
  EXPECT_EQ(parse_frontier_planner("ompl", "--planner"), FrontierPlanner::kOmpl);
  EXPECT_EQ(to_string(FrontierPlanner::kGrid), "grid");
  EXPECT_THROW((void)parse_frontier_planner("rrt", "--planner"), InputError);
}

// PRM::solve grows the roadmap in one thread, checks for solutions in another and
// stops on wall time; plan_to_frontier runs on a work budget in the caller's thread
// with every generator seeded, so a plan is a function of its inputs and seed, also
// when plans run side by side (as `ferret experiment --jobs 2` runs them).
TEST(FrontierWeights, PlansRepeatGivenTheSeedAlsoInParallelThreads) {
  Room r;
  auto c = std::make_shared<FrontierCandidates>(rapid_candidates(r.state(), 2.0));
  FrontierPlanBudget with_bounces;  // exercises PRM's random-bounce expansion too
  with_bounces.grow_milestones = 4;
  with_bounces.expand_bounces = 6;
  for (const FrontierPlanBudget& budget : {FrontierPlanBudget{}, with_bounces}) {
    constexpr int kSeeds = 6;
    std::vector<FrontierPlan> once;
    for (int seed = 0; seed < kSeeds; ++seed)
      once.push_back(plan_to_frontier(r.state(), c, budget, seed));
    std::vector<FrontierPlan> a(kSeeds), b(kSeeds);
    std::thread ta([&] {
      for (int seed = 0; seed < kSeeds; ++seed)
        a[seed] = plan_to_frontier(r.state(), c, budget, seed);
    });
    std::thread tb([&] {
      for (int seed = kSeeds - 1; seed >= 0; --seed)
        b[seed] = plan_to_frontier(r.state(), c, budget, seed);
    });
    ta.join();
    tb.join();
    bool some_differ = false;
    for (int seed = 0; seed < kSeeds; ++seed) {
      ASSERT_TRUE(once[seed].solved) << seed;
      EXPECT_GT(once[seed].samples_drawn, 0u);
      for (const FrontierPlan* p : {&a[seed], &b[seed]}) {
        EXPECT_EQ(p->samples_drawn, once[seed].samples_drawn) << seed;
        EXPECT_EQ(p->goal, once[seed].goal) << seed;
        EXPECT_EQ(p->path_W, once[seed].path_W) << seed;
        EXPECT_EQ(p->roadmap_W, once[seed].roadmap_W) << seed;
      }
      some_differ = some_differ || once[seed].roadmap_W != once[0].roadmap_W;
    }
    EXPECT_TRUE(some_differ);  // the seed matters
  }
}

TEST(FrontierSampler, OmplPoliciesAreRegisteredAsVariantsNotMethods) {
  EXPECT_TRUE(has_exploration_policy("cdos+ompl"));
  EXPECT_TRUE(has_exploration_policy("rapid+ompl"));
  EXPECT_EQ(make_exploration_policy("rapid+ompl", PolicyOptions{})->name(), "rapid+ompl");
  const auto methods = exploration_policy_names();
  EXPECT_EQ(std::find(methods.begin(), methods.end(), "cdos+ompl"), methods.end());
  EXPECT_NE(std::find(methods.begin(), methods.end(), "cdos"), methods.end());
}

}  // namespace
}  // namespace ferret
