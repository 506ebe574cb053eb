// MissionAssembly (mission/mission_assembly.hpp): the UAV's options filled from the world
// and checked once, for every backend set; bad input named by its file and field.

#include "ferret/mission/mission_assembly.hpp"

#include <gtest/gtest.h>

#include <string>

#include "ferret/core/error.hpp"
#include "two_sites_mission.hpp"

namespace ferret {
namespace {

using Loaded = test::TwoSitesMission;

TEST(MissionAssembly, FillsTheUavOptionsFromTheWorld) {
  const Loaded l;
  ASSERT_TRUE(l.settings.uav.openings.empty());  // the world's, not the mission YAML's
  const MissionAssembly assembly(l.world, l.uav, l.settings, 1, "m.yaml");
  const auto& openings = assembly.uav_options().openings;
  ASSERT_EQ(openings.size(), world_openings(*l.world.spec).size());
  EXPECT_EQ(openings.size(), l.world.spec->hidden_spaces.size());
  EXPECT_EQ(assembly.uav_options().tether.total_length_m,
            l.settings.ugv.exploration.mission.tether.total_length_m);
}

TEST(MissionAssembly, BadUavOptionsAreBadInputNamingTheFileAndField) {
  Loaded l;
  l.settings.uav.search_speed_mps = -1.0;
  try {
    const MissionAssembly assembly(l.world, l.uav, l.settings, 1, "m.yaml");
    FAIL() << "a negative search speed was accepted";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("m.yaml"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("uav.search_speed_mps"), std::string::npos) << e.what();
  }
}

TEST(MissionAssembly, AUavWithoutItsCamerasIsBadInput) {
  const Loaded l;
  // The miniUGV's URDF has no marker camera for the UAV's search.
  EXPECT_THROW((void)MissionAssembly(l.world, l.ugv, l.settings, 1, "m.yaml"), InputError);
}

}  // namespace
}  // namespace ferret
