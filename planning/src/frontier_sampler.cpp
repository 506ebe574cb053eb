#include "ferret/planning/frontier_sampler.hpp"

#include <ompl/base/OptimizationObjective.h>
#include <ompl/base/ProblemDefinition.h>
#include <ompl/base/SpaceInformation.h>
#include <ompl/base/spaces/SE2StateSpace.h>
#include <ompl/datastructures/NearestNeighborsLinear.h>
#include <ompl/geometric/PathGeometric.h>
#include <ompl/geometric/planners/prm/PRM.h>
#include <ompl/util/Console.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <functional>

#include "ferret/core/pose.hpp"
#include "ferret/planning/curiosity.hpp"
#include "ferret/planning/policies.hpp"

namespace ob = ompl::base;

namespace ferret {

void FrontierCandidates::finalize(std::optional<std::size_t> first) {
  cumulative.resize(weights.size());
  double sum = 0.0;
  for (std::size_t k = 0; k < weights.size(); ++k) cumulative[k] = sum += weights[k];
  by_cell_.assign(geometry.size(), -1);
  for (std::size_t k = 0; k < cells.size(); ++k)
    by_cell_[geometry.index(cells[k])] = static_cast<int>(k);
  order.resize(cells.size());
  for (std::size_t k = 0; k < order.size(); ++k) order[k] = k;
  std::stable_sort(order.begin(), order.end(),
                   [this](std::size_t a, std::size_t b) { return weights[a] > weights[b]; });
  if (const auto it = std::find(order.begin(), order.end(), first.value_or(order.size()));
      it != order.end())
    std::rotate(order.begin(), it, it + 1);
}

std::size_t FrontierCandidates::draw(Rng& rng) const {
  const double u = rng.uniform01() * cumulative.back();
  const auto it = std::upper_bound(cumulative.begin(), cumulative.end(), u);
  return std::min<std::size_t>(static_cast<std::size_t>(it - cumulative.begin()), cells.size() - 1);
}

int FrontierCandidates::find(double x_m, double y_m) const {
  const Cell c = geometry.cell_at(x_m, y_m);
  return geometry.contains(c) ? by_cell_[geometry.index(c)] : -1;
}

namespace {

FrontierCandidates rapid_weights(const ExplorationState& s, double max_velocity_mps) {
  FrontierCandidates out;
  out.geometry = s.grid.geometry();
  const Eigen::Vector2d p = s.X_WG.position();
  if (!s.frontier_sets().visible.empty()) {
    Eigen::Vector2d v = s.v_W;
    if (v.norm() < 0.05)
      v = 0.05 * Eigen::Vector2d(std::cos(s.X_WG.yaw_rad), std::sin(s.X_WG.yaw_rad));
    for (const Cell& c : s.frontier_sets().visible) {
      const Eigen::Vector2d to = out.geometry.center(c) - p;
      const Eigen::Vector2d u =
          to.norm() > 1e-9 ? Eigen::Vector2d(to.normalized()) : Eigen::Vector2d(v.normalized());
      out.cells.push_back(c);
      out.weights.push_back(
          std::exp(-(max_velocity_mps * u - v).norm() / (0.25 * max_velocity_mps)));
    }
    out.rule = GoalRule::kRapid;
  } else {
    for (const Cell& c : s.frontier_sets().global) {
      out.cells.push_back(c);
      out.weights.push_back(std::exp(-static_cast<double>(s.paths.distance_m(c)) / 1.0));
    }
    out.rule = GoalRule::kNearest;
  }
  // Far candidates underflow to 0: keep every weight positive but tiny.
  for (double& w : out.weights) w = std::max(w, 1e-12);
  std::optional<std::size_t> first;
  if (out.rule == GoalRule::kRapid)  // the rapid policy's goal, near-ties resolved as there
    if (const auto goal = RapidFrontierPolicy::choose_visible(s, max_velocity_mps))
      first = static_cast<std::size_t>(std::find(out.cells.begin(), out.cells.end(), goal->cell) -
                                       out.cells.begin());
  out.finalize(first);
  return out;
}

}  // namespace

FrontierCandidates rapid_candidates(const ExplorationState& s, double max_velocity_mps) {
  return rapid_weights(s, max_velocity_mps);
}

FrontierCandidates cdos_candidates(const ExplorationState& s, const CuriosityOptions& options,
                                   double max_velocity_mps, bool global) {
  const auto evidence = collect_evidence(s.objects);
  const std::vector<Cell>& set = global ? s.frontier_sets().global : s.frontier_sets().visible;
  if (!evidence.empty() && !set.empty()) {
    const auto scored =
        score_frontiers(set, s.grid.geometry(), s.X_WG.position(), evidence, options);
    double best = 0.0;
    for (const auto& f : scored) best = std::max(best, f.loss);
    if (best > 0.0) {
      FrontierCandidates out;
      out.geometry = s.grid.geometry();
      for (const auto& f : scored) {
        out.cells.push_back(f.cell);
        // Sharpened: a candidate with 10% less loss than the best is 1/e as likely.
        out.weights.push_back(std::max(std::exp((f.loss - best) / (0.1 * best)), 1e-12));
      }
      out.rule = GoalRule::kCuriosity;
      out.finalize(
          cdos_argmax(scored, strongest_evidence(evidence).p_W));  // the cdos policy's goal first
      return out;
    }
  }
  return rapid_weights(s, max_velocity_mps);
}

FrontierValidStateSampler::FrontierValidStateSampler(
    const ob::SpaceInformation* si, std::shared_ptr<const FrontierCandidates> candidates,
    std::uint64_t seed, std::shared_ptr<std::atomic<std::size_t>> counter)
    : ob::ValidStateSampler(si),
      candidates_(std::move(candidates)),
      rng_(seed),
      counter_(std::move(counter)) {
  name_ = "frontier";
}

bool FrontierValidStateSampler::fill(ob::State* state, std::size_t k) {
  const GridGeometry& g = candidates_->geometry;
  const Eigen::Vector2d c = g.center(candidates_->cells[k]);
  auto* se2 = state->as<ob::SE2StateSpace::StateType>();
  se2->setXY(c.x() + rng_.uniform(-0.5, 0.5) * g.resolution_m,
             c.y() + rng_.uniform(-0.5, 0.5) * g.resolution_m);
  se2->setYaw(rng_.uniform(-3.14159, 3.14159));
  if (counter_) ++*counter_;
  return si_->isValid(state);
}

bool FrontierValidStateSampler::sample(ob::State* state) {
  if (candidates_->empty()) return false;
  for (unsigned a = 0; a < attempts_; ++a)
    if (fill(state, candidates_->draw(rng_))) return true;
  return false;
}

bool FrontierValidStateSampler::sampleNear(ob::State* state, const ob::State* near,
                                           double distance) {
  if (candidates_->empty()) return false;
  const auto* n = near->as<ob::SE2StateSpace::StateType>();
  const Eigen::Vector2d p(n->getX(), n->getY());
  for (unsigned a = 0; a < attempts_; ++a) {
    const std::size_t k = candidates_->draw(rng_);
    if ((candidates_->geometry.center(candidates_->cells[k]) - p).norm() > distance) continue;
    if (fill(state, k)) return true;
  }
  return false;
}

ob::ValidStateSamplerAllocator frontier_sampler_allocator(
    std::shared_ptr<const FrontierCandidates> candidates, std::uint64_t seed,
    std::shared_ptr<std::atomic<std::size_t>> counter) {
  auto calls = std::make_shared<std::uint64_t>(0);
  return [candidates, seed, counter,
          calls](const ob::SpaceInformation* si) -> ob::ValidStateSamplerPtr {
    // Each allocated sampler gets its own stream, derived deterministically.
    return std::make_shared<FrontierValidStateSampler>(si, candidates,
                                                       derive_seed(seed, {(*calls)++}), counter);
  };
}

FrontierGoal::FrontierGoal(const ob::SpaceInformationPtr& si,
                           std::shared_ptr<const FrontierCandidates> candidates, Reach within_reach)
    : ob::GoalSampleableRegion(si),
      candidates_(std::move(candidates)),
      within_reach_(std::move(within_reach)) {
  // Satisfied on a candidate cell: within half a cell diagonal of its centre.
  setThreshold(0.75 * candidates_->geometry.resolution_m);
}

double FrontierGoal::distanceGoal(const ob::State* state) const {
  const auto* se2 = state->as<ob::SE2StateSpace::StateType>();
  if (candidates_->find(se2->getX(), se2->getY()) >= 0) return 0.0;
  double best = std::numeric_limits<double>::infinity();
  const Eigen::Vector2d p(se2->getX(), se2->getY());
  for (const Cell& c : candidates_->cells)
    best = std::min(best, (candidates_->geometry.center(c) - p).norm());
  return best;
}

void FrontierGoal::sampleGoal(ob::State* state) const {
  const std::size_t k = candidates_->order[next_++ % candidates_->order.size()];
  const Eigen::Vector2d c = candidates_->geometry.center(candidates_->cells[k]);
  auto* se2 = state->as<ob::SE2StateSpace::StateType>();
  se2->setXY(c.x(), c.y());
  se2->setYaw(0.0);
}

bool FrontierGoal::path_within_reach(const std::vector<Eigen::Vector2d>& path_W) const {
  if (!within_reach_ || path_W.empty()) return true;
  return within_reach_(candidates_->geometry.cell_at(path_W.back().x(), path_W.back().y()), path_W);
}

unsigned int FrontierGoal::maxSampleCount() const {
  return static_cast<unsigned>(candidates_->cells.size());
}

namespace {

// OMPL's default SE2 sampler draws from generators seeded by OMPL's process-wide seed
// generator in construction order, which threads running side by side make random;
// this one draws uniformly from its own stream (PRM's random-bounce expansion uses it).
class SeededSe2Sampler final : public ob::StateSampler {
 public:
  SeededSe2Sampler(const ob::StateSpace* space, std::uint64_t seed)
      : ob::StateSampler(space), rng_(seed) {}
  void sampleUniform(ob::State* state) override {
    const auto& b = space_->as<ob::SE2StateSpace>()->getBounds();
    auto* se2 = state->as<ob::SE2StateSpace::StateType>();
    se2->setXY(rng_.uniform(b.low[0], b.high[0]), rng_.uniform(b.low[1], b.high[1]));
    se2->setYaw(rng_.uniform(-kPi, kPi));
  }
  void sampleUniformNear(ob::State* state, const ob::State* near, double distance) override {
    const auto& b = space_->as<ob::SE2StateSpace>()->getBounds();
    const auto* n = near->as<ob::SE2StateSpace::StateType>();
    auto* se2 = state->as<ob::SE2StateSpace::StateType>();
    se2->setXY(std::clamp(n->getX() + rng_.uniform(-distance, distance), b.low[0], b.high[0]),
               std::clamp(n->getY() + rng_.uniform(-distance, distance), b.low[1], b.high[1]));
    se2->setYaw(wrap_angle_rad(n->getYaw() + rng_.uniform(-distance, distance)));
  }
  void sampleGaussian(ob::State* state, const ob::State* mean, double stdDev) override {
    const auto& b = space_->as<ob::SE2StateSpace>()->getBounds();
    const auto* m = mean->as<ob::SE2StateSpace::StateType>();
    auto* se2 = state->as<ob::SE2StateSpace::StateType>();
    se2->setXY(std::clamp(rng_.normal(m->getX(), stdDev), b.low[0], b.high[0]),
               std::clamp(rng_.normal(m->getY(), stdDev), b.low[1], b.high[1]));
    se2->setYaw(wrap_angle_rad(rng_.normal(m->getYaw(), stdDev)));
  }

