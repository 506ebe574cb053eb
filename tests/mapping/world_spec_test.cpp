#include "ferret/mapping/world_spec.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "ferret/core/error.hpp"

namespace ferret {
namespace {
using ::testing::HasSubstr;

// One hidden space, opening in its -x wall; interior x in [-0.5, 1.5], y in [-1.6, -0.4].
const char* const kBase = R"(
resolution_m: 0.025
bounds_m: {min: [-3, -3, -0.2], max: [3, 3, 1.0]}
hidden_spaces:
  - name: cellar
    center_m: [0.5, -1.0]
    interior_size_m: [2.0, 1.2, 0.3]
    wall_thickness_m: 0.1
    opening: {wall: -x, width_m: 0.15, height_m: 0.075}
    marker: {id: 7, size_m: 0.2}
)";
const std::string kWorld = std::string(kBase) + R"(objects:
  - {name: canister, hidden_space: cellar, position_m: [0.5, 0.3], size_m: [0.06, 0.06, 0.05]}
drop_zone: {center_m: [-2, -2], radius_m: 0.5}
)";

std::string with(const std::string& extra) { return kWorld + extra; }

void expect_field(const std::string& yaml, const std::string& field,
                  const std::string& expected_part = "") {
  try {
    (void)parse_world(yaml, "w.yaml");
    FAIL() << "expected InputError at " << field;
  } catch (const InputError& e) {
    EXPECT_EQ(e.source(), "w.yaml");
    EXPECT_EQ(e.field(), field) << e.what();
    if (!expected_part.empty()) {
      EXPECT_THAT(e.what(), HasSubstr(expected_part));
    }
  }
}

TEST(WorldSpec, HiddenSpaceEntryMarkerAndObject) {
  const WorldSpec w = parse_world(kWorld, "w.yaml");
  ASSERT_EQ(w.hidden_spaces.size(), 1u);
  const HiddenSpace& h = w.hidden_spaces[0];
  // Entry: bottom centre of the opening on the outer face of the -x wall.
  EXPECT_NEAR(h.p_WE.x(), -0.6, 1e-12);
  EXPECT_NEAR(h.p_WE.y(), -1.0, 1e-12);
  EXPECT_NEAR(h.p_WE.z(), 0.0, 1e-12);
  EXPECT_NEAR(h.entry_yaw_rad, 0.0, 1e-12);  // drive along +x into the space
  // Marker upright on the wall, facing out (-x), centred in the 0.325 m above the opening.
  const Pose3& X_WM = h.marker.X_WM;
  EXPECT_EQ(h.marker.id, 7);
  EXPECT_NEAR(X_WM.translation().x(), -0.601, 1e-12);
  EXPECT_NEAR(X_WM.translation().z(), 0.075 + 0.325 / 2, 1e-12);
  EXPECT_TRUE(X_WM.linear().col(2).isApprox(Eigen::Vector3d(-1, 0, 0)));
  EXPECT_TRUE(X_WM.linear().col(1).isApprox(Eigen::Vector3d(0, 0, 1)));
  EXPECT_NEAR(X_WM.linear().determinant(), 1.0, 1e-12);
  // The object rests on the floor at H (0.5, 0.3).
  ASSERT_EQ(w.objects.size(), 1u);
  EXPECT_EQ(w.objects[0].hidden_space, 0);
  EXPECT_TRUE(w.objects[0].p_WO().isApprox(Eigen::Vector3d(1.0, -0.7, 0.025)));
  ASSERT_TRUE(w.drop_zone.has_value());
  EXPECT_DOUBLE_EQ(w.drop_zone->radius_m, 0.5);
}

TEST(WorldSpec, MarkerFamilyAndDictionary) {
  const WorldSpec aruco = parse_world(kWorld, "w.yaml");
  EXPECT_EQ(aruco.hidden_spaces[0].marker.dictionary.family, MarkerFamily::kAruco);
  EXPECT_EQ(aruco.hidden_spaces[0].marker.dictionary.name, "DICT_4X4_50");
  std::string yaml = kWorld;
  yaml.replace(yaml.find("{id: 7, size_m: 0.2}"), 20, "{id: 300, size_m: 0.2, family: apriltag}");
  const WorldSpec tag = parse_world(yaml, "w.yaml");
  EXPECT_EQ(tag.hidden_spaces[0].marker.dictionary.family, MarkerFamily::kAprilTag);
  EXPECT_EQ(tag.hidden_spaces[0].marker.dictionary.name, "tag36h11");  // the family's default
  EXPECT_EQ(tag.hidden_spaces[0].marker.id, 300);
}

