#include "ferret/core/output_set.hpp"

#include <gtest/gtest.h>
#include <sys/stat.h>
#include <sys/types.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <string>

#include "ferret/core/atomic_file.hpp"
#include "ferret/core/error.hpp"

namespace ferret {
namespace {
namespace fs = std::filesystem;

class OutputSetTest : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() /
           ("ferret_output_set_" + std::to_string(::getpid()) + "_" +
            ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::remove_all(dir_);
    fs::create_directories(dir_);
  }
  void TearDown() override {
    fs::permissions(dir_, fs::perms::owner_all, fs::perm_options::add);
    fs::remove_all(dir_);
  }
  [[nodiscard]] std::size_t entries(const fs::path& d) const {
    return static_cast<std::size_t>(
        std::distance(fs::directory_iterator(d), fs::directory_iterator{}));
  }
  static std::string slurp(const fs::path& p) {
    std::ifstream in(p);
    std::stringstream s;
    s << in.rdbuf();
    return s.str();
  }
  // The InputError `f` throws (fails the test when it throws none).
  template <typename F>
  static InputError error_of(F&& f) {
    try {
      f();
    } catch (const InputError& e) {
      return e;
    }
    ADD_FAILURE() << "no InputError";
    return InputError("", "", "");
  }
  fs::path dir_;
};

TEST_F(OutputSetTest, NewDirectoryAppearsWithAllFilesAndNothingElse) {
  const fs::path out = dir_ / "run";
  {
    OutputSet set(out, OutputKind::kDirectory);
    set.write_text("a.csv", "1\n");
    set.write_text("sub/b.csv", "2\n");
    EXPECT_FALSE(fs::exists(out));  // nothing is visible before the commit
    set.commit();
  }
  EXPECT_EQ(slurp(out / "a.csv"), "1\n");
  EXPECT_EQ(slurp(out / "sub" / "b.csv"), "2\n");
  EXPECT_EQ(entries(out), 2U);
  EXPECT_EQ(entries(dir_), 1U);  // no staging directory left beside it
}

TEST_F(OutputSetTest, ExceptionInTheThirdOfFourFilesLeavesNoneOfThem) {
  for (const bool existing : {false, true}) {
    const fs::path out = dir_ / (existing ? "existing" : "new");
    if (existing) fs::create_directories(out);
    fs::path staging;
    EXPECT_THROW(
        {
          OutputSet set(out, OutputKind::kDirectory);
          staging = set.staging_dir();
          set.write_text("1.csv", "one");
          set.write_text("2.csv", "two");
          set.write("3.png", [](const fs::path& p) {
            std::ofstream(p) << "half a PNG";
            throw std::runtime_error("disk full");
          });
          set.write_text("4.csv", "four");
          set.commit();
        },
        std::runtime_error);
    EXPECT_FALSE(staging.empty());
    EXPECT_FALSE(fs::exists(staging));
    EXPECT_EQ(fs::exists(out), existing);
    if (existing) {
      EXPECT_EQ(entries(out), 0U);
    }
  }
  EXPECT_EQ(entries(dir_), 1U);  // only "existing"
}

TEST_F(OutputSetTest, ExistingDirectoryKeepsUnrelatedFilesAndReplacesSetFiles) {
  const fs::path out = dir_ / "run";
  fs::create_directories(out);
  write_text_atomically(out / "notes.txt", "mine");
  write_text_atomically(out / "runs.csv", "old");
  OutputSet set(out, OutputKind::kDirectory);
  set.write_text("runs.csv", "new");
  set.write_text("summary.csv", "s");
  set.commit();
  EXPECT_EQ(slurp(out / "notes.txt"), "mine");
  EXPECT_EQ(slurp(out / "runs.csv"), "new");
  EXPECT_EQ(slurp(out / "summary.csv"), "s");
  EXPECT_EQ(entries(out), 3U);
}

// "f<k>.csv" (appends: GCC 12 warns falsely on an operator+ chain here).
std::string file_name(int k) {
  std::string name = "f";
  name.append(std::to_string(k));
  name.append(".csv");
  return name;
}

TEST_F(OutputSetTest, ADirectoryWhereALaterFileGoesRefusesTheWholeSet) {
  // Eight files, one blocked by a directory of its name: a commit that moved files
  // before checking them all would leave some of the other seven.
  const fs::path out = dir_ / "run";
  fs::create_directories(out / "f4.csv");
  OutputSet set(out, OutputKind::kDirectory);
  for (int k = 0; k < 8; ++k) set.write_text(file_name(k), "x");
  const InputError e = error_of([&] { set.commit(); });
  EXPECT_EQ(e.source(), (out / "f4.csv").string());
  EXPECT_NE(std::string(e.what()).find("a directory"), std::string::npos) << e.what();
  EXPECT_EQ(entries(out), 2U);  // f4.csv and the staging directory, until the set goes
  EXPECT_TRUE(fs::is_directory(out / "f4.csv"));
  EXPECT_TRUE(fs::is_empty(out / "f4.csv"));
  for (int k = 0; k < 8; ++k) {
    if (k != 4) {
      EXPECT_FALSE(fs::exists(out / (file_name(k)))) << k;
    }
  }
}

TEST_F(OutputSetTest, StagingDirectoryIsBesideTheTarget) {
  {
    OutputSet file(dir_ / "plan.json", OutputKind::kFile);
    EXPECT_EQ(file.staging_dir().parent_path(), fs::absolute(dir_).lexically_normal());
    // The staged file keeps the target's name: writers choose formats by the extension.
    EXPECT_EQ(file.path().filename(), "plan.json");
    EXPECT_EQ(file.path().parent_path(), file.staging_dir());
  }
  {
    OutputSet dir(dir_ / "new" / "", OutputKind::kDirectory);  // trailing separator
    EXPECT_EQ(dir.staging_dir().parent_path(), fs::absolute(dir_).lexically_normal());
  }
  EXPECT_EQ(entries(dir_), 0U);  // both rolled back: no staging and no "new"
}

TEST_F(OutputSetTest, FileTargetReplacesAnOldFileOnlyOnCommit) {
  const fs::path out = dir_ / "a" / "b" / "plan.json";
  {
    OutputSet set(out, OutputKind::kFile);
    set.write_text({}, "new");
    // Without a commit the parents the set created go too.
  }
  EXPECT_FALSE(fs::exists(dir_ / "a"));
  write_text_atomically(out, "old");
  EXPECT_THROW(write_file_atomically(out, [](const fs::path&) { throw InputError("x", "", "y"); }),
               InputError);
  EXPECT_EQ(slurp(out), "old");
  write_text_atomically(out, "new");
  EXPECT_EQ(slurp(out), "new");
  EXPECT_EQ(entries(out.parent_path()), 1U);
}

TEST_F(OutputSetTest, FifoTargetIsRefusedAndStaysAFifo) {
  const fs::path fifo = dir_ / "pipe";
  ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0);
  const InputError e = error_of([&] { check_output_target(fifo, OutputKind::kFile, "--out"); });
  EXPECT_EQ(e.source(), fifo.string());
  EXPECT_EQ(e.expected(), "a regular file path for --out");
  EXPECT_NE(std::string(e.what()).find("a FIFO"), std::string::npos) << e.what();
  EXPECT_THROW(write_text_atomically(fifo, "x"), InputError);
  EXPECT_THROW(OutputSet(fifo, OutputKind::kDirectory), InputError);
  EXPECT_TRUE(fs::is_fifo(fifo));
  EXPECT_EQ(entries(dir_), 1U);
}

