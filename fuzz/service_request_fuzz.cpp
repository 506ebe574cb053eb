// Planner service request bodies (docs/service.md) -> the real service on loopback.
// The first byte picks the route, the rest is the body: a JSON body for the planning
// routes and next-goal, a raw multipart/form-data body (boundary "b") for a map_server
// map's PUT. Beyond "no crash", the
// service's contract is checked: every answer is JSON, a status from the documented
// set, and every error names a code. Deadlines are kept to milliseconds so a body
// that happens to be a valid request plans briefly.
#include <chrono>
#include <cstdint>
#include <cstdlib>
#include <memory>
#include <nlohmann/json.hpp>
#include <string>

#include "ferret/service/planner_service.hpp"
#include "fuzz_support.hpp"

// clang-format off: httplib after every header that includes Eigen
#include <httplib.h>  // after Eigen (service/src/planner_service_impl.hpp says why)
// clang-format on

namespace {

// A 12 x 8 m hidden space with one block in it (examples/scenarios/tether_detour.yaml).
const char* kWorld = R"(name: fuzz_detour
resolution_m: 0.1
bounds_m: {min: [-1, -1, -0.2], max: [13, 9, 1.0]}
ground: {height_m: 0.0}
hidden_spaces:
  - name: cellar
    center_m: [6, 4]
    yaw_deg: 0
    interior_size_m: [12, 8, 0.4]
    wall_thickness_m: 0.1
    opening: {wall: -x, width_m: 0.15, height_m: 0.1}
    marker: {id: 5, size_m: 0.2, placement: wall}
boxes:
  - {name: block, center_m: [6, 4], size_m: [6, 3, 0.3]}
)";

struct Fixture {
  Fixture() {
    ferret::PlannerServiceOptions o;
    o.port = 0;
    o.default_deadline_s = 0.01;
    o.max_deadline_s = 0.02;
    o.max_body_bytes = 1 << 20;
    o.max_map_nodes = 200'000;  // an uploaded map stays small enough to build quickly
    service = std::make_unique<ferret::PlannerService>(o);
    service->put_map("detour", kWorld, "fuzz world");
    port = service->start();
    client = std::make_unique<httplib::Client>("127.0.0.1", port);
    client->set_keep_alive(true);
    // Loading a map has no deadline but its node budget; under ASan it may take seconds.
    client->set_read_timeout(std::chrono::seconds(60));
    client->set_tcp_nodelay(true);  // no 40 ms Nagle wait an input
  }
  std::unique_ptr<ferret::PlannerService> service;
  std::unique_ptr<httplib::Client> client;
  int port = 0;
};

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  static Fixture f;
  if (size == 0) return 0;
  static const char* routes[] = {"/v1/plan/ugv", "/v1/plan/ugv/return",   "/v1/plan/uav",
                                 "/v1/validate", "/v1/explore/next-goal", "/v1/maps/fz"};
  const std::size_t route = data[0] % 6;
  const std::string body = ferret::fuzz::as_string(data + 1, size - 1);
  const auto r = route == 5 ? f.client->Put(routes[route], body, "multipart/form-data; boundary=b")
                            : f.client->Post(routes[route], body, "application/json");
  if (!r) std::abort();  // the service must answer
  const int st = r->status;
  if (st != 200 && st != 201 && st != 400 && st != 404 && st != 413 && st != 422 && st != 503 &&
      st != 507)
    std::abort();
  const auto j = nlohmann::json::parse(r->body, nullptr, false);
  if (!j.is_object()) std::abort();
  if (st >= 300 &&
      !(j.contains("error") && j["error"].contains("code") && j["error"]["code"].is_string() &&
        !j["error"]["code"].get<std::string>().empty()))
    std::abort();
  return 0;
}
