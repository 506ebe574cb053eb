// The URDF loader survives hostile input: malformed XML, nesting, element, size, link
// and joint counts past their limits, joint graphs that are no tree, and numbers that
// are not finite or out of range. Every input is generated here; each failure is one
// printable line naming the file and the field, and a robot at exactly the limits loads.

#include <gtest/gtest.h>

// GCC 12 reports -Wrestrict falsely on inlined std::string concatenation (GCC PR 105329).
#pragma GCC diagnostic ignored "-Wrestrict"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "ferret/core/error.hpp"
#include "ferret/urdf/robot_description.hpp"

namespace ferret {
namespace {

struct Failure {
  std::string source, field, expected, what;
};

/// True when `text` is one line of printable characters (ASCII or UTF-8 of >= 2 bytes).
bool one_printable_line(const std::string& text) {
  for (const char ch : text) {
    const auto c = static_cast<unsigned char>(ch);
    if (c < 0x20 || c == 0x7f) return false;
  }
  return true;
}

Failure load_failure(const std::string& xml, const std::string& source = "bad.urdf") {
  testing::internal::CaptureStderr();
  Failure f;
  bool threw = false;
  try {
    (void)robot_description_from_string(xml, source);
  } catch (const InputError& e) {
    threw = true;
    f = {e.source(), e.field(), e.expected(), e.what()};
  }
  const std::string printed = testing::internal::GetCapturedStderr();
  EXPECT_TRUE(threw) << "no InputError for:\n" << xml.substr(0, 400);
  EXPECT_EQ(printed, "") << "the loader printed to the console";
  EXPECT_TRUE(one_printable_line(f.what)) << "not one printable line: " << f.what;
  return f;
}

/// prefix + i, appended (GCC 12 warns falsely, -Wrestrict, on "l" + std::to_string(i)).
std::string numbered(const char* prefix, int i) {
  std::string out = prefix;
  out += std::to_string(i);
  return out;
}

bool has(const std::string& text, const std::string& part) {
  return text.find(part) != std::string::npos;
}

const std::string kBase =
    "<link name=\"base_link\"><collision><geometry><box size=\"0.1 0.1 "
    "0.1\"/></geometry></collision></link>";

/// `<robot>` on line 1, the base link on line 2, `body` from line 3.
std::string robot(const std::string& body) {
  return "<robot name=\"r\">\n" + kBase + "\n" + body + "\n</robot>\n";
}

// ---------------------------------------------------------------- malformed XML

struct XmlCase {
  std::string what, xml, field, expected_part, got_part;
};

TEST(UrdfLimits, MalformedXmlIsRefusedWithLineAndColumn) {
  const XmlCase cases[] = {
      // The comment opened on line 3 swallows a link and the end tag: TinyXML took it.
      {"unterminated comment", robot("<!-- a note\n<link name=\"swallowed\"/>"), "line 6 column 1",
       "a comment closed by -->", "Comment not terminated"},
      {"text after the root", robot("") + "trailing words\n", "line 5 column 1",
       "nothing but comments and whitespace after the root element", "Extra content"},
      {"element after the root", robot("") + "<link name=\"late\"/>\n", "line 5 column 1",
       "after the root element", "Extra content"},
      {"unquoted attribute", robot("<link name=late/>"), "line 3 column 12",
       "an attribute value in quotes", "AttValue"},
      // libxml2's column is where it stood: after the token at fault.
      {"duplicate attribute", robot("<link name=\"a\" name=\"b\"/>"), "line 3 column 24",
       "each attribute at most once in an element", "redefined"},
      {"mismatched tags", robot("<link name=\"a\">\n</joint>"), "line 4 column 9",
       "an end tag matching the open element", "mismatch"},
      {"unterminated tag", "<robot name=\"r\">\n<link name=\"a\"", "line 2 column 15",
       "well-formed XML 1.0", ""},
      {"unterminated CDATA", robot("<![CDATA[ never closed"), "line 3 column 10",
       "a complete document (a comment, CDATA section or tag is not closed)", ""},
      {"NUL byte", robot(std::string("<link name=\"a\"/>\0<link name=\"b\"/>", 34)),
       "line 3 column 17", "UTF-8 text of XML characters", "0x0"},
      {"invalid UTF-8", robot("<link name=\"a\xff\xfe\"/>"), "line 3 column 14",
       "UTF-8 text of XML characters", "0xFF 0xFE"},
      {"undeclared entity", robot("<link name=\"&ghost;\"/>"), "line 3 column 20",
       "only the predefined entities", "ghost"},
      {"no root", "<!-- only a comment -->\n", "line 2 column 1", "a <robot> root element", ""},
  };
  for (const auto& c : cases) {
    SCOPED_TRACE(c.what);
    const auto f = load_failure(c.xml);
    EXPECT_EQ(f.source, "bad.urdf") << f.what;
    EXPECT_EQ(f.field, c.field) << f.what;
    EXPECT_TRUE(has(f.expected, c.expected_part)) << f.what;
    EXPECT_TRUE(has(f.what, c.got_part)) << f.what;
  }
}

TEST(UrdfLimits, DoctypeAndEntityExpansionAreRefused) {
  // Billion laughs: ten levels of ten references would expand to 10^9 "lol"s.
  std::string lol = "<?xml version=\"1.0\"?>\n<!DOCTYPE robot [\n<!ENTITY l0 \"lol\">\n";
  for (int i = 1; i <= 9; ++i) {
    lol += "<!ENTITY ";
    lol += numbered("l", i);
    lol += " \"";
    for (int k = 0; k < 10; ++k) {
      lol += '&';
      lol += numbered("l", i - 1);
      lol += ';';
    }
    lol += "\">\n";
  }
  lol += "]>\n<robot name=\"&l9;\">" + kBase + "</robot>\n";
  auto f = load_failure(lol);
  EXPECT_EQ(f.source, "bad.urdf");
  EXPECT_EQ(f.field, "line 2");
  EXPECT_EQ(f.expected, "no DOCTYPE or entity declarations (a URDF has no DTD)");
  // A DOCTYPE without entities is refused too: a URDF has no DTD.
  f = load_failure("<?xml version=\"1.0\"?>\n<!DOCTYPE robot>\n" + robot(""));
  EXPECT_EQ(f.field, "line 2");
  EXPECT_EQ(f.expected, "no DOCTYPE or entity declarations (a URDF has no DTD)");
  // An external entity is never fetched.
  f = load_failure(
      "<?xml version=\"1.0\"?>\n<!DOCTYPE robot [<!ENTITY x SYSTEM \"file:///etc/passwd\">]>\n"
      "<robot name=\"&x;\">" +
      kBase + "</robot>\n");
  EXPECT_EQ(f.field, "line 2");
  EXPECT_TRUE(has(f.expected, "DOCTYPE")) << f.what;
  EXPECT_FALSE(has(f.what, "root:")) << f.what;
  // Behind comments and a processing instruction it is found all the same.
  f = load_failure("<!-- a -->\n<?pi x?>\n<!--\n-->\n<!DOCTYPE robot>\n" + robot(""));
  EXPECT_EQ(f.field, "line 5");
}

TEST(UrdfLimits, OnlyUtf8Encodings) {
  auto f = load_failure("<?xml version=\"1.0\" encoding=\"ISO-8859-1\"?>\n" + robot(""));
  EXPECT_EQ(f.field, "line 1");
  EXPECT_TRUE(has(f.expected, "UTF-8")) << f.what;
  EXPECT_TRUE(has(f.what, "ISO-8859-1")) << f.what;
  // A declared UTF-8 and predefined entities and character references are fine.
  const auto r = robot_description_from_string(
      "<?xml version=\"1.0\" encoding=\"utf-8\"?>\n<robot name=\"a&amp;b&#x43;\">" + kBase +
          "</robot>",
      "ok.urdf");
  EXPECT_EQ(r.name, "a&bC");
}

TEST(UrdfLimits, EmptyFile) {
  for (const std::string text : {"", "  \n\t\n"}) {
    const auto f = load_failure(text);
    EXPECT_EQ(f.source, "bad.urdf");
    EXPECT_EQ(f.expected, "a <robot> root element");
  }
}

// ---------------------------------------------------------------- size, depth, elements

std::string nested(int levels) {
  std::string open, close;
  for (int i = 0; i < levels; ++i) {
    open += "<a>\n";
    close += "</a>\n";
  }
  return open + close;
}

TEST(UrdfLimits, FiftyThousandNestedElementsAreRefusedAtLevel33) {
  // robot is level 1 on line 1, the base link line 2, <gazebo> level 2 on line 3, and
  // the n-th <a> level n + 2 on line n + 3: level 33 is on line 34.
  const auto f = load_failure(robot("<gazebo>\n" + nested(50000) + "</gazebo>"));
  EXPECT_EQ(f.source, "bad.urdf");
  EXPECT_EQ(f.field, "line 34");
  EXPECT_EQ(f.expected, "elements nested at most 32 levels deep");
  EXPECT_TRUE(has(f.what, "<a> at level 33")) << f.what;
}

TEST(UrdfLimits, NestingOfExactly32LevelsLoads) {
  // <robot> 1, <gazebo> 2, 30 levels of <a>: 32. Neither ferret nor urdfdom reads them.
  const auto r =
      robot_description_from_string(robot("<gazebo>\n" + nested(30) + "</gazebo>"), "ok.urdf");
  EXPECT_EQ(r.base_link, "base_link");
  const auto f = load_failure(robot("<gazebo>\n" + nested(31) + "</gazebo>"));
  EXPECT_EQ(f.field, "line 34");
}

TEST(UrdfLimits, ElementCountIsBounded) {
  // <robot>, the base link's 4 elements, <gazebo>: 6, so 99994 <e/> make 100000.
  auto body = [](int n) {
    std::string s = "<gazebo>\n";
    for (int i = 0; i < n; ++i) s += "<e/>\n";
    return s + "</gazebo>";
  };
  const auto r = robot_description_from_string(robot(body(99994)), "ok.urdf");
  EXPECT_EQ(r.collision_shapes.size(), 1u);
  // One more: the whole file is at fault.
  const auto f = load_failure(robot(body(99995)));
  EXPECT_EQ(f.source, "bad.urdf");
  EXPECT_EQ(f.field, "(document)");
  EXPECT_EQ(f.expected, "a URDF of at most 100000 elements");
}

TEST(UrdfLimits, FileSizeIsBoundedBeforeReadingItWhole) {
  const std::string head = robot("");
  constexpr std::size_t kLimit = 16u << 20;
  // Padded with comments of 1 MiB (libxml2 takes at most 10^7 bytes in one) to
  // exactly 16 MiB: loads.
  std::string exact = head;
  while (exact.size() < kLimit) {
    const std::size_t n = std::min<std::size_t>(1u << 20, kLimit - exact.size() - 7);
    exact += "<!--";
    exact.append(n, 'x');
    exact += "-->";
  }
  ASSERT_EQ(exact.size(), kLimit);
  EXPECT_EQ(robot_description_from_string(exact, "ok.urdf").base_link, "base_link");
  exact.insert(head.size() + 4, "y");  // one byte more
  auto f = load_failure(exact, "big.urdf");
  EXPECT_EQ(f.source, "big.urdf");
  EXPECT_EQ(f.field, "");
  EXPECT_EQ(f.expected, "a URDF of at most 16 MiB (16777216 bytes)");

  const auto path =
      std::filesystem::temp_directory_path() / (numbered("ferret_big_", ::getpid()) + ".urdf");
  std::ofstream(path, std::ios::binary) << exact;
  try {
    (void)load_robot_description(path);
    ADD_FAILURE() << "no InputError";
  } catch (const InputError& e) {
    EXPECT_EQ(e.source(), path.string());
    EXPECT_EQ(e.expected(), "a URDF of at most 16 MiB (16777216 bytes)");
  }
  std::filesystem::remove(path);
}

TEST(UrdfLimits, OneCommentOfMoreThanTenMillionBytes) {
  const std::string huge = "<!--" + std::string(10'000'001, 'x') + "-->";
  const auto f = load_failure(robot(huge));
  EXPECT_EQ(f.source, "bad.urdf");
  EXPECT_EQ(f.expected, "text, comments and attribute values of at most 10000000 bytes each");
}

// ---------------------------------------------------------------- links and joints

/// A chain base_link -> l1 -> ... -> l<n-1> of n links, each joint 0.01 m along x, one
/// link and one joint a line from line 3.
std::string chain(int links) {
  std::string body;
  for (int i = 1; i < links; ++i) {
    const std::string parent = i == 1 ? "base_link" : numbered("l", i - 1);
    const std::string link = numbered("l", i);
    const std::string joint = numbered("j", i);
    body += "<link name=\"" + link + "\"/>\n<joint name=\"" + joint +
            "\" type=\"fixed\"><origin xyz=\"0.01 0 0\"/><parent link=\"" + parent +
            "\"/><child link=\"" + link + "\"/></joint>\n";
  }
  return robot(body);
}

TEST(UrdfLimits, AThousandLinkChainLoadsAndIsPlacedLinkByLink) {
  const auto r = robot_description_from_string(chain(1000), "ok.urdf");
  ASSERT_EQ(r.frames.size(), 1000u);
  // 999 joints of 0.01 m each.
  EXPECT_NEAR(r.frames.at("l999").translation().x(), 9.99, 1e-9);
  EXPECT_NEAR(r.frames.at("l500").translation().x(), 5.00, 1e-9);
  EXPECT_NEAR(r.frames.at("l999").translation().y(), 0.0, 1e-12);
}

TEST(UrdfLimits, MoreThanAThousandLinksAreRefused) {
  // Link l1000 is the 1001st link, on line 3 + 2 * 999.
  const auto f = load_failure(chain(1001));
  EXPECT_EQ(f.source, "bad.urdf:2001");
  EXPECT_EQ(f.field, "link[l1000]");
  EXPECT_EQ(f.expected, "a robot of at most 1000 links");
}

TEST(UrdfLimits, MoreThanAThousandJointsAreRefused) {
  std::string body;
  for (int i = 1; i <= 1001; ++i) {
    const std::string name = numbered("j", i);
    body += "<joint name=\"" + name +
            "\" type=\"fixed\"><parent link=\"base_link\"/><child link=\"base_link\"/></joint>\n";
  }
  const auto f = load_failure(robot(body));
  EXPECT_EQ(f.source, "bad.urdf:1003");
  EXPECT_EQ(f.field, "joint[j1001]");
  EXPECT_EQ(f.expected, "a robot of at most 1000 joints");
}

TEST(UrdfLimits, AFiftyThousandLinkChainIsRefusedWithoutRecursion) {
  // 50000 links and 49999 joints of 3 elements: the element limit comes first.
  const auto f = load_failure(chain(50000));
  EXPECT_EQ(f.source, "bad.urdf");
  EXPECT_EQ(f.expected, "a URDF of at most 100000 elements");
}

TEST(UrdfLimits, MoreThanAThousandSensorsAreRefused) {
  // urdfdom <sensor>s and Gazebo ones count together: 600 + 401, one a line from line 3.
  auto sensors = [](int urdf, int gazebo) {
    std::string body;
    for (int i = 0; i < urdf; ++i) {
      const std::string name = numbered("u", i);
      body += "<sensor name=\"" + name +
              "\" parent_link_name=\"base_link\"><camera><image "
              "width=\"4\" height=\"3\" hfov=\"1\" near=\"0\" far=\"1\"/></camera></sensor>\n";
    }
    body += "<gazebo reference=\"base_link\">\n";
    for (int i = 0; i < gazebo; ++i) {
      const std::string name = numbered("g", i);
      body += "<sensor type=\"imu\" name=\"" + name + "\"/>\n";
    }
    return robot(body + "</gazebo>");
  };
  const auto r = robot_description_from_string(sensors(600, 400), "ok.urdf");
  EXPECT_EQ(r.cameras.size(), 600u);
  EXPECT_EQ(r.frames.size(), 1001u);  // base_link and every sensor
  const auto f = load_failure(sensors(600, 401));
  // g400 is the 1001st: line 3 + 600 sensors + the <gazebo> line + 400.
  EXPECT_EQ(f.source, "bad.urdf:1004");
  EXPECT_EQ(f.field, "sensor[g400]");
  EXPECT_EQ(f.expected, "a robot of at most 1000 sensors");
}

std::string joint(const std::string& name, const std::string& parent, const std::string& child,
                  const std::string& type = "fixed", const std::string& inner = "") {
  return "<joint name=\"" + name + "\" type=\"" + type + "\">" + inner + "<parent link=\"" +
         parent + "\"/><child link=\"" + child + "\"/></joint>";
}

TEST(UrdfLimits, JointGraphsThatAreNoTree) {
  const std::string ab = "<link name=\"a\"/>\n<link name=\"b\"/>\n";  // lines 3, 4
  // a -> b -> a beside the root: every link of the cycle has a parent.
  auto f = load_failure(robot(ab + joint("j1", "a", "b") + "\n" + joint("j2", "b", "a")));
  EXPECT_EQ(f.source, "bad.urdf:6");
  EXPECT_EQ(f.field, "joint[j2]");
  EXPECT_EQ(f.expected, "a kinematic tree (no cycle of joints)");
  EXPECT_TRUE(has(f.what, "the cycle a -> b -> a")) << f.what;
  // Longer: base -> a -> b -> c -> a reaches a twice.
  f = load_failure(robot(ab + "<link name=\"c\"/>\n" + joint("j1", "base_link", "a") + "\n" +
                         joint("j2", "a", "b") + "\n" + joint("j3", "b", "c") + "\n" +
                         joint("j4", "c", "a")));
  EXPECT_EQ(f.source, "bad.urdf:9");
  EXPECT_EQ(f.field, "joint[j4]/child@link");
  EXPECT_TRUE(has(f.expected,
                  "the child of one joint only (it is the child of joint 'j1' at "
                  "bad.urdf:6)"))
      << f.what;
  // A link its own parent.
  f = load_failure(robot(joint("j", "base_link", "base_link")));
  EXPECT_EQ(f.field, "joint[j]/child@link");
  EXPECT_TRUE(has(f.expected, "a joint cycle")) << f.what;
  // Two roots.
  f = load_failure(robot("<link name=\"orphan\"/>"));
  EXPECT_EQ(f.source, "bad.urdf:3");
  EXPECT_EQ(f.field, "link[orphan]");
  EXPECT_EQ(f.expected,
            "one root link: every other link the child of a joint (the root is 'base_link' at "
            "bad.urdf:2)");
  // Two joints of one name.
  f = load_failure(robot(ab + joint("j", "base_link", "a") + "\n" + joint("j", "base_link", "b")));
  EXPECT_EQ(f.source, "bad.urdf:6");
  EXPECT_EQ(f.field, "joint[j]");
  EXPECT_EQ(f.expected, "a unique joint name (first at bad.urdf:5)");
}

TEST(UrdfLimits, JointsUrdfdomWouldRejectOnItsConsole) {
  const std::string a = "<link name=\"a\"/>\n";
  auto f = load_failure(robot(a + joint("j", "base_link", "a", "hinge")));
  EXPECT_EQ(f.field, "joint[j]@type");
  EXPECT_TRUE(has(f.expected, "one of revolute, continuous")) << f.what;
  f = load_failure(robot(a + joint("j", "base_link", "a", "revolute")));
  EXPECT_EQ(f.source, "bad.urdf:4");
  EXPECT_EQ(f.field, "joint[j]/limit");
  f = load_failure(robot(a + joint("j", "base_link", "a", "revolute", "<limit effort=\"1\"/>")));
  EXPECT_EQ(f.field, "joint[j]/limit@velocity");
  EXPECT_EQ(f.expected, "a number >= 0 (rad/s or m/s)");
  f = load_failure(
      robot(a + joint("j", "base_link", "a", "revolute",
                      "<limit lower=\"1\" upper=\"-1\" effort=\"1\" velocity=\"1\"/>")));
  EXPECT_EQ(f.field, "joint[j]/limit@upper");
  EXPECT_EQ(f.expected, "a number >= lower (1)");
}

TEST(UrdfLimits, RobotNameVersionAndMaterialsUrdfdomWouldRejectOnItsConsole) {
  auto f = load_failure("<robot>\n" + kBase + "\n</robot>");
  EXPECT_EQ(f.source, "bad.urdf:1");
  EXPECT_EQ(f.field, "robot@name");
  for (const std::string version : {"nan", "2.0", "1.0.1", "", "1.", "-1.0"}) {
    SCOPED_TRACE(version);
    f = load_failure("<robot name=\"r\" version=\"" + version + "\">\n" + kBase + "\n</robot>");
    EXPECT_EQ(f.field, "robot@version");
    EXPECT_EQ(f.expected, "version 1.0 (the only one urdfdom reads)");
  }
  EXPECT_EQ(robot_description_from_string("<robot name=\"r\" version=\"1.0\">" + kBase + "</robot>",
                                          "ok.urdf")
                .name,
            "r");
  f = load_failure(robot("<material name=\"m\"/>\n<material name=\"m\"/>"));
  EXPECT_EQ(f.source, "bad.urdf:4");
  EXPECT_EQ(f.field, "material[m]");
  EXPECT_EQ(f.expected, "a unique material name (first at bad.urdf:3)");
}

// ---------------------------------------------------------------- numbers

/// `{}` in a template is replaced by the bad value.
std::string fill(std::string pattern, const std::string& value) {
  const auto at = pattern.find("{}");
  EXPECT_NE(at, std::string::npos);
  return pattern.replace(at, 2, value);
}

struct NumberCase {
  std::string pattern;   ///< with {} for the value
  std::string field;     ///< the field the error names
  std::string expected;  ///< the exact expectation
};

TEST(UrdfLimits, NonFiniteNumbersAreRefusedInEveryAttribute) {
  const std::string ja = "<link name=\"a\"/>";  // then the joint, on line 3
  const std::string col = "<link name=\"s\"><collision>";
  const std::string geo = "<link name=\"s\"><collision><geometry>";
  const std::string end = "</geometry></collision></link>";
  const std::string js = "joint[j]";
  // Each pattern is the body of robot() on line 3 (an extra link "s" hangs from base_link
  // through a joint on line 4 where the pattern needs it).
  const std::string hang_s = "\n" + joint("js", "base_link", "s");
  const NumberCase cases[] = {
      {ja + joint("j", "base_link", "a", "fixed", "<origin xyz=\"0 {} 0\"/>"), js + "/origin@xyz",
       "3 numbers >= -1000 and <= 1000 (metres)"},
      {ja + joint("j", "base_link", "a", "fixed", "<origin rpy=\"{} 0 0\"/>"), js + "/origin@rpy",
       "3 finite numbers (radians)"},
      {col +
           "<origin xyz=\"{} 0 0\"/><geometry><sphere "
           "radius=\"1\"/></geometry></collision></link>" +
           hang_s,
       "link[s]/collision[0]/origin@xyz", "3 numbers >= -1000 and <= 1000 (metres)"},
      {"<link name=\"s\"><visual><origin rpy=\"0 0 {}\"/><geometry><sphere "
       "radius=\"1\"/></geometry></visual></link>" +
           hang_s,
       "link[s]/visual[0]/origin@rpy", "3 finite numbers (radians)"},
      {geo + "<box size=\"1 {} 1\"/>" + end + hang_s, "link[s]/collision[0]/geometry/box@size",
       "3 numbers > 0 and <= 1000 (metres)"},
      {geo + "<cylinder radius=\"{}\" length=\"1\"/>" + end + hang_s,
       "link[s]/collision[0]/geometry/cylinder@radius", "a number > 0 and <= 1000 (metres)"},
      {geo + "<cylinder radius=\"1\" length=\"{}\"/>" + end + hang_s,
       "link[s]/collision[0]/geometry/cylinder@length", "a number > 0 and <= 1000 (metres)"},
      {geo + "<sphere radius=\"{}\"/>" + end + hang_s,
       "link[s]/collision[0]/geometry/sphere@radius", "a number > 0 and <= 1000 (metres)"},
      {geo + "<mesh filename=\"m.stl\" scale=\"1 1 {}\"/>" + end + hang_s,
       "link[s]/collision[0]/geometry/mesh@scale", "3 non-zero numbers >= -1000 and <= 1000"},
      {ja + joint("j", "base_link", "a", "revolute",
                  "<limit lower=\"{}\" upper=\"1\" effort=\"1\" velocity=\"1\"/>"),
       js + "/limit@lower", "a finite number (radians or metres)"},
      {ja + joint("j", "base_link", "a", "revolute",
                  "<limit lower=\"0\" upper=\"{}\" effort=\"1\" velocity=\"1\"/>"),
       js + "/limit@upper", "a finite number (radians or metres)"},
      {ja + joint("j", "base_link", "a", "revolute", "<limit effort=\"{}\" velocity=\"1\"/>"),
       js + "/limit@effort", "a number >= 0 (N m or N)"},
      {ja + joint("j", "base_link", "a", "continuous", "<limit effort=\"1\" velocity=\"{}\"/>"),
       js + "/limit@velocity", "a number >= 0 (rad/s or m/s)"},
      {ja + joint("j", "base_link", "a", "continuous", "<axis xyz=\"0 0 {}\"/>"), js + "/axis@xyz",
       "3 finite numbers, not all 0"},
      {ja + joint("j", "base_link", "a", "continuous", "<dynamics damping=\"{}\"/>"),
       js + "/dynamics@damping", "a number >= 0"},
      {ja + joint("j", "base_link", "a", "continuous", "<mimic joint=\"x\" multiplier=\"{}\"/>"),
       js + "/mimic@multiplier", "a finite number"},
      {"<link name=\"s\"><inertial><mass value=\"{}\"/><inertia ixx=\"1\" ixy=\"0\" ixz=\"0\" "
       "iyy=\"1\" iyz=\"0\" izz=\"1\"/></inertial></link>" +
           hang_s,
       "link[s]/inertial/mass@value", "a number >= 0 (kg)"},
      {"<link name=\"s\"><inertial><mass value=\"1\"/><inertia ixx=\"{}\" ixy=\"0\" ixz=\"0\" "
       "iyy=\"1\" iyz=\"0\" izz=\"1\"/></inertial></link>" +
           hang_s,
       "link[s]/inertial/inertia@ixx", "a finite number (kg m^2)"},
      {"<material name=\"m\"><color rgba=\"1 {} 1 1\"/></material>", "material[m]/color@rgba",
       "4 numbers >= 0 and <= 1"},
  };
  for (const std::string bad : {"nan", "NaN", "inf", "-inf", "infinity", "1e400", "-1e400", "0x10",
                                "1,5", "", "1 2 3 4 5"}) {
    for (const auto& c : cases) {
      SCOPED_TRACE(c.field + " = '" + bad + "'");
      const auto f = load_failure(robot(fill(c.pattern, bad)));
      EXPECT_EQ(f.source, "bad.urdf:3") << f.what;
      EXPECT_EQ(f.field, c.field) << f.what;
      EXPECT_EQ(f.expected, c.expected) << f.what;
    }
  }
}

TEST(UrdfLimits, NumbersOutOfTheirRange) {
  const std::string ja = "<link name=\"a\"/>";  // then the joint, on line 3
  const std::string geo = "<link name=\"s\"><collision><geometry>";
  const std::string end = "</geometry></collision></link>\n" + joint("js", "base_link", "s");
  struct Case {
    std::string body, field;
  };
  const Case cases[] = {
      {ja + joint("j", "base_link", "a", "fixed", "<origin xyz=\"1000.5 0 0\"/>"),
       "joint[j]/origin@xyz"},
      {geo + "<box size=\"1 1 1001\"/>" + end, "link[s]/collision[0]/geometry/box@size"},
      {geo + "<box size=\"1 0 1\"/>" + end, "link[s]/collision[0]/geometry/box@size"},
      {geo + "<sphere radius=\"-1\"/>" + end, "link[s]/collision[0]/geometry/sphere@radius"},
      {geo + "<mesh filename=\"m.stl\" scale=\"1 0 1\"/>" + end,
       "link[s]/collision[0]/geometry/mesh@scale"},
      {ja + joint("j", "base_link", "a", "continuous", "<limit effort=\"1\" velocity=\"-1\"/>"),
       "joint[j]/limit@velocity"},
      {ja + joint("j", "base_link", "a", "continuous", "<limit effort=\"-0.1\" velocity=\"1\"/>"),
       "joint[j]/limit@effort"},
      {ja + joint("j", "base_link", "a", "continuous", "<axis xyz=\"0 0 0\"/>"),
       "joint[j]/axis@xyz"},
      {"<material name=\"m\"><color rgba=\"1 1 1 1.5\"/></material>", "material[m]/color@rgba"},
  };
  for (const auto& c : cases) {
    SCOPED_TRACE(c.field);
    const auto f = load_failure(robot(c.body));
    EXPECT_EQ(f.source, "bad.urdf:3") << f.what;
    EXPECT_EQ(f.field, c.field) << f.what;
  }
}

/// Sensor values (urdfdom <sensor> and Gazebo blocks).
TEST(UrdfLimits, SensorNumbers) {
  const std::string cam_link =
      "<link name=\"c\"/>\n" + joint("jc", "base_link", "c") + "\n";  // lines 3, 4; sensor 5
  auto urdf_camera = [&](const std::string& image, const std::string& rate = "30") {
    return cam_link + "<sensor name=\"cam\" parent_link_name=\"c\" update_rate=\"" + rate +
           "\"><camera><image " + image + "/></camera></sensor>";
  };
  const std::string good_image = "width=\"64\" height=\"48\" hfov=\"1\" near=\"0.1\" far=\"4\"";
  auto gazebo = [&](const std::string& inner) {
    return cam_link + "<gazebo reference=\"c\"><sensor type=\"ray\" name=\"ir\">" + inner +
           "</sensor></gazebo>";
  };
  const std::string scan =
      "<ray><scan><horizontal><samples>3</samples><min_angle>-0.1</min_angle><max_angle>0.1</"
      "max_angle></horizontal></scan><range><min>0.1</min><max>{}</max></range></ray>";
  struct Case {
    std::string body, field, expected_part;
  };
  const Case cases[] = {
      {urdf_camera("width=\"64\" height=\"48\" hfov=\"nan\" near=\"0.1\" far=\"4\""),
       "sensor[cam]/camera/image@hfov", "a finite number"},
      {urdf_camera("width=\"64\" height=\"48\" hfov=\"3.2\" near=\"0.1\" far=\"4\""),
       "sensor[cam]/camera/image@hfov", "(0, pi) radians"},
      {urdf_camera("width=\"100001\" height=\"48\" hfov=\"1\" near=\"0.1\" far=\"4\""),
       "sensor[cam]/camera/image@width", "an integer in [1, 100000]"},
      {urdf_camera("width=\"64\" height=\"inf\" hfov=\"1\" near=\"0.1\" far=\"4\""),
       "sensor[cam]/camera/image@height", "a finite number"},
      {urdf_camera("width=\"64\" height=\"48\" hfov=\"1\" near=\"0.1\" far=\"1e400\""),
       "sensor[cam]/camera/image@far", "a finite number"},
      {urdf_camera(good_image, "-inf"), "sensor[cam]@update_rate", "a finite number"},
      {urdf_camera(good_image, "0"), "sensor[cam]@update_rate", "a rate > 0 (Hz)"},
      {gazebo(fill(scan, "inf")), "gazebo[c]/sensor[ir]/ray/range/max", "a finite number"},
      {gazebo(fill(scan, "0")), "gazebo[c]/sensor[ir]/ray/range/max", "> 0"},
      {gazebo("<pose>0 0 nan 0 0 0</pose>" + fill(scan, "2")), "gazebo[c]/sensor[ir]/pose",
       "six numbers"},
      {gazebo("<pose>0 0 2000 0 0 0</pose>" + fill(scan, "2")), "gazebo[c]/sensor[ir]/pose",
       "within 1000 metres"},
      {gazebo("<update_rate>nan</update_rate>" + fill(scan, "2")),
       "gazebo[c]/sensor[ir]/update_rate", "a finite number"},
  };
  for (const auto& c : cases) {
    SCOPED_TRACE(c.field + ": " + c.body);
    const auto f = load_failure(robot(c.body));
    EXPECT_EQ(f.source, "bad.urdf:5") << f.what;
    EXPECT_EQ(f.field, c.field) << f.what;
    EXPECT_TRUE(has(f.expected, c.expected_part)) << f.what;
  }
}

TEST(UrdfLimits, NamesFromTheFileAreQuotedPrintably) {
  // A link name with a newline and a tab (character references) and a control byte.
  // A second root link whose name holds a newline and a tab (character references).
  const auto f = load_failure(robot("<link name=\"x&#10;y&#9;z\"/>"));
  EXPECT_TRUE(one_printable_line(f.what)) << f.what;
  EXPECT_TRUE(has(f.what, "link[x y z]")) << f.what;
}

}  // namespace
}  // namespace ferret