 private:
  static constexpr double kPi = 3.14159265358979323846;
  Rng rng_;
};

// A termination condition that is true after `n` evaluations: OMPL's roadmap loops
// evaluate it once per step, in this thread, so the work done depends on nothing else.
ob::PlannerTerminationCondition after_evaluations(std::size_t n) {
  return ob::PlannerTerminationCondition([left = n]() mutable {
    if (left == 0) return true;
    --left;
    return false;
  });
}

// PRM driven in the caller's thread on a work budget. PRM::solve grows the roadmap in
// one thread while a second looks for a solution every millisecond, and stops on wall
// time: its result depends on the machine's load. This keeps PRM's pattern (grow,
// optionally expand by random bounces, goals added as it goes) but counts the work and
// checks for a solution between batches, so the same seed gives the same roadmap.
class BudgetedPrm final : public ompl::geometric::PRM {
 public:
  /// World waypoints to add to the roadmap before a goal (none: nothing).
  using Seeds = std::function<std::vector<Eigen::Vector2d>(const ob::State* goal)>;

  explicit BudgetedPrm(const ob::SpaceInformationPtr& si) : PRM(si) {
    // Exact k-nearest with a fixed tie order (GNAT's pivots come from OMPL's RNG).
    setNearestNeighbors<ompl::NearestNeighborsLinear>();
    nn_->setDistanceFunction([this](Vertex a, Vertex b) {
      return distanceFunction(a, b);
    });  // setup() only sets its own
  }

