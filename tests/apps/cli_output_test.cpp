// Every command's outputs appear all together or not at all, and a bad output target
// (empty, a FIFO, a device, a directory where a file goes, a path under a regular file,
// a later file of a set that cannot be written) is bad input: exit 2, one line naming
// the path, no output file. The targets are built here, never shipped.

#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <sys/stat.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <functional>
#include <sstream>
#include <string>
#include <vector>

#include "support/cli_runner.hpp"
#include "support/test_maps.hpp"

namespace ferret::test {
namespace {
namespace fs = std::filesystem;
using ::testing::HasSubstr;
using ::testing::Not;
using ::testing::StartsWith;

std::string q(const std::string& path) { return "'" + path + "'"; }

std::string slurp(const fs::path& p) {
  std::ifstream in(p);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

void expect_refused(const CliResult& r, const std::string& named, const std::string& what) {
  EXPECT_EQ(r.exit_code, 2) << what << "\n" << r.err;
  EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << what << ": one line\n" << r.err;
  EXPECT_THAT(r.err, StartsWith("ferret: error: ")) << what;
  EXPECT_THAT(r.err, HasSubstr(named)) << what;
}

// The entries of `dir`, names sorted (to show nothing appeared, and no staging is left).
std::vector<std::string> entries(const fs::path& dir) {
  std::vector<std::string> names;
  for (const auto& e : fs::directory_iterator(dir)) names.push_back(e.path().filename().string());
  std::sort(names.begin(), names.end());
  return names;
}

// A command that writes one file: `args(out)` is its command line with -o out.
struct FileCommand {
  std::string name;
  std::string extension;
  std::function<std::string(const std::string& out)> args;
};

std::vector<FileCommand> file_commands(const TempDir& dir) {
  save_map_server(small_hidden_space(), dir.path() / "room.yaml");
  const std::string room = q(dir / "room.yaml");
  return {
      {"world build", ".bt",
       [](const std::string& o) { return "world build examples/worlds/small.yaml -o " + o; }},
      {"world slice", ".yaml",
       [](const std::string& o) {
         return "world slice examples/worlds/small.yaml --z 0.2 -o " + o;
       }},
      {"plan ugv", ".json",
       [](const std::string& o) {
         return "plan ugv --world examples/scenarios/tether_detour.yaml --driven '1,6.5;10,6.5' "
                "--from 10,4.5,-1.57 --to 10,1.5,-1.57 --tether 12.5 -o " +
                o;
       }},
      {"render", ".png", [room](const std::string& o) { return "render " + room + " -o " + o; }},
      {"config", ".yaml", [](const std::string& o) { return "config --dump -o " + o; }},
  };
}

TEST(OutputCli, FileOutputsRefuseSpecialFilesDirectoriesAndPathsUnderFiles) {
  TempDir dir;
  for (const auto& c : file_commands(dir)) {
    // Each good target writes exactly its file(s) (so the refusals below are not
    // failures of the command itself).
    const std::string good = dir / ("good" + c.extension);
    ASSERT_EQ(run_cli(c.args(q(good))).exit_code, 0) << c.name;
    EXPECT_TRUE(fs::is_regular_file(good)) << c.name;

    const std::string fifo = dir / ("fifo" + c.extension);
    ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0);
    auto r = run_cli(c.args(q(fifo)));
    expect_refused(r, fifo, c.name + " -o FIFO");
    EXPECT_THAT(r.err, HasSubstr("a FIFO")) << c.name;
    EXPECT_TRUE(fs::is_fifo(fifo)) << c.name << ": the FIFO is left a FIFO";
    fs::remove(fifo);

    r = run_cli(c.args("/dev/null"));
    expect_refused(r, "/dev/null", c.name + " -o /dev/null");
    EXPECT_THAT(r.err, HasSubstr("a character device")) << c.name;
    EXPECT_TRUE(fs::is_character_file("/dev/null"));

    const std::string a_dir = dir / ("dir" + c.extension);
    fs::create_directory(a_dir);
    r = run_cli(c.args(q(a_dir)));
    expect_refused(r, a_dir, c.name + " -o DIR");
    EXPECT_THAT(r.err, HasSubstr("a directory")) << c.name;
    EXPECT_TRUE(fs::is_empty(a_dir)) << c.name;
    fs::remove(a_dir);

    const std::string file = dir / "file";
    std::ofstream(file) << "keep";
    const std::string under = file + "/sub/out" + c.extension;
    r = run_cli(c.args(q(under)));
    expect_refused(r, under, c.name + " -o under a regular file");
    EXPECT_THAT(r.err, HasSubstr("is a regular file")) << c.name;
    EXPECT_EQ(slurp(file), "keep") << c.name;
    fs::remove(file);

    r = run_cli(c.args("''"));
    expect_refused(r, "--out", c.name + " --out ''");

    fs::remove(good);
    fs::path pgm = good;
    fs::remove(pgm.replace_extension(".pgm"));
    EXPECT_EQ(entries(dir.path()), (std::vector<std::string>{"room.pgm", "room.yaml"})) << c.name;
  }
}

TEST(OutputCli, WorldSliceWritesNeitherYamlNorPgmWhenThePgmCannotBeWritten) {
  TempDir dir;
  fs::create_directory(dir / "map.pgm");
  const auto r =
      run_cli("world slice examples/worlds/small.yaml --z 0.2 -o " + q(dir / "map.yaml"));
  expect_refused(r, dir / "map.pgm", "slice");
  EXPECT_EQ(entries(dir.path()), std::vector<std::string>{"map.pgm"});
  EXPECT_TRUE(fs::is_empty(dir / "map.pgm"));
}

// A command that writes a directory of files: `args(out)` is its command line with
// -o out, `files` what it writes there, `blocked` one of them (not the first).
struct DirCommand {
  std::string name;
  std::function<std::string(const std::string& out)> args;
  std::vector<std::string> files;
  std::string blocked;
};

std::vector<DirCommand> dir_commands(const TempDir& dir) {
  save_map_server(small_hidden_space(), dir.path() / "room.yaml");
  {
    std::ofstream out(dir.path() / "exp.yaml");
    out << "seed: 2\nobjects_per_zone: 1\nmethods: [rapid, oracle]\nmaps:\n  - name: room\n"
           "    map: room.yaml\n    start: [0.5, 1.0, 0.0]\n    zones:\n"
           "      1: [1.0, 0.5, 1.8, 1.5]\n";
  }
  const std::string room = q(dir / "room.yaml"), exp = q(dir / "exp.yaml");
  return {
      {"experiment",
       [exp](const std::string& o) { return "experiment " + exp + " --no-plots --quiet -o " + o; },
       {"runs.csv", "summary.csv"},
       "summary.csv"},
      {"explore",
       [room](const std::string& o) {
         return "explore --map " + room + " --start 0.5,1,0 --object 3.2,0.8 --out " + o;
       },
       {"G.png", "G_O.png", "O.png", "log.json"},
       "log.json"},
      {"tether-sim",
       [](const std::string& o) { return "tether-sim --controller baseline --out " + o; },
       {"tether_baseline.csv", "tether_baseline.json", "tether_baseline.png"},
       "tether_baseline.png"},
      {"bench-plan",
       [](const std::string& o) {
         return "bench-plan --world examples/scenarios/tether_detour.yaml --robots ugv "
                "--problems 2 --runs 1 --time-limit 0.1 --planners rrtconnect -o " +
                o;
       },
       {"ugv_0.log", "ugv_1.log"},
       "ugv_1.log"},
  };
}

TEST(OutputCli, DirectoryOutputsAppearWholeOrNotAtAll) {
  TempDir dir;
  for (const auto& c : dir_commands(dir)) {
    // Into a new directory: exactly the set, nothing else (no staging directory left).
    const std::string fresh = dir / "fresh";
    auto r = run_cli(c.args(q(fresh)));
    ASSERT_EQ(r.exit_code, 0) << c.name << "\n" << r.err;
    EXPECT_EQ(entries(fresh), c.files) << c.name;

    // Into an existing directory where a later file cannot go (a directory has its
    // name): none of the set appears, the user's file stays.
    const fs::path existing = dir.path() / "existing";
    fs::create_directories(existing / c.blocked);
    std::ofstream(existing / "mine.txt") << "mine";
    r = run_cli(c.args(q(existing.string())));
    expect_refused(r, (existing / c.blocked).string(), c.name + " blocked " + c.blocked);
    std::vector<std::string> left{c.blocked, "mine.txt"};
    std::sort(left.begin(), left.end());
    EXPECT_EQ(entries(existing), left) << c.name;
    EXPECT_EQ(slurp(existing / "mine.txt"), "mine");

    // The same directory, unblocked: the set is added, the user's file left alone.
    fs::remove(existing / c.blocked);
    r = run_cli(c.args(q(existing.string())));
    ASSERT_EQ(r.exit_code, 0) << c.name << "\n" << r.err;
    std::vector<std::string> with_mine = c.files;
    with_mine.push_back("mine.txt");
    std::sort(with_mine.begin(), with_mine.end());
    EXPECT_EQ(entries(existing), with_mine) << c.name;

    // Targets refused before the work starts: the one line is the error (no progress).
    const std::string fifo = dir / "fifo";
    ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0);
    r = run_cli(c.args(q(fifo)));
    expect_refused(r, fifo, c.name + " -o FIFO");
    EXPECT_THAT(r.err, HasSubstr("expected a directory path for --out (got a FIFO)"));
    EXPECT_TRUE(fs::is_fifo(fifo)) << c.name;

    const std::string file = dir / "file";
    std::ofstream(file) << "keep";
    r = run_cli(c.args(q(file)));
    expect_refused(r, file, c.name + " -o a regular file");
    const std::string under = file + "/out";
    r = run_cli(c.args(q(under)));
    expect_refused(r, under, c.name + " -o under a regular file");
    EXPECT_EQ(slurp(file), "keep");

    r = run_cli(c.args("''"));
    expect_refused(r, "--out", c.name + " --out ''");

    fs::remove_all(fresh);
    fs::remove_all(existing);
    fs::remove(fifo);
    fs::remove(file);
    EXPECT_EQ(entries(dir.path()), (std::vector<std::string>{"exp.yaml", "room.pgm", "room.yaml"}))
        << c.name;
  }
  // Refused before the first run: no progress line before the error.
  const std::string fifo = dir / "fifo";
  ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0);
  expect_refused(run_cli("experiment " + q(dir / "exp.yaml") + " -o " + q(fifo)), fifo,
                 "experiment with progress");
}