TEST(WorldSpec, GroundTruthGeometry) {
  const WorldSpec w = parse_world(kWorld, "w.yaml");
  const HiddenSpace& h = w.hidden_spaces[0];
  EXPECT_TRUE(w.is_solid({-0.55, -1.3, 0.15}));   // -x wall beside the opening
  EXPECT_FALSE(w.is_solid({0.5, -1.0, 0.15}));    // interior
  EXPECT_FALSE(w.is_solid({-0.55, -1.0, 0.03}));  // through the opening
  EXPECT_TRUE(w.is_solid({-0.55, -1.0, 0.1}));    // lintel above the opening
  EXPECT_TRUE(w.is_solid({-0.55, -0.9, 0.03}));   // just beside the 15 cm opening
  EXPECT_TRUE(w.is_solid({0.5, -1.0, 0.35}));     // roof
  EXPECT_TRUE(w.is_solid({1.55, -1.0, 0.15}));    // +x wall
  EXPECT_TRUE(w.is_solid({0.5, -0.35, 0.15}));    // +y wall
  EXPECT_TRUE(w.is_solid({0.0, 0.0, -0.1}));      // ground
  EXPECT_FALSE(w.is_solid({0.0, 0.0, 0.5}));
  EXPECT_FALSE(w.is_solid({0.0, 0.0, -0.5}));  // below the bounds: not known
  EXPECT_TRUE(w.is_solid({1.0, -0.7, 0.02}));  // the object
  EXPECT_TRUE(h.interior_contains({0.5, -1.0, 0.15}));
  EXPECT_TRUE(h.interior_contains({-0.55, -1.0, 0.03}));
  EXPECT_FALSE(h.interior_contains({-0.55, -1.0, 0.1}));
  EXPECT_FALSE(h.interior_contains({-0.65, -1.0, 0.03}));
}

TEST(WorldSpec, RotatedHiddenSpaceAndOpeningOnYWall) {
  // Yaw 90 deg: H's +y wall faces world -x. The entry heads into H along -y_H = world +x.
  const WorldSpec w = parse_world(R"(
resolution_m: 0.05
bounds_m: {min: [-5, -5, -0.5], max: [5, 5, 2]}
hidden_spaces:
  - name: s
    center_m: [1, 1]
    yaw_deg: 90
    interior_size_m: [2, 1, 0.4]
    opening: {wall: +y, width_m: 0.2, height_m: 0.1, offset_m: 0.3}
    marker: {id: 1, size_m: 0.1, placement: ground}
)",
                                  "w.yaml");
  const HiddenSpace& h = w.hidden_spaces[0];
  // E in H: (0.3, 0.5 + 0.1, 0) -> world (1 - 0.6, 1 + 0.3, 0).
  EXPECT_TRUE(h.p_WE.isApprox(Eigen::Vector3d(0.4, 1.3, 0.0)));
  EXPECT_NEAR(h.entry_yaw_rad, 0.0, 1e-12);
  // Ground marker in front of the opening (outside, -x of E), face up.
  EXPECT_NEAR(h.marker.X_WM.translation().x(), 0.4 - 0.1, 1e-12);
  EXPECT_TRUE(h.marker.X_WM.linear().col(2).isApprox(Eigen::Vector3d::UnitZ()));
  EXPECT_FALSE(w.is_solid({0.45, 1.3, 0.05}));  // in the opening
  EXPECT_TRUE(w.is_solid({0.45, 1.0, 0.05}));   // wall beside it
}

TEST(WorldSpec, EnclosureMayReachTheBounds) {
  // Walls span x in [0, 1.6] and y in [-0.8, 0.8]; the bounds end 5 cm beyond them.
  const std::string yaml = R"(
resolution_m: 0.05
bounds_m: {min: [-1, -0.85, -0.5], max: [1.65, 0.85, 1]}
hidden_spaces:
  - {name: s, center_m: [0.8, 0], interior_size_m: [1.2, 1.2, 0.4], wall_thickness_m: 0.2,
     opening: {wall: -x, width_m: 0.15, height_m: 0.07}, marker: {id: 1, size_m: 0.1}}
)";
  EXPECT_NO_THROW((void)parse_world(yaml, "w.yaml"));
  std::string tighter = yaml;
  tighter.replace(tighter.find("1.65"), 4, "1.55");
  expect_field(tighter, "hidden_spaces[0].center_m", "inside bounds");
}

TEST(WorldSpec, RotatedNeighboursMayStandCloseWithoutOverlapping) {
  // Rotated 45 deg, the annex's axis-aligned bounds reach into the cellar's, its walls do not.
  EXPECT_NO_THROW(
      (void)parse_world(std::string(kBase) + R"(  - {name: annex, center_m: [2.1, 0.2], yaw_deg: 45,
     interior_size_m: [0.8, 0.8, 0.3], marker: {id: 2}, opening: {wall: +x, width_m: 0.15, height_m: 0.07}}
)",
                        "w.yaml"));
}

