// The planner service's HTTP handlers: one route a request, its body read by
// request_parsing.cpp, its work done holding a worker, its answer or error as JSON;
// authentication, draining and the service's own error pages before and around them.

#include <arpa/inet.h>
#include <fmt/format.h>
#include <netinet/in.h>
#include <sys/socket.h>

#include <algorithm>
#include <cerrno>
#include <chrono>
#include <filesystem>
#include <iostream>
#include <new>

#include "ferret/core/error.hpp"
#include "ferret/urdf/robot_description.hpp"
#include "planner_service_impl.hpp"

namespace ferret {
namespace {

using internal::Admission;
using internal::ApiError;
using internal::bad_request;
using internal::Body;
using internal::cached_setup;
using internal::error_body;
using internal::from_input_error;
using internal::json;
using internal::MapEntry;
using internal::offer_setup;
using internal::read_next_goal_request;
using internal::read_plan;
using internal::read_uav_request;
using internal::read_ugv_request;
using internal::read_validate_request;
using internal::utc_now;
using internal::valid_map_name;
using Clock = internal::Clock;

// Planning outcomes (PlanFailure) as the service's codes, in the manner of nav2's
// planner server: each a reason a client can act on.
const char* failure_code(PlanFailure f) {
  switch (f) {
    case PlanFailure::kStartInvalid:
      return "START_OCCUPIED";
    case PlanFailure::kGoalInvalid:
      return "GOAL_OCCUPIED";
    case PlanFailure::kStartOutside:
      return "START_OUTSIDE_MAP";
    case PlanFailure::kGoalOutside:
      return "GOAL_OUTSIDE_MAP";
    case PlanFailure::kTetherTooShort:
      return "TETHER_TOO_SHORT";
    case PlanFailure::kTimeout:
      return "TIMEOUT";
    case PlanFailure::kCancelled:
      return "CANCELLED";
    case PlanFailure::kNoPath:
    case PlanFailure::kNone:
      break;
  }
  return "NO_VALID_PATH";
}

bool same_token(const std::string& a, const std::string& b) {
  // Constant time in the token's length: no early exit on the first wrong byte.
  unsigned char diff = a.size() == b.size() ? 0 : 1;
  for (std::size_t k = 0; k < a.size(); ++k) diff |= a[k] ^ (k < b.size() ? b[k] : 0);
  return diff == 0;
}

// The socket of the connection a request came on. cpp-httplib 0.11 does not hand it to
// a handler, so it is found by the peer's address and port among this process's
// sockets (they stay open while the handler runs, so the descriptor cannot be reused
// under it). -1 when not found: the search then ends by its deadline only.
int connection_fd(const std::string& remote_addr, int remote_port, int want_local_port) {
  std::error_code ec;
  for (const auto& entry : std::filesystem::directory_iterator("/proc/self/fd", ec)) {
    int fd = -1;
    try {
      fd = std::stoi(entry.path().filename().string());
    } catch (const std::exception&) {
      continue;
    }
    sockaddr_storage peer{}, local{};
    socklen_t peer_len = sizeof peer, local_len = sizeof local;
    if (::getpeername(fd, reinterpret_cast<sockaddr*>(&peer), &peer_len) != 0) continue;
    if (::getsockname(fd, reinterpret_cast<sockaddr*>(&local), &local_len) != 0) continue;
    char host[INET6_ADDRSTRLEN] = {};
    int peer_port = -1, local_port = -1;
    if (peer.ss_family == AF_INET) {
      const auto* a = reinterpret_cast<const sockaddr_in*>(&peer);
      ::inet_ntop(AF_INET, &a->sin_addr, host, sizeof host);
      peer_port = ntohs(a->sin_port);
      local_port = ntohs(reinterpret_cast<const sockaddr_in*>(&local)->sin_port);
    } else if (peer.ss_family == AF_INET6) {
      const auto* a = reinterpret_cast<const sockaddr_in6*>(&peer);
      ::inet_ntop(AF_INET6, &a->sin6_addr, host, sizeof host);
      peer_port = ntohs(a->sin6_port);
      local_port = ntohs(reinterpret_cast<const sockaddr_in6*>(&local)->sin6_port);
    } else {
      continue;
    }
    if (peer_port == remote_port && local_port == want_local_port && remote_addr == host) return fd;
  }
  return -1;
}

// Has the peer closed its end? A peek that reads 0 bytes is an orderly close; bytes
// waiting (a pipelined request) or nothing yet both mean the client is still there.
bool peer_closed(int fd) {
  char c = 0;
  const ssize_t n = ::recv(fd, &c, 1, MSG_PEEK | MSG_DONTWAIT);
  if (n == 0) return true;
  return n < 0 && errno != EAGAIN && errno != EWOULDBLOCK && errno != EINTR;
}

}  // namespace

void PlannerService::Impl::send(httplib::Response& res, int status, const json& body) {
  res.status = status;
  // A string that is not UTF-8 is a bug upstream; it must not turn the answer into a 500.
  res.set_content(body.dump(-1, ' ', false, json::error_handler_t::replace) + "\n",
                  "application/json");
}

// A deadline from the request (seconds from arrival), within the service's bounds.
Clock::time_point PlannerService::Impl::deadline_of(const Body& body,
                                                    Clock::time_point arrived) const {
  double d = options.default_deadline_s;
  if (body.has("deadline_s"))
    d = body.number("deadline_s", 1e-3, options.max_deadline_s,
                    fmt::format("seconds in [0.001, {:g}]", options.max_deadline_s));
  return arrived + std::chrono::duration_cast<Clock::duration>(std::chrono::duration<double>(d));
}

// Runs `work` holding a worker, or answers 503 / TIMEOUT without it.
template <typename Work>
void PlannerService::Impl::with_worker(httplib::Response& res, Clock::time_point deadline,
                                       Work work) {
  switch (admission.enter(deadline)) {
    case Admission::Result::kOverloaded:
      res.set_header("Retry-After", "1");
      throw ApiError{503, "OVERLOADED", "every worker is busy and the queue is full: retry later",
                     ""};
    case Admission::Result::kDeadline:
      throw ApiError{422, "TIMEOUT", "the deadline passed while the request waited for a worker",
                     "deadline_s"};
    case Admission::Result::kAdmitted:
      break;
  }
  struct Leave {
    Admission& a;
    ~Leave() { a.leave(); }
  } leave{admission};
  work();
}

double PlannerService::Impl::seconds_left(Clock::time_point deadline) {
  return std::chrono::duration<double>(deadline - Clock::now()).count();
}

// The search stops when the service shuts down or the client hangs up. Most plans
// end within milliseconds, so the client's socket is looked for only once a search
// has run 10 ms, and then peeked at every 10 ms at most (a search's checks stay cheap).
std::function<bool()> PlannerService::Impl::cancel_flag(const httplib::Request& req) {
  struct Watch {
    std::string remote_addr;
    int remote_port = -1, local_port = -1;
    int fd = -2;  // -2: not looked for yet; -1: not found
    Clock::time_point next{};
    bool gone = false;
  };
  auto watch = std::make_shared<Watch>();
  watch->remote_addr = req.remote_addr;
  watch->remote_port = req.remote_port;
  watch->local_port = req.local_port;
  watch->next = Clock::now() + std::chrono::milliseconds(10);
  return [this, watch] {
    if (cancel_all.load(std::memory_order_relaxed)) return true;
    if (watch->gone || watch->fd == -1) return watch->gone;
    const auto now = Clock::now();
    if (now < watch->next) return false;
    watch->next = now + std::chrono::milliseconds(10);
    if (watch->fd == -2)
      watch->fd = connection_fd(watch->remote_addr, watch->remote_port, watch->local_port);
    watch->gone = watch->fd >= 0 && peer_closed(watch->fd);
    return watch->gone;
  };
}

json PlannerService::Impl::plan_response(const PlanResult& r, double wall_s,
                                         httplib::Response& res) {
  const bool cancelled = !r.solved && r.failure == PlanFailure::kCancelled;
  metrics.record_plan(r.solved    ? internal::PlanOutcome::kSolved
                      : cancelled ? internal::PlanOutcome::kCancelled
                                  : internal::PlanOutcome::kFailed);
  if (!r.solved) {
    const ApiError e{422, failure_code(r.failure), r.status, ""};
    json body = error_body(e);
    body["planning_time_s"] = wall_s;
    res.status = cancelled ? 503 : 422;
    return body;
  }
  res.status = 200;
  return json{{"status", "solved"},
              {"planning_time_s", wall_s},
              {"plan", json::parse(plan_to_json(r.plan))}};
}

// A PUT's map: the whole body, or a map_server map as multipart/form-data with the
// parts "yaml" and "image" (nothing else).
internal::MapUpload PlannerService::Impl::map_upload(const httplib::Request& req) {
  MapUpload u;
  if (!req.is_multipart_form_data()) {
    u.body = req.body;
    return u;
  }
  for (const auto& [key, part] : req.files)
    if (key != "yaml" && key != "image")
      throw ApiError{400, "INVALID_MAP",
                     fmt::format("{}: expected only the parts yaml and image (a map_server map)",
                                 printable(key, 64)),
                     printable(key, 64)};
  for (const char* key : {"yaml", "image"}) {
    if (req.files.count(key) != 1)
      throw ApiError{
          400, "INVALID_MAP",
          fmt::format(
              "{0}: expected one part called {0} (a map_server map: its YAML and its image)", key),
          key};
  }
  u.map_2d = Map2DUpload{req.get_file_value("yaml").content, req.get_file_value("image").content};
  return u;
}

UgvPathRequest PlannerService::Impl::ugv_defaults() const {
  UgvPathRequest r;
  r.robot = {options.robot_ugv, false};
  r.mission = options.mission;
  return r;
}

std::string PlannerService::Impl::ugv_key(const HiddenSpaceFrame& s) {
  return fmt::format("{:.17g},{:.17g},{:.17g},{:.17g},{:.17g},{:.17g},{:.17g}", s.lo_m.x(),
                     s.lo_m.y(), s.hi_m.x(), s.hi_m.y(), s.floor_z_m, s.p_WE.x(), s.p_WE.y());
}

void PlannerService::Impl::plan_ugv(const httplib::Request& req, httplib::Response& res,
                                    bool return_path) {
  const auto arrived = Clock::now();
  const Body body(req.body, {"map", "start", "goal", "hidden_space", "bounds", "floor_z_m", "entry",
                             "tether_budget_m", "driven", "deadline_s", "seed"});
  const auto deadline = deadline_of(body, arrived);
  const auto map = find_map(body.required_text("map"));
  UgvPathRequest r = ugv_defaults();
  read_ugv_request(body, r);
  r.mode = return_path ? UgvPathMode::kReturnAlongTether : UgvPathMode::kPlan;
  r.cancelled = cancel_flag(req);
  const std::map<std::string, std::string> fields{{"start", "start"},
                                                  {"goal", "goal"},
                                                  {"hidden_space", "hidden_space"},
                                                  {"bounds", "bounds"},
                                                  {"p_WE", "entry"},
                                                  {"floor_z_m", "floor_z_m"},
                                                  {"tether_budget_m", "tether_budget_m"},
                                                  {"driven", "driven"},
                                                  {"time_limit_s", "deadline_s"}};
  with_worker(res, deadline, [&] {
    try {
      const HiddenSpaceFrame space = ugv_request_space(map->world, r);
      const auto setup = cached_setup(map->ugv, ugv_key(space), [&] {
        metrics.record_setup_built("ugv");
        return prepare_ugv_path(map->world, r, space);
      });
      const double left_s = seconds_left(deadline);
      if (left_s < 1e-3)
        throw ApiError{422, "TIMEOUT", "the deadline passed before the search could start",
                       "deadline_s"};
      r.time_limit_s = std::min(left_s, 3600.0);
      const UgvPathResult result = plan_ugv_path(map->world, r, *setup);
      json out =
          plan_response(result, std::chrono::duration<double>(Clock::now() - arrived).count(), res);
      if (result.solved) {
        json wraps = json::array();
        for (const WrapPoint& w : result.final_wraps) wraps.push_back({w.p_W.x(), w.p_W.y()});
        out["tether"] = {{"budget_m", result.tether_budget_m},
                         {"length_at_goal_m", result.plan.states.back().tether_length_m},
                         {"wraps_at_goal_m", wraps}};
      }
      send(res, res.status, out);
    } catch (const InputError& e) {
      throw from_input_error(e, fields);
    }
  });
}

std::string PlannerService::Impl::uav_key(const UavApproachRequest& r) {
  std::string k =
      fmt::format("{},{}", to_string(r.unknown),
                  r.tether_released_m ? fmt::format("{:.17g}", *r.tether_released_m) : "-");
  if (r.bounds)
    k += fmt::format(",{:.17g},{:.17g},{:.17g},{:.17g},{:.17g},{:.17g}", r.bounds->lo.x(),
                     r.bounds->lo.y(), r.bounds->lo.z(), r.bounds->hi.x(), r.bounds->hi.y(),
                     r.bounds->hi.z());
  return k;
}

void PlannerService::Impl::plan_uav(const httplib::Request& req, httplib::Response& res) {
  const auto arrived = Clock::now();
  const Body body(req.body, {"map", "start", "goal", "hidden_space", "tether_released_m", "bounds",
                             "unknown", "planner", "deadline_s", "seed"});
  const auto deadline = deadline_of(body, arrived);
  const auto map = find_map(body.required_text("map"));
  UavApproachRequest r;
  r.robot = {options.robot_uav, false};
  r.mission = options.mission;
  read_uav_request(body, r);
  r.cancelled = cancel_flag(req);
  const std::map<std::string, std::string> fields{{"start", "start"},
                                                  {"goal", "goal"},
                                                  {"hidden_space", "hidden_space"},
                                                  {"tether_released_m", "tether_released_m"},
                                                  {"bounds", "bounds"},
                                                  {"planner", "planner"},
                                                  {"time_limit_s", "deadline_s"}};
  with_worker(res, deadline, [&] {
    try {
      const auto setup = cached_setup(map->uav, uav_key(r), [&] {
        metrics.record_setup_built("uav");
        UavApproachSetup made = prepare_uav_approach(map->world, r);
        // The same collision map checks this map's UAV plans: validating a plan
        // just made costs no second build.
        offer_setup(
            map->validation,
            collision_map_options_key(uav_map_options(map->world.spec, r.unknown, made.geofence)),
            MapEntry::ValidationMap{made.map});
        return made;
      });
      const double left_s = seconds_left(deadline);
      if (left_s < 1e-3)
        throw ApiError{422, "TIMEOUT", "the deadline passed before the search could start",
                       "deadline_s"};
      r.time_limit_s = std::min(left_s, 3600.0);
      const PlanResult result = plan_uav_approach(map->world, r, *setup);
      const json out =
          plan_response(result, std::chrono::duration<double>(Clock::now() - arrived).count(), res);
      send(res, res.status, out);
    } catch (const InputError& e) {
      throw from_input_error(e, fields);
    }
  });
}

void PlannerService::Impl::validate(const httplib::Request& req, httplib::Response& res) {
  const auto arrived = Clock::now();
  const Body body(req.body, {"map", "plan", "builtin_shapes", "bounds", "tether_budget_m", "entry",
                             "unknown", "floor_z_m", "deadline_s"});
  const auto deadline = deadline_of(body, arrived);
  const auto map = find_map(body.required_text("map"));
  PlanFile plan = read_plan(body);
  ValidateRequest v;
  // The robot is the service's, by the plan's kind: a request never names a file
  // on the server.
  v.robot_urdf = plan.robot == PlanRobot::kUgv ? options.robot_ugv : options.robot_uav;
  if (v.robot_urdf->empty())
    v.robot_urdf = find_model(plan.robot == PlanRobot::kUgv ? "miniugv.urdf" : "m100.urdf");
  v.mission = options.mission_path;
  read_validate_request(body, v);
  // A plan can ask for a million collision checks: the deadline bounds them too.
  const auto stop = cancel_flag(req);
  v.cancelled = [stop, deadline] { return Clock::now() >= deadline || stop(); };
  v.collision_map = [this, &map](const octomap::OcTree& tree, const CollisionMapOptions& o) {
    return cached_setup(map->validation, collision_map_options_key(o),
                        [&] {
                          metrics.record_setup_built("validation");
                          return MapEntry::ValidationMap{CollisionMap::build(tree, o)};
                        })
        ->map;
  };
  with_worker(res, deadline, [&] {
    try {
      const ValidationReport report = validate_plan(std::move(plan), map->world, v, "plan");
      json out = json::parse(validation_report_to_json(report));
      out["planning_time_s"] = std::chrono::duration<double>(Clock::now() - arrived).count();
      send(res, 200, out);
    } catch (const InputError& e) {
      throw ApiError{400, "INVALID_REQUEST", printable(e.what()),
                     e.field().empty() ? "plan" : e.field()};
    } catch (const ValidationCancelled&) {
      if (Clock::now() >= deadline)
        throw ApiError{422, "TIMEOUT", "the deadline passed before the plan was checked whole",
                       "deadline_s"};
      throw ApiError{503, "CANCELLED", "the validation was stopped (the service is stopping)", ""};
    }
  });
}

void PlannerService::Impl::next_goal(const httplib::Request& req, httplib::Response& res) {
  const auto arrived = Clock::now();
  const Body body(req.body,
                  {"grid", "object_probability", "object_confidence", "pose", "velocity", "method",
                   "ir_fov_rad", "ir_range_m", "camera_range_m", "seed", "deadline_s"});
  const auto deadline = deadline_of(body, arrived);
  NextGoalRequest r;
  r.mission = options.mission;
  read_next_goal_request(body, r);
  with_worker(res, deadline, [&] {
    try {
      const auto goal = next_exploration_goal(r);
      const double wall_s = std::chrono::duration<double>(Clock::now() - arrived).count();
      if (!goal) {
        json out = error_body({422, "NO_FRONTIER",
                               "no frontier is reachable: nothing left to explore from here", ""});
        out["planning_time_s"] = wall_s;
        send(res, 422, out);
        return;
      }
      json path = json::array();
      for (const Eigen::Vector2d& q : goal->path_W) path.push_back({q.x(), q.y()});
      json g{
          {"x_m", goal->p_W.x()}, {"y_m", goal->p_W.y()},   {"cell", {goal->cell.i, goal->cell.j}},
          {"score", goal->score}, {"reason", goal->reason}, {"path_m", path}};
      g["heading_rad"] = goal->heading_rad ? json(*goal->heading_rad) : json(nullptr);
      send(res, 200, json{{"goal", g}, {"method", r.method}, {"planning_time_s", wall_s}});
    } catch (const InputError& e) {
      throw from_input_error(e, {{"pose", "pose"}, {"method", "method"}, {"velocity", "velocity"}});
    }
  });
}

template <typename Handler>
httplib::Server::Handler PlannerService::Impl::route(const std::string& label, Handler handler) {
  return [this, label, handler](const httplib::Request& req, httplib::Response& res) {
    const auto t0 = Clock::now();
    ++in_flight;
    try {
      handler(req, res);
    } catch (const ApiError& e) {
      send(res, e.http, error_body(e));
    } catch (const InputError& e) {
      send(res, 400, error_body({400, "INVALID_REQUEST", printable(e.what()), e.field()}));
    } catch (const std::bad_alloc&) {
      send(res, 507,
           error_body({507, "INSUFFICIENT_STORAGE",
                       "the request needs more memory than the service has", ""}));
    } catch (const std::exception& e) {
      send(res, 500, error_body({500, "INTERNAL", printable(e.what()), ""}));
    }
    --in_flight;
    metrics.record(label, res.status, std::chrono::duration<double>(Clock::now() - t0).count());
  };
}

void PlannerService::Impl::install_routes() {
  auto& s = server;
  s.set_payload_max_length(options.max_body_bytes);
  s.set_keep_alive_max_count(1000);
  // Answers are small and clients wait for them: without TCP_NODELAY, Nagle's
  // algorithm and the client's delayed ACK hold each answer's last segment ~40 ms.
  s.set_tcp_nodelay(true);
  // A request's own wait for a worker is bounded by Admission; the HTTP threads must
  // outnumber workers + queue so that a request past the queue is answered 503 at
  // once instead of waiting unseen for a thread.
  const std::size_t threads = static_cast<std::size_t>(options.workers + options.queue + 8);
  s.new_task_queue = [threads] { return new httplib::ThreadPool(threads); };

  s.set_pre_routing_handler([this](const httplib::Request& req, httplib::Response& res) {
    if (req.path == "/healthz") return httplib::Server::HandlerResponse::Unhandled;
    if (!options.token.empty()) {
      const std::string auth = req.get_header_value("Authorization");
      const std::string prefix = "Bearer ";
      if (auth.rfind(prefix, 0) != 0 || !same_token(auth.substr(prefix.size()), options.token)) {
        res.set_header("WWW-Authenticate", "Bearer realm=\"ferret-plannerd\"");
        send(res, 401,
             error_body({401, "UNAUTHORIZED",
                         auth.empty() ? "Authorization: expected a bearer token"
                                      : "Authorization: the bearer token is not the service's",
                         "Authorization"}));
        metrics.record("auth", 401, 0.0);
        return httplib::Server::HandlerResponse::Handled;
      }
    }
    if (draining && req.path != "/readyz" && req.path != "/metrics") {
      res.set_header("Retry-After", "5");
      send(res, 503, error_body({503, "DRAINING", "the service is shutting down", ""}));
      metrics.record("draining", 503, 0.0);
      return httplib::Server::HandlerResponse::Handled;
    }
    return httplib::Server::HandlerResponse::Unhandled;
  });
  // An exception that escapes a route (none should): a JSON 500, without cpp-httplib's
  // default EXCEPTION_WHAT header, which would hand the client the exception's text.
  s.set_exception_handler([this](const httplib::Request&, httplib::Response& res,
                                 std::exception_ptr) {
    res.headers.clear();
    send(res, 500, error_body({500, "INTERNAL", "the service failed to answer this request", ""}));
    metrics.record("other", 500, 0.0);
  });
  s.set_error_handler([this](const httplib::Request& req, httplib::Response& res) {
    if (!res.body.empty()) return;  // a route's own error
    const int st = res.status;
    std::string code = "NOT_FOUND", msg = "no route " + printable(req.method + " " + req.path, 120);
    if (st == 413) {
      code = "PAYLOAD_TOO_LARGE";
      msg = fmt::format("body: expected at most {} bytes", options.max_body_bytes);
    } else if (st == 400) {
      code = "INVALID_REQUEST";
      msg = "a malformed HTTP request";
    } else if (st != 404) {
      code = "HTTP_" + std::to_string(st);
      msg = "the request could not be served";
    }
    send(res, st, error_body({st, code, msg, st == 413 ? "body" : ""}));
    metrics.record("other", st, 0.0);
  });

  s.Get("/healthz", route("/healthz", [](const httplib::Request&, httplib::Response& res) {
          send(res, 200, json{{"status", "ok"}});
        }));
  s.Get("/readyz", route("/readyz", [this](const httplib::Request&, httplib::Response& res) {
          if (draining) {
            send(res, 503, json{{"status", "draining"}});
            return;
          }
          send(res, 200, json{{"status", "ready"}, {"maps", map_count()}});
        }));
  s.Get("/metrics", route("/metrics", [this](const httplib::Request&, httplib::Response& res) {
          const auto [active, waiting] = admission.load();
          res.status = 200;
          res.set_content(metrics.text(waiting, active, map_count(), draining),
                          "text/plain; version=0.0.4");
        }));

  const std::string name_re = "/v1/maps/([^/]+)";
  s.Put(
      name_re,
      route("/v1/maps/{name}", [this](const httplib::Request& req, httplib::Response& res) {
        const auto arrived = Clock::now();
        const std::string name = req.matches[1];
        if (!valid_map_name(name))
          bad_request("name", "1 to 64 letters, digits, '_', '-' or '.'", name);
        {
          const std::lock_guard lock(maps_mutex);
          if (!maps.count(name) && maps.size() >= options.max_maps)
            throw ApiError{507, "TOO_MANY_MAPS",
                           fmt::format("maps: the service holds its limit of {} (DELETE one first)",
                                       options.max_maps),
                           "name"};
        }
        // Loading a map is work like planning: it takes a worker, within the longest deadline.
        const auto deadline = arrived + std::chrono::duration_cast<Clock::duration>(
                                            std::chrono::duration<double>(options.max_deadline_s));
        with_worker(res, deadline, [&] {
          std::shared_ptr<MapEntry> entry;
          const MapUpload upload = map_upload(req);
          try {
            entry = map_builder.run_here([&] { return load_map(name, upload, "body"); });
          } catch (const InputError& e) {
            // A map_server map's errors name their part (yaml, image), a whole body's "body".
            const std::string part = upload.map_2d ? e.source() : "body";
            throw ApiError{400, "INVALID_MAP", printable(e.what()),
                           e.field().empty() ? part : part + "." + e.field()};
          }
          bool replaced = false;
          {
            const std::lock_guard lock(maps_mutex);
            replaced = maps.count(name) > 0;
            if (!replaced && maps.size() >= options.max_maps)
              throw ApiError{
                  507, "TOO_MANY_MAPS",
                  fmt::format("maps: the service holds its limit of {}", options.max_maps), "name"};
            maps[name] = entry;
          }
          send(res, replaced ? 200 : 201, map_metadata(*entry));
        });
      }));
  s.Get(name_re,
        route("/v1/maps/{name}", [this](const httplib::Request& req, httplib::Response& res) {
          send(res, 200, map_metadata(*find_map(req.matches[1])));
        }));
  s.Delete(name_re,
           route("/v1/maps/{name}", [this](const httplib::Request& req, httplib::Response& res) {
             const std::string name = req.matches[1];
             const std::lock_guard lock(maps_mutex);
             if (maps.erase(name) == 0)
               throw ApiError{404, "UNKNOWN_MAP",
                              fmt::format("map: no map called '{}'", printable(name, 64)), "name"};
             res.status = 204;
           }));
  s.Get("/v1/maps", route("/v1/maps", [this](const httplib::Request&, httplib::Response& res) {
          std::vector<std::shared_ptr<MapEntry>> all;
          {
            const std::lock_guard lock(maps_mutex);
            for (const auto& [name, m] : maps) all.push_back(m);
          }
          json list = json::array();
          for (const auto& m : all) list.push_back(map_metadata(*m));
          send(res, 200, json{{"maps", list}});
        }));
  s.Post("/v1/plan/ugv",
         route("/v1/plan/ugv", [this](const httplib::Request& req, httplib::Response& res) {
           plan_ugv(req, res, false);
         }));
  s.Post("/v1/plan/ugv/return",
         route("/v1/plan/ugv/return", [this](const httplib::Request& req, httplib::Response& res) {
           plan_ugv(req, res, true);
         }));
  s.Post("/v1/plan/uav",
         route("/v1/plan/uav", [this](const httplib::Request& req, httplib::Response& res) {
           plan_uav(req, res);
         }));
  s.Post("/v1/explore/next-goal",
         route("/v1/explore/next-goal", [this](const httplib::Request& req,
                                               httplib::Response& res) { next_goal(req, res); }));
  s.Post("/v1/validate",
         route("/v1/validate", [this](const httplib::Request& req, httplib::Response& res) {
           validate(req, res);
         }));

  if (options.json_log)
    s.set_logger([](const httplib::Request& req, const httplib::Response& res) {
      json line{{"ts", utc_now()},
                {"method", req.method},
                {"path", printable(req.path, 200)},
                {"status", res.status},
                {"remote", req.remote_addr}};
      if (res.status >= 400) {
        const auto body = json::parse(res.body, nullptr, false);
        if (body.is_object() && body.contains("error"))
          line["code"] = body["error"].value("code", "");
      }
      std::cerr << line.dump() << "\n";
    });
}

}  // namespace ferret