  // The path found within `budget`, or null; `cap` (wall time) is only a safety net.
  ob::PathPtr solve_on_budget(const FrontierPlanBudget& budget, std::uint64_t seed,
                              const std::atomic<std::size_t>& draws,
                              const ob::PlannerTerminationCondition& cap, const Seeds& seeds) {
    checkValidity();
    rng_.setLocalSeed(static_cast<std::uint_fast32_t>(derive_seed(seed, {0x9e3}) & 0x7fffffffu) |
                      1u);
    auto* goal = dynamic_cast<FrontierGoal*>(pdef_->getGoal().get());
    if (goal == nullptr) return nullptr;
    while (const ob::State* st = pis_.nextStart())
      startM_.push_back(addMilestone(si_->cloneState(st)));
    if (startM_.empty()) return nullptr;
    if (!sampler_) sampler_ = si_->allocValidStateSampler();
    if (!simpleSampler_) simpleSampler_ = si_->allocStateSampler();
    ob::State* work = si_->allocState();
    std::vector<ob::State*> bounce(kBounceSteps);
    si_->allocStates(bounce);
    ob::PathPtr solution;
    for (std::size_t round = 0; round < budget.rounds && !cap && !solution; ++round) {
      // Grow: `grow_milestones` new frontier states, or `grow_draws` sampler draws.
      const std::size_t milestones = milestoneCount() + budget.grow_milestones;
      const std::size_t draw_limit = draws.load() + budget.grow_draws;
      growRoadmap(ob::PlannerTerminationCondition([&] {
                    return milestoneCount() >= milestones || draws.load() >= draw_limit || cap();
                  }),
                  work);
      // The next goal; a goal refused for the tether's reach does not use up the
      // round: the next one comes at once (up to kMaxRefusals a plan).
      for (std::size_t refused = out_of_reach_ + 1;
           !solution && refused != out_of_reach_ && out_of_reach_ < kMaxRefusals && !cap;) {
        refused = out_of_reach_;
        if (goal->maxSampleCount() > goalM_.size())
          if (const ob::State* st = pis_.nextGoal()) {
            Vertex last = startM_.front();
            if (seeds) last = add_seeds(seeds(st), work);
            goalM_.push_back(addMilestone(si_->cloneState(st)));
            if (seeds) connect(last, goalM_.back());
          }
        solution = best_connected(*goal);
      }
      if (!solution && budget.expand_bounces > 0) {
        expandRoadmap(
            ob::plannerOrTerminationCondition(after_evaluations(budget.expand_bounces), cap),
            bounce);
        solution = best_connected(*goal);
      }
    }
    si_->freeStates(bounce);
    si_->freeState(work);
    return solution;
  }

