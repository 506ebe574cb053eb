#include "ferret/planning/curiosity.hpp"

#include <algorithm>
#include <cmath>

#include "ferret/mapping/ir_grid.hpp"
#include "ferret/planning/mission_config.hpp"

namespace ferret {
namespace {
double relabel(double p, const CuriosityOptions& o) {
  if (p < o.lambda1) return 0.0;
  if (p > o.lambda2) return p;
  return 0.5;
}

// Distance from q to the segment a-b.
double segment_distance(const Eigen::Vector2d& q, const Eigen::Vector2d& a,
                        const Eigen::Vector2d& b) {
  const Eigen::Vector2d ab = b - a;
  const double len2 = ab.squaredNorm();
  const double t = len2 > 0 ? std::clamp((q - a).dot(ab) / len2, 0.0, 1.0) : 0.0;
  return (a + t * ab - q).norm();
}
}  // namespace

CuriosityOptions CuriosityOptions::from(const MissionConfig& mission, double camera_range_m) {
  CuriosityOptions o;
  o.params = mission.curiosity;
  o.eta_m = mission.object_search.eta_m;
  o.conf_floor = mission.object_search.conf_floor;
  o.conf_cap = mission.object_search.conf_cap;
  o.lambda1 = mission.object_search.lambda1;
  o.lambda2 = mission.object_search.lambda2;
  o.camera_range_m = camera_range_m;
  return o;
}

double curiosity(double p, const CuriosityParams& params) {
  return -(p + params.a) * (p + params.a) / (4.0 * params.b) + params.K;
}

double fuse_probability(double p, double p_measurement) {
  return inverse_logit(logit(p) + logit(p_measurement));
}

double predicted_confidence(double conf_t, double d_t, double d_next, const CuriosityOptions& o) {
  if (d_next > o.camera_range_m) return 0.0;
  d_next = std::max(d_next, 1e-3);
  double conf = conf_t * d_t / d_next;
  if (o.cap_prediction) {
    conf = std::min(conf, distance_confidence(o.eta_m, d_next));
    conf = std::clamp(conf, o.conf_floor, o.conf_cap);
  } else {
    conf = std::clamp(conf, 1e-3, o.conf_cap);  // still a probability
  }
  return conf;
}

std::vector<EvidenceCell> collect_evidence(const ObjectMap& objects) {
  std::vector<std::size_t> cells = objects.evidence_cells();
  std::sort(cells.begin(), cells.end());
  std::vector<EvidenceCell> out;
  out.reserve(cells.size());
  for (const std::size_t idx : cells)
    out.push_back({objects.geometry().center(objects.geometry().cell_of_index(idx)),
                   objects.probability_at(idx), objects.last_confidence(idx)});
  return out;
}

const EvidenceCell& strongest_evidence(std::span<const EvidenceCell> evidence) {
  return *std::max_element(evidence.begin(), evidence.end(), [](const auto& a, const auto& b) {
    return a.probability < b.probability;
  });
}

double curiosity_loss(const Eigen::Vector2d& p_W_goal, const Eigen::Vector2d& p_W_robot,
                      std::span<const EvidenceCell> evidence, const CuriosityOptions& o) {
  double loss = 0.0;
  for (const auto& e : evidence) {
    const double d_t = (e.p_W - p_W_robot).norm();
    const double d_next = o.closest_approach ? segment_distance(e.p_W, p_W_robot, p_W_goal)
                                             : (e.p_W - p_W_goal).norm();
    const double conf = predicted_confidence(e.last_confidence, d_t, d_next, o);
    if (conf <= 0.0) continue;
    const double p_next = fuse_probability(e.probability, conf);
    const double p_now = o.use_labels ? relabel(e.probability, o) : e.probability;
    const double p_then = o.use_labels ? relabel(p_next, o) : p_next;
    loss += curiosity(p_now, o.params) - curiosity(p_then, o.params);
  }
  return loss;
}

std::vector<ScoredFrontier> score_frontiers(std::span<const Cell> candidates,
                                            const GridGeometry& geometry,
                                            const Eigen::Vector2d& p_W_robot,
                                            std::span<const EvidenceCell> evidence,
                                            const CuriosityOptions& options) {
  std::vector<ScoredFrontier> out;
  out.reserve(candidates.size());
  for (const Cell& c : candidates) {
    const Eigen::Vector2d p = geometry.center(c);
    out.push_back({c, p, curiosity_loss(p, p_W_robot, evidence, options)});
  }
  return out;
}

}  // namespace ferret
