// ferret-plannerd: ferret's planners as a long-lived HTTP/JSON service (docs/service.md).
// Options follow docs/cli.md: bad input is one line on stderr and exit 2; SIGTERM or
// SIGINT drain the service (new requests 503, those in flight end by their deadlines)
// and exit 0.

#include <fmt/format.h>
#include <malloc.h>
#include <signal.h>
#include <sys/stat.h>

#include <CLI/CLI.hpp>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <sstream>
#include <string>
#include <vector>

#include "ferret/core/error.hpp"
#include "ferret/core/number.hpp"
#include "ferret/mapping/occupancy_map_2d.hpp"
#include "ferret/planning/mission_config.hpp"
#include "ferret/service/planner_service.hpp"
#include "ferret/urdf/robot_description.hpp"

namespace {

namespace fs = std::filesystem;
using ferret::InputError;

std::string slurp(const fs::path& path, const std::string& option) {
  std::error_code ec;
  if (!fs::is_regular_file(path, ec))
    throw InputError(option, "", "a readable file", ferret::printable_path(path.string()));
  std::ifstream in(path, std::ios::binary);
  std::ostringstream s;
  s << in.rdbuf();
  if (!in && !in.eof())
    throw InputError(option, "", "a readable file", ferret::printable_path(path.string()));
  return s.str();
}

// A shipped model's name (m100, miniugv) or a URDF path.
fs::path robot_path(const std::string& robot, const std::string& option) {
  if (robot.empty()) return {};
  if (robot.find('/') == std::string::npos && robot.find('.') == std::string::npos) {
    try {
      return ferret::find_model(robot + ".urdf");
    } catch (const std::exception&) {
      throw InputError(option, "", "a URDF path or a shipped model's name (m100, miniugv)", robot);
    }
  }
  std::error_code ec;
  if (!fs::is_regular_file(robot, ec))
    throw InputError(option, "", "a URDF file", ferret::printable_path(robot));
  return robot;
}

// The token's file: its first line. A file others may read is refused (the token
// would not be a secret), as ssh refuses a private key anyone can read.
std::string read_token(const std::string& path) {
  struct stat st {};
  if (::stat(path.c_str(), &st) != 0)
    throw InputError("--token-file", "", "a readable file", ferret::printable_path(path));
  if (st.st_mode & (S_IRWXG | S_IRWXO))
    throw InputError("--token-file", "", "a file only its owner may read (chmod 600)",
                     ferret::printable_path(path));
  std::string token = slurp(path, "--token-file");
  token = token.substr(0, token.find('\n'));
  while (!token.empty() && (token.back() == '\r' || token.back() == ' ')) token.pop_back();
  if (token.size() < 16 || token.size() > 4096)
    throw InputError("--token-file", "", "a token of 16 to 4096 characters on the first line",
                     std::to_string(token.size()) + " characters");
  for (const unsigned char c : token)
    if (c < 0x21 || c > 0x7e)
      throw InputError("--token-file", "", "a token of printable ASCII without spaces");
  return token;
}

void parse_listen(const std::string& listen, ferret::PlannerServiceOptions& o) {
  const auto colon = listen.rfind(':');
  if (colon == std::string::npos || colon == 0 || colon + 1 == listen.size())
    throw InputError("--listen", "", "HOST:PORT, e.g. 127.0.0.1:8642", listen);
  o.host = listen.substr(0, colon);
  if (o.host.front() == '[' && o.host.back() == ']') o.host = o.host.substr(1, o.host.size() - 2);
  const std::string port = listen.substr(colon + 1);
  if (!ferret::integer_error(port, true).empty() || port.size() > 5 || std::stoi(port) > 65535)
    throw InputError("--listen", "port", "a port in [0, 65535]", port);
  o.port = std::stoi(port);
}

int run(int argc, char** argv) {
  CLI::App app{"ferret-plannerd: ferret's planners as an HTTP/JSON service (docs/service.md)"};
  ferret::PlannerServiceOptions o;
  std::string listen = "127.0.0.1:8642", robot_uav, robot_ugv, mission, token_file;
  std::vector<std::string> preload;
  bool check_config = false;
  double deadline_s = o.default_deadline_s, max_deadline_s = o.max_deadline_s;
  app.add_option("--listen", listen,
                 "HOST:PORT to serve on; loopback by default, 0.0.0.0:PORT for every interface")
      ->capture_default_str();
  app.add_option("--robot-uav", robot_uav,
                 "the UAV's URDF, or a shipped model's name [default: m100]");
  app.add_option("--robot-ugv", robot_ugv,
                 "the miniUGV's URDF, or a shipped model's name [default: miniugv]");
  app.add_option("--mission", mission,
                 "mission YAML: motion limits, tether L and l_0 (default: the built-in values)");
  app.add_option("--token-file", token_file,
                 "a file (mode 600) whose first line is the bearer token every route but /healthz "
                 "requires (default: no token)");
  app.add_option("--workers", o.workers, "requests planning or loading a map at once")
      ->capture_default_str();
  app.add_option("--queue", o.queue, "requests waiting for a worker; beyond it: 503")
      ->capture_default_str();
  app.add_option("--max-body-bytes", o.max_body_bytes, "the largest request body, bytes")
      ->capture_default_str();
  app.add_option("--deadline", deadline_s, "a request's deadline when it names none, seconds")
      ->capture_default_str();
  app.add_option("--max-deadline", max_deadline_s,
                 "the longest deadline a request may ask for, seconds")
      ->capture_default_str();
  app.add_option("--max-maps", o.max_maps, "maps held at once")->capture_default_str();
  app.add_option("--map", preload,
                 "preload a map: NAME=FILE (.bt, .ot, world YAML or map_server YAML); repeatable");
  app.add_flag("--log-json", o.json_log, "one JSON line a request on stderr");
  app.add_flag("--check-config", check_config,
               "check the options, robots, mission and maps, print what would be served, and exit");
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    if (e.get_exit_code() == 0) return app.exit(e);
    std::cerr << "ferret-plannerd: error: " << ferret::printable(e.what()) << "\n";
    return 2;
  }