  [[nodiscard]] std::size_t out_of_reach() const { return out_of_reach_; }
  [[nodiscard]] std::vector<Eigen::Vector2d> roadmap() const {
    std::vector<Eigen::Vector2d> out;
    for (auto [v, end] = boost::vertices(g_); v != end; ++v) out.push_back(xy(stateProperty_[*v]));
    return out;
  }
  static Eigen::Vector2d xy(const ob::State* st) {
    const auto* se2 = st->as<ob::SE2StateSpace::StateType>();
    return {se2->getX(), se2->getY()};
  }

 private:
  static constexpr unsigned kBounceSteps = 5;      // PRM's magic::MAX_RANDOM_BOUNCE_STEPS
  static constexpr std::size_t kMaxRefusals = 32;  // goals refused for reach, a plan

  // The seed points as a chain from the start (besides their k-nearest connections:
  // in a room full of frontier states the start is seldom among a goal's neighbours);
  // returns the chain's last vertex.
  Vertex add_seeds(const std::vector<Eigen::Vector2d>& points, ob::State* work) {
    Vertex last = startM_.front();
    for (const auto& p : points) {
      work->as<ob::SE2StateSpace::StateType>()->setXY(p.x(), p.y());
      work->as<ob::SE2StateSpace::StateType>()->setYaw(0.0);
      if (!si_->isValid(work)) continue;
      const Vertex v = addMilestone(si_->cloneState(work));
      connect(last, v);
      last = v;
    }
    return last;
  }