TEST(WorldSpec, RubbleIsSeededAndKeepsClear) {
  const std::string rubble = R"(
rubble:
  - {seed: 11, count: 40, region_m: {min: [-3, -3], max: [3, 3]}, size_min_m: [0.1, 0.1, 0.1],
     size_max_m: [0.3, 0.3, 0.2], clearance_m: 0.2}
)";
  const WorldSpec a = parse_world(with(rubble), "w.yaml");
  const WorldSpec b = parse_world(with(rubble), "w.yaml");
  ASSERT_EQ(a.rubble.size(), 40u);
  const HiddenSpace& h = a.hidden_spaces[0];
  for (std::size_t i = 0; i < a.rubble.size(); ++i) {
    EXPECT_EQ(a.rubble[i].center_m, b.rubble[i].center_m);
    const auto& c = a.rubble[i].center_m;
    const double r = a.rubble[i].size_m.head<2>().norm() / 2;
    // Clear of the enclosure (x in [-0.6, 1.6], y in [-1.7, -0.3]) by 0.2 m.
    const bool near_space =
        c.x() > -0.8 - r && c.x() < 1.8 + r && c.y() > -1.9 - r && c.y() < -0.1 + r;
    EXPECT_FALSE(near_space) << i;
    EXPECT_GT((c.head<2>() - a.drop_zone->center_m).norm(), 0.7 + r - 1e-9);
    EXPECT_NEAR(c.z(), a.rubble[i].size_m.z() / 2, 1e-12);  // resting on flat ground
  }
  // The enclosure's box the check above uses, from the world's own geometry.
  const auto box = h.outer_bounds_m();
  EXPECT_NEAR(box.min().x(), -0.6, 1e-9);
  EXPECT_NEAR(box.max().x(), 1.6, 1e-9);
  EXPECT_NEAR(box.min().y(), -1.7, 1e-9);
  EXPECT_NEAR(box.max().y(), -0.3, 1e-9);
}

