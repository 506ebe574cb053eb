#pragma once
// Bayesian viewpoint search (`bayes`, docs/object_search.md): where CDOS has no object
// evidence it falls back to the rapid-frontier rule, which explores for the map, not
// for the object. This policy searches for the object: the object is equally likely in
// every cell it could stand in, a cell the camera has measured without a detection
// keeps only `searched_weight` of that (the negative evidence of every frame), and the
// next goal is the viewpoint (a reachable pose and heading) that brings the most of the
// remaining probability mass into the camera's view per second of travel:
//
//   m(c)       = 0 (G occupied) | searched_weight (the camera measured c) | 1 (otherwise)
//   V(x, th)   = sum of m(c) over the cells the camera sees from x facing th: within
//                D_cam and the field of view, on a line of sight through G that no
//                occupied cell blocks (unknown cells let the view through: they are
//                what is left to see), each weighted by the area its ray stands for
//   T(x, th)   = path distance / v_max + turns / yaw rate + overhead_s
//   goal       = argmax V / T over reachable cells on a lattice and the frontier cells
//
// Once there is evidence (a cell with p > 0.5) it looks at it: the goal is the nearest
// reachable pose within the view distance of the strongest evidence (where one frame's
// confidence passes lambda2), facing it, as the oracle does with the truth; evidence
// nearer than evidence_view_min_m, or none such pose, leaves the choice to CDOS's
// curiosity. Without evidence the chosen viewpoint
// is kept while it still holds keep_fraction of the mass it was chosen for.

#include <Eigen/Core>
#include <optional>
#include <vector>

#include "ferret/core/grid.hpp"
#include "ferret/planning/exploration_policy.hpp"
#include "ferret/planning/policies.hpp"

namespace ferret {

class IrGrid;
class ObjectMap;

struct ViewpointSearchOptions {
  double camera_fov_rad = 1.5707963267948966;  ///< the object camera's horizontal field of view
  double camera_range_m = 4.0;                 ///< D_cam
  /// Mass left in a cell the camera measured without a detection: 1 - the detector's
  /// recall (the simulated detector's detection_probability is 0.9 within D_cam).
  double searched_weight = 0.1;
  int rays = 72;                 ///< rays of a viewpoint's 360-degree profile
  double lattice_m = 0.5;        ///< spacing of the candidate viewpoints on known free ground
  int max_frontier_candidates = 64;  ///< frontier cells also tried (evenly subsampled)
  double max_velocity_mps = 2.0;
  double max_yaw_rate_radps = 2.0;
  double overhead_s = 1.0;      ///< added to every travel time (starting, stopping, settling)
  double keep_fraction = 0.9;   ///< keep the goal while it holds this much of its chosen mass
  /// A new choice waits while this much of what the camera faces now is unsearched
  /// (its next frames search it on the way; CDOS's rule drives meanwhile).
  double fresh_view_fraction = 0.5;
  /// Evidence at least this far from the robot is looked at from a pose within the
  /// view distance of it (viewing_goal); nearer evidence is left to CDOS's curiosity.
  double evidence_view_min_m = 1.5;
};

/// m(c) of the header comment, for the cell at `idx`.
[[nodiscard]] double unsearched_mass(const IrGrid& grid, const ObjectMap& objects, std::size_t idx,
                                     double searched_weight);

/// The mass each of `options.rays` rays (ray k at bearing 2 pi k / rays in the world
/// frame) brings into view from p_W, area-weighted.
[[nodiscard]] std::vector<double> view_profile(const IrGrid& grid, const ObjectMap& objects,
                                               const Eigen::Vector2d& p_W,
                                               const ViewpointSearchOptions& options);

struct HeadingValue {
  double heading_rad = 0.0;
  double mass = 0.0;  ///< V(x, heading)
};
/// The heading whose field of view holds the most of `profile`'s mass (ties: the
/// lowest ray index), and that mass.
[[nodiscard]] HeadingValue best_heading(const std::vector<double>& profile, double fov_rad);
/// V(x, heading): the mass of the rays inside the field of view centred on heading_rad.
[[nodiscard]] double mass_in_view(const std::vector<double>& profile, double heading_rad, double fov_rad);

class ViewpointSearchPolicy final : public ExplorationPolicy {
 public:
  explicit ViewpointSearchPolicy(const PolicyOptions& options);
  [[nodiscard]] std::string_view name() const override { return "bayes"; }
  [[nodiscard]] std::optional<ExplorationGoal> choose(const ExplorationState& state) override;
  void goal_done() override {
    committed_.reset();
    cdos_.goal_done();
  }
  [[nodiscard]] bool keeps_goal(const ObjectMap& objects, const FrontierTracker& tracker) const override;
  [[nodiscard]] const ViewpointSearchOptions& options() const { return options_; }

 private:
  std::optional<ExplorationGoal> choose_viewpoint(const ExplorationState& s);
  [[nodiscard]] bool fresh_view(const ExplorationState& s) const;

  ViewpointSearchOptions options_;
  CdosPolicy cdos_;
  std::optional<ExplorationGoal> committed_;
  double committed_mass_ = 0.0;
  double view_distance_m_ = 0.95;
};

}  // namespace ferret