  // An edge a-b if the motion is valid and they are not connected yet (as addMilestone adds one).
  void connect(Vertex a, Vertex b) {
    if (sameComponent(a, b) || !si_->checkMotion(stateProperty_[a], stateProperty_[b])) return;
    boost::add_edge(a, b, opt_->motionCost(stateProperty_[a], stateProperty_[b]), g_);
    uniteComponents(a, b);
  }

  // The best-weighted goal (goals come heaviest first) in the start's component whose
  // path, shortened, is within the tether's reach; goals refused once stay refused.
  ob::PathPtr best_connected(const FrontierGoal& goal) {
    refused_.resize(goalM_.size(), false);
    for (std::size_t k = 0; k < goalM_.size(); ++k) {
      if (refused_[k] || !sameComponent(startM_.front(), goalM_[k])) continue;
      ob::PathPtr path = constructSolution(startM_.front(), goalM_[k]);
      if (!path) continue;
      auto& geometric = *path->as<ompl::geometric::PathGeometric>();
      shorten(geometric);
      std::vector<Eigen::Vector2d> points;
      for (const ob::State* st : geometric.getStates()) points.push_back(xy(st));
      if (goal.path_within_reach(points)) return path;
      refused_[k] = true;
      ++out_of_reach_;
    }
    return nullptr;
  }

  // From each state, straight on to the furthest later state in line of sight
  // (deterministic, unlike OMPL's randomised shortcutting).
  void shorten(ompl::geometric::PathGeometric& path) const {
    auto& states = path.getStates();
    std::vector<ob::State*> kept{states.front()};
    std::size_t anchor = 0;
    while (anchor + 1 < states.size()) {
      std::size_t next = states.size() - 1;
      while (next > anchor + 1 && !si_->checkMotion(states[anchor], states[next])) --next;
      kept.push_back(states[next]);
      anchor = next;
    }
    for (ob::State* st : states)
      if (std::find(kept.begin(), kept.end(), st) == kept.end()) si_->freeState(st);
    states = std::move(kept);
  }