TEST_F(OutputSetTest, DeviceDirectoryAndEmptyTargetsAreRefused) {
  const InputError dev =
      error_of([&] { check_output_target("/dev/null", OutputKind::kFile, "--out"); });
  EXPECT_EQ(dev.source(), "/dev/null");
  EXPECT_NE(std::string(dev.what()).find("a character device"), std::string::npos) << dev.what();

  const InputError d = error_of([&] { write_text_atomically(dir_, "x"); });
  EXPECT_EQ(d.source(), dir_.string());
  EXPECT_NE(std::string(d.what()).find("a directory"), std::string::npos) << d.what();
  EXPECT_THROW(check_output_target(dir_ / "x" / "", OutputKind::kFile), InputError);

  const InputError empty = error_of([&] { check_output_target("", OutputKind::kFile, "--out"); });
  EXPECT_EQ(empty.source(), "--out");
  EXPECT_EQ(empty.expected(), "a non-empty output path");
  EXPECT_THROW(OutputSet("", OutputKind::kDirectory), InputError);

  write_text_atomically(dir_ / "file", "x");
  const InputError not_dir =
      error_of([&] { check_output_target(dir_ / "file", OutputKind::kDirectory, "--out"); });
  EXPECT_EQ(not_dir.expected(), "a directory path for --out");
  EXPECT_EQ(entries(dir_), 1U);
}