TEST(OutputCli, ExperimentPlotsArePartOfTheSet) {
  if (std::system("/usr/bin/python3 -c 'import matplotlib' 2>/dev/null") != 0)
    GTEST_SKIP() << "no python3-matplotlib: the experiment draws no plots";
  TempDir dir;
  (void)dir_commands(dir);  // the map and the experiment config
  auto args = [&](const std::string& out) {
    return "experiment " + q(dir / "exp.yaml") +
           " --plot-script examples/plot_experiment.py --quiet -o " + out;
  };
  // A plot file cannot be written (the script writes ratios.csv): the CSVs do not
  // appear either.
  const fs::path out = dir.path() / "out";
  fs::create_directories(out / "ratios.csv");
  auto r = run_cli(args(q(out.string())));
  expect_refused(r, (out / "ratios.csv").string(), "experiment with a blocked plot");
  EXPECT_EQ(entries(out), std::vector<std::string>{"ratios.csv"});

  fs::remove(out / "ratios.csv");
  r = run_cli(args(q(out.string())));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_THAT(r.out, HasSubstr("plotted: "));
  EXPECT_THAT(r.out, Not(HasSubstr("staging")));  // the lines name the target only
  const auto names = entries(out);
  EXPECT_NE(std::find(names.begin(), names.end(), "ratios.csv"), names.end());
  EXPECT_NE(std::find(names.begin(), names.end(), "summary.csv"), names.end());
  EXPECT_GE(std::count_if(names.begin(), names.end(),
                          [](const std::string& n) { return n.ends_with(".png"); }),
            1);
  for (const auto& n : names) EXPECT_THAT(n, Not(StartsWith("."))) << "staging left: " << n;
}

}  // namespace
}  // namespace ferret::test
