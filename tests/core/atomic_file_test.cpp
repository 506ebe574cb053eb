#include "ferret/core/atomic_file.hpp"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <stdexcept>

#include "ferret/core/error.hpp"

namespace ferret {
namespace {
namespace fs = std::filesystem;

class AtomicFile : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() /
           ("ferret_atomic_" + std::to_string(::testing::UnitTest::GetInstance()->random_seed()) +
            ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::remove_all(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }
  fs::path dir_;
};

TEST_F(AtomicFile, WritesIntoNewDirectory) {
  const auto out = dir_ / "sub" / "a.txt";
  write_text_atomically(out, "hello");
  std::ifstream in(out);
  std::string s;
  in >> s;
  EXPECT_EQ(s, "hello");
  EXPECT_EQ(std::distance(fs::directory_iterator(out.parent_path()), fs::directory_iterator{}), 1);
}

TEST_F(AtomicFile, FailingWriterLeavesNothingBehind) {
  const auto out = dir_ / "b.png";
  EXPECT_THROW(write_file_atomically(out,
                                     [](const fs::path& tmp) {
                                       EXPECT_EQ(tmp.extension(),
                                                 ".png");  // writers pick formats by it
                                       std::ofstream(tmp) << "partial";
                                       throw std::runtime_error("disk full");
                                     }),
               std::runtime_error);
  EXPECT_FALSE(fs::exists(out));
  EXPECT_FALSE(fs::exists(dir_));  // the parent it created is removed again
}

TEST_F(AtomicFile, FailingWriterKeepsPreviousFile) {
  const auto out = dir_ / "c.txt";
  write_text_atomically(out, "old");
  EXPECT_THROW(write_file_atomically(out, [](const fs::path&) { throw InputError("x", "", "y"); }),
               InputError);
  std::ifstream in(out);
  std::string s;
  in >> s;
  EXPECT_EQ(s, "old");
}

TEST_F(AtomicFile, WriterThatProducesNoFileIsAnError) {
  EXPECT_THROW(write_file_atomically(dir_ / "d.txt", [](const fs::path&) {}), InputError);
  EXPECT_FALSE(fs::exists(dir_ / "d.txt"));
}

}  // namespace
}  // namespace ferret
