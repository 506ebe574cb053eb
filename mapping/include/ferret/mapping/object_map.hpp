#pragma once
// The object map O of the object search (paper sect. IV-A): per cell, the
// probability that the cell holds the searched object, prior 0.5, accumulated in
// log-odds (paper eq. (p_o_update) with prior 0.5 is l_t = l_{t-1} + logit(conf)).
//
// The camera is a range finder of fov alpha and range D_cam. How the paper's open
// steps are read (docs/object_search.md):
//  - a detection at distance d is weak positive evidence, conf = clip(eta / d,
//    conf_floor, conf_cap), on the cells within object_radius_m of the detected spot;
//  - cells the camera sees without a detection get a "no object" likelihood that
//    rises from miss_likelihood at the camera to 0.5 (no information) at D_cam;
//  - a cell takes a new camera measurement only from a new viewpoint (moved
//    min_move_m or turned min_turn_rad since its last update) or after
//    max_period_s: repeated frames from one spot are not independent evidence;
//  - labels (paper eq. (cap_O)): free below lambda1, object above lambda2, unknown
//    between; the object is found when a cell passes lambda2.

#include <Eigen/Core>
#include <cstdint>
#include <optional>
#include <vector>

#include "ferret/core/grid.hpp"
#include "ferret/mapping/ir_grid.hpp"
#include "ferret/mapping/object_search_params.hpp"

namespace ferret {

/// One output of the object detector, in the camera frame.
struct ObjectDetection {
  double bearing_rad = 0.0;  ///< from the image column
  double distance_m = 0.0;   ///< d = k_c / gamma (apparent size, paper sect. IV-A)
  double confidence = 0.0;   ///< the detector's raw confidence (eta / d in the model)
};

/// One camera frame: the camera as a range finder (where it can see) plus detections.
struct CameraFrame {
  double time_s = 0.0;
  RangeScan view;  ///< beams up to the first obstacle, max_range_m = D_cam
  std::vector<ObjectDetection> detections;
};

/// conf = eta / d (paper sect. IV-A): the detection model's confidence at distance d,
/// before the object map clips it. The one formula of the codebase: the simulator's
/// geometric detector, the image detector (ugv/) and the planner's prediction call it.
/// @pre distance_m > 0
[[nodiscard]] double distance_confidence(double eta_m, double distance_m);
/// clip(raw, conf_floor, conf_cap): a detection is always weak positive evidence.
[[nodiscard]] double clip_confidence(double raw, double conf_floor, double conf_cap);

enum class ObjectLabel : std::uint8_t { kFree, kUnknown, kObject };

class ObjectMap {
 public:
  struct Options {
    // The object search's defaults have one home: ObjectSearchParams.
    double lambda1 = ObjectSearchParams{}.lambda1;
    double lambda2 = ObjectSearchParams{}.lambda2;
    double eta_m = ObjectSearchParams{}.eta_m;
    double conf_floor = ObjectSearchParams{}.conf_floor;
    double conf_cap = ObjectSearchParams{}.conf_cap;
    /// "no object" likelihood of a cell seen at distance 0
    double miss_likelihood = ObjectSearchParams{}.miss_likelihood;
    double camera_range_m = 4.0;       ///< D_cam: the miss likelihood is 0.5 from here on
    double object_radius_m = 0.1;      ///< cells within this of a detected spot take the detection
    double min_move_m = 0.2;           ///< a new viewpoint: moved this far ...
    double min_turn_rad = 0.26;        ///< ... or turned this much since the cell's last update
    double max_period_s = 1.0;         ///< ... or this long ago
    bool gate_viewpoints = true;       ///< false: fuse every frame (the paper to the letter)
    double clamp_probability = 0.999;  ///< log-odds are clamped to +-logit of this

    /// The mission's object-search parameters plus the camera range.
    [[nodiscard]] static Options from(const ObjectSearchParams& params, double camera_range_m);
  };

  ObjectMap(GridGeometry geometry, Options options);

  /// Folds one frame in (see the header comment for the model).
  void integrate_frame(const CameraFrame& frame);

  /// One Bayes update of one cell with the measurement likelihood `p_measurement`
  /// (paper eq. (p_o_update), prior 0.5).
  void fuse(Cell c, double p_measurement);
  /// Sets a cell as a map received from elsewhere has it (the planner service's
  /// next-goal request): its probability (clamped as fusion clamps) and the confidence
  /// of the last detection fused into it (0: none), which CDOS's prediction starts from.
  /// A probability other than 0.5 marks the cell observed (measured where the map was made).
  void set_cell(Cell c, double probability, double last_confidence);

  /// conf = clip(raw, conf_floor, conf_cap): a detection is always weak positive evidence.
  [[nodiscard]] double detection_confidence(double raw_confidence) const;
  /// The "no object" likelihood of a cell seen without detection at `distance_m`.
  [[nodiscard]] double miss_likelihood(double distance_m) const;

  [[nodiscard]] const GridGeometry& geometry() const { return geometry_; }
  [[nodiscard]] const Options& options() const { return options_; }
  [[nodiscard]] double probability(Cell c) const { return probability_at(geometry_.index(c)); }
  [[nodiscard]] double probability_at(std::size_t idx) const;
  /// The cell's log-odds, logit(p) (0: the prior; clamped as fusion clamps).
  [[nodiscard]] float log_odds_at(std::size_t idx) const { return log_odds_[idx]; }
  /// The label of a probability (paper eq. (cap_O)).
  [[nodiscard]] ObjectLabel label_of(double p) const;
  [[nodiscard]] ObjectLabel label(Cell c) const { return label_of(probability(c)); }
  /// The relabelled probability of paper eq. (cap_O): 0 if free, 0.5 if unknown, p if object.
  [[nodiscard]] double labelled_probability(double p) const;
  /// The confidence of the last detection fused into a cell (0 if none).
  [[nodiscard]] double last_confidence(std::size_t idx) const { return last_conf_[idx]; }
  /// True once the camera has measured the cell.
  [[nodiscard]] bool observed(std::size_t idx) const { return last_time_[idx] > -1e29f; }
  /// Cells with object evidence (p > 0.5), in no particular order.
  [[nodiscard]] const std::vector<std::size_t>& evidence_cells() const { return evidence_; }
  /// Where and when cells changed (their odds, or their first observation), for readers
  /// that keep what they computed from them.
  [[nodiscard]] const BlockRevisions& revisions() const { return revisions_; }
  /// The most probable cell once one has passed lambda2.
  [[nodiscard]] std::optional<Cell> found_cell() const;

 private:
  bool new_viewpoint(std::size_t idx, const Pose2& X_WC, double time_s) const;
  void track_evidence(std::size_t idx);  // keeps evidence_ in step with the cell's log-odds
  void remember_viewpoint(std::size_t idx, const Pose2& X_WC, double time_s);

  GridGeometry geometry_;
  Options options_;
  float l_clamp_;
  std::vector<float> log_odds_;
  std::vector<float> last_conf_;
  std::vector<float> last_x_, last_y_, last_yaw_, last_time_;
  std::vector<std::int32_t> evidence_pos_;  ///< index into evidence_, -1 if absent
  std::vector<std::size_t> evidence_;
  std::vector<std::uint32_t> stamp_;  ///< frame stamps: one update per cell per frame
  BlockRevisions revisions_{geometry_};
  std::uint32_t frame_id_ = 0;
};

}  // namespace ferret