TEST_F(OutputSetTest, PathUnderARegularFileIsRefused) {
  write_text_atomically(dir_ / "file", "x");
  for (const auto kind : {OutputKind::kFile, OutputKind::kDirectory}) {
    const fs::path target = dir_ / "file" / "sub" / "out.json";
    const InputError e = error_of([&] { check_output_target(target, kind, "--out"); });
    EXPECT_EQ(e.source(), target.string());
    EXPECT_NE(std::string(e.what()).find((dir_ / "file").string() + "' is a regular file"),
              std::string::npos)
        << e.what();
    EXPECT_THROW(OutputSet(target, kind), InputError);
  }
  EXPECT_EQ(slurp(dir_ / "file"), "x");
  EXPECT_EQ(entries(dir_), 1U);
}

TEST_F(OutputSetTest, ReadOnlyParentIsInputError) {
  if (::geteuid() == 0) GTEST_SKIP() << "root ignores directory permissions";
  const fs::path ro = dir_ / "ro";
  fs::create_directories(ro);
  fs::permissions(ro, fs::perms::owner_read | fs::perms::owner_exec);
  for (const auto& [target, kind] : {std::pair{ro / "plan.json", OutputKind::kFile},
                                     {ro / "run", OutputKind::kDirectory},
                                     {ro, OutputKind::kDirectory},
                                     {ro / "a" / "b.json", OutputKind::kFile}}) {
    const InputError e = error_of([&] { OutputSet set(target, kind); });
    EXPECT_EQ(e.source(), target.string());
    EXPECT_EQ(e.expected(), "a writable directory");
  }
  fs::permissions(ro, fs::perms::owner_all);
  EXPECT_EQ(entries(ro), 0U);
}

TEST_F(OutputSetTest, UnwritableLocationIsInputErrorEvenForRoot) {
  // sysfs refuses new entries to everyone, root included.
  if (!fs::is_directory("/sys/kernel")) GTEST_SKIP() << "no /sys";
  for (const auto kind : {OutputKind::kFile, OutputKind::kDirectory}) {
    const InputError e = error_of([&] { OutputSet set("/sys/kernel/ferret_out/x.json", kind); });
    EXPECT_EQ(e.source(), "/sys/kernel/ferret_out/x.json");
    EXPECT_EQ(e.expected(), "a writable directory");
  }
  EXPECT_FALSE(fs::exists("/sys/kernel/ferret_out"));
}

TEST_F(OutputSetTest, FilesWrittenIntoTheStagingDirectoryByOthersAreCommitted) {
  // The experiment's plot script writes into the staging directory itself.
  const fs::path out = dir_ / "run";
  fs::create_directories(out);
  OutputSet set(out, OutputKind::kDirectory);
  set.write_text("summary.csv", "s");
  std::ofstream(set.staging_dir() / "plot.png") << "png";
  set.commit();
  EXPECT_EQ(slurp(out / "plot.png"), "png");
  EXPECT_EQ(entries(out), 2U);
}

TEST_F(OutputSetTest, WriterThatProducesNoFileIsAnError) {
  OutputSet set(dir_ / "out", OutputKind::kDirectory);
  const InputError e = error_of([&] { set.write("a.png", [](const fs::path&) {}); });
  EXPECT_EQ(e.source(), (dir_ / "out" / "a.png").string());
  EXPECT_THROW((void)set.path("../escape.csv"), std::invalid_argument);
}

}  // namespace
}  // namespace ferret
