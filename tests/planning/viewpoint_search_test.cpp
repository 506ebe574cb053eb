// The Bayesian viewpoint search (bayes): the mass a viewpoint sees, against hand-computed
// areas; negative evidence and walls lowering it; the policy's choices.
#include "ferret/planning/viewpoint_search.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <optional>
#include <vector>

#include "exploration_room.hpp"

namespace ferret {
namespace {

constexpr double kPi = std::numbers::pi;

// An 8 x 8 m room at 0.05 m, every cell known free, nothing looked at by the camera.
struct OpenRoom {
  GridGeometry geo{0.0, 0.0, 0.05, 160, 160};
  IrGrid grid{geo, {}};
  ObjectMap objects{geo, {}};
  OpenRoom() {
    for (int j = 0; j < geo.height; ++j)
      for (int i = 0; i < geo.width; ++i) grid.update_cell({i, j}, false);
  }
  // The camera at `pose` saw its whole 90-degree, `range_m` view and detected nothing.
  void look(const Pose2& pose, double range_m) {
    CameraFrame frame;
    frame.time_s = 0.0;
    frame.view.X_WS = pose;
    frame.view.max_range_m = range_m;
    for (int k = -90; k <= 90; ++k) frame.view.beams.push_back({deg_to_rad(0.5 * k), range_m});
    objects.integrate_frame(frame);
  }
};

ViewpointSearchOptions options(double range_m) {
  ViewpointSearchOptions o;
  o.camera_range_m = range_m;
  o.camera_fov_rad = kPi / 2;
  o.rays = 360;
  return o;
}

TEST(ViewpointSearch, AnUnsearchedViewHoldsItsAreaInCells) {
  OpenRoom room;
  const auto o = options(2.0);
  const auto profile = view_profile(room.grid, room.objects, {4.0, 4.0}, o);
  ASSERT_EQ(profile.size(), 360u);
  // A quarter disc of radius 2 m (91 rays of the 360 are in view: 91/360 of the disc),
  // in 0.05 m cells: pi * 2^2 * 91 / 360 / 0.0025 = 1270.6.
  const double expected = kPi * 4.0 * 91.0 / 360.0 / 0.0025;
  EXPECT_NEAR(mass_in_view(profile, 0.0, o.camera_fov_rad), expected, 0.05 * expected);
  EXPECT_NEAR(mass_in_view(profile, 2.0, o.camera_fov_rad), expected, 0.05 * expected);
  // Every direction the same: the whole disc is four views.
  double all = 0.0;
  for (const double m : profile) all += m;
  EXPECT_NEAR(all, kPi * 4.0 / 0.0025, 0.05 * kPi * 4.0 / 0.0025);
}

TEST(ViewpointSearch, NegativeEvidenceLowersARegionsValue) {
  OpenRoom room;
  const auto o = options(2.0);
  const double before =
      mass_in_view(view_profile(room.grid, room.objects, {4.0, 4.0}, o), 0.0, o.camera_fov_rad);
  // The camera looked east from here and saw nothing: what it saw keeps searched_weight.
  room.look({4.0, 4.0, 0.0}, 2.0);
  const auto profile = view_profile(room.grid, room.objects, {4.0, 4.0}, o);
  const double east = mass_in_view(profile, 0.0, o.camera_fov_rad);
  EXPECT_NEAR(east, o.searched_weight * before, 0.1 * o.searched_weight * before + 15.0);
  // West was not looked at: its value is untouched, and it is the best heading now.
  EXPECT_NEAR(mass_in_view(profile, kPi, o.camera_fov_rad), before, 0.02 * before);
  const HeadingValue best = best_heading(profile, o.camera_fov_rad);
  EXPECT_GT(std::abs(wrap_angle_rad(best.heading_rad)),
            kPi / 2 - 0.05);  // facing away from the searched side
  EXPECT_NEAR(best.mass, before, 0.05 * before);
}

TEST(ViewpointSearch, AWallEndsTheViewAndHoldsNoMass) {
  OpenRoom room;
  const auto o = options(2.0);
  // A wall 1 m east of the viewpoint, across the whole view.
  for (int j = 0; j < room.geo.height; ++j)
    room.grid.update_cell(room.geo.cell_at(5.0, j * 0.05 + 0.025), true);
  const auto profile = view_profile(room.grid, room.objects, {4.0, 4.0}, o);
  // East: a triangle-ish sector cut at x = 5: the 90-degree view to 1 m ahead holds the
  // triangle of half-width 1 m, 1 m^2 = 400 cells (up to the rays' sampling).
  EXPECT_NEAR(mass_in_view(profile, 0.0, o.camera_fov_rad), 400.0, 40.0);
  // West sees its whole quarter disc.
  EXPECT_GT(mass_in_view(profile, kPi, o.camera_fov_rad), 1200.0);
  // unsearched_mass: an occupied cell holds none, a free unseen cell 1.
  EXPECT_EQ(
      unsearched_mass(room.grid, room.objects, room.geo.index(room.geo.cell_at(5.0, 4.0)), 0.1),
      0.0);
  EXPECT_EQ(
      unsearched_mass(room.grid, room.objects, room.geo.index(room.geo.cell_at(3.0, 4.0)), 0.1),
      1.0);
}

TEST(ViewpointSearch, BestHeadingFindsTheRichestWindowAcrossTheWrap) {
  std::vector<double> profile(8, 0.0);
  profile[7] = 2.0;  // bearing 315 degrees
  profile[0] = 1.0;  // 0 degrees
  profile[3] = 2.5;  // 135 degrees
  // A 90-degree view holds three rays of 45 degrees: rays 7, 0, 1 hold 3.0.
  const HeadingValue best = best_heading(profile, kPi / 2);
  EXPECT_NEAR(best.mass, 3.0, 1e-12);
  EXPECT_NEAR(best.heading_rad, 0.0, 1e-12);  // centred on ray 0
  EXPECT_NEAR(mass_in_view(profile, 3 * kPi / 4, kPi / 2), 2.5, 1e-12);
}

TEST(ViewpointSearch, ThePolicyFacesTheUnsearchedHalfOfTheRoom) {
  test::HalfSeenRoom w;  // left half known free, right half unknown; robot at (0.5, 1) facing +x
  // The camera has searched the known half (looked at from where the robot stands).
  CameraFrame frame;
  frame.view.X_WS = {0.5, 1.0, kPi};
  frame.view.max_range_m = 4.0;
  for (int k = -180; k < 180; ++k) frame.view.beams.push_back({deg_to_rad(k), 4.0});
  w.objects.integrate_frame(frame);
  w.pose.yaw_rad = kPi;  // facing the searched wall, so its view holds nothing new
  w.refresh();
  PolicyOptions po = PolicyOptions::from(MissionConfig{}, 4.0, 2.0);
  auto policy = make_exploration_policy("bayes", po);
  EXPECT_EQ(policy->name(), "bayes");
  const auto goal = policy->choose(w.state());
  ASSERT_TRUE(goal);
  EXPECT_EQ(to_string(goal->reason), "viewpoint");
  ASSERT_TRUE(goal->heading_rad);
  // It looks into the unknown half (+x), from the known side.
  EXPECT_LT(std::abs(wrap_angle_rad(*goal->heading_rad)), kPi / 4);
  EXPECT_LT(goal->p_W.x(), 2.0);
  // A viewpoint that sees more mass wins: nearer the unknown half than the robot.
  const auto o = options(4.0);
  const double there =
      best_heading(view_profile(w.grid, w.objects, goal->p_W, o), o.camera_fov_rad).mass;
  const double here =
      best_heading(view_profile(w.grid, w.objects, w.pose.position(), o), o.camera_fov_rad).mass;
  EXPECT_GT(there, here);
  // It keeps the goal while the goal still holds its mass.
  const auto again = policy->choose(w.state());
  ASSERT_TRUE(again);
  EXPECT_EQ(again->cell, goal->cell);
}

// At the entry the frames of one pose have searched the view; bayes still drives in by
// CDOS's rule (the object map's next look comes only from a new pose), and chooses its
// viewpoint once the robot has left the entry.
TEST(ViewpointSearch, AtTheEntryItDrivesInByCdossRule) {
  test::HalfSeenRoom w;
  CameraFrame frame;
  frame.view.X_WS = w.pose;  // facing +x, into the unknown half
  frame.view.max_range_m = 4.0;
  for (int k = -45; k <= 45; ++k) frame.view.beams.push_back({deg_to_rad(k), 4.0});
  w.objects.integrate_frame(frame);
  w.refresh();
  const PolicyOptions po = PolicyOptions::from(MissionConfig{}, 4.0, 2.0);
  ExplorationState at_entry = w.state();
  at_entry.at_entry = true;
  const auto entering = make_exploration_policy("bayes", po)->choose(at_entry);
  const auto cdos = make_exploration_policy("cdos", po)->choose(w.state());
  ASSERT_TRUE(entering && cdos);
  EXPECT_EQ(entering->cell, cdos->cell);
  EXPECT_EQ(entering->reason, cdos->reason);
  const auto left = make_exploration_policy("bayes", po)->choose(w.state());
  ASSERT_TRUE(left);
  EXPECT_EQ(to_string(left->reason), "viewpoint");  // the view it faces is searched: elsewhere
}

// One far detection of an object at `object_W`, seen from the robot's pose.
void detect(test::HalfSeenRoom& w, const Eigen::Vector2d& object_W) {
  CameraFrame frame;
  frame.view = {w.pose, 4.0, {}};
  const Eigen::Vector2d to = object_W - w.pose.position();
  frame.detections = {{std::atan2(to.y(), to.x()), to.norm(), 1.0 / to.norm()}};
  w.objects.integrate_frame(frame);
}

TEST(ViewpointSearch, EvidenceItCanReachIsLookedAtFromTheViewDistance) {
  test::HalfSeenRoom w;
  w.pose = {0.2, 0.4, 0.0};
  w.refresh();
  const Eigen::Vector2d object{1.8, 1.6};  // in the known half, 2 m away
  detect(w, object);
  ASSERT_FALSE(w.objects.evidence_cells().empty());
  const PolicyOptions po = PolicyOptions::from(MissionConfig{}, 4.0, 2.0);
  auto bayes = make_exploration_policy("bayes", po);
  const auto goal = bayes->choose(w.state());
  ASSERT_TRUE(goal);
  EXPECT_EQ(to_string(goal->reason), "evidence");
  // Within the view distance of the evidence (which lies within the object's radius of
  // the object), on the robot's side of it, facing it.
  EXPECT_LE((goal->p_W - object).norm(), po.view_distance_m + 0.15);
  EXPECT_LT((goal->p_W - w.pose.position()).norm(), (object - w.pose.position()).norm());
  ASSERT_TRUE(goal->heading_rad);
  const Eigen::Vector2d to = object - goal->p_W;
  EXPECT_NEAR(wrap_angle_rad(*goal->heading_rad - std::atan2(to.y(), to.x())), 0.0, 0.2);
}

TEST(ViewpointSearch, EvidenceNearOrOutOfReachIsLeftToCdos) {
  test::HalfSeenRoom w;
  detect(w, {3.0, 1.8});  // in the unknown half: no known pose within the view distance
  ASSERT_FALSE(w.objects.evidence_cells().empty());
  const PolicyOptions po = PolicyOptions::from(MissionConfig{}, 4.0, 2.0);
  auto bayes = make_exploration_policy("bayes", po);
  auto cdos = make_exploration_policy("cdos", po);
  const auto a = bayes->choose(w.state()), b = cdos->choose(w.state());
  ASSERT_TRUE(a && b);
  EXPECT_EQ(to_string(a->reason), "curiosity");
  EXPECT_EQ(a->cell, b->cell);
  // Near evidence (1 m, under evidence_view_min_m): CDOS's choice too.
  test::HalfSeenRoom near;
  detect(near, {1.5, 1.1});
  auto bayes_near = make_exploration_policy("bayes", po);
  auto cdos_near = make_exploration_policy("cdos", po);
  const auto c = bayes_near->choose(near.state()), d = cdos_near->choose(near.state());
  ASSERT_TRUE(c && d);
  EXPECT_EQ(c->reason, d->reason);
  EXPECT_EQ(c->cell, d->cell);
}

// Far evidence straight ahead, inside the IR fan: CDOS's curiosity drives at it through
// the frontier cells around it and confirms it on the way; a view of it would stop
// short. The same evidence off to the side is looked at from the view distance.
TEST(ViewpointSearch, FarEvidenceInsideTheIrFanIsLeftToCdos) {
  const PolicyOptions po = PolicyOptions::from(MissionConfig{}, 4.0, 2.0);
  const Eigen::Vector2d object{1.9, 1.1};
  for (const double yaw :
       {0.0, 0.75}) {  // the state's IR fan is 60 degrees: +-30 about the heading
    test::HalfSeenRoom w;
    w.pose = {0.2, 1.0, yaw};
    w.refresh();
    // 1.7 m away, 3 degrees left of the x axis, in the camera's 90 degrees either way.
    CameraFrame frame;
    frame.view = {w.pose, 4.0, {}};
    const Eigen::Vector2d to = object - w.pose.position();
    frame.detections = {
        {wrap_angle_rad(std::atan2(to.y(), to.x()) - yaw), to.norm(), 1.0 / to.norm()}};
    w.objects.integrate_frame(frame);
    ASSERT_FALSE(w.objects.evidence_cells().empty());
    auto bayes = make_exploration_policy("bayes", po);
    auto cdos = make_exploration_policy("cdos", po);
    const auto a = bayes->choose(w.state()), b = cdos->choose(w.state());
    ASSERT_TRUE(a && b);
    if (yaw == 0.0) {
      EXPECT_EQ(a->reason, b->reason);
      EXPECT_EQ(a->cell, b->cell);
    } else {
      EXPECT_EQ(to_string(a->reason), "evidence");  // 40 degrees off the heading
      EXPECT_LE((a->p_W - object).norm(), po.view_distance_m + 0.15);
    }
  }
}

// Evidence the next frames dismiss while the robot is still far from it is looked at
// once more from the view distance, once, when the robot would turn to a new view and
// the place is out of its camera's view; not while the camera faces unsearched ground
// (it drives on) or the place itself (its frames look again), nor when it is near.
TEST(ViewpointSearch, EvidenceDismissedFromAfarIsLookedAtOnceMore) {
  const PolicyOptions po = PolicyOptions::from(MissionConfig{}, 4.0, 2.0);
  const Eigen::Vector2d object{1.8, 1.6};
  struct Case {
    Pose2 at;                  // where it saw the object and the frames dismissed it (facing +x)
    std::vector<double> yaws;  // where it faces at each choice after (the last one decides)
    bool recheck;
  };
  for (const Case& c : {Case{{0.2, 0.4, 0.0}, {-0.6}, true},  // 2 m away, facing what it searched
                        Case{{0.2, 0.4, 0.0}, {0.5, -0.6}, true},  // facing the place first: later
                        Case{{0.2, 0.4, 0.0}, {2.0}, false},  // facing the unsearched north-west
                        Case{{0.2, 0.4, 0.0}, {0.5}, false},  // facing the place
                        Case{{1.2, 1.2, 0.0}, {-1.2}, false}}) {  // 0.7 m away
    test::HalfSeenRoom w;
    w.pose = c.at;
    w.refresh();
    detect(w, object);
    auto bayes = make_exploration_policy("bayes", po);
    ASSERT_TRUE(bayes->choose(w.state()));  // it has seen the evidence
    // Frames from here that show the object's cells without a detection, until the
    // evidence is gone.
    for (int k = 1; k <= 20 && !w.objects.evidence_cells().empty(); ++k) {
      CameraFrame frame;
      frame.time_s = 10.0 * k;
      frame.view.X_WS = w.pose;
      frame.view.max_range_m = 4.0;
      for (int b = -45; b <= 45; ++b) frame.view.beams.push_back({deg_to_rad(b), 4.0});
      w.objects.integrate_frame(frame);
    }
    ASSERT_TRUE(w.objects.evidence_cells().empty());
    std::optional<ExplorationGoal> goal;
    for (const double yaw : c.yaws) {
      w.pose.yaw_rad = yaw;
      w.refresh();
      goal = bayes->choose(w.state());
      ASSERT_TRUE(goal);
      if (goal->reason.rule != GoalRule::kRecheck) bayes->goal_done();
    }
    if (!c.recheck) {
      EXPECT_NE(to_string(goal->reason), "recheck") << c.at.x_m << " " << c.yaws.back();
      continue;
    }
    EXPECT_EQ(to_string(goal->reason), "recheck") << c.yaws.size();
    EXPECT_LE((goal->p_W - object).norm(), po.view_distance_m + 0.15);
    // Kept until reached, then not again.
    const auto again = bayes->choose(w.state());
    ASSERT_TRUE(again);
    EXPECT_EQ(again->cell, goal->cell);
    bayes->goal_done();
    const auto after = bayes->choose(w.state());
    ASSERT_TRUE(after);
    EXPECT_NE(to_string(after->reason), "recheck");
  }
}

TEST(ViewpointSearch, AMapSentAsProbabilitiesMarksItsMeasuredCellsObserved) {
  OpenRoom room;
  const Cell c{10, 10};
  EXPECT_FALSE(room.objects.observed(room.geo.index(c)));
  room.objects.set_cell(c, 0.5, 0.0);  // the prior: not measured
  EXPECT_FALSE(room.objects.observed(room.geo.index(c)));
  room.objects.set_cell(c, 0.45, 0.0);  // one far look: counted as one whole look
  EXPECT_TRUE(room.objects.observed(room.geo.index(c)));
  EXPECT_NEAR(unsearched_mass(room.grid, room.objects, room.geo.index(c), 0.1), 0.1, 1e-12);
  // Odds of 0.3 / 0.7 are logit(0.3) / logit(0.4) = 2.090 close looks (miss likelihood
  // 0.4): 0.1^2.090 = 0.00813 of the mass is left.
  room.objects.set_cell(c, 0.3, 0.0);
  EXPECT_NEAR(unsearched_mass(room.grid, room.objects, room.geo.index(c), 0.1), 0.008133, 1e-5);
}

TEST(ViewpointSearch, EveryLookLowersTheMassFurther) {
  OpenRoom room;
  const Cell c = room.geo.cell_at(4.5, 4.0);  // 0.5 m ahead of the camera
  const std::size_t idx = room.geo.index(c);
  double before = unsearched_mass(room.grid, room.objects, idx, 0.1);
  EXPECT_EQ(before, 1.0);
  for (int look = 0; look < 3; ++look) {
    CameraFrame frame;  // from a new viewpoint each time (the object map gates repeats)
    frame.time_s = 2.0 * look;
    frame.view = {{4.0, 4.0 - 0.1 * look, 0.0}, 2.0, {}};
    for (int k = -45; k <= 45; ++k) frame.view.beams.push_back({deg_to_rad(k), 2.0});
    room.objects.integrate_frame(frame);
    const double after = unsearched_mass(room.grid, room.objects, idx, 0.1);
    EXPECT_LT(after, before) << "look " << look;
    before = after;
  }
  EXPECT_LT(before, 0.01);
}

TEST(ViewpointSearch, UnknownCellsDimTheViewBeyondThem) {
  OpenRoom room;
  auto o = options(2.0);
  o.unknown_block_probability = 0.02;
  const double open =
      mass_in_view(view_profile(room.grid, room.objects, {4.0, 4.0}, o), 0.0, o.camera_fov_rad);
  // The same space unknown to G (a grid nothing was integrated into): each cell's view is
  // dimmed by the unknown cells before it.
  const IrGrid unknown(room.geo, {});
  const double dim =
      mass_in_view(view_profile(unknown, room.objects, {4.0, 4.0}, o), 0.0, o.camera_fov_rad);
  EXPECT_LT(dim, 0.6 * open);
  EXPECT_GT(dim, 0.2 * open);  // about 0.98^(r / 5 cm) over the area: ~0.45 of it at 2 m
}

TEST(ViewpointSearch, AReachedViewpointIsNotChosenAgainNorWhatItCouldNotShow) {
  test::HalfSeenRoom w;
  CameraFrame frame;
  frame.view.X_WS = {0.5, 1.0, kPi};
  frame.view.max_range_m = 4.0;
  for (int k = -180; k < 180; ++k) frame.view.beams.push_back({deg_to_rad(k), 4.0});
  w.objects.integrate_frame(frame);
  w.pose.yaw_rad = kPi;
  w.refresh();
  auto policy = make_exploration_policy("bayes", PolicyOptions::from(MissionConfig{}, 4.0, 2.0));
  const auto first = policy->choose(w.state());
  ASSERT_TRUE(first && first->heading_rad);
  // The robot gets there and faces the view; its camera shows nothing of it (as if a
  // wall G has not seen stood right in front of it).
  w.pose = {first->p_W.x(), first->p_W.y(), *first->heading_rad};
  w.refresh();
  (void)policy->choose(w.state());  // keeps the goal; remembers where the robot is
  policy->goal_done();
  const auto second = policy->choose(w.state());
  ASSERT_TRUE(second);
  EXPECT_GT((second->p_W - first->p_W).norm() +
                std::abs(wrap_angle_rad(*second->heading_rad - *first->heading_rad)),
            0.3);
  // What the first view held is no longer counted: the second view's mass is not the
  // first's region again (it faces elsewhere or sees less of it).
  EXPECT_NE(second->cell, first->cell);
}

// A search in a 12 x 6 m space with a box and a wall: the west half known at the start,
// the east half found by the IR within 1.5 m of the robot as it drives east, the camera
// looking 4 m: at each step a fresh choice (the last goal given up, or reached every
// third step, which marks what its view could not show). The views kept between
// choices (while no cell within D_cam of them changed) must give exactly the choices
// of computing every view afresh.
TEST(ViewpointSearch, KeptViewsChooseExactlyAsViewsComputedAfresh) {
  const GridGeometry geo{0.0, 0.0, 0.05, 240, 120};
  IrGrid grid(geo, {});
  ObjectMap objects(geo, {});
  FrontierTracker tracker(geo);
  GridPathPlanner paths(geo);
  const auto solid = [](const Eigen::Vector2d& p) {
    return (p.x() > 4.0 && p.x() < 4.6 && p.y() > 2.0 && p.y() < 3.2) ||  // a box
           (p.x() > 8.0 && p.x() < 8.15 && p.y() > 1.0);  // a wall with a gap at the bottom
  };
  for (int j = 0; j < geo.height; ++j)
    for (int i = 0; i < geo.width / 2; ++i) grid.update_cell({i, j}, solid(geo.center({i, j})));
  Pose2 pose{1.0, 3.0, 0.0};
  FrontierSets sets;
  // The sensors at `pose`: the ground within 1.5 m revealed (free, or occupied where
  // solid), the camera's 90-degree, 4 m view looked at without a detection.
  const auto sense = [&] {
    const Cell c0 = geo.cell_at(pose.x_m, pose.y_m);
    for (int dj = -30; dj <= 30; ++dj)
      for (int di = -30; di <= 30; ++di) {
        const Cell c{c0.i + di, c0.j + dj};
        if (!geo.contains(c) || di * di + dj * dj > 30 * 30) continue;
        grid.update_cell(c, solid(geo.center(c)));
      }
    CameraFrame frame;
    frame.time_s = pose.x_m + pose.y_m;  // every frame is fused
    frame.view.X_WS = pose;
    frame.view.max_range_m = 4.0;
    for (int k = -45; k <= 45; ++k) frame.view.beams.push_back({deg_to_rad(k), 4.0});
    objects.integrate_frame(frame);
    tracker.update(grid);
    paths.compute(grid, geo.cell_at(pose.x_m, pose.y_m), GridPathPlanner::Traversal::kKnownFree);
    sets = tracker.extract(paths.distances_m(), pose, deg_to_rad(30), 4.0);
  };
  const auto state = [&] {
    return ExplorationState{grid, objects,    tracker,        sets, paths,
                            pose, {0.0, 0.0}, deg_to_rad(30), 4.0,  std::nullopt};
  };
  const PolicyOptions po = PolicyOptions::from(MissionConfig{}, 4.0, 2.0);
  ViewpointSearchPolicy kept(po, true), afresh(po, false);
  int compared = 0;
  for (int step = 0; step < 24; ++step) {
    pose = {1.0 + 0.45 * step, 3.0 + 1.2 * std::sin(0.9 * step), 2.5 * std::sin(0.7 * step)};
    if (solid(pose.position())) pose.y_m = 0.6;
    sense();
    const auto a = kept.choose(state());
    const auto b = afresh.choose(state());
    ASSERT_EQ(a.has_value(), b.has_value()) << "step " << step;
    if (!a) continue;
    EXPECT_EQ(a->cell, b->cell) << "step " << step;
    EXPECT_EQ(a->heading_rad, b->heading_rad) << "step " << step;
    EXPECT_EQ(a->score, b->score) << "step " << step;
    EXPECT_EQ(a->reason, b->reason) << "step " << step;
    ++compared;
    // Every view on a 0.25 m lattice, kept or not, is the one computed afresh.
    for (int j = 2; j < geo.height; j += 5)
      for (int i = 2; i < geo.width; i += 5) {
        const HeadingValue x = kept.view_from(grid, objects, {i, j}),
                           y = afresh.view_from(grid, objects, {i, j});
        ASSERT_EQ(x.mass, y.mass) << "step " << step << " cell " << i << "," << j;
        ASSERT_EQ(x.heading_rad, y.heading_rad) << "step " << step << " cell " << i << "," << j;
      }
    if (step % 3 == 2 && a->heading_rad && a->reason.rule == GoalRule::kViewpoint) {
      // Reached: the robot stands there facing the view, and looks.
      pose = {a->p_W.x(), a->p_W.y(), *a->heading_rad};
      sense();
      (void)kept.choose(state());
      (void)afresh.choose(state());
    }
    kept.goal_done();
    afresh.goal_done();
  }
  EXPECT_GE(compared, 20);
  // The kept views were used (the test would prove nothing otherwise), and not always.
  EXPECT_GT(kept.views_kept(), kept.views_computed() / 8);
  EXPECT_GT(kept.views_computed(), 0u);
  EXPECT_EQ(afresh.views_kept(), 0u);
}

}  // namespace
}  // namespace ferret
