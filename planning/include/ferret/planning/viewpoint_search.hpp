#pragma once
// Bayesian viewpoint search (`bayes`, docs/object_search.md): where CDOS has no object
// evidence it falls back to the rapid-frontier rule, which explores for the map, not
// for the object. This policy searches for the object: the object is equally likely in
// every cell it could stand in, a cell the camera has measured without a detection
// keeps only `searched_weight` of that (the negative evidence of every frame), and the
// next goal is the viewpoint (a reachable pose and heading) that brings the most of the
// remaining probability mass into the camera's view per second of travel:
//
//   m(c)       = 0 (G occupied) | 1 (the camera never measured c) | searched_weight^k
//                after k looks without a detection (k >= 1, counted by the object map's
//                odds, which hold every frame's evidence on the cell)
//   V(x, th)   = sum of m(c) over the cells the camera sees from x facing th: within
//                D_cam and the field of view, on a line of sight through G that an
//                occupied cell ends and each unknown cell dims by (1 - 0.02) (the
//                clutter the IR has not met yet), each weighted by the area of the view
//                it holds
//   T(x, th)   = path distance / v_max + turns / yaw rate + overhead_s
//   goal       = argmax V / T over reachable cells on a lattice and the frontier cells
//
// Once there is evidence (a cell with p > 0.5) it looks at it: the goal is the nearest
// reachable pose within the view distance of the strongest evidence (where one frame's
// confidence passes lambda2), facing it, as the oracle does with the truth; evidence
// nearer than evidence_view_min_m, or inside the IR fan ahead (where CDOS's frontier
// cells lead straight at it), or no such pose, leaves the choice to CDOS's curiosity.
// Evidence that later frames dismiss is looked at once more from the view distance when
// the robot would next turn to a new view, if it is then farther than 1.5 view
// distances from it (a few misses from afar would otherwise leave the place as searched
// as any). While its camera faces unsearched ground, and at the entry until the robot
// has moved the object map's min_move_m (ExplorationState::at_entry), it drives on as
// CDOS does. Without evidence the chosen viewpoint is kept while it still holds
// keep_fraction of the mass it was chosen for; once reached it is not chosen again, and
// what its view did not show holds no mass from then on (hidden by what G has not seen).

#include <Eigen/Core>
#include <cstdint>
#include <functional>
#include <optional>
#include <unordered_map>
#include <vector>

#include "ferret/core/grid.hpp"
#include "ferret/mapping/block_revisions.hpp"
#include "ferret/planning/exploration_policy.hpp"
#include "ferret/planning/policies.hpp"

namespace ferret {

class IrGrid;
class ObjectMap;

struct ViewpointSearchOptions {
  double camera_fov_rad = 1.5707963267948966;  ///< the object camera's horizontal field of view
  double camera_range_m = 4.0;                 ///< D_cam
  /// Mass a look without a detection leaves in a cell: 1 - the detector's recall (the
  /// simulated detector's detection_probability is 0.9 within D_cam). The first look
  /// counts whole wherever in D_cam it was; further looks are counted by the object
  /// map's odds (unsearched_mass).
  double searched_weight = 0.1;
  int rays = 72;  ///< rays of a viewpoint's 360-degree profile
  /// The chance that an unknown cell of G ends the camera's view (each cell's share of
  /// the clutter the IR has not seen yet): the view through n unknown cells is worth
  /// (1 - this)^n.
  double unknown_block_probability = 0.02;
  double lattice_m = 0.5;            ///< spacing of the candidate viewpoints on known free ground
  int max_frontier_candidates = 64;  ///< frontier cells also tried (evenly subsampled)
  double max_velocity_mps = 2.0;
  double max_yaw_rate_radps = 2.0;
  double overhead_s = 1.0;     ///< added to every travel time (starting, stopping, settling)
  double keep_fraction = 0.9;  ///< keep the goal while it holds this much of its chosen mass
  /// A new choice waits while this much of what the camera faces now is unsearched
  /// (its next frames search it on the way; CDOS's rule drives meanwhile).
  double fresh_view_fraction = 0.5;
  /// Evidence at least this far from the robot is looked at from a pose within the
  /// view distance of it (viewing_goal); nearer evidence is left to CDOS's curiosity.
  double evidence_view_min_m = 1.5;
  /// A candidate this near a viewpoint already reached, facing within half the field of
  /// view of its heading, is not chosen again.
  double revisit_radius_m = 0.5;
};

/// m(c) of the header comment, for the cell at `idx`.
[[nodiscard]] double unsearched_mass(const IrGrid& grid, const ObjectMap& objects, std::size_t idx,
                                     double searched_weight);

/// The mass each of `options.rays` rays (ray k at bearing 2 pi k / rays in the world
/// frame) brings into view from p_W, area-weighted. Cells flagged in `unseeable` (one
/// byte a cell, or empty) hold none.
[[nodiscard]] std::vector<double> view_profile(const IrGrid& grid, const ObjectMap& objects,
                                               const Eigen::Vector2d& p_W,
                                               const ViewpointSearchOptions& options,
                                               const std::vector<std::uint8_t>& unseeable = {});
/// Calls visit(idx) for every cell the camera would see from `X_WC` (its field of view,
/// D_cam, lines of sight that G's occupied cells end).
void for_each_cell_in_view(const IrGrid& grid, const Pose2& X_WC,
                           const ViewpointSearchOptions& options,
                           const std::function<void(std::size_t)>& visit);

struct HeadingValue {
  double heading_rad = 0.0;
  double mass = 0.0;  ///< V(x, heading)
};
/// The heading whose field of view holds the most of `profile`'s mass (ties: the
/// lowest ray index), and that mass.
[[nodiscard]] HeadingValue best_heading(const std::vector<double>& profile, double fov_rad);
/// V(x, heading): the mass of the rays inside the field of view centred on heading_rad.
[[nodiscard]] double mass_in_view(const std::vector<double>& profile, double heading_rad,
                                  double fov_rad);

class ViewpointSearchPolicy final : public ExplorationPolicy {
 public:
  /// keep_views false computes every candidate's view afresh each choice (the tests'
  /// reference for the kept views, which must choose the same).
  explicit ViewpointSearchPolicy(const PolicyOptions& options, bool keep_views = true);
  [[nodiscard]] std::string_view name() const override { return "bayes"; }
  [[nodiscard]] std::optional<ExplorationGoal> choose(const ExplorationState& state) override;
  /// The viewpoint was reached (or given up): it is not chosen again (see visited_).
  void goal_done() override;
  [[nodiscard]] bool keeps_goal(const ObjectMap& objects,
                                const FrontierTracker& tracker) const override;
  [[nodiscard]] const ViewpointSearchOptions& options() const { return options_; }
  /// The best view from cell c's centre (best_heading of its view_profile, what the
  /// robot's reached views could not show left out), kept or computed, on the maps of
  /// the last choose(), which must be the maps given.
  [[nodiscard]] HeadingValue view_from(const IrGrid& grid, const ObjectMap& objects, Cell c);
  /// Candidate views taken from the kept ones, and computed, since construction.
  [[nodiscard]] std::size_t views_kept() const { return views_kept_; }
  [[nodiscard]] std::size_t views_computed() const { return views_computed_; }

