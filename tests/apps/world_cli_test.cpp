// End-to-end tests of `ferret world build | slice | info | generate-hidden`.

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <fstream>
#include <sstream>

#include "ferret/mapping/occupancy_map_2d.hpp"
#include "support/cli_runner.hpp"

namespace ferret::test {
namespace {
using ::testing::HasSubstr;
using ::testing::Not;

const std::string kSmall = "examples/worlds/small.yaml";

void write(const std::string& path, const std::string& text) {
  std::ofstream(path, std::ios::binary) << text;
}
std::string read(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

TEST(WorldCli, BuildSliceInfo) {
  TempDir dir;
  const auto built = run_cli("world build " + kSmall + " -o " + (dir / "w.bt"));
  ASSERT_EQ(built.exit_code, 0) << built.err;
  EXPECT_THAT(built.out, HasSubstr("built 'small'"));
  EXPECT_EQ(built.err, "");

  const auto info = run_cli("world info " + (dir / "w.bt"));
  ASSERT_EQ(info.exit_code, 0) << info.err;
  EXPECT_THAT(info.out, HasSubstr("resolution_m: 0.025"));
  EXPECT_THAT(info.out, HasSubstr("known_min_m: [-3, -3, -0.2]"));

  const auto sliced = run_cli("world slice " + (dir / "w.bt") + " --z 0.03 -o " + (dir / "s.yaml"));
  ASSERT_EQ(sliced.exit_code, 0) << sliced.err;
  const OccupancyMap2D m = load_map_server(dir / "s.yaml");
  EXPECT_EQ(m.geometry.width, 240);
  EXPECT_EQ(m.state_at(-0.55, -1.3), CellState::kOccupied);  // cellar wall
  EXPECT_EQ(m.state_at(-0.55, -1.0), CellState::kFree);      // its opening
  EXPECT_EQ(m.state_at(0.5, -1.0), CellState::kFree);        // its interior
  EXPECT_EQ(dir.count(), 3u);                                // w.bt, s.yaml, s.pgm
}

TEST(WorldCli, OtOutputAndSliceStraightFromYaml) {
  TempDir dir;
  ASSERT_EQ(run_cli("world build " + kSmall + " -o " + (dir / "w.ot")).exit_code, 0);
  EXPECT_EQ(read(dir / "w.ot").rfind("# Octomap OcTree file\n", 0), 0u);
  ASSERT_EQ(run_cli("world slice " + kSmall + " --z 0.2 -o " + (dir / "a.yaml")).exit_code, 0);
  ASSERT_EQ(run_cli("world slice " + (dir / "w.ot") + " --z 0.2 -o " + (dir / "b.yaml")).exit_code,
            0);
  EXPECT_TRUE(load_map_server(dir / "a.yaml") == load_map_server(dir / "b.yaml"));
  const auto info = run_cli("world info " + kSmall);
  EXPECT_THAT(info.out, HasSubstr("p_WE: [-0.6, -1, 0]"));
  EXPECT_THAT(info.out, HasSubstr("marker: {id: 7"));
}

TEST(WorldCli, SliceOfOneHiddenSpace) {
  TempDir dir;
  const auto r = run_cli("world slice " + kSmall + " --space cellar -o " + (dir / "c.yaml"));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const OccupancyMap2D m = load_map_server(dir / "c.yaml");
  // Enclosure x [-0.6, 1.6], y [-1.7, -0.3], plus 0.5 m: 3.2 x 2.4 m at 2.5 cm.
  EXPECT_EQ(m.geometry.width, 128);
  EXPECT_EQ(m.geometry.height, 96);
  EXPECT_EQ(m.state_at(-0.55, -1.0), CellState::kFree);  // the opening
  const auto bad = run_cli("world slice " + kSmall + " --space attic -o " + (dir / "d.yaml"));
  EXPECT_EQ(bad.exit_code, 2);
  EXPECT_THAT(bad.err, HasSubstr("one of: cellar"));
  EXPECT_EQ(dir.count(), 2u);
}

TEST(WorldCli, BadWorldYamlExitsTwoNamingFieldWithoutOutput) {
  TempDir dir;
  const std::string base = read(FERRET_SOURCE_DIR "/" + kSmall);
  struct Case {
    std::string yaml, field;
  };
  const Case cases[] = {
      {"resolution_m: [1, 2]\nbounds_m: {min: [0, 0, 0], max: [1, 1, 1]}\n", "resolution_m"},
      {base + "flavour: mint\n", "flavour"},
      {"resolution_m: 0.1\nbounds_m: {min: [0, 0, 0], max: [2, 2, 2]}\n"
       "boxes:\n  - {center_m: [1, 1], size_m: [0.5, -0.5, 0.5]}\n",
       "boxes[0].size_m[1]"},
      {"resolution_m: 0.1\nbounds_m: {min: [0, 0, 0], max: [2, 2, 2]}\ncylinders:\n  - {center_m: "
       "[1, 1], radius_m: "
       "0.2, height_m: tall}\n",
       "cylinders[0].height_m"},
      {"resolution_m: 0.1\nbounds_m: [0, 0, 0]\n", "bounds_m"},
      {"resolution_m: 0.1\nbounds_m: {min: [0, 0, 0], max: [2, 2, 2]\n", "line"},
  };
  for (const Case& c : cases) {
    write(dir / "bad.yaml", c.yaml);
    const auto r = run_cli("world build " + (dir / "bad.yaml") + " -o " + (dir / "out.bt"));
    EXPECT_EQ(r.exit_code, 2) << c.field;
    EXPECT_THAT(r.err, HasSubstr("bad.yaml: " + c.field)) << r.err;
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;  // one line
    EXPECT_EQ(dir.count(), 1u) << "output left behind for " << c.field;
  }
}

TEST(WorldCli, TruncatedOrGarbageBtExitsTwoWithoutOutput) {
  TempDir dir;
  ASSERT_EQ(run_cli("world build " + kSmall + " -o " + (dir / "w.bt")).exit_code, 0);
  const std::string bytes = read(dir / "w.bt");
  write(dir / "cut.bt", bytes.substr(0, bytes.size() / 2));
  write(dir / "junk.bt", "# Octomap OcTree binary file\nid OcTree\nsize 99\nres 0.1\ndata\n" +
                             std::string(500, '\xff'));
  for (const std::string name : {"cut.bt", "junk.bt"}) {
    for (const std::string& cmd : {"world slice " + (dir / name) + " -o " + (dir / "s.yaml"),
                                   "world info " + (dir / name)}) {
      const auto r = run_cli(cmd);
      EXPECT_EQ(r.exit_code, 2) << cmd;
      EXPECT_THAT(r.err, HasSubstr(name + ": data")) << r.err;
    }
  }
  EXPECT_EQ(dir.count(), 3u);  // no s.yaml, no s.pgm
}

TEST(WorldCli, OutputExtensionsAreChecked) {
  TempDir dir;
  auto r = run_cli("world build " + kSmall + " -o " + (dir / "w.txt"));
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_THAT(r.err, HasSubstr(".bt or .ot"));
  r = run_cli("world slice " + kSmall + " -o " + (dir / "s.pgm"));
  EXPECT_EQ(r.exit_code, 2);
  r = run_cli("world slice " + kSmall + " --z 5000 -o " + (dir / "s.yaml"));
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_THAT(r.err, HasSubstr("--z"));
  r = run_cli("world build no/such/world.yaml -o " + (dir / "w.bt"));
  EXPECT_EQ(r.exit_code, 2);
  for (const char* bad : {"--z nan", "--z inf", "--band -1", "--band nan"}) {
    r = run_cli("world slice " + kSmall + " " + bad + " -o " + (dir / "s.yaml"));
    EXPECT_EQ(r.exit_code, 2) << bad;
    EXPECT_THAT(r.err, HasSubstr(std::string(bad).substr(0, std::string(bad).find(' '))));
  }
  EXPECT_EQ(dir.count(), 0u);
}

TEST(WorldCli, OutFollowsTheCliConvention) {
  TempDir dir;
  // -o/--out, with --output kept as a hidden alias; a missing one names --out.
  ASSERT_EQ(run_cli("world build " + kSmall + " --out " + (dir / "a.bt")).exit_code, 0);
  ASSERT_EQ(run_cli("world build " + kSmall + " --output " + (dir / "b.bt")).exit_code, 0);
  EXPECT_EQ(read(dir / "a.bt"), read(dir / "b.bt"));
  ASSERT_EQ(run_cli("world slice " + (dir / "a.bt") + " --out " + (dir / "s.yaml")).exit_code, 0);
  for (const std::string& cmd : {"world build " + kSmall, "world slice " + kSmall}) {
    const auto r = run_cli(cmd);
    EXPECT_EQ(r.exit_code, 2) << cmd;
    EXPECT_THAT(r.err, HasSubstr("--out")) << cmd;
  }
  const auto help = run_cli("world slice --help");
  EXPECT_THAT(help.out, HasSubstr("-o,--out"));
  EXPECT_THAT(help.out, Not(HasSubstr("--output")));
  EXPECT_THAT(help.out, HasSubstr("--z FLOAT=0.03"));  // defaults are shown
  EXPECT_EQ(dir.count(), 4u);                          // a.bt, b.bt, s.yaml, s.pgm
}

TEST(WorldCli, GenerateHiddenWritesAMapWithItsSearchAndIsReproducible) {
  TempDir dir;
  const auto a = run_cli("world generate-hidden --seed 4 --clutter dense -o " + (dir / "a.yaml"));
  ASSERT_EQ(a.exit_code, 0) << a.err;
  EXPECT_THAT(a.out, HasSubstr("dense hidden space, seed 4: 240 x 160 cells"));
  const OccupancyMap2D m = load_map_server(dir / "a.yaml");
  EXPECT_EQ(m.geometry.width, 240);
  EXPECT_GT(m.count(CellState::kOccupied), 0u);
  EXPECT_THAT(read(dir / "a.yaml"), HasSubstr("search:\n  start: [1, "));
  ASSERT_EQ(
      run_cli("world generate-hidden --seed 4 --clutter dense -o " + (dir / "b.yaml")).exit_code,
      0);
  EXPECT_EQ(read(dir / "a.pgm"), read(dir / "b.pgm"));
  ASSERT_EQ(
      run_cli("world generate-hidden --seed 5 --clutter dense -o " + (dir / "c.yaml")).exit_code,
      0);
  EXPECT_NE(read(dir / "a.pgm"), read(dir / "c.pgm"));
  const auto big =
      run_cli("world generate-hidden --size 24,10 --resolution 0.1 -o " + (dir / "d.yaml"));
  ASSERT_EQ(big.exit_code, 0) << big.err;
  EXPECT_THAT(big.out, HasSubstr("240 x 100 cells"));
  // A search with it runs: ferret explore takes the map as any other.
  const auto e = run_cli("explore --map " + (dir / "a.yaml") +
                         " --start 1,4,0 --object 10,1.5 --time-limit 5");
  EXPECT_NE(e.exit_code, 2) << e.err;
  EXPECT_EQ(dir.count(), 8u);
}

TEST(WorldCli, GenerateHiddenBadOptionsExitTwoAndWriteNothing) {
  TempDir dir;
  const std::string out = " -o " + (dir / "g.yaml");
  for (const auto& [args, option] :
       std::vector<std::pair<std::string, std::string>>{{"--clutter medium", "--clutter"},
                                                        {"--size 4,4", "--size"},
                                                        {"--size 12,80", "--size"},
                                                        {"--resolution 0.5", "--resolution"},
                                                        {"--seed -3", "--seed"}}) {
    const auto r = run_cli("world generate-hidden " + args + out);
    EXPECT_EQ(r.exit_code, 2) << args;
    EXPECT_THAT(r.err, HasSubstr(option)) << args;
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
  }
  const auto txt = run_cli("world generate-hidden -o " + (dir / "g.txt"));
  EXPECT_EQ(txt.exit_code, 2);
  EXPECT_EQ(dir.count(), 0u);
}

}  // namespace
}  // namespace ferret::test
