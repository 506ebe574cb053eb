#include "ferret/core/yaml_config.hpp"

#include <gtest/gtest.h>

namespace ferret::yaml {
namespace {

MapReader reader(const std::string& text) {
  return MapReader(load_string(text, "mission.yaml"), "mission.yaml");
}

TEST(YamlConfig, ReadsTypedFieldsAndDefaults) {
  const auto r = reader("a: 1.5\nb: 3\nname: x\nnested: {c: true}\nlist: [1, 2, 3]\n");
  EXPECT_DOUBLE_EQ(r.get<double>("a"), 1.5);
  EXPECT_EQ(r.get<int>("b"), 3);
  EXPECT_EQ(r.get<std::string>("name"), "x");
  EXPECT_TRUE(r.child("nested").get<bool>("c"));
  EXPECT_EQ(r.get_list<int>("list", 3), (std::vector<int>{1, 2, 3}));
  EXPECT_DOUBLE_EQ(r.get_or<double>("missing", 7.0), 7.0);
}

TEST(YamlConfig, WrongTypeNamesFileFieldAndExpectation) {
  const auto r = reader("sensors: {camera_fov_deg: wide}\n");
  try {
    (void)r.child("sensors").get<double>("camera_fov_deg");
    FAIL() << "expected InputError";
  } catch (const InputError& e) {
    EXPECT_EQ(e.source(), "mission.yaml");
    EXPECT_EQ(e.field(), "sensors.camera_fov_deg");
    EXPECT_STREQ(e.what(),
                 "mission.yaml: sensors.camera_fov_deg: expected a finite number (got 'wide')");
  }
}

TEST(YamlConfig, MissingRequiredFieldIsAnError) {
  const auto r = reader("a: 1\n");
  EXPECT_THROW((void)r.get<double>("b"), InputError);
  EXPECT_THROW((void)r.child("b"), InputError);
}

TEST(YamlConfig, RangeChecks) {
  const auto r = reader("fov: 200\nrange: -1\nok: 0.5\n");
  EXPECT_THROW((void)r.get_in_range("fov", 0, 180), InputError);
  EXPECT_THROW((void)r.get_in_range("range", 0, 10), InputError);
  EXPECT_DOUBLE_EQ(r.get_in_range("ok", 0, 1), 0.5);
}

TEST(YamlConfig, ListOfWrongLengthIsAnError) {
  const auto r = reader("start: [1, 2]\n");
  try {
    (void)r.get_list<double>("start", 3);
    FAIL();
  } catch (const InputError& e) {
    EXPECT_EQ(e.field(), "start");
    EXPECT_NE(std::string(e.what()).find("a list of 3 values"), std::string::npos);
  }
}

TEST(YamlConfig, UnknownKeyIsRejected) {
  const auto r = reader("lambda1: 0.1\nlamda2: 0.95\n");
  try {
    r.allow_only({"lambda1", "lambda2"});
    FAIL();
  } catch (const InputError& e) {
    EXPECT_EQ(e.field(), "lamda2");
  }
}

TEST(YamlConfig, RepeatedKeyIsRejected) {
  // yaml-cpp would keep the first value and silently drop the second.
  const auto r = reader("lambda1: 0.1\nlambda2: 0.9\nlambda1: 0.2\n");
  try {
    r.allow_only({"lambda1", "lambda2"});
    FAIL();
  } catch (const InputError& e) {
    EXPECT_EQ(e.field(), "lambda1");
    EXPECT_NE(std::string(e.what()).find("each key once"), std::string::npos);
  }
}

TEST(YamlConfig, KeyThatIsAListOrMappingIsAnInputError) {
  // `? [a]` makes a list the key; yaml-cpp's own conversion error escaped before
  // (fuzz/regressions/mission/list_as_top_level_key.yaml).
  const auto top = reader("lambda1: 0.1\n? [lambda2]\n: 0.9\n");
  try {
    top.allow_only({"lambda1", "lambda2"});
    FAIL();
  } catch (const InputError& e) {
    EXPECT_EQ(e.source(), "mission.yaml");
    EXPECT_EQ(e.field(), "(document)");
    EXPECT_NE(std::string(e.what()).find("a list of 1"), std::string::npos) << e.what();
  }
  const auto nested = reader("curiosity: {? {a: 1} : 2}\n").child("curiosity");
  try {
    nested.allow_only({"a", "b", "K"});
    FAIL();
  } catch (const InputError& e) {
    EXPECT_EQ(e.field(), "curiosity");
    EXPECT_NE(std::string(e.what()).find("a mapping"), std::string::npos) << e.what();
  }
}

TEST(YamlConfig, SyntaxErrorReportsLine) {
  try {
    (void)load_string("a: [1, 2\nb: 3\n", "bad.yaml");
    FAIL();
  } catch (const InputError& e) {
    EXPECT_EQ(e.source(), "bad.yaml");
    EXPECT_NE(e.field().find("line"), std::string::npos);
  }
}

TEST(YamlConfig, MissingFileIsAnError) {
  EXPECT_THROW((void)load_file("/nonexistent/mission.yaml"), InputError);
}

TEST(YamlConfig, DocumentThatIsNotAMappingIsAnError) {
  EXPECT_THROW(reader("- 1\n- 2\n"), InputError);
}

}  // namespace
}  // namespace ferret::yaml

namespace ferret {
namespace {
TEST(YamlConfig, TextThatIsNotUtf8IsRefusedWithItsLineAndColumn) {
  try {
    (void)yaml::load_string("a: 1\nb: x\xed\xa0\x80y\n", "w.yaml");
    FAIL() << "accepted a surrogate";
  } catch (const InputError& e) {
    EXPECT_EQ(e.field(), "line 2 column 5");
    EXPECT_STREQ(e.what(), "w.yaml: line 2 column 5: expected UTF-8 text (got the byte 0xed)");
  }
  EXPECT_THROW((void)yaml::load_string("\x80: 1\n", "w.yaml"), InputError);
  EXPECT_EQ(yaml::load_string("name: Zürich\n", "w.yaml")["name"].as<std::string>(), "Zürich");
}
}  // namespace
}  // namespace ferret
