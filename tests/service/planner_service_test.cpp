// The planner service over real HTTP on a loopback port: every route's happy path,
// its error paths, auth, overload, a map replaced while a plan runs on it, and a
// drain while busy. Plans are checked against collision ground truth (the library's
// validator, FCL on the world's OctoMap), not against themselves.

#include "ferret/service/planner_service.hpp"

#include <arpa/inet.h>
#include <gtest/gtest.h>
#include <netinet/in.h>
#include <sys/socket.h>
#include <unistd.h>

#include <chrono>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <future>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include "ferret/mapping/world_octree.hpp"
#include "ferret/mapping/world_spec.hpp"
#include "ferret/planning/plan_file.hpp"
#include "ferret/planning/plan_validation.hpp"
#include "ferret/planning/planning_world.hpp"
#include "support/cli_runner.hpp"

// clang-format off: httplib after every header that includes Eigen
#include <httplib.h>  // after Eigen (see service/src/planner_service_impl.hpp)
// clang-format on

namespace ferret {
namespace {

using json = nlohmann::json;
using test::TempDir;
const std::string kDetour = FERRET_SOURCE_DIR "/examples/scenarios/tether_detour.yaml";
const std::string kDefault = FERRET_SOURCE_DIR "/examples/worlds/default.yaml";

std::string slurp(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

// A service on a free loopback port, and a client for it.
struct Served {
  explicit Served(PlannerServiceOptions o = {})
      : service([&] {
          o.port = 0;
          return o;
        }()) {
    port = service.start();
  }
  [[nodiscard]] httplib::Client client(double read_timeout_s = 30.0) const {
    httplib::Client c("127.0.0.1", port);
    c.set_read_timeout(std::chrono::milliseconds(static_cast<int>(read_timeout_s * 1000)));
    c.set_tcp_nodelay(true);
    return c;
  }
  PlannerService service;
  int port = 0;
};

json body_of(const httplib::Result& r) {
  EXPECT_TRUE(r) << "no response";
  if (!r) return {};
  return json::parse(r->body, nullptr, false);
}

std::string error_code(const httplib::Result& r) {
  const json b = body_of(r);
  return b.is_object() && b.contains("error") ? b["error"].value("code", "") : "";
}

std::string error_field(const httplib::Result& r) {
  const json b = body_of(r);
  return b.is_object() && b.contains("error") ? b["error"].value("field", "") : "";
}

void put_detour(httplib::Client& c, const std::string& name = "detour") {
  const auto r = c.Put("/v1/maps/" + name, slurp(kDetour), "application/yaml");
  ASSERT_TRUE(r);
  ASSERT_TRUE(r->status == 201 || r->status == 200) << r->body;
}

// The detour scenario's miniUGV request (tests/planning/ugv_path_test.cpp): round a
// block whose near side the tether already wraps.
json detour_request() {
  return json{{"map", "detour"},
              {"start", {10.0, 4.5, -1.57}},
              {"goal", {10.0, 1.5, -1.57}},
              {"driven", {{1.0, 6.5}, {10.0, 6.5}}},
              {"tether_budget_m", 12.5},
              {"deadline_s", 5.0},
              {"seed", 3}};
}

// Ground truth: the plan the service returned, checked by the offline validator (FCL
// against the world's OctoMap) in this process.
void expect_collision_free(const json& plan, const std::string& world) {
  const PlanningWorld w = load_planning_world(world);
  ValidateRequest v;
  const ValidationReport report =
      validate_plan(parse_plan(plan.dump(), "response"), w, v, "response");
  EXPECT_TRUE(report.valid()) << (report.violations.empty() ? "" : report.violations[0].describe());
}

TEST(PlannerService, HealthReadinessAndMetricsAnswer) {
  Served s;
  auto c = s.client();
  const auto h = c.Get("/healthz");
  ASSERT_TRUE(h);
  EXPECT_EQ(h->status, 200);
  EXPECT_EQ(body_of(h)["status"], "ok");
  const auto ready = c.Get("/readyz");
  ASSERT_TRUE(ready);
  EXPECT_EQ(ready->status, 200);
  EXPECT_EQ(body_of(ready)["maps"], 0);
  (void)c.Get("/v1/maps/none");
  const auto m = c.Get("/metrics");
  ASSERT_TRUE(m);
  EXPECT_EQ(m->status, 200);
  EXPECT_NE(m->get_header_value("Content-Type").find("text/plain"), std::string::npos);
  // The 404 just asked for is counted under its route pattern, not its raw path.
  EXPECT_NE(m->body.find("ferret_requests_total{route=\"/v1/maps/{name}\",code=\"404\"} 1"),
            std::string::npos)
      << m->body;
  EXPECT_NE(
      m->body.find("ferret_request_duration_seconds_bucket{route=\"/healthz\",le=\"+Inf\"} 1"),
      std::string::npos);
  EXPECT_NE(m->body.find("ferret_maps_loaded 0"), std::string::npos);
  EXPECT_NE(m->body.find("process_resident_memory_bytes "), std::string::npos);
  EXPECT_EQ(m->body.find("/v1/maps/none"), std::string::npos);
}

TEST(PlannerService, MapsArePutListedDescribedReplacedAndDeleted) {
  Served s;
  auto c = s.client();
  const auto put = c.Put("/v1/maps/detour", slurp(kDetour), "application/yaml");
  ASSERT_TRUE(put);
  EXPECT_EQ(put->status, 201) << put->body;
  const json meta = body_of(put);
  EXPECT_EQ(meta["name"], "detour");
  EXPECT_EQ(meta["format"], "world_yaml");
  EXPECT_DOUBLE_EQ(meta["resolution_m"].get<double>(), 0.05);
  ASSERT_EQ(meta["hidden_spaces"].size(), 1u);
  EXPECT_EQ(meta["hidden_spaces"][0]["name"], "cellar");
  EXPECT_EQ(c.Put("/v1/maps/detour", slurp(kDetour), "application/yaml")->status, 200);  // replaced

  // An OctoMap .bt body of the same world.
  TempDir dir;
  save_octree(*build_world_octree(load_world(kDetour)), dir / "detour.bt");
  const auto bt = c.Put("/v1/maps/detour_bt", slurp(dir / "detour.bt"), "application/octet-stream");
  ASSERT_TRUE(bt);
  EXPECT_EQ(bt->status, 201) << bt->body;
  EXPECT_EQ(body_of(bt)["format"], "octomap_bt");
  EXPECT_TRUE(body_of(bt)["hidden_spaces"].empty());  // an OctoMap names none

  const json list = body_of(c.Get("/v1/maps"));
  ASSERT_EQ(list["maps"].size(), 2u);
  EXPECT_EQ(list["maps"][0]["name"], "detour");
  EXPECT_EQ(list["maps"][1]["name"], "detour_bt");
  EXPECT_EQ(body_of(c.Get("/v1/maps/detour_bt"))["nodes"], body_of(bt)["nodes"]);
  EXPECT_EQ(c.Delete("/v1/maps/detour_bt")->status, 204);
  EXPECT_EQ(c.Delete("/v1/maps/detour_bt")->status, 404);
  EXPECT_EQ(c.Get("/v1/maps/detour_bt")->status, 404);
  EXPECT_EQ(body_of(c.Get("/readyz"))["maps"], 1);
}

TEST(PlannerService, BadMapsAreRefusedNamingTheBodyAndKeepNothing) {
  PlannerServiceOptions o;
  o.max_maps = 2;
  o.max_body_bytes = 64 * 1024;
  Served s(o);
  auto c = s.client();
  // Not a map at all.
  auto r = c.Put("/v1/maps/junk", std::string("\x89PNG\r\n\x1a\n\xff\xfe", 10),
                 "application/octet-stream");
  EXPECT_EQ(r->status, 400);
  EXPECT_EQ(error_code(r), "INVALID_MAP");
  EXPECT_EQ(error_field(r), "body");
  // A world YAML with a bad field: the field is named under body.
  r = c.Put("/v1/maps/bad", "name: x\nresolution_m: -1\n", "application/yaml");
  EXPECT_EQ(r->status, 400) << r->body;
  EXPECT_EQ(error_code(r), "INVALID_MAP");
  EXPECT_EQ(error_field(r), "body.resolution_m") << r->body;
  // A truncated OctoMap file.
  TempDir dir;
  save_octree(*build_world_octree(load_world(kDetour)), dir / "d.bt");
  const std::string bt = slurp(dir / "d.bt");
  r = c.Put("/v1/maps/cut", bt.substr(0, bt.size() / 2), "application/octet-stream");
  EXPECT_EQ(r->status, 400);
  EXPECT_EQ(error_code(r), "INVALID_MAP");
  // A name that could be a path, and a body past the limit.
  EXPECT_EQ(c.Put("/v1/maps/..%2Fetc", slurp(kDetour), "application/yaml")->status,
            404);  // no such route
  r = c.Put("/v1/maps/a%20b", slurp(kDetour), "application/yaml");
  EXPECT_EQ(r->status, 400);
  EXPECT_EQ(error_field(r), "name");
  r = c.Put("/v1/maps/big", std::string(65 * 1024, '#'), "application/yaml");
  EXPECT_EQ(r->status, 413);
  EXPECT_EQ(error_code(r), "PAYLOAD_TOO_LARGE");
  EXPECT_EQ(body_of(c.Get("/v1/maps"))["maps"].size(), 0u);
  // The map limit.
  put_detour(c, "a");
  put_detour(c, "b");
  r = c.Put("/v1/maps/c", slurp(kDetour), "application/yaml");
  EXPECT_EQ(r->status, 507);
  EXPECT_EQ(error_code(r), "TOO_MANY_MAPS");
  EXPECT_EQ(c.Put("/v1/maps/a", slurp(kDetour), "application/yaml")->status,
            200);  // replacing is fine
}

// A multipart/form-data body as curl -F sends it: one part a (name, content).
std::string multipart(const std::vector<std::pair<std::string, std::string>>& parts) {
  std::string body;
  for (const auto& [name, content] : parts)
    body += "--ferret-test\r\nContent-Disposition: form-data; name=\"" + name + "\"; filename=\"" +
            name + "\"\r\nContent-Type: application/octet-stream\r\n\r\n" + content + "\r\n";
  return body + "--ferret-test--\r\n";
}
const char* kMultipart = "multipart/form-data; boundary=ferret-test";
const std::string kSparse = FERRET_SOURCE_DIR "/examples/maps/sparse.yaml";
const std::string kSparsePgm = FERRET_SOURCE_DIR "/examples/maps/sparse.pgm";

TEST(PlannerService, AMapServerMapIsUploadedAsItsYamlAndImageAndPlannedIn) {
  Served s;
  auto c = s.client();
  // The YAML's image key names a file the service must never open: the part is the image.
  std::string yaml = slurp(kSparse);
  yaml.replace(yaml.find("image: sparse.pgm"), 17, "image: /etc/shadow");
  auto r = c.Put("/v1/maps/sparse", multipart({{"yaml", yaml}, {"image", slurp(kSparsePgm)}}),
                 kMultipart);
  ASSERT_EQ(r->status, 201) << r->body;
  const json meta = body_of(r);
  EXPECT_EQ(meta["format"], "map_server");
  EXPECT_EQ(meta["map_2d"]["width"], 240);
  EXPECT_EQ(meta["map_2d"]["height"], 160);
  EXPECT_EQ(meta["map_2d"]["bounds_xy_m"], json({0.0, 0.0, 12.0, 8.0}));
  // Round the block at x 8.5..9.3 on y = 4; the entry comes with the request.
  json req{{"map", "sparse"},
           {"start", {1.0, 4.0, 0.0}},
           {"goal", {10.0, 4.0, 0.0}},
           {"entry", {0.2, 4.0}},
           {"deadline_s", 5.0}};
  r = c.Post("/v1/plan/ugv", req.dump(), "application/json");
  ASSERT_EQ(r->status, 200) << r->body;
  const json plan = body_of(r)["plan"];
  expect_collision_free(plan, kSparse);  // FCL against the same map loaded from its files
  EXPECT_EQ(plan["bounds"]["max"][0], 12.0);
  req.erase("entry");
  r = c.Post("/v1/plan/ugv", req.dump(), "application/json");
  EXPECT_EQ(r->status, 400);
  EXPECT_EQ(error_field(r), "entry") << r->body;
}

TEST(PlannerService, ABrokenMapServerUploadNamesItsPart) {
  Served s;
  auto c = s.client();
  const std::string yaml = slurp(kSparse), pgm = slurp(kSparsePgm);
  const auto put = [&](const std::vector<std::pair<std::string, std::string>>& parts) {
    return c.Put("/v1/maps/m", multipart(parts), kMultipart);
  };
  auto r = put({{"yaml", yaml}});
  EXPECT_EQ(r->status, 400);
  EXPECT_EQ(error_code(r), "INVALID_MAP");
  EXPECT_EQ(error_field(r), "image") << r->body;
  r = put({{"yaml", yaml}, {"image", pgm}, {"extra", "x"}});
  EXPECT_EQ(r->status, 400);
  EXPECT_EQ(error_field(r), "extra") << r->body;
  r = put({{"yaml", "image: m.pgm\nresolution: -0.05\norigin: [0, 0, 0]\n"}, {"image", pgm}});
  EXPECT_EQ(r->status, 400);
  EXPECT_EQ(error_field(r), "yaml.resolution") << r->body;
  r = put({{"yaml", yaml}, {"image", pgm.substr(0, pgm.size() - 100)}});  // truncated raster
  EXPECT_EQ(r->status, 400);
  EXPECT_EQ(error_field(r), "image.pixels") << r->body;
  r = put({{"yaml", yaml}, {"image", "not an image"}});
  EXPECT_EQ(r->status, 400);
  EXPECT_EQ(error_field(r), "image") << r->body;
  // A key that is not UTF-8 (fuzz/regressions/service_request/map_yaml_key_not_utf8.bin):
  // the answer named it in bytes JSON cannot hold, and turned into a 500.
  r = put({{"yaml",
            std::string("image: m.pgm\nresolution: 0.1\norigin: [0, 0, 0]\nne\0Ngate: 0\n", 59)},
           {"image", pgm}});
  EXPECT_EQ(r->status, 400) << r->body;
  EXPECT_EQ(error_field(r).rfind("yaml.ne", 0), 0u) << r->body;
  EXPECT_TRUE(r->get_header_value("EXCEPTION_WHAT").empty());
  EXPECT_EQ(body_of(c.Get("/v1/maps"))["maps"].size(), 0u);
}

// A half-seen room as a client's occupancy grid (nav_msgs/OccupancyGrid values: -1
// unknown, 0..100 percent occupied): 4 x 2 m at 0.05 m, the left half free.
json half_seen_grid() {
  json occupancy = json::array();
  for (int j = 0; j < 40; ++j)
    for (int i = 0; i < 80; ++i) occupancy.push_back(i < 40 ? 0 : -1);
  return json{{"origin", {0.0, 0.0}},
              {"resolution_m", 0.05},
              {"width", 80},
              {"height", 40},
              {"occupancy", occupancy}};
}

TEST(PlannerService, ExploreNextGoalAnswersThePolicysChoiceOrWhyNot) {
  Served s;
  auto c = s.client();
  json req{{"grid", half_seen_grid()}, {"pose", {0.5, 1.0, 0.0}}, {"method", "rapid"}};
  auto r = c.Post("/v1/explore/next-goal", req.dump(), "application/json");
  ASSERT_EQ(r->status, 200) << r->body;
  json goal = body_of(r)["goal"];
  // At rest, facing the frontier column x = 1.975: straight ahead.
  EXPECT_NEAR(goal["x_m"].get<double>(), 1.975, 0.051);
  EXPECT_NEAR(goal["y_m"].get<double>(), 1.0, 0.051);
  ASSERT_GE(goal["path_m"].size(), 2u);
  EXPECT_NEAR(goal["path_m"][0][0].get<double>(), 0.5, 0.051);
  EXPECT_TRUE(body_of(r).contains("planning_time_s"));
  // Evidence near the frontier's top end draws CDOS there.
  json p = json::array();
  for (int j = 0; j < 40; ++j)
    for (int i = 0; i < 80; ++i)
      p.push_back(std::hypot(0.05 * i + 0.025 - 3.0, 0.05 * j + 0.025 - 1.8) < 0.3 ? 0.8 : 0.5);
  req["method"] = "cdos";
  req["object_probability"] = p;
  r = c.Post("/v1/explore/next-goal", req.dump(), "application/json");
  ASSERT_EQ(r->status, 200) << r->body;
  goal = body_of(r)["goal"];
  EXPECT_EQ(goal["reason"], "curiosity");
  // The IR cone (30 degrees by default) sees the frontier for |y - 1| <= 1.475 tan 15 =
  // 0.395 m: CDOS takes its top end, rapid took its middle.
  EXPECT_GT(goal["y_m"].get<double>(), 1.3);
  EXPECT_LT(goal["y_m"].get<double>(), 1.4);
  // Errors name the field.
  const auto field_of = [&](json bad) {
    const auto a = c.Post("/v1/explore/next-goal", bad.dump(), "application/json");
    EXPECT_EQ(a->status, 400) << a->body;
    return error_field(a);
  };
  json bad = req;
  bad["grid"]["occupancy"].erase(0);
  EXPECT_EQ(field_of(bad), "grid.occupancy");
  bad = req;
  bad["grid"]["occupancy"][3] = 101;
  EXPECT_EQ(field_of(bad), "grid.occupancy[3]");
  bad = req;
  bad["object_probability"][2] = "high";
  EXPECT_EQ(field_of(bad), "object_probability[2]");
  bad = req;
  bad["method"] = "oracle";
  EXPECT_EQ(field_of(bad), "method");
  bad = req;
  bad["pose"] = {9.0, 1.0, 0.0};
  EXPECT_EQ(field_of(bad), "pose");
  bad = req;
  bad["grid"]["width"] = 0;
  EXPECT_EQ(field_of(bad), "grid.width");
  bad = req;
  bad["grid"]["colour"] = "red";
  EXPECT_EQ(field_of(bad), "grid.colour");
  // Everything known: nothing to explore, said as such.
  json known = req;
  known.erase("object_probability");
  for (auto& v : known["grid"]["occupancy"]) v = 0;
  for (int j = 0; j < 40; ++j)
    for (int i = 0; i < 80; ++i)
      if (i == 0 || j == 0 || i == 79 || j == 39) known["grid"]["occupancy"][j * 80 + i] = 100;
  r = c.Post("/v1/explore/next-goal", known.dump(), "application/json");
  EXPECT_EQ(r->status, 422) << r->body;
  EXPECT_EQ(error_code(r), "NO_FRONTIER");
}

TEST(PlannerService, AUgvPlanIsTetherFeasibleAndCollisionFree) {
  Served s;
  auto c = s.client();
  put_detour(c);
  const auto r = c.Post("/v1/plan/ugv", detour_request().dump(), "application/json");
  ASSERT_TRUE(r);
  ASSERT_EQ(r->status, 200) << r->body;
  const json b = body_of(r);
  EXPECT_EQ(b["status"], "solved");
  EXPECT_GT(b["planning_time_s"].get<double>(), 0.0);
  const json& plan = b["plan"];
  ASSERT_GE(plan["states"].size(), 2u);
  EXPECT_DOUBLE_EQ(plan["states"].back()["x_m"].get<double>(), 10.0);
  EXPECT_DOUBLE_EQ(plan["states"].back()["y_m"].get<double>(), 1.5);
  for (const json& st : plan["states"]) EXPECT_LE(st["tether_length_m"].get<double>(), 12.5 + 1e-9);
  EXPECT_LE(b["tether"]["length_at_goal_m"].get<double>(), 12.5);
  expect_collision_free(plan, kDetour);
  // The same request and seed: the same plan (the miniUGV planner is seeded per request).
  const json again = body_of(c.Post("/v1/plan/ugv", detour_request().dump(), "application/json"));
  EXPECT_EQ(again["plan"]["states"], plan["states"]);

  // Back along the tether from the goal.
  json back = detour_request();
  back["start"] = {10.0, 4.5, -1.57};
  back["goal"] = {1.0, 6.5, 3.14};
  const auto ret = c.Post("/v1/plan/ugv/return", back.dump(), "application/json");
  ASSERT_EQ(ret->status, 200) << ret->body;
  expect_collision_free(body_of(ret)["plan"], kDetour);
}

TEST(PlannerService, UgvPlanFailuresCarryTheirCodes) {
  Served s;
  auto c = s.client();
  put_detour(c);
  const auto post = [&](const json& j) {
    return c.Post("/v1/plan/ugv", j.dump(), "application/json");
  };
  json j = detour_request();
  j["start"] = {6.0, 4.0, 0.0};  // inside the block
  auto r = post(j);
  EXPECT_EQ(r->status, 422);
  EXPECT_EQ(error_code(r), "START_OCCUPIED");
  EXPECT_TRUE(body_of(r).contains("planning_time_s"));
  j = detour_request();
  j["goal"] = {6.0, 4.0, 0.0};
  EXPECT_EQ(error_code(post(j)), "GOAL_OCCUPIED");
  j = detour_request();
  j["goal"] = {11.0, 0.5, -1.57};  // 11.64 m from the entry in a straight line
  j["tether_budget_m"] = 11.0;
  EXPECT_EQ(error_code(post(j)), "TETHER_TOO_SHORT");
  j["tether_budget_m"] = 11.66;  // the line fits, no way round the block does
  j["deadline_s"] = 0.3;
  r = post(j);
  EXPECT_EQ(r->status, 422);
  EXPECT_EQ(error_code(r), "TIMEOUT");
  EXPECT_LT(body_of(r)["planning_time_s"].get<double>(), 5.0);  // bounded by its deadline
  j = detour_request();
  j["map"] = "elsewhere";
  r = post(j);
  EXPECT_EQ(r->status, 404);
  EXPECT_EQ(error_code(r), "UNKNOWN_MAP");
}

TEST(PlannerService, MalformedRequestsGet400NamingTheField) {
  Served s;
  auto c = s.client();
  put_detour(c);
  const auto post = [&](const std::string& body) {
    return c.Post("/v1/plan/ugv", body, "application/json");
  };
  auto r = post("{\"map\": \"detour\", ");
  EXPECT_EQ(r->status, 400);
  EXPECT_EQ(error_field(r), "body");
  EXPECT_EQ(error_field(post("[1, 2]")), "body");
  json j = detour_request();
  j["start"] = "10,4.5,0";
  r = post(j.dump());
  EXPECT_EQ(r->status, 400);
  EXPECT_EQ(error_code(r), "INVALID_REQUEST");
  EXPECT_EQ(error_field(r), "start");
  j = detour_request();
  j["start"] = {10.0, 4.5};
  EXPECT_EQ(error_field(post(j.dump())), "start");
  j = detour_request();
  j["goal"] = {10.0, 1e300, 0.0};  // absurd
  EXPECT_EQ(error_field(post(j.dump())), "goal[1]");
  // JSON has no infinity: 1e999 is either a parse error or a number out of range.
  const std::string inf_field =
      error_field(post(R"({"map":"detour","start":[10,4.5,0],"goal":[10,1.5,1e999]})"));
  EXPECT_TRUE(inf_field == "body" || inf_field == "goal[2]") << inf_field;
  j = detour_request();
  j["deadline_s"] = 1e6;  // past the service's longest
  EXPECT_EQ(error_field(post(j.dump())), "deadline_s");
  j = detour_request();
  j["seed"] = -1;
  EXPECT_EQ(error_field(post(j.dump())), "seed");
  j = detour_request();
  j["tether_budget_m"] = 0;
  EXPECT_EQ(error_field(post(j.dump())), "tether_budget_m");
  j = detour_request();
  j["hidden_space"] = "attic";  // the map has only 'cellar'
  r = post(j.dump());
  EXPECT_EQ(r->status, 400);
  EXPECT_EQ(error_field(r), "hidden_space");
  EXPECT_NE(r->body.find("cellar"), std::string::npos) << r->body;
  j = detour_request();
  j["tether"] = 3;  // a typo for tether_budget_m is not ignored
  EXPECT_EQ(error_field(post(j.dump())), "tether");
  j = detour_request();
  j.erase("map");
  EXPECT_EQ(error_field(post(j.dump())), "map");
  // Routes that do not exist answer JSON too.
  r = c.Get("/v2/plan");
  EXPECT_EQ(r->status, 404);
  EXPECT_EQ(error_code(r), "NOT_FOUND");
}

TEST(PlannerService, UavPlansAndValidationAgreeWithGroundTruth) {
  Served s;
  auto c = s.client(60.0);
  const auto put = c.Put("/v1/maps/site", slurp(kDefault), "application/yaml");
  ASSERT_EQ(put->status, 201) << put->body;
  const json req{{"map", "site"},
                 {"start", {-20.0, -20.0, 3.0, 0.0}},
                 {"hidden_space", "house_void"},
                 {"deadline_s", 20.0}};
  const auto r = c.Post("/v1/plan/uav", req.dump(), "application/json");
  ASSERT_TRUE(r);
  ASSERT_EQ(r->status, 200) << r->body;
  const json plan = body_of(r)["plan"];
  expect_collision_free(plan, kDefault);
  // /v1/validate agrees, and finds the collision in a plan moved into the container.
  const auto ok =
      c.Post("/v1/validate", json{{"map", "site"}, {"plan", plan}, {"deadline_s", 30.0}}.dump(),
             "application/json");
  ASSERT_EQ(ok->status, 200) << ok->body;
  EXPECT_EQ(body_of(ok)["verdict"], "valid") << ok->body;
  json bad = plan;
  for (json& st : bad["states"]) {
    st["x_m"] = 5.0;  // the container at (5, 15), 2.59 m tall
    st["y_m"] = 15.0;
    st["z_m"] = 1.5;
  }
  const auto hit =
      c.Post("/v1/validate", json{{"map", "site"}, {"plan", bad}, {"deadline_s", 30.0}}.dump(),
             "application/json");
  ASSERT_EQ(hit->status, 200) << hit->body;
  EXPECT_EQ(body_of(hit)["verdict"], "invalid");
  EXPECT_FALSE(body_of(hit)["violations"].empty());
  // The plan's own collision map served both. Unknown space as occupied in a box is another.
  const auto built = [&c] {
    const std::string m = c.Get("/metrics")->body;
    const std::string key = "ferret_setups_built_total{kind=\"validation\"} ";
    const auto at = m.find(key);
    return at == std::string::npos ? -1 : std::stoi(m.substr(at + key.size()));
  };
  EXPECT_EQ(built(), 0);
  json boxed = bad;
  boxed["bounds"] = {{"min", {-10.0, 0.0, 0.5}}, {"max", {20.0, 25.0, 5.0}}};
  const auto hit2 = c.Post(
      "/v1/validate",
      json{{"map", "site"}, {"plan", boxed}, {"unknown", "occupied"}, {"deadline_s", 30.0}}.dump(),
      "application/json");
  ASSERT_EQ(hit2->status, 200) << hit2->body;
  EXPECT_EQ(body_of(hit2)["verdict"], "invalid");
  EXPECT_EQ(built(), 1);
  // A UAV goal inside the container.
  json inside = req;
  inside.erase("hidden_space");
  inside["goal"] = {5.0, 15.0, 1.5, 0.0};
  EXPECT_EQ(error_code(c.Post("/v1/plan/uav", inside.dump(), "application/json")), "GOAL_OCCUPIED");
  json both = req;
  both["goal"] = {5.0, 10.0, 2.0, 0.0};
  EXPECT_EQ(error_field(c.Post("/v1/plan/uav", both.dump(), "application/json")), "goal");
  json broken{{"map", "site"}, {"plan", {{"format", "ferret-plan"}, {"states", 3}}}};
  const auto v = c.Post("/v1/validate", broken.dump(), "application/json");
  EXPECT_EQ(v->status, 400);
  EXPECT_EQ(error_field(v).rfind("plan", 0), 0u) << v->body;
}

// A plan that asks for hundreds of thousands of collision checks is stopped by its
// deadline; one whose box would take hours to fill is refused at once.
TEST(PlannerService, AValidationPastItsDeadlineIsATimeoutAndAnAbsurdBoxIsRefused) {
  Served s;
  auto c = s.client();
  put_detour(c);
  // Back and forth along y = 6.5 (above the block) 400 times: 4 km, 200 000 poses.
  json states = json::array();
  for (int k = 0; k <= 400; ++k)
    states.push_back({{"t_s", 10.0 * k},
                      {"x_m", k % 2 ? 11.0 : 1.0},
                      {"y_m", 6.5},
                      {"z_m", 0.0},
                      {"yaw_rad", 0.0}});
  json plan{{"format", "ferret-plan"},
            {"version", 1},
            {"robot", "ugv"},
            {"frame", "world"},
            {"bounds", {{"min", {0.0, 0.0, 0.0}}, {"max", {12.0, 8.0, 0.2}}}},
            {"tether", {{"entry", {-0.1, 4.0}}, {"total_length_m", 13.0}, {"entry_offset_m", 1.0}}},
            {"states", states}};
  auto t0 = std::chrono::steady_clock::now();
  auto r =
      c.Post("/v1/validate", json{{"map", "detour"}, {"plan", plan}, {"deadline_s", 0.02}}.dump(),
             "application/json");
  double took_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  ASSERT_TRUE(r);
  EXPECT_EQ(r->status, 422) << r->body.substr(0, 300);
  EXPECT_EQ(error_code(r), "TIMEOUT") << r->body.substr(0, 300);
  EXPECT_LT(took_s, 2.0);  // a bound with room for a slow machine, not a benchmark
  // With time enough, the same plan is checked whole.
  r = c.Post("/v1/validate", json{{"map", "detour"}, {"plan", plan}, {"deadline_s", 30.0}}.dump(),
             "application/json");
  ASSERT_TRUE(r);
  EXPECT_EQ(r->status, 200) << r->body.substr(0, 300);
  // 3 x 3 km, 0.2 m high, unknown filled as occupied: billions of voxels. Refused.
  plan["bounds"] = {{"min", {-1500.0, -1500.0, 0.0}}, {"max", {1500.0, 1500.0, 0.2}}};
  t0 = std::chrono::steady_clock::now();
  r = c.Post("/v1/validate", json{{"map", "detour"}, {"plan", plan}, {"deadline_s", 30.0}}.dump(),
             "application/json");
  took_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  ASSERT_TRUE(r);
  EXPECT_EQ(r->status, 400) << r->body.substr(0, 300);
  EXPECT_EQ(error_field(r), "bounds") << r->body.substr(0, 300);
  EXPECT_LT(took_s, 2.0);
}

TEST(PlannerService, TheTokenGuardsEveryRouteButHealth) {
  PlannerServiceOptions o;
  o.token = "correct-horse-battery-staple";
  Served s(o);
  auto c = s.client();
  EXPECT_EQ(c.Get("/healthz")->status, 200);
  auto r = c.Get("/v1/maps");
  EXPECT_EQ(r->status, 401);
  EXPECT_EQ(error_code(r), "UNAUTHORIZED");
  EXPECT_FALSE(r->get_header_value("WWW-Authenticate").empty());
  EXPECT_EQ(c.Get("/metrics")->status, 401);
  c.set_bearer_token_auth("correct-horse-battery-stapl");
  EXPECT_EQ(c.Get("/v1/maps")->status, 401);
  c.set_bearer_token_auth("correct-horse-battery-staplee");
  EXPECT_EQ(c.Get("/v1/maps")->status, 401);
  c.set_bearer_token_auth("correct-horse-battery-staple");
  EXPECT_EQ(c.Get("/v1/maps")->status, 200);
  EXPECT_EQ(c.Get("/readyz")->status, 200);
}

// A request that holds a worker for about `seconds`: a goal no way round the block
// reaches, searched until its deadline.
json slow_request(double seconds) {
  json j = detour_request();
  j["goal"] = {11.0, 0.5, -1.57};
  j["tether_budget_m"] = 11.66;
  j["deadline_s"] = seconds;
  return j;
}

// Waits (up to 20 s) until the service reports `active` requests holding a worker and
// `queued` waiting: the tests below sequence on the service's state, not on sleeps.
void wait_for_load(const Served& s, int active, int queued) {
  auto c = s.client();
  const std::string a = "ferret_active_requests " + std::to_string(active) + "\n";
  const std::string q = "ferret_queue_depth " + std::to_string(queued) + "\n";
  for (int k = 0; k < 2000; ++k) {
    const auto m = c.Get("/metrics");
    if (m && m->body.find(a) != std::string::npos && m->body.find(q) != std::string::npos) return;
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  }
  FAIL() << "the service never had " << active << " active and " << queued << " queued";
}

TEST(PlannerService, PastTheQueueRequestsAreShedWith503) {
  PlannerServiceOptions o;
  o.workers = 1;
  o.queue = 1;
  Served s(o);
  auto c = s.client();
  put_detour(c);
  auto busy = std::async(std::launch::async, [&] {
    auto c1 = s.client();
    return c1.Post("/v1/plan/ugv", slow_request(1.5).dump(), "application/json")->status;
  });
  wait_for_load(s, 1, 0);
  auto queued = std::async(std::launch::async, [&] {
    auto c2 = s.client();
    return c2.Post("/v1/plan/ugv", detour_request().dump(), "application/json")->status;
  });
  wait_for_load(s, 1, 1);
  const auto shed = c.Post("/v1/plan/ugv", detour_request().dump(), "application/json");
  ASSERT_TRUE(shed);
  EXPECT_EQ(shed->status, 503);
  EXPECT_EQ(error_code(shed), "OVERLOADED");
  EXPECT_EQ(shed->get_header_value("Retry-After"), "1");
  EXPECT_EQ(busy.get(), 422);    // its own deadline
  EXPECT_EQ(queued.get(), 200);  // waited, then planned
  // A queued request whose deadline passes before a worker frees gives up.
  auto busy2 = std::async(std::launch::async, [&] {
    auto c1 = s.client();
    return c1.Post("/v1/plan/ugv", slow_request(1.0).dump(), "application/json")->status;
  });
  wait_for_load(s, 1, 0);
  json hurry = detour_request();
  hurry["deadline_s"] = 0.2;
  const auto late = c.Post("/v1/plan/ugv", hurry.dump(), "application/json");
  EXPECT_EQ(error_code(late), "TIMEOUT");
  EXPECT_EQ(busy2.get(), 422);
}

TEST(PlannerService, AClientThatHangsUpCancelsItsSearch) {
  PlannerServiceOptions o;
  o.max_deadline_s = 60.0;
  Served s(o);
  auto c = s.client();
  put_detour(c);
  // A raw connection: send a search that would run 60 s, then hang up.
  const int fd = ::socket(AF_INET, SOCK_STREAM, 0);
  ASSERT_GE(fd, 0);
  sockaddr_in addr{};
  addr.sin_family = AF_INET;
  addr.sin_port = htons(static_cast<std::uint16_t>(s.port));
  addr.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
  ASSERT_EQ(::connect(fd, reinterpret_cast<sockaddr*>(&addr), sizeof addr), 0);
  const std::string body = slow_request(60.0).dump();
  const std::string request =
      "POST /v1/plan/ugv HTTP/1.1\r\nHost: x\r\nContent-Type: application/json\r\n"
      "Content-Length: " +
      std::to_string(body.size()) + "\r\n\r\n" + body;
  ASSERT_EQ(::send(fd, request.data(), request.size(), 0), static_cast<ssize_t>(request.size()));
  wait_for_load(s, 1, 0);
  ::close(fd);
  // The search notices and stops: counted as cancelled, its worker free again.
  wait_for_load(s, 0, 0);
  const auto m = c.Get("/metrics");
  EXPECT_NE(m->body.find("ferret_plans_total{result=\"cancelled\"} 1"), std::string::npos)
      << m->body;
}

TEST(PlannerService, AMapReplacedOrDeletedWhilePlansRunOnItIsSafe) {
  PlannerServiceOptions o;
  o.workers = 2;
  Served s(o);
  auto c = s.client();
  put_detour(c);
  auto running = std::async(std::launch::async, [&] {
    auto c1 = s.client();
    return error_code(c1.Post("/v1/plan/ugv", slow_request(1.0).dump(), "application/json"));
  });
  wait_for_load(s, 1, 0);
  // Replace the map under the running plan, then delete it.
  const auto put = c.Put("/v1/maps/detour", slurp(kDetour), "application/yaml");
  EXPECT_EQ(put->status, 200);
  EXPECT_EQ(c.Delete("/v1/maps/detour")->status, 204);
  EXPECT_EQ(running.get(), "TIMEOUT");  // finished on its snapshot
  EXPECT_EQ(error_code(c.Post("/v1/plan/ugv", detour_request().dump(), "application/json")),
            "UNKNOWN_MAP");
  put_detour(c);
  EXPECT_EQ(c.Post("/v1/plan/ugv", detour_request().dump(), "application/json")->status, 200);
}

TEST(PlannerService, ADrainFinishesWorkInFlightAndTurnsNewWorkAway) {
  auto s = std::make_unique<Served>();
  auto c = s->client();
  put_detour(c);
  auto running = std::async(std::launch::async, [&] {
    auto c1 = s->client();
    const auto r = c1.Post("/v1/plan/ugv", slow_request(1.5).dump(), "application/json");
    return r ? r->status : -1;
  });
  wait_for_load(*s, 1, 0);
  auto drained = std::async(std::launch::async, [&] { s->service.drain(10.0); });
  while (!s->service.draining()) std::this_thread::yield();
  auto late = s->client();
  const auto r = late.Post("/v1/plan/ugv", detour_request().dump(), "application/json");
  ASSERT_TRUE(r);  // the listener stays open while work is in flight
  EXPECT_EQ(r->status, 503);
  EXPECT_EQ(error_code(r), "DRAINING");
  EXPECT_EQ(late.Get("/readyz")->status, 503);
  EXPECT_EQ(running.get(), 422);  // answered, by its deadline
  drained.get();
  EXPECT_FALSE(s->client().Get("/healthz"));  // stopped
}

}  // namespace
}  // namespace ferret
