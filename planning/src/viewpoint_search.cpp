#include "ferret/planning/viewpoint_search.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>

#include "ferret/mapping/frontier.hpp"
#include "ferret/mapping/ir_grid.hpp"
#include "ferret/mapping/object_map.hpp"
#include "ferret/planning/curiosity.hpp"
#include "ferret/planning/grid_path_planner.hpp"

namespace ferret {
namespace {

constexpr double kTwoPi = 2.0 * std::numbers::pi;

double direction_rad(const Eigen::Vector2d& v) { return std::atan2(v.y(), v.x()); }

// True when p_W lies within range_m of the robot and within half of fov_rad of its heading.
bool in_sector(const Pose2& X_WG, const Eigen::Vector2d& p_W, double fov_rad, double range_m) {
  const Eigen::Vector2d to = p_W - X_WG.position();
  return to.norm() <= range_m &&
         std::abs(wrap_angle_rad(direction_rad(to) - X_WG.yaw_rad)) <= 0.5 * fov_rad;
}

// Along the ray from p in the unit direction u, the distance to where it leaves the map.
double distance_to_edge_m(const GridGeometry& g, const Eigen::Vector2d& p,
                          const Eigen::Vector2d& u) {
  const double c = u.x(), s = u.y();
  const double x0 = g.origin_x_m, x1 = g.origin_x_m + g.width * g.resolution_m;
  const double y0 = g.origin_y_m, y1 = g.origin_y_m + g.height * g.resolution_m;
  double t = std::numeric_limits<double>::infinity();
  if (c > 1e-12) t = std::min(t, (x1 - p.x()) / c);
  if (c < -1e-12) t = std::min(t, (x0 - p.x()) / c);
  if (s > 1e-12) t = std::min(t, (y1 - p.y()) / s);
  if (s < -1e-12) t = std::min(t, (y0 - p.y()) / s);
  return std::max(0.0, t);
}

// The unit direction of each of `rays` rays, ray k at bearing 2 pi k / rays.
std::vector<Eigen::Vector2d> ray_directions(int rays) {
  const double dphi = kTwoPi / rays;
  std::vector<Eigen::Vector2d> u(static_cast<std::size_t>(rays));
  for (int k = 0; k < rays; ++k)
    u[static_cast<std::size_t>(k)] = {std::cos(k * dphi), std::sin(k * dphi)};
  return u;
}

int ray_of(double bearing_rad, int rays) {
  const double u = bearing_rad / kTwoPi;
  const int k = static_cast<int>(std::floor((u - std::floor(u)) * rays + 0.5));
  return k % rays;
}

ViewpointSearchOptions options_from(const PolicyOptions& p) {
  ViewpointSearchOptions o;
  o.camera_fov_rad = p.camera_fov_rad;
  o.camera_range_m = p.curiosity.camera_range_m;
  o.max_velocity_mps = p.max_velocity_mps;
  o.max_yaw_rate_radps = p.max_yaw_rate_radps;
  return o;
}

// 1 / logit(miss likelihood): log-odds to looks (one close miss is one look).
double looks_per_log_odds(const ObjectMap& objects) {
  const double miss = objects.options().miss_likelihood;
  return 1.0 / std::log(miss / (1.0 - miss));
}

double mass_of(const IrGrid& grid, const ObjectMap& objects, std::size_t idx,
               double searched_weight, double looks_per_log_odds) {
  if (grid.label_at(idx) == GridLabel::kOccupied) return 0.0;
  if (!objects.observed(idx)) return 1.0;
  // Each further look leaves searched_weight of what was left: the looks are counted by
  // the object map's odds (one miss at close range lowers them by the miss likelihood's;
  // far looks count less), the first look whole. Most cells were looked at once or
  // from afar (looks <= 1): no power to take.
  const double looks =
      std::min(0.0, static_cast<double>(objects.log_odds_at(idx))) * looks_per_log_odds;
  return looks <= 1.0 ? searched_weight : std::pow(searched_weight, looks);
}
}  // namespace

double unsearched_mass(const IrGrid& grid, const ObjectMap& objects, std::size_t idx,
                       double searched_weight) {
  return mass_of(grid, objects, idx, searched_weight, looks_per_log_odds(objects));
}

void for_each_cell_in_view(const IrGrid& grid, const Pose2& X_WC,
                           const ViewpointSearchOptions& options,
                           const std::function<void(std::size_t)>& visit) {
  const GridGeometry& g = grid.geometry();
  const int rays = std::max(1, options.rays);
  const double dphi = kTwoPi / rays;
  const int half = static_cast<int>(std::floor(0.5 * options.camera_fov_rad / dphi + 1e-9));
  const int centre = ray_of(X_WC.yaw_rad, rays);
  const Eigen::Vector2d p = X_WC.position();
  for (int d = -half; d <= half; ++d) {
    const double phi = (centre + d) * dphi;
    const Eigen::Vector2d to =
        p + options.camera_range_m * Eigen::Vector2d(std::cos(phi), std::sin(phi));
    trace_ray(g, p, to, [&](Cell c, double) {
      const std::size_t idx = g.index(c);
      if (grid.label_at(idx) == GridLabel::kOccupied) return false;
      visit(idx);
      return true;
    });
  }
}

namespace {
// view_profile with m(c) from `mass_at(idx)` (the unseeable cells already 0).
// `directions` is ray_directions(options.rays).
template <class MassAt>
std::vector<double> profile_with(const IrGrid& grid, const Eigen::Vector2d& p_W,
                                 const ViewpointSearchOptions& options,
                                 const std::vector<Eigen::Vector2d>& directions, MassAt&& mass_at) {
  const GridGeometry& g = grid.geometry();
  const int rays = static_cast<int>(directions.size());
  const double dphi = kTwoPi / rays;
  // The ray's length inside a cell, times the arc r * dphi its sector is wide there, is
  // the sector's area in that cell: in cells, length * r * dphi / resolution^2. (Each
  // cell a ray touches counted whole would count diagonal rays up to 1.4 times over.)
  const double per_m2 = dphi / (g.resolution_m * g.resolution_m);
  std::vector<double> profile(static_cast<std::size_t>(rays), 0.0);
  for (int k = 0; k < rays; ++k) {
    const Eigen::Vector2d& u = directions[static_cast<std::size_t>(k)];
    const Eigen::Vector2d to = p_W + options.camera_range_m * u;
    double sum = 0.0, mass = 0.0, entry_m = 0.0, transmission = 1.0;
    const auto close_cell = [&](double exit_m) {  // the cell entered at entry_m, left at exit_m
      const double r_mid = 0.5 * (entry_m + exit_m);
      sum += mass * (exit_m - entry_m) * r_mid * per_m2;
    };
    bool blocked = false;
    trace_ray(g, p_W, to, [&](Cell c, double distance_m) {
      const std::size_t idx = g.index(c);
      close_cell(distance_m);
      entry_m = distance_m;
      if (grid.label_at(idx) == GridLabel::kOccupied) {  // the view ends at a wall
        blocked = true;
        return false;
      }
      mass = transmission * mass_at(idx);
      // An unknown cell may hold what ends the view: the view beyond it is worth less.
      if (grid.label_at(idx) == GridLabel::kUnknown)
        transmission *= 1.0 - options.unknown_block_probability;
      return true;
    });
    if (!blocked) close_cell(std::min(options.camera_range_m, distance_to_edge_m(g, p_W, u)));
    profile[static_cast<std::size_t>(k)] = sum;
  }
  return profile;
}
}  // namespace

std::vector<double> view_profile(const IrGrid& grid, const ObjectMap& objects,
                                 const Eigen::Vector2d& p_W, const ViewpointSearchOptions& options,
                                 const std::vector<std::uint8_t>& unseeable) {
  const double looks_per_m = looks_per_log_odds(objects);
  return profile_with(
      grid, p_W, options, ray_directions(std::max(1, options.rays)), [&](std::size_t idx) {
        return !unseeable.empty() && unseeable[idx] != 0
                   ? 0.0
                   : mass_of(grid, objects, idx, options.searched_weight, looks_per_m);
      });
}

std::vector<double> ViewpointSearchPolicy::cached_profile(const IrGrid& grid,
                                                          const ObjectMap& objects,
                                                          const Eigen::Vector2d& p_W) {
  const double looks_per_m = looks_per_log_odds(objects);
  return profile_with(grid, p_W, options_, directions_, [&](std::size_t idx) {
    if (memo_stamp_[idx] != memo_generation_) {
      memo_stamp_[idx] = memo_generation_;
      memo_mass_[idx] = !unseeable_.empty() && unseeable_[idx] != 0
                            ? 0.0
                            : mass_of(grid, objects, idx, options_.searched_weight, looks_per_m);
    }
    return memo_mass_[idx];
  });
}

HeadingValue ViewpointSearchPolicy::view_from(const IrGrid& grid, const ObjectMap& objects,
                                              Cell c) {
  const GridGeometry& g = grid.geometry();
  // Every cell a ray from c's centre can reach (D_cam, and a cell for the ray's end).
  const int reach = static_cast<int>(std::ceil(options_.camera_range_m / g.resolution_m)) + 1;
  const Cell lo{c.i - reach, c.j - reach}, hi{c.i + reach, c.j + reach};
  const std::uint64_t unseeable = unseeable_revisions_ ? unseeable_revisions_->revision() : 0;
  const auto it = keep_views_ ? kept_views_.find(g.index(c)) : kept_views_.end();
  if (it != kept_views_.end() &&
      grid.label_revisions().unchanged_since(it->second.labels, lo, hi) &&
      objects.revisions().unchanged_since(it->second.odds, lo, hi) &&
      (!unseeable_revisions_ ||
       unseeable_revisions_->unchanged_since(it->second.unseeable, lo, hi))) {
    ++views_kept_;
    return it->second.view;
  }
  ++views_computed_;
  const HeadingValue view =
      best_heading(cached_profile(grid, objects, g.center(c)), options_.camera_fov_rad);
  if (keep_views_)
    kept_views_[g.index(c)] = {view, grid.label_revisions().revision(),
                               objects.revisions().revision(), unseeable};
  return view;
}

void ViewpointSearchPolicy::begin_cycle(std::size_t cells) {
  if (memo_stamp_.size() != cells) {
    memo_stamp_.assign(cells, 0);
    memo_mass_.assign(cells, 0.0);
    memo_generation_ = 0;
  }
  if (++memo_generation_ == 0) {  // wrapped after 2^32 cycles: forget every stamp
    std::fill(memo_stamp_.begin(), memo_stamp_.end(), 0u);
    memo_generation_ = 1;
  }
}

double mass_in_view(const std::vector<double>& profile, double heading_rad, double fov_rad) {
  const int rays = static_cast<int>(profile.size());
  if (rays == 0) return 0.0;
  const int half = static_cast<int>(std::floor(0.5 * fov_rad / (kTwoPi / rays) + 1e-9));
  const int centre = ray_of(heading_rad, rays);
  double sum = 0.0;
  for (int d = -half; d <= half; ++d)
    sum += profile[static_cast<std::size_t>(((centre + d) % rays + rays) % rays)];
  return sum;
}

HeadingValue best_heading(const std::vector<double>& profile, double fov_rad) {
  const int rays = static_cast<int>(profile.size());
  HeadingValue best;
  if (rays == 0) return best;
  const int half = static_cast<int>(std::floor(0.5 * fov_rad / (kTwoPi / rays) + 1e-9));
  // A sliding window over the circle.
  double window = 0.0;
  for (int d = -half; d <= half; ++d)
    window += profile[static_cast<std::size_t>(((d % rays) + rays) % rays)];
  best.mass = window;
  for (int k = 1; k < rays; ++k) {
    window += profile[static_cast<std::size_t>((k + half) % rays)] -
              profile[static_cast<std::size_t>(((k - half - 1) % rays + rays) % rays)];
    if (window > best.mass + 1e-12) {
      best.mass = window;
      best.heading_rad = k * kTwoPi / rays;
    }
  }
  best.heading_rad = wrap_angle_rad(best.heading_rad);
  return best;
}

ViewpointSearchPolicy::ViewpointSearchPolicy(const PolicyOptions& options, bool keep_views)
    : options_(options_from(options)),
      cdos_(options, false),
      view_distance_m_(options.view_distance_m),
      directions_(ray_directions(std::max(1, options_.rays))),
      keep_views_(keep_views) {}

void ViewpointSearchPolicy::goal_done() {
  if (committed_ && committed_->heading_rad) {
    const Pose2 view{committed_->p_W.x(), committed_->p_W.y(), *committed_->heading_rad};
    visited_.push_back(view);
    // Reached (not given up): what its view did not show, no view of it can.
    if (grid_ && objects_ &&
        (last_robot_W_ - committed_->p_W).norm() <= options_.revisit_radius_m) {
      if (unseeable_.empty()) {
        unseeable_.assign(grid_->geometry().size(), 0);
        unseeable_revisions_.emplace(grid_->geometry());
      }
      for_each_cell_in_view(*grid_, view, options_, [&](std::size_t idx) {
        if (!objects_->observed(idx) && unseeable_[idx] == 0) {
          unseeable_[idx] = 1;
          unseeable_revisions_->touch(idx);
        }
      });
    }
  }
  committed_.reset();
  recheck_.reset();
  cdos_.goal_done();
}

bool ViewpointSearchPolicy::keeps_goal(const ObjectMap& objects,
                                       const FrontierTracker& tracker) const {
  if (!objects.evidence_cells().empty()) return !committed_ && cdos_.keeps_goal(objects, tracker);
  // Without evidence the viewpoint is kept by choose() (its mass is looked at again
  // there, which the maps alone cannot tell).
  (void)tracker;
  return false;
}

std::optional<ExplorationGoal> ViewpointSearchPolicy::choose(const ExplorationState& s) {
  if (grid_ != &s.grid || objects_ != &s.objects)
    kept_views_.clear();  // other maps: nothing kept holds
  grid_ = &s.grid;
  objects_ = &s.objects;
  begin_cycle(s.grid.geometry().size());
  last_robot_W_ = s.X_WG.position();
  if (!s.objects.evidence_cells().empty()) {
    committed_.reset();  // evidence: curiosity decides until it is confirmed or dismissed
    // Evidence farther than evidence_view_min_m: drive to a pose that sees it from
    // within view_distance_m (the nearest such known-free cell, facing it), as the
    // oracle does with the truth; nearer, or ahead inside the IR fan (F_v lies round
    // it: CDOS drives at it without stopping short), CDOS's curiosity confirms it on
    // its way.
    const auto evidence = collect_evidence(s.objects);
    const EvidenceCell& strongest = strongest_evidence(evidence);
    last_evidence_W_ = strongest.p_W;
    const bool ahead = in_sector(s.X_WG, strongest.p_W, s.ir_fov_rad, s.ir_range_m);
    if (!ahead && (strongest.p_W - s.X_WG.position()).norm() >= options_.evidence_view_min_m)
      if (auto goal = viewing_goal(s.grid, s.tracker, s.paths, strongest.p_W, view_distance_m_)) {
        goal->reason = {GoalRule::kEvidence};
        return goal;
      }
    return cdos_.choose(s);
  }
  if (recheck_) {
    if (s.paths.reachable(recheck_->cell) && !s.tracker.blacklisted(recheck_->cell))
      return recheck_;
    recheck_.reset();
  }
  if (committed_ && s.paths.reachable(committed_->cell) &&
      !s.tracker.blacklisted(committed_->cell)) {
    const auto profile = cached_profile(s.grid, s.objects, committed_->p_W);
    const double mass =
        mass_in_view(profile, committed_->heading_rad.value_or(0.0), options_.camera_fov_rad);
    if (mass >= options_.keep_fraction * committed_mass_ && mass > 0.0) return committed_;
  }
  committed_.reset();
  // The camera searches what it faces at its next frame: while most of its view is
  // still unsearched (the start, a new room), there is no reason to turn away; CDOS
  // (the rapid rule without evidence) drives on into it.
  // At the entry the object map has the looks of one pose, and takes the next only from
  // a new pose: CDOS's rule drives in until then, rather than the first frames' misses
  // turning the robot away from the view it entered facing (an object in it that those
  // frames missed is found by the next ones on the way in).
  if (s.at_entry || fresh_view(s)) return cdos_.choose(s);
  // Evidence the frames dismissed before the robot came near it: when the robot would
  // turn to a new view and that place is out of the camera's view, it looks at it once
  // more, from the view distance (a few misses from afar do not make it searched).
  // While the camera faces unsearched ground (above), or faces the place, its next
  // frames may see the object again; once they looked from near, it is done.
  if (last_evidence_W_) {
    const Eigen::Vector2d at = *last_evidence_W_;
    const bool far = (at - s.X_WG.position()).norm() > 1.5 * view_distance_m_;
    const bool in_view = in_sector(s.X_WG, at, options_.camera_fov_rad, options_.camera_range_m);
    if (!in_view || !far) last_evidence_W_.reset();
    const bool rechecked =
        std::any_of(rechecked_W_.begin(), rechecked_W_.end(),
                    [&](const Eigen::Vector2d& r) { return (r - at).norm() < 0.5; });
    if (!in_view && far && !rechecked)
      if (auto goal = viewing_goal(s.grid, s.tracker, s.paths, at, view_distance_m_)) {
        rechecked_W_.push_back(at);
        goal->reason = {GoalRule::kRecheck};
        recheck_ = goal;
        return recheck_;
      }
  }
  if (auto goal = choose_viewpoint(s)) {
    committed_ = goal;
    committed_mass_ = goal->score;  // see choose_viewpoint: the mass, not the rate
    committed_->score = goal->score;
    return committed_;
  }
  return cdos_.choose(s);  // nothing left to see from known ground: explore as CDOS does
}

bool ViewpointSearchPolicy::fresh_view(const ExplorationState& s) const {
  const Eigen::Vector2d p = s.X_WG.position();
  ViewpointSearchOptions all = options_;
  all.searched_weight = 1.0;
  const double full = mass_in_view(view_profile(s.grid, s.objects, p, all), s.X_WG.yaw_rad,
                                   options_.camera_fov_rad);
  const double left = mass_in_view(view_profile(s.grid, s.objects, p, options_), s.X_WG.yaw_rad,
                                   options_.camera_fov_rad);
  return full > 0.0 && left >= options_.fresh_view_fraction * full;
}

std::optional<ExplorationGoal> ViewpointSearchPolicy::choose_viewpoint(const ExplorationState& s) {
  const GridGeometry& g = s.grid.geometry();
  std::vector<Cell> candidates;
  const int stride =
      std::max(1, static_cast<int>(std::lround(options_.lattice_m / g.resolution_m)));
  for (int j = stride / 2; j < g.height; j += stride)
    for (int i = stride / 2; i < g.width; i += stride) {
      const Cell c{i, j};
      if (s.paths.reachable(c) && !s.tracker.blacklisted(c)) candidates.push_back(c);
    }
  for (const auto* set : {&s.frontier_sets().visible, &s.frontier_sets().global}) {
    const std::size_t n = set->size();
    const std::size_t limit =
        static_cast<std::size_t>(std::max(1, options_.max_frontier_candidates));
    const std::size_t step = std::max<std::size_t>(1, (n + limit - 1) / limit);
    for (std::size_t k = 0; k < n; k += step) {
      const Cell c = (*set)[k];
      if (s.paths.reachable(c) && !s.tracker.blacklisted(c)) candidates.push_back(c);
    }
  }
  const Eigen::Vector2d p = s.X_WG.position();
  // Turning to leave, driving, turning to face the view (the arrival heading taken as
  // the straight line's: the path's own bends are not priced). All but the last turn
  // is known before the view is: the least time a candidate can take.
  struct Timed {
    Cell cell;
    double along_rad, leave_turn_rad, least_s;
  };
  std::vector<Timed> timed;
  timed.reserve(candidates.size());
  for (const Cell& c : candidates) {
    const Eigen::Vector2d to = g.center(c) - p;
    const bool moves = to.norm() > 1e-6;
    const double along = moves ? direction_rad(to) : s.X_WG.yaw_rad;
    const double leave_turn =
        std::abs(wrap_angle_rad(along - s.X_WG.yaw_rad)) * (moves ? 1.0 : 0.0);
    timed.push_back({c, along, leave_turn,
                     s.paths.distance_m(c) / options_.max_velocity_mps +
                         leave_turn / options_.max_yaw_rate_radps + options_.overhead_s});
  }
  // No view holds more than every cell of the field of view's sectors at mass 1, seen
  // whole (a ray's segments sum to the integral of r dr over at most D_cam): a
  // candidate whose least time makes even that slower than the best so far cannot win,
  // nor can any after it in order of that time. The choice is the full scan's.
  const int rays = static_cast<int>(directions_.size());
  const double dphi = kTwoPi / rays;
  const int half = static_cast<int>(std::floor(0.5 * options_.camera_fov_rad / dphi + 1e-9));
  const double most_mass = (1.0 + 1e-9) * (2 * half + 1) * 0.5 * options_.camera_range_m *
                           options_.camera_range_m * dphi / (g.resolution_m * g.resolution_m);
  std::stable_sort(timed.begin(), timed.end(),
                   [](const Timed& a, const Timed& b) { return a.least_s < b.least_s; });
  std::optional<ExplorationGoal> best;
  double best_rate = 0.0;
  for (const Timed& t : timed) {
    if (best && most_mass / t.least_s < best_rate) break;
    const Cell& c = t.cell;
    const Eigen::Vector2d q = g.center(c);
    const HeadingValue view = view_from(s.grid, s.objects, c);
    if (view.mass <= 1e-9) continue;
    const bool seen_from_here = std::any_of(visited_.begin(), visited_.end(), [&](const Pose2& v) {
      return (v.position() - q).norm() < options_.revisit_radius_m &&
             std::abs(wrap_angle_rad(v.yaw_rad - view.heading_rad)) < 0.5 * options_.camera_fov_rad;
    });
    if (seen_from_here) continue;
    const double turns =
        t.leave_turn_rad + std::abs(wrap_angle_rad(view.heading_rad - t.along_rad));
    const double time_s = s.paths.distance_m(c) / options_.max_velocity_mps +
                          turns / options_.max_yaw_rate_radps + options_.overhead_s;
    const double rate = view.mass / time_s;
    if (!best || rate > best_rate + 1e-12) {
      best_rate = rate;
      best = ExplorationGoal{};
      best->cell = c;
      best->p_W = q;
      best->heading_rad = view.heading_rad;
      best->score = view.mass;
      best->reason = {GoalRule::kViewpoint};
    }
  }
  return best;
}

}  // namespace ferret
