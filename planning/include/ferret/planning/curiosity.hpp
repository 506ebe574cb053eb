#pragma once
// Curiosity scoring of frontier candidates (paper sect. IV-C), usable on its own:
// the CDOS exploration policy calls it, and so can an OMPL valid-state sampler that
// wants to draw frontier goals in proportion to their curiosity loss.
//
//   const auto evidence = collect_evidence(object_map);          // cells with p > 0.5
//   const auto scored = score_frontiers(frontiers.visible, grid_geometry,
//                                       X_WG.position(), evidence, options);
//   // scored[k].loss >= 0 is the expected curiosity loss L(C) of driving to
//   // scored[k].cell; use it as a weight, or take the argmax (paper eq. (action_select)).
//
// The equations:
//   c(p) = -(p + a)^2 / (4 b) + K                         paper eq. (curiosity)
//   conf_{t+1} = min(conf_t d_t / d_{t+1}, eta / d_{t+1})  paper's prediction, capped
//   p' = Bayes(p, conf_{t+1})  (log-odds, prior 0.5)       paper eq. (p_o_update)
//   L(C) = sum over evidence cells of c(p) - c(p')         paper eq. (C_loss)
// By default c is taken of the raw probability (the reading of ARCHITECTURE.md); with
// `use_labels` it is taken of the relabelled one (paper eq. (cap_O), the literal
// reading), where the loss is zero unless one step crosses lambda2.

#include <Eigen/Core>
#include <span>
#include <vector>

#include "ferret/core/grid.hpp"
#include "ferret/mapping/object_map.hpp"
#include "ferret/mapping/object_search_params.hpp"
#include "ferret/planning/curiosity_params.hpp"

namespace ferret {

struct MissionConfig;

struct CuriosityOptions {
  CuriosityParams params;  ///< a, b, K
  // The object search's defaults have one home: ObjectSearchParams.
  double eta_m = ObjectSearchParams{}.eta_m;  ///< conf = eta / d
  /// A predicted detection is clipped like a real one.
  double conf_floor = ObjectSearchParams{}.conf_floor;
  double conf_cap = ObjectSearchParams{}.conf_cap;
  double lambda1 = ObjectSearchParams{}.lambda1;  ///< for use_labels
  double lambda2 = ObjectSearchParams{}.lambda2;
  double camera_range_m = 4.0;  ///< D_cam: no observation is predicted beyond it
  bool use_labels = false;      ///< c of the relabelled probability (literal reading)
  bool cap_prediction =
      true;  ///< cap conf_t d_t / d_{t+1} at eta / d_{t+1} (and clip to the floor)
  bool closest_approach =
      false;  ///< d_{t+1}: closest distance along the straight drive, not at its end

  [[nodiscard]] static CuriosityOptions from(const MissionConfig& mission, double camera_range_m);
};

/// c(p), paper eq. (curiosity).
[[nodiscard]] double curiosity(double p, const CuriosityParams& params);

/// The Bayes update of p by a measurement likelihood (prior 0.5), paper eq. (p_o_update).
[[nodiscard]] double fuse_probability(double p, double p_measurement);

/// The predicted confidence of observing a cell from distance d_next, given the last
/// confidence conf_t and the current distance d_t; 0 (no observation) beyond D_cam.
[[nodiscard]] double predicted_confidence(double conf_t, double d_t, double d_next,
                                          const CuriosityOptions& options);

/// A cell of the object map with object evidence.
struct EvidenceCell {
  Eigen::Vector2d p_W = Eigen::Vector2d::Zero();
  double probability = 0.5;      ///< raw p(o | z_1:t)
  double last_confidence = 0.0;  ///< conf_t: the last detection fused into it
};

/// Every cell with p > 0.5, sorted by cell index (deterministic).
[[nodiscard]] std::vector<EvidenceCell> collect_evidence(const ObjectMap& objects);

/// The evidence cell of highest probability. @pre !evidence.empty()
[[nodiscard]] const EvidenceCell& strongest_evidence(std::span<const EvidenceCell> evidence);

/// Expected curiosity loss L(C) of moving from `p_W_robot` to `p_W_goal` (paper eq. (C_loss)).
[[nodiscard]] double curiosity_loss(const Eigen::Vector2d& p_W_goal,
                                    const Eigen::Vector2d& p_W_robot,
                                    std::span<const EvidenceCell> evidence,
                                    const CuriosityOptions& options);

struct ScoredFrontier {
  Cell cell;
  Eigen::Vector2d p_W = Eigen::Vector2d::Zero();
  double loss = 0.0;  ///< L(C) >= 0 with the default options
};

/// L(C) of every candidate cell, in the candidates' order.
[[nodiscard]] std::vector<ScoredFrontier> score_frontiers(std::span<const Cell> candidates,
                                                          const GridGeometry& geometry,
                                                          const Eigen::Vector2d& p_W_robot,
                                                          std::span<const EvidenceCell> evidence,
                                                          const CuriosityOptions& options);

}  // namespace ferret