 private:
  std::optional<ExplorationGoal> choose_viewpoint(const ExplorationState& s);
  [[nodiscard]] bool fresh_view(const ExplorationState& s) const;
  /// A new cycle's maps: the masses remembered from the last one are stale.
  void begin_cycle(std::size_t cells);
  /// view_profile with the unseeable cells, each cell's m(c) computed once a cycle (a
  /// cell is in view of most candidates, and m(c) of a cell looked at twice is a pow).
  [[nodiscard]] std::vector<double> cached_profile(const IrGrid& grid, const ObjectMap& objects,
                                                   const Eigen::Vector2d& p_W);

  ViewpointSearchOptions options_;
  CdosPolicy cdos_;
  std::optional<ExplorationGoal> committed_;
  double committed_mass_ = 0.0;
  double view_distance_m_ = 0.95;
  std::optional<Eigen::Vector2d>
      last_evidence_W_;  ///< the strongest evidence of the last choice that had some
  std::optional<ExplorationGoal> recheck_;    ///< a view of dismissed evidence, kept until reached
  std::vector<Eigen::Vector2d> rechecked_W_;  ///< evidence looked at once more: not again
  std::vector<Eigen::Vector2d> directions_;   ///< the rays' unit directions (ray_directions)
  /// Viewpoints reached or given up. What a view still holds there is mass the camera
  /// cannot reach from it (behind a wall G has not seen, which the view's unknown
  /// cells let through): chosen again, the robot would shuttle between such views.
  std::vector<Pose2> visited_;
  /// Cells that were in view of a viewpoint the robot stood at, and that its camera did
  /// not measure: something G has not seen hides them there (the inside of a box whose
  /// sides the IR has not met). They hold no mass from then on, or the robot would
  /// keep coming back for what no view of it can show.
  std::vector<std::uint8_t> unseeable_;
  Eigen::Vector2d last_robot_W_ = Eigen::Vector2d::Constant(1e9);
  // m(c) of this cycle, valid where memo_stamp_ is memo_generation_ (no pass over the
  // map to clear it each cycle).
  std::vector<double> memo_mass_;
  std::vector<std::uint32_t> memo_stamp_;
  std::uint32_t memo_generation_ = 0;
  /// The best view from each candidate cell, kept while no cell within D_cam of it
  /// changed (its labels, its odds, its being unseeable; the maps' BlockRevisions): a
  /// frame changes the views near the robot, the rest are taken from here.
  struct KeptView {
    HeadingValue view;
    std::uint64_t labels = 0, odds = 0, unseeable = 0;  ///< the revisions it was computed at
  };
  std::unordered_map<std::size_t, KeptView> kept_views_;
  bool keep_views_ = true;
  std::size_t views_kept_ = 0, views_computed_ = 0;
  std::optional<BlockRevisions> unseeable_revisions_;

  // The maps of the last choice (the caller's, alive for the search): goal_done() reads them.
  const IrGrid* grid_ = nullptr;
  const ObjectMap* objects_ = nullptr;
};

}  // namespace ferret
