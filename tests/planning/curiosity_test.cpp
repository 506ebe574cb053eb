#include "ferret/planning/curiosity.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

namespace ferret {
namespace {

TEST(Curiosity, PaperCurveValues) {
  const CuriosityParams p;  // a = -0.5, b = 0.1, K = 0.62
  EXPECT_NEAR(curiosity(0.5, p), 0.62, 1e-12);
  EXPECT_NEAR(curiosity(0.0, p), -0.005, 1e-12);
  EXPECT_NEAR(curiosity(1.0, p), -0.005, 1e-12);
  EXPECT_NEAR(curiosity(0.6, p), 0.595, 1e-12);
}

TEST(Curiosity, PredictedConfidenceIsCappedAtEtaOverDistance) {
  CuriosityOptions o;
  // conf_t d_t / d_{t+1} = 0.6 * 3 / 2 = 0.9, capped at eta / 2 = 0.5, then the floor.
  EXPECT_DOUBLE_EQ(predicted_confidence(0.6, 3.0, 2.0, o), 0.55);
  EXPECT_DOUBLE_EQ(predicted_confidence(0.6, 3.0, 1.0, o), 0.99);  // 1.8 -> eta/1 = 1 -> cap
  EXPECT_DOUBLE_EQ(predicted_confidence(0.6, 3.0, 1.25, o), 0.8);  // min(1.44, 0.8)
  EXPECT_DOUBLE_EQ(predicted_confidence(0.6, 3.0, 4.5, o), 0.0);   // beyond D_cam: no observation
  o.cap_prediction = false;
  EXPECT_NEAR(predicted_confidence(0.6, 3.0, 2.0, o), 0.9,
              1e-12);  // the paper's formula as written
}

// Evidence cell at (3, 0) with p = 0.6 and last conf 0.55; the robot at the origin.
// Frontier A at (2, 0): conf_{t+1} = min(0.55*3/1, 1/1) -> 0.99, p' = 0.993311,
//   L = c(0.6) - c(0.993311) = 0.595 - 0.011611 = 0.583389.
// Frontier B at (0, 2): d = sqrt(13), conf = min(0.4576, 0.2774) -> floor 0.55,
//   p' = 0.647059, L = 0.595 - 0.565934 = 0.029066.
TEST(Curiosity, LossOfAHandBuiltTwoFrontierCase) {
  const GridGeometry geo{-0.5, -0.5, 1.0, 5, 5};  // cell centres on integer coordinates
  const std::vector<EvidenceCell> evidence{{{3.0, 0.0}, 0.6, 0.55}};
  const std::vector<Cell> candidates{geo.cell_at(2.0, 0.0), geo.cell_at(0.0, 2.0)};
  const CuriosityOptions o;
  const auto scored = score_frontiers(candidates, geo, {0.0, 0.0}, evidence, o);
  ASSERT_EQ(scored.size(), 2u);
  EXPECT_NEAR(scored[0].loss, 0.5833894, 1e-6);
  EXPECT_NEAR(scored[1].loss, 0.0290657, 1e-6);
  // Literal reading: c of the relabelled probability. A crosses lambda2 (0.62 - c(0.9933)),
  // B stays "unknown" (0.5 -> 0.5): zero loss.
  CuriosityOptions lit = o;
  lit.use_labels = true;
  lit.cap_prediction = false;
  const auto literal = score_frontiers(candidates, geo, {0.0, 0.0}, evidence, lit);
  EXPECT_NEAR(literal[0].loss, 0.6083894, 1e-6);
  EXPECT_NEAR(literal[1].loss, 0.0, 1e-12);
}

TEST(Curiosity, ClosestApproachCountsThePassBy) {
  const std::vector<EvidenceCell> evidence{{{2.0, 1.0}, 0.6, 0.55}};
  CuriosityOptions o;
  const double end_only = curiosity_loss({4.0, 0.0}, {0.0, 0.0}, evidence, o);  // d_{t+1} = sqrt(5)
  o.closest_approach = true;                                                    // passes at 1 m
  const double pass_by = curiosity_loss({4.0, 0.0}, {0.0, 0.0}, evidence, o);
  EXPECT_GT(pass_by, end_only);
  EXPECT_NEAR(pass_by, curiosity(0.6, o.params) - curiosity(fuse_probability(0.6, 0.99), o.params),
              1e-9);
}

TEST(Curiosity, StrongestEvidenceAndFusion) {
  EXPECT_NEAR(fuse_probability(0.8, 0.8), 0.9411765, 1e-6);
  const std::vector<EvidenceCell> ev{{{0, 0}, 0.6, 0.55}, {{1, 0}, 0.8, 0.7}, {{2, 0}, 0.7, 0.6}};
  EXPECT_DOUBLE_EQ(strongest_evidence(ev).p_W.x(), 1.0);
}

}  // namespace
}  // namespace ferret
