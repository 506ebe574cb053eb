// docs/service.md's examples, executed verbatim against a service on loopback: each
// ```http request block is sent as written (a body "@FILE" is that file's contents;
// in a multipart body, each line "@FILE" is, and lines end in CRLF as on the wire)
// and the ```http block after it is the answer it must get: its status, and every
// field it shows (strings and booleans equal, numbers any number, an empty string or
// array any string or array).

#include <gtest/gtest.h>

#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>
#include <vector>

#include "ferret/service/planner_service.hpp"

// clang-format off: httplib after every header that includes Eigen
#include <httplib.h>  // after Eigen (see service/src/planner_service_impl.hpp)
// clang-format on

namespace ferret {
namespace {

using json = nlohmann::json;

std::string slurp(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

std::vector<std::string> http_blocks(const std::string& markdown) {
  std::vector<std::string> blocks;
  std::istringstream in(markdown);
  std::string line, block;
  bool inside = false;
  while (std::getline(in, line)) {
    if (!inside && line == "```http") {
      inside = true;
      block.clear();
    } else if (inside && line == "```") {
      inside = false;
      blocks.push_back(block);
    } else if (inside) {
      block += line + "\n";
    }
  }
  return blocks;
}

// Every field the documented answer shows is in the actual one (see the file's head).
void expect_shown(const json& shown, const json& got, const std::string& path) {
  if (shown.is_object()) {
    ASSERT_TRUE(got.is_object()) << path << ": " << got.dump();
    for (const auto& [key, value] : shown.items()) {
      ASSERT_TRUE(got.contains(key)) << path << "." << key << " missing in " << got.dump();
      expect_shown(value, got.at(key), path + "." + key);
    }
  } else if (shown.is_array()) {
    ASSERT_TRUE(got.is_array()) << path;
    ASSERT_GE(got.size(), shown.size()) << path;
    for (std::size_t k = 0; k < shown.size(); ++k)
      expect_shown(shown[k], got[k], path + "[" + std::to_string(k) + "]");
  } else if (shown.is_string()) {
    ASSERT_TRUE(got.is_string()) << path;
    if (!shown.get<std::string>().empty()) {
      EXPECT_EQ(got, shown) << path;
    }
  } else if (shown.is_number()) {
    EXPECT_TRUE(got.is_number()) << path;
  } else {
    EXPECT_EQ(got, shown) << path;
  }
}

TEST(PlannerServiceDocs, EveryExampleAnswersAsDocumented) {
  const std::string doc = slurp(FERRET_SOURCE_DIR "/docs/service.md");
  const auto blocks = http_blocks(doc);
  ASSERT_GE(blocks.size(), 10u) << "docs/service.md lost its examples";
  ASSERT_EQ(blocks.size() % 2, 0u) << "each request needs its answer";
  PlannerServiceOptions o;
  o.port = 0;
  PlannerService service(o);
  httplib::Client c("127.0.0.1", service.start());
  c.set_read_timeout(std::chrono::seconds(60));
  for (std::size_t k = 0; k < blocks.size(); k += 2) {
    std::istringstream req(blocks[k]);
    std::string method, path, line;
    req >> method >> path;
    std::getline(req, line);
    std::string content_type = "application/json";
    while (std::getline(req, line) && !line.empty())
      if (line.rfind("Content-Type: ", 0) == 0) content_type = line.substr(14);
    std::string body((std::istreambuf_iterator<char>(req)), std::istreambuf_iterator<char>());
    while (!body.empty() && body.back() == '\n') body.pop_back();
    if (content_type.rfind("multipart/", 0) == 0) {
      std::istringstream lines(body);
      std::string wire;
      while (std::getline(lines, line))
        wire += (!line.empty() && line[0] == '@'
                     ? slurp(std::string(FERRET_SOURCE_DIR "/") + line.substr(1))
                     : line) +
                "\r\n";
      body = wire;
    } else if (!body.empty() && body[0] == '@') {
      body = slurp(std::string(FERRET_SOURCE_DIR "/") + body.substr(1));
    }
    SCOPED_TRACE(method + " " + path);
    httplib::Result r = method == "GET"      ? c.Get(path)
                        : method == "DELETE" ? c.Delete(path)
                        : method == "PUT"    ? c.Put(path, body, content_type)
                                             : c.Post(path, body, content_type);
    ASSERT_TRUE(r) << "no answer";

    std::istringstream res(blocks[k + 1]);
    std::string version;
    int status = 0;
    res >> version >> status;
    std::getline(res, line);
    EXPECT_EQ(r->status, status) << r->body;
    std::string shown((std::istreambuf_iterator<char>(res)), std::istreambuf_iterator<char>());
    if (shown.find_first_not_of(" \n") == std::string::npos) continue;
    const json want = json::parse(shown, nullptr, false);
    ASSERT_FALSE(want.is_discarded()) << "the documented answer is not JSON: " << shown;
    const json got = json::parse(r->body, nullptr, false);
    ASSERT_FALSE(got.is_discarded()) << r->body;
    expect_shown(want, got, "answer");
  }
}

}  // namespace
}  // namespace ferret
