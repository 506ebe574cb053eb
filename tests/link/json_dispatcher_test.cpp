#include "ferret/link/json_dispatcher.hpp"

#include <gtest/gtest.h>

#include <stdexcept>
#include <string>

#include "ferret/core/error.hpp"

namespace ferret::link {
namespace {

using nlohmann::json;

// A dispatcher with an echo, a refusing op, an op whose device fails, one that throws
// InputError, and one that answers with a blob.
JsonDispatcher make_dispatcher(int& calls) {
  JsonDispatcher d("the test protocol 7");
  d.add("echo", [&calls](const JsonRequest& r) -> JsonReply {
    ++calls;
    return json{{"x", request_number(r.fields, "x", -10, 10)}};
  });
  d.add("nothing", [&calls](const JsonRequest&) -> JsonReply {
    ++calls;
    return {};
  });
  d.add("flag", [](const JsonRequest& r) -> JsonReply {
    return json{{"was", request_bool(r.fields, "on")}};
  });
  d.add("broken", [](const JsonRequest&) -> JsonReply {
    throw std::runtime_error("the servo does not answer");
  });
  d.add("input", [](const JsonRequest&) -> JsonReply {
    throw InputError("req.json", "x", "a number", "got a string");
  });
  d.add("blob", [](const JsonRequest& r) -> JsonReply {
    std::vector<std::uint8_t> b = r.blob;
    b.push_back(42);
    return {json{{"n", b.size()}}, b};
  });
  return d;
}

json reply_of(const JsonDispatcher& d, const std::string& header,
              std::vector<std::uint8_t> blob = {}) {
  const StreamMessage m = d.handle({header, std::move(blob)});
  const json j = json::parse(m.header);  // every reply is JSON
  EXPECT_TRUE(j.is_object());
  EXPECT_TRUE(j.contains("ok") && j["ok"].is_boolean()) << m.header;
  return j;
}

std::string error_of(const JsonDispatcher& d, const std::string& header) {
  const json j = reply_of(d, header);
  EXPECT_FALSE(j.value("ok", true)) << header;
  EXPECT_TRUE(j.contains("op") && j["op"].is_string()) << header;
  return j.value("error", "");
}

TEST(JsonDispatcher, AnswersAKnownOpWithItsFieldsAndOk) {
  int calls = 0;
  const JsonDispatcher d = make_dispatcher(calls);
  EXPECT_EQ(d.handle({R"({"op": "echo", "x": 2.5})", {}}).header, R"({"ok":true,"x":2.5})");
  EXPECT_EQ(d.handle({R"({"op": "nothing"})", {}}).header, R"({"ok":true})");
  EXPECT_EQ(calls, 2);
  const StreamMessage m = d.handle({R"({"op": "blob"})", {1, 2}});
  EXPECT_EQ(m.header, R"({"n":3,"ok":true})");
  EXPECT_EQ(m.blob, (std::vector<std::uint8_t>{1, 2, 42}));
}

TEST(JsonDispatcher, ARequestThatIsNotAnObjectIsRefused) {
  int calls = 0;
  const JsonDispatcher d = make_dispatcher(calls);
  for (const std::string bad : {"", "not json", "[1, 2]", "\"echo\"", "42", "null", "{\"op\": "}) {
    EXPECT_EQ(error_of(d, bad), "the request is not a JSON object") << bad;
    EXPECT_EQ(reply_of(d, bad).at("op"), "") << bad;
  }
  EXPECT_EQ(calls, 0);
}

TEST(JsonDispatcher, AMissingOrNonStringOpIsRefused) {
  int calls = 0;
  const JsonDispatcher d = make_dispatcher(calls);
  for (const std::string bad : {R"({})", R"({"x": 1})", R"({"op": 1})", R"({"op": null})",
                                R"({"op": ["echo"]})", R"({"op": {"name": "echo"}})"})
    EXPECT_EQ(error_of(d, bad), "'op': expected a string") << bad;
  EXPECT_EQ(calls, 0);
}

TEST(JsonDispatcher, AnUnknownOpIsNamedWithTheKnownOnes) {
  int calls = 0;
  const JsonDispatcher d = make_dispatcher(calls);
  const json j = reply_of(d, R"({"op": "fly"})");
  EXPECT_FALSE(j.at("ok").get<bool>());
  EXPECT_EQ(j.at("op"), "fly");
  EXPECT_EQ(j.at("error"),
            "'op': 'fly' is not an op of the test protocol 7 (known: blob, broken, echo, flag, "
            "input, nothing)");
  // Case matters: an op is its exact name.
  EXPECT_NE(error_of(d, R"({"op": "Echo"})").find("'Echo' is not an op"), std::string::npos);
  EXPECT_EQ(calls, 0);
}

TEST(JsonDispatcher, AHandlersErrorsBecomeRefusalsNotCrashes) {
  int calls = 0;
  const JsonDispatcher d = make_dispatcher(calls);
  EXPECT_EQ(error_of(d, R"({"op": "echo"})"), "'x': expected a number");
  EXPECT_EQ(error_of(d, R"({"op": "echo", "x": 11})"),
            "'x': expected a number in [-10.0, 10.0], got 11.0");
  EXPECT_EQ(error_of(d, R"({"op": "flag", "on": 1})"), "'on': expected a boolean");
  EXPECT_EQ(error_of(d, R"({"op": "broken"})"), "the servo does not answer");
  const std::string input = error_of(d, R"({"op": "input"})");
  EXPECT_NE(input.find("req.json"), std::string::npos) << input;
  EXPECT_NE(input.find("a number"), std::string::npos) << input;
  EXPECT_EQ(reply_of(d, R"({"op": "broken"})").at("op"), "broken");
}

TEST(JsonDispatcher, AnOpAddedTwiceIsABug) {
  JsonDispatcher d("p");
  d.add("a", [](const JsonRequest&) -> JsonReply { return {}; });
  EXPECT_THROW(d.add("a", [](const JsonRequest&) -> JsonReply { return {}; }), std::logic_error);
  EXPECT_TRUE(d.contains("a"));
  EXPECT_FALSE(d.contains("b"));
  EXPECT_EQ(d.ops(), std::vector<std::string>{"a"});
}

TEST(JsonDispatcher, RepliesWithBytesThatAreNotUtf8StillDump) {
  JsonDispatcher d("p");
  d.add("bad", [](const JsonRequest&) -> JsonReply {
    return json{{"s", std::string("\xff\xfe")}};
  });
  d.add("bad_error", [](const JsonRequest&) -> JsonReply {
    throw std::runtime_error(std::string("device said \xff"));
  });
  EXPECT_TRUE(json::parse(d.handle({R"({"op": "bad"})", {}}).header).at("ok").get<bool>());
  EXPECT_FALSE(json::parse(d.handle({R"({"op": "bad_error"})", {}}).header).at("ok").get<bool>());
}

}  // namespace
}  // namespace ferret::link