  parse_listen(listen, o);
  o.default_deadline_s = deadline_s;
  o.max_deadline_s = max_deadline_s;
  o.robot_uav = robot_path(robot_uav, "--robot-uav");
  o.robot_ugv = robot_path(robot_ugv, "--robot-ugv");
  if (!mission.empty()) {
    o.mission = ferret::load_mission_config(mission);
    o.mission_path = mission;
  }
  if (!token_file.empty()) o.token = read_token(token_file);
  std::vector<std::pair<std::string, std::string>> maps;
  for (const std::string& m : preload) {
    const auto eq = m.find('=');
    if (eq == std::string::npos || eq == 0 || eq + 1 == m.size())
      throw InputError("--map", "", "NAME=FILE", m);
    maps.emplace_back(m.substr(0, eq), m.substr(eq + 1));
  }

  // Signals are taken by sigwait below, never by a handler: block them before any
  // thread starts, so every thread inherits the mask.
  sigset_t signals;
  sigemptyset(&signals);
  sigaddset(&signals, SIGTERM);
  sigaddset(&signals, SIGINT);
  pthread_sigmask(SIG_BLOCK, &signals, nullptr);

  // Large blocks (a map's distance fields, OcTree buffers) always from mmap, so a
  // replaced map's go back to the system when freed. glibc otherwise raises its mmap
  // threshold to the largest block freed (up to 32 MiB), after which they come from the
  // heap, where a long-lived block between them keeps the pages.
  mallopt(M_MMAP_THRESHOLD, 1 << 20);
  // An arena a thread (glibc's default is 8 a core, fewer than the HTTP threads), so the
  // service's map builder keeps its own (service/src/map_store.hpp, MapBuilder).
  mallopt(M_ARENA_MAX, o.workers + o.queue + 16);
  ferret::PlannerService service(o);  // checks the options and loads both robots
  for (const auto& [name, file] : maps) {
    if (ferret::is_map_server_yaml(file)) {
      // A map_server map: its image is read where its YAML says, as ferret's commands do.
      const ferret::MapServerMeta meta = ferret::load_map_server_meta(file);
      const fs::path image =
          meta.image.is_absolute() ? meta.image : fs::path(file).parent_path() / meta.image;
      service.put_map_2d(name, slurp(file, "--map " + name), slurp(image, "--map " + name),
                         ferret::printable_path(file), ferret::printable_path(image.string()));
    } else {
      service.put_map(name, slurp(file, "--map " + name), ferret::printable_path(file));
    }
  }
  const std::string auth = o.token.empty() ? "none" : "bearer token";
  if (check_config) {
    std::cout << fmt::format(
        "config ok: listen {}:{}, {} workers, queue {}, deadline {:g} s (max {:g} s), body <= {} "
        "bytes, "
        "auth {}, {} map(s) preloaded\n",
        o.host, o.port, o.workers, o.queue, o.default_deadline_s, o.max_deadline_s,
        o.max_body_bytes, auth, maps.size());
    return 0;
  }
  int port = 0;
  try {
    port = service.start();
  } catch (const std::runtime_error&) {
    throw InputError("--listen", "", "an address of this machine with a free port", listen);
  }
  std::cerr << fmt::format("ferret-plannerd: serving on {}:{} ({} workers, queue {}, auth {})\n",
                           o.host, port, o.workers, o.queue, auth);
  int sig = 0;
  sigwait(&signals, &sig);
  std::cerr << fmt::format("ferret-plannerd: {} received, draining\n",
                           sig == SIGTERM ? "SIGTERM" : "SIGINT");
  service.drain(o.max_deadline_s + 1.0);
  std::cerr << "ferret-plannerd: stopped\n";
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  try {
    return run(argc, argv);
  } catch (const InputError& e) {
    std::cerr << "ferret-plannerd: error: " << ferret::printable(e.what()) << "\n";
    return 2;
  } catch (const std::exception& e) {
    std::cerr << "ferret-plannerd: error: " << ferret::printable(e.what()) << "\n";
    return 3;
  }
}
