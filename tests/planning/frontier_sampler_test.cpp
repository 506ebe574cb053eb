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
#include <thread>

#include "exploration_room.hpp"
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
  c->rule = "test";
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
  // A wall across y = 5 with a gap at x > 8: the frontiers up left need a detour.
  auto si = open_plane([](double x, double y) { return !(y > 4.8 && y < 5.2 && x < 8.0); });
  auto counter = std::make_shared<std::atomic<std::size_t>>(0);
  si->setValidStateSamplerAllocator(frontier_sampler_allocator(c, 11, counter));
  auto run = [&](ob::Planner& planner) {
    auto pdef = std::make_shared<ob::ProblemDefinition>(si);
    ob::ScopedState<ob::SE2StateSpace> start(si->getStateSpace());
    start->setXY(1.0, 1.0);
    start->setYaw(0.0);
    pdef->addStartState(start);
    pdef->setGoal(std::make_shared<FrontierGoal>(si, c, 11));
    planner.setProblemDefinition(pdef);
    planner.setup();
    // Until the first exact solution, with a generous wall-clock cap: a fixed 1 s budget
    // made PRM fail on a loaded machine (the test is about which sampler is called).
    const auto status = planner.solve(ob::plannerOrTerminationCondition(
        ob::timedPlannerTerminationCondition(60.0), ob::exactSolnPlannerTerminationCondition(pdef)));
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
  return static_cast<std::size_t>(std::max_element(c.weights.begin(), c.weights.end()) - c.weights.begin());
}

TEST(FrontierWeights, RapidAndCdosWeighTheFrontier) {
  Room r;
  const auto options = PolicyOptions::from(MissionConfig{}, 4.0, 2.0);
  ASSERT_FALSE(r.sets.visible.empty());
  // At rest, facing +x: the rapid weight peaks straight ahead (y = 1).
  const FrontierCandidates rapid = rapid_candidates(r.state(), 2.0);
  EXPECT_EQ(rapid.rule, "rapid");
  EXPECT_EQ(rapid.cells.size(), r.sets.visible.size());
  EXPECT_NEAR(r.geo.center(rapid.cells[heaviest(rapid)]).y(), 1.0, 0.05);
  // Without object evidence CDOS weighs as rapid does.
  const FrontierCandidates same = cdos_candidates(r.state(), options.curiosity);
  EXPECT_EQ(same.rule, "rapid");
  EXPECT_EQ(same.weights, rapid.weights);
  // A weak detection at (3, 1.8): the curiosity weights peak level with it.
  const Eigen::Vector2d object{3.0, 1.8};
  CameraFrame frame;
  frame.view = {r.pose, 4.0, {}};
  const Eigen::Vector2d to = object - r.pose.position();
  frame.detections = {{std::atan2(to.y(), to.x()), to.norm(), 1.0 / to.norm()}};
  r.objects.integrate_frame(frame);
  const FrontierCandidates curious = cdos_candidates(r.state(), options.curiosity);
  EXPECT_EQ(curious.rule, "curiosity");
  const std::size_t best = heaviest(curious);
  EXPECT_DOUBLE_EQ(curious.weights[best], 1.0);  // exp(0): the largest loss
  EXPECT_NEAR(r.geo.center(curious.cells[best]).y(), object.y(), 0.03);
  // The loss ranks the cells: the far end of the visible frontier weighs less.
  EXPECT_LT(curious.weights.front(), 1.0);
}

TEST(FrontierWeights, PrmPlansFromTheRobotToAFrontier) {
  Room r;
  auto c = std::make_shared<FrontierCandidates>(rapid_candidates(r.state(), 2.0));
  const FrontierPlan plan = plan_to_frontier(r.state(), c, FrontierPlanBudget{}, 3);
  ASSERT_TRUE(plan.solved);
  EXPECT_GT(plan.samples_drawn, 0u);
  EXPECT_TRUE(plan.path_W.front().isApprox(r.pose.position()));
  EXPECT_GE(c->find(plan.path_W.back().x(), plan.path_W.back().y()), 0);
  EXPECT_EQ(plan.goal.i, 39);
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
      }
      some_differ = some_differ || once[seed].path_W != once[0].path_W;
    }
    EXPECT_TRUE(some_differ);  // the seed matters
  }
}

TEST(FrontierSampler, OmplPoliciesAreRegistered) {
  EXPECT_TRUE(has_exploration_policy("cdos+ompl"));
  EXPECT_TRUE(has_exploration_policy("rapid+ompl"));
  EXPECT_EQ(make_exploration_policy("rapid+ompl", PolicyOptions{})->name(), "rapid+ompl");
}

}  // namespace
}  // namespace ferret