  std::vector<bool> refused_;
  std::size_t out_of_reach_ = 0;
};

}  // namespace

FrontierPlan plan_to_frontier(const ExplorationState& s,
                              std::shared_ptr<const FrontierCandidates> candidates,
                              const FrontierPlanBudget& budget, std::uint64_t seed,
                              double escape_radius_m) {
  const auto t0 = std::chrono::steady_clock::now();
  FrontierPlan out;
  if (!candidates || candidates->empty()) return out;
  ompl::msg::setLogLevel(ompl::msg::LOG_WARN);  // PRM reports every roadmap at "info"
  const GridGeometry& g = s.grid.geometry();
  auto space = std::make_shared<ob::SE2StateSpace>();
  ob::RealVectorBounds bounds(2);
  bounds.setLow(0, g.origin_x_m);
  bounds.setHigh(0, g.origin_x_m + g.width_m());
  bounds.setLow(1, g.origin_y_m);
  bounds.setHigh(1, g.origin_y_m + g.height_m());
  space->setBounds(bounds);
  space->setStateSamplerAllocator([seed](const ob::StateSpace* sp) {
    return std::make_shared<SeededSe2Sampler>(sp, derive_seed(seed, {0x5e2}));
  });
  auto si = std::make_shared<ob::SpaceInformation>(space);
  const Eigen::Vector2d robot = s.X_WG.position();
  const IrGrid& grid = s.grid;
  si->setStateValidityChecker([&grid, g, robot, escape_radius_m](const ob::State* st) {
    const auto* se2 = st->as<ob::SE2StateSpace::StateType>();
    const Cell c = g.cell_at(se2->getX(), se2->getY());
    if (!g.contains(c)) return false;
    const std::size_t idx = g.index(c);
    if (grid.traversable(idx)) return true;
    // Near the robot known free suffices (it may stand inside a wall's clearance).
    return grid.label_at(idx) == GridLabel::kFree &&
           (Eigen::Vector2d(se2->getX(), se2->getY()) - robot).norm() <= escape_radius_m;
  });
  // Checks every half cell along a motion.
  si->setStateValidityCheckingResolution(0.5 * g.resolution_m / space->getMaximumExtent());
  auto counter = std::make_shared<std::atomic<std::size_t>>(0);
  si->setValidStateSamplerAllocator(frontier_sampler_allocator(candidates, seed, counter));
  si->setup();
  auto pdef = std::make_shared<ob::ProblemDefinition>(si);
  ob::ScopedState<ob::SE2StateSpace> start(space);
  start->setXY(robot.x(), robot.y());
  start->setYaw(s.X_WG.yaw_rad);
  // A robot beyond the escape radius of free space has no plan (PRM would warn).
  if (!si->isValid(start.get())) return out;
  pdef->addStartState(start);
  pdef->setGoal(std::make_shared<FrontierGoal>(si, candidates, s.within_reach));
  BudgetedPrm prm(si);
  prm.setProblemDefinition(pdef);
  prm.setup();
  BudgetedPrm::Seeds seeds;
  if (budget.seed_grid_paths)
    seeds = [&s, &g](const ob::State* goal) {
      // G's shortest path to the goal, less its ends (the start cell's centre, the goal).
      auto path = s.paths.path_to(g.cell_at(BudgetedPrm::xy(goal).x(), BudgetedPrm::xy(goal).y()));
      if (path.size() <= 2) return std::vector<Eigen::Vector2d>{};
      return std::vector<Eigen::Vector2d>(path.begin() + 1, path.end() - 1);
    };
  const ob::PathPtr solution = prm.solve_on_budget(
      budget, seed, *counter, ob::timedPlannerTerminationCondition(budget.safety_cap_s), seeds);
  out.samples_drawn = counter->load();
  out.out_of_reach = prm.out_of_reach();
  out.roadmap_W = prm.roadmap();
  out.planning_time_s =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  if (!solution) return out;
  auto& path = *solution->as<ompl::geometric::PathGeometric>();
  for (const ob::State* st : path.getStates()) {
    const auto* se2 = st->as<ob::SE2StateSpace::StateType>();
    out.path_W.emplace_back(se2->getX(), se2->getY());
  }
  out.goal = g.cell_at(out.path_W.back().x(), out.path_W.back().y());
  out.solved = candidates->find(out.path_W.back().x(), out.path_W.back().y()) >= 0;
  return out;
}

}  // namespace ferret