TEST(WorldSpec, BadInputNamesFileAndField) {
  expect_field("resolution_m: fine\nbounds_m: {min: [0, 0, 0], max: [1, 1, 1]}\n", "resolution_m",
               "a number");
  expect_field(with("colour: red\n"), "colour", "known key");
  expect_field(with("drop_zone: {center_m: [1, 1], radius_m: 1}\n"), "drop_zone", "each key once");
  std::string marker = kWorld;
  marker.replace(marker.find("{id: 7, size_m: 0.2}"), 20, "{id: 50, size_m: 0.2}");
  expect_field(marker, "hidden_spaces[0].marker.id", "[0, 49] of DICT_4X4_50");
  marker.replace(marker.find("{id: 50, size_m: 0.2}"), 21,
                 "{id: 7, size_m: 0.2, dictionary: DICT_9X9_5}");
  expect_field(marker, "hidden_spaces[0].marker.dictionary");
  // An AprilTag family's dictionary is not an OpenCV name, and the other way round.
  std::string tag = kWorld;
  tag.replace(tag.find("{id: 7, size_m: 0.2}"), 20,
              "{id: 7, size_m: 0.2, family: apriltag, dictionary: DICT_4X4_50}");
  expect_field(tag, "hidden_spaces[0].marker.dictionary", "tag36h11");
  tag = kWorld;
  tag.replace(tag.find("{id: 7, size_m: 0.2}"), 20, "{id: 7, size_m: 0.2, family: qr}");
  expect_field(tag, "hidden_spaces[0].marker.family", "aruco or apriltag");
  tag = kWorld;
  tag.replace(tag.find("{id: 7, size_m: 0.2}"), 20, "{id: 587, size_m: 0.2, family: apriltag}");
  expect_field(tag, "hidden_spaces[0].marker.id", "[0, 586] of tag36h11");
  expect_field(with("boxes:\n  - {center_m: [0, 0], size_m: [1, -1, 1]}\n"), "boxes[0].size_m[1]",
               "> 0");
  expect_field(with("boxes:\n  - {center_m: [0, 0], size_m: [1, 1, 1], colour: red}\n"),
               "boxes[0].colour");
  expect_field(with("boxes:\n  - {center_m: [0], size_m: [1, 1, 1]}\n"), "boxes[0].center_m");
  expect_field(with("boxes: 3\n"), "boxes", "a list of mappings");
  expect_field(with("cylinders:\n  - {center_m: [0, 0], radius_m: -0.2, height_m: 1}\n"),
               "cylinders[0].radius_m");
  const std::string base(kBase);
  expect_field(base +
                   "objects:\n  - {name: x, hidden_space: nowhere, position_m: [0, 0], size_m: "
                   "[0.1, 0.1, 0.1]}\n",
               "objects[0].hidden_space");
  expect_field(base +
                   "objects:\n  - {name: x, hidden_space: cellar, position_m: [0.99, 0], size_m: "
                   "[0.1, 0.1, 0.1]}\n",
               "objects[0].position_m", "wholly inside");
  expect_field(base + "drop_zone: {center_m: [0, 0], radius_m: 0}\n", "drop_zone.radius_m");
  // The object at world (1.0, -0.7) inside debris, then inside a post.
  const std::string object =
      "objects:\n  - {name: x, hidden_space: cellar, position_m: [0.5, 0.3], size_m: [0.06, 0.06, "
      "0.05]}\n";
  expect_field(
      base + "boxes:\n  - {center_m: [1.1, -0.7], size_m: [0.2, 0.2, 0.1], yaw_deg: 45}\n" + object,
      "objects[0].position_m", "clear of boxes[0]");
  expect_field(
      base + "cylinders:\n  - {center_m: [0.93, -0.7], radius_m: 0.05, height_m: 0.3}\n" + object,
      "objects[0].position_m", "clear of cylinders[0]");
  EXPECT_NO_THROW((void)parse_world(
      base + "boxes:\n  - {center_m: [1.2, -0.7], size_m: [0.2, 0.2, 0.1], yaw_deg: 45}\n" + object,
      "w.yaml"));
  // 0.01 m voxels reach only +-327.67 m.
  expect_field("resolution_m: 0.01\nbounds_m: {min: [-400, 0, 0], max: [1, 1, 1]}\n",
               "bounds_m.min", "key range");
  expect_field("resolution_m: 0.1\nbounds_m: {min: [0, 0, 0], max: [1, -1, 1]}\n",
               "bounds_m.max[1]");
  expect_field(R"(
resolution_m: 0.05
bounds_m: {min: [-3, -3, -1], max: [3, 3, 1]}
hidden_spaces:
  - {name: s, center_m: [0, 0], interior_size_m: [1, 1, 0.3], marker: {id: 1},
     opening: {wall: -x, width_m: 1.2, height_m: 0.07}}
)",
               "hidden_spaces[0].opening.width_m");
  expect_field(R"(
resolution_m: 0.05
bounds_m: {min: [-3, -3, -1], max: [3, 3, 1]}
hidden_spaces:
  - {name: s, center_m: [0, 0], interior_size_m: [1, 1, 0.3], marker: {id: 1},
     opening: {wall: up, width_m: 0.1, height_m: 0.07}}
)",
               "hidden_spaces[0].opening.wall");
  expect_field(R"(
resolution_m: 0.05
bounds_m: {min: [-3, -3, -1], max: [3, 3, 1]}
hidden_spaces:
  - {name: s, center_m: [2.9, 0], interior_size_m: [1, 1, 0.3], marker: {id: 1},
     opening: {wall: -x, width_m: 0.1, height_m: 0.07}}
)",
               "hidden_spaces[0].center_m", "inside bounds");
  // A second space whose walls cut the first one's (rotated: only the exact test sees it).
  expect_field(
      std::string(kBase) +
          R"(  - {name: annex, center_m: [2.1, -1.0], yaw_deg: 45, interior_size_m: [1, 0.6, 0.3],
     marker: {id: 2}, opening: {wall: +x, width_m: 0.15, height_m: 0.07}}
)",
      "hidden_spaces[1].center_m", "clear of 'cellar'");
  // Sloped ground rises into the interior unless the floor is raised.
  expect_field(R"(
resolution_m: 0.05
bounds_m: {min: [-3, -3, -1], max: [3, 3, 1]}
ground: {slope: [0.1, 0]}
hidden_spaces:
  - {name: s, center_m: [0, 0], interior_size_m: [1, 1, 0.3], marker: {id: 1},
     opening: {wall: -x, width_m: 0.1, height_m: 0.07}}
)",
               "hidden_spaces[0].floor_z_m");
  expect_field(
      with("rubble:\n  - {seed: 1, count: 50, region_m: {min: [-2.2, -2.2], max: [-1.8, -1.8]},"
           " size_min_m: [0.1, 0.1, 0.1], size_max_m: [0.2, 0.2, 0.2]}\n"),
      "rubble[0].count", "room for 50");
}

}  // namespace
}  // namespace ferret
