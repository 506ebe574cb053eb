#include "ferret/mapping/object_map.hpp"

#include <gtest/gtest.h>

#include <cmath>

namespace ferret {
namespace {

GridGeometry geometry() { return {0.0, 0.0, 0.05, 80, 40}; }

CameraFrame frame(Pose2 pose, double t, std::vector<ObjectDetection> detections = {}) {
  CameraFrame f;
  f.time_s = t;
  f.view.X_WS = pose;
  f.view.max_range_m = 4.0;
  f.view.beams = {{0.0, 4.0}};
  f.detections = std::move(detections);
  return f;
}

TEST(ObjectMap, DetectionConfidenceIsClippedAboveOneHalf) {
  ObjectMap m(geometry(), {});
  EXPECT_DOUBLE_EQ(m.detection_confidence(1.0 / 3.0),
                   0.55);  // far: eta/d = 0.33, still weak evidence
  EXPECT_DOUBLE_EQ(m.detection_confidence(0.8), 0.8);
  EXPECT_DOUBLE_EQ(m.detection_confidence(2.0), 0.99);
}

TEST(ObjectMap, BayesUpdateWithPriorOneHalf) {
  ObjectMap m(geometry(), {});
  const Cell c{10, 10};
  EXPECT_DOUBLE_EQ(m.probability(c), 0.5);
  m.fuse(c, 0.8);
  EXPECT_NEAR(m.probability(c), 0.8, 1e-6);
  m.fuse(c, 0.8);  // 0.8*0.8 / (0.8*0.8 + 0.2*0.2)
  EXPECT_NEAR(m.probability(c), 0.9411765, 1e-6);
  EXPECT_EQ(m.evidence_cells().size(), 1u);
  m.fuse(c, 0.05);
  m.fuse(c, 0.05);
  EXPECT_TRUE(m.evidence_cells().empty());
}

TEST(ObjectMap, LabelsAtLambdaThresholds) {
  ObjectMap m(geometry(), {});
  EXPECT_EQ(m.label_of(0.09), ObjectLabel::kFree);
  EXPECT_EQ(m.label_of(0.10), ObjectLabel::kUnknown);
  EXPECT_EQ(m.label_of(0.95), ObjectLabel::kUnknown);
  EXPECT_EQ(m.label_of(0.951), ObjectLabel::kObject);
  EXPECT_DOUBLE_EQ(m.labelled_probability(0.05), 0.0);
  EXPECT_DOUBLE_EQ(m.labelled_probability(0.7), 0.5);
  EXPECT_DOUBLE_EQ(m.labelled_probability(0.97), 0.97);
}

TEST(ObjectMap, MissLikelihoodWeakensWithDistance) {
  ObjectMap m(geometry(), {});
  EXPECT_DOUBLE_EQ(m.miss_likelihood(0.0), 0.4);
  EXPECT_DOUBLE_EQ(m.miss_likelihood(2.0), 0.45);
  EXPECT_DOUBLE_EQ(m.miss_likelihood(5.0), 0.5);
}

TEST(ObjectMap, FusesOnlyFromNewViewpointsOrAfterThePeriod) {
  ObjectMap m(geometry(), {});
  const Pose2 pose{0.5, 1.0, 0.0};
  const ObjectDetection far{0.0, 3.0, 1.0 / 3.0};  // object at (3.5, 1.0)
  const Cell c = geometry().cell_at(3.5, 1.0);
  m.integrate_frame(frame(pose, 0.0, {far}));
  EXPECT_NEAR(m.probability(c), 0.55, 1e-6);
  m.integrate_frame(frame(pose, 0.1, {far}));  // same viewpoint: no new evidence
  EXPECT_NEAR(m.probability(c), 0.55, 1e-6);
  m.integrate_frame(frame({0.75, 1.0, 0.0}, 0.2, {{0.0, 2.75, 1.0 / 2.75}}));  // moved 0.25 m
  EXPECT_NEAR(m.probability(c), 0.55 * 0.55 / (0.55 * 0.55 + 0.45 * 0.45), 1e-6);
  m.integrate_frame(frame({0.75, 1.0, 0.0}, 1.3, {{0.0, 2.75, 1.0 / 2.75}}));  // a second later
  EXPECT_GT(m.probability(c), 0.64);
  EXPECT_FALSE(m.found_cell().has_value());
  // Close and confident: one frame passes lambda2.
  m.integrate_frame(frame({2.7, 1.0, 0.0}, 1.4, {{0.0, 0.8, 1.0 / 0.8}}));
  ASSERT_TRUE(m.found_cell().has_value());
  EXPECT_LE((geometry().center(*m.found_cell()) - Eigen::Vector2d(3.5, 1.0)).norm(), 0.1);
}

TEST(ObjectMap, CellsSeenWithoutDetectionLoseProbability) {
  ObjectMap m(geometry(), {});
  m.integrate_frame(frame({0.5, 1.0, 0.0}, 0.0));
  EXPECT_NEAR(m.probability(geometry().cell_at(0.6, 1.0)), m.miss_likelihood(0.075), 0.01);
  EXPECT_LT(m.probability(geometry().cell_at(1.5, 1.0)), 0.5);
  EXPECT_DOUBLE_EQ(m.probability(geometry().cell_at(1.5, 1.5)), 0.5);  // not in the beam
  EXPECT_TRUE(m.evidence_cells().empty());
}

TEST(ObjectMap, UngatedFusionCountsEveryFrame) {
  ObjectMap::Options o;
  o.gate_viewpoints = false;
  ObjectMap m(geometry(), o);
  const ObjectDetection far{0.0, 3.0, 1.0 / 3.0};
  for (int k = 0; k < 20; ++k) m.integrate_frame(frame({0.5, 1.0, 0.0}, 0.1 * k, {far}));
  // 20 frames from one spot add up to "found" from 3 m: why the gate exists.
  EXPECT_TRUE(m.found_cell().has_value());
}

}  // namespace
}  // namespace ferret
