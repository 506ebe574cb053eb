// `ferret config --dump --robot` on URDFs that crashed the loader before (a stack
// overflow on deep nesting and on a long chain of links) or that TinyXML let through:
// exit 2, one line naming the file and the field, no output file.

#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <string>

#include "support/cli_runner.hpp"

// GCC 12 reports -Wrestrict falsely on inlined std::string concatenation (GCC PR 105329).
#pragma GCC diagnostic ignored "-Wrestrict"

namespace ferret::test {
namespace {

const std::string kBase =
    "<link name=\"base_link\"><collision><geometry><box size=\"0.1 0.1 "
    "0.1\"/></geometry></collision></link>\n";

/// Runs config --dump on `xml` written to DIR/robot.urdf with -o DIR/out.yaml and checks
/// the bad-input contract; returns stderr.
std::string dump_fails(const std::string& xml, const std::string& field) {
  TempDir dir;
  const std::string urdf = dir / "robot.urdf", out = dir / "out.yaml";
  std::ofstream(urdf, std::ios::binary) << xml;
  const auto r = run_cli("config --dump --robot '" + urdf + "' -o '" + out + "'");
  EXPECT_EQ(r.exit_code, 2) << r.err;
  EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << "not one line:\n" << r.err;
  EXPECT_EQ(r.err.rfind("ferret: error: " + urdf, 0), 0u) << r.err;
  EXPECT_NE(r.err.find(field), std::string::npos) << r.err;
  EXPECT_FALSE(std::filesystem::exists(out)) << "output written for a bad URDF";
  EXPECT_EQ(dir.count(), 1u) << "a file beside robot.urdf was left behind";
  EXPECT_TRUE(r.out.empty()) << r.out;
  return r.err;
}

TEST(UrdfLimitsCli, FiftyThousandNestedElements) {
  std::string xml = "<robot name=\"r\">\n" + kBase + "<gazebo>\n";
  for (int i = 0; i < 50000; ++i) xml += "<a>";
  for (int i = 0; i < 50000; ++i) xml += "</a>";
  xml += "\n</gazebo>\n</robot>\n";
  // Level 33 is the 31st <a>, on line 4 with the others.
  const auto err = dump_fails(xml, ": line 4: expected elements nested at most 32 levels deep");
  EXPECT_NE(err.find("<a> at level 33"), std::string::npos) << err;
}

TEST(UrdfLimitsCli, FiftyThousandLinkChain) {
  std::string xml = "<robot name=\"r\">\n" + kBase;
  for (int i = 1; i < 50000; ++i) {
    const std::string link = "l" + std::to_string(i);
    const std::string parent = i == 1 ? "base_link" : "l" + std::to_string(i - 1);
    xml += "<link name=\"" + link + "\"/><joint name=\"j" + std::to_string(i) +
           "\" type=\"fixed\"><parent link=\"" + parent + "\"/><child link=\"" + link +
           "\"/></joint>\n";
  }
  xml += "</robot>\n";
  dump_fails(xml, "expected a URDF of at most 100000 elements");
}

TEST(UrdfLimitsCli, ThousandAndOneLinksWithinTheElementLimit) {
  // A chain past the link limit but far within the element limit: the link count speaks.
  std::string xml = "<robot name=\"r\">\n" + kBase;
  for (int i = 1; i <= 1000; ++i) {
    const std::string link = "l" + std::to_string(i);
    const std::string parent = i == 1 ? "base_link" : "l" + std::to_string(i - 1);
    xml += "<link name=\"" + link + "\"/><joint name=\"j" + std::to_string(i) +
           "\" type=\"fixed\"><parent link=\"" + parent + "\"/><child link=\"" + link +
           "\"/></joint>\n";
  }
  xml += "</robot>\n";
  // l1000, the 1001st link, is on line 2 + 1000.
  dump_fails(xml, ":1002: link[l1000]: expected a robot of at most 1000 links");
}

TEST(UrdfLimitsCli, AnUnterminatedCommentNoLongerSwallowsALink) {
  const std::string xml =
      "<robot name=\"r\">\n" + kBase + "<!-- note\n<link name=\"hidden\"/>\n</robot>\n";
  dump_fails(xml, ": line 6 column 1: expected a comment closed by -->");
}

TEST(UrdfLimitsCli, NanInAJointOrigin) {
  const std::string xml = "<robot name=\"r\">\n" + kBase +
                          "<link name=\"a\"/><joint name=\"j\" type=\"fixed\"><origin xyz=\"0 "
                          "nan 0\"/><parent link=\"base_link\"/><child link=\"a\"/></joint>\n"
                          "</robot>\n";
  dump_fails(xml, ":3: joint[j]/origin@xyz: expected 3 numbers >= -1000 and <= 1000 (metres)");
}

}  // namespace
}  // namespace ferret::test
