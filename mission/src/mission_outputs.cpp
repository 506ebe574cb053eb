#include "ferret/mission/mission_outputs.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <functional>
#include <limits>
#include <memory>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "ferret/core/data_path.hpp"
#include "ferret/core/error.hpp"
#include "ferret/core/foxglove_log.hpp"
#include "ferret/core/output_set.hpp"
#include "ferret/mapping/map_render.hpp"
#include "ferret/mapping/world_octree.hpp"
#include "ferret/mission/exploration_run.hpp"
#include "ferret/mission/safety_report.hpp"
#include "ferret/mission/search_robot.hpp"
#include "ferret/mission/ugv_mission_log.hpp"
#include "ferret/planning/exploration_policy.hpp"
#include "ferret/planning/mission_config.hpp"
#include "ferret/planning/planning_world.hpp"
#include "ferret/sim/mission_run.hpp"
#include "ferret/sim/robot_backends.hpp"
#include "ferret/sim/tether_sim.hpp"
#include "ferret/sim/time_series_plot.hpp"
#include "ferret/uav/uav_mission_config.hpp"
#include "ferret/urdf/robot_description.hpp"

namespace ferret {
namespace {

namespace fs = std::filesystem;

nlohmann::json xyz(const Eigen::Vector3d& p) { return {p.x(), p.y(), p.z()}; }

int ugv_body_contacts(const MissionRunResult& r) {
  int n = 0;
  for (const UgvDeployment& d : r.deployments) n += d.result.body_contacts;
  return n;
}

// What each side of a run knows (RunSide): the UAV's mission (its visits, pattern, time
// in state), the truth of the simulated world, the miniUGV's controllers.
bool knows_uav_mission(RunSide side) { return side == RunSide::kMission || side == RunSide::kUav; }
bool knows_truth(RunSide side) { return side == RunSide::kMission || side == RunSide::kWorld; }
bool knows_ugv_controller(RunSide side) {
  return side == RunSide::kMission || side == RunSide::kUgv;
}

nlohmann::json summary_json(RunSide side, const MissionRunResult& r) {
  nlohmann::json s = nlohmann::json::object();
  if (knows_uav_mission(side)) {
    s["hidden_spaces_found"] = r.visits.size();
    s["objects_retrieved"] = std::count_if(r.visits.begin(), r.visits.end(),
                                           [](const auto& v) { return v.object_retrieved; });
    s["leg_spacing_m"] = r.leg_spacing_m;
    s["pattern_waypoints"] = r.pattern_waypoints;
    s["pattern_done"] = r.pattern_done;
    s["marker_frames"] = r.frames;
  }
  if (side != RunSide::kUgv) {  // the UAV's flight and winch: measured, or the truth
    s["flown_m"] = r.flown_m;
    s["battery_left"] = r.battery_left;
    s["tether_max_released_m"] = r.max_released_m;
    s["tether_max_tension_n"] = r.max_tension_n;
  }
  if (knows_truth(side)) {
    s["hidden_spaces_in_world"] = r.hidden_spaces_in_world;
    s["objects_in_world"] = r.objects_in_world;
    s["objects_dropped"] = r.objects_dropped;
    s["uav_collisions"] = r.uav_collisions;
    s["ugv_body_contacts"] = ugv_body_contacts(r);
    s["tether_required_over_length_steps"] = r.required_over_length;
    s["tether_over_tension_events"] = r.over_tension_events;
  }
  if (side == RunSide::kMission) s["marker_frames_rendered"] = r.marker_frames_rendered;
  if (side == RunSide::kUgv) s["searches"] = r.deployments.size();
  return s;
}

nlohmann::json visits_json(const MissionRunResult& r) {
  nlohmann::json visits = nlohmann::json::array();
  for (const HiddenSpaceVisit& v : r.visits) {
    nlohmann::json e = {{"marker_id", v.marker_id},
                        {"detected_s", v.detected_s},
                        {"detected_on_pass", v.pattern_index < r.first_pass_waypoints ? 1 : 2},
                        {"opening_estimate_m", xyz(v.opening.p_WE)},
                        {"entry_yaw_rad", v.opening.entry_yaw_rad},
                        {"state", std::string(to_string(v.state))},
                        {"note", v.note},
                        {"landed", v.landed},
                        {"deployed_s", v.deployed_s},
                        {"retracted_s", v.retracted_s},
                        {"ugv_outcome", v.ugv_outcome},
                        {"object_retrieved", v.object_retrieved},
                        {"object_dropped", v.object_dropped},
                        {"tether_max_released_m", v.max_released_m}};
    e["landing_zone"] =
        v.landing_zone
            ? nlohmann::json{{"center_m", xyz(v.landing_zone->center_m)},
                             {"slope_deg", v.landing_zone->slope_deg},
                             {"clearance_m", v.landing_zone->clearance_m},
                             {"distance_to_opening_m", v.landing_zone->distance_to_opening_m}}
            : nlohmann::json();
    visits.push_back(e);
  }
  return visits;
}

// Each deployment with what the side saw of it: the world the base and the truth, the
// miniUGV its controller.
nlohmann::json deployments_json(RunSide side, const MissionRunResult& r) {
  nlohmann::json deps = nlohmann::json::array();
  for (const UgvDeployment& d : r.deployments) {
    const UgvMissionRunResult& u = d.result;
    nlohmann::json e = {{"deployed_s", d.deployed_s}, {"time_s", u.time_s}};
    if (knows_truth(side)) {
      e["hidden_space"] = d.hidden_space;
      e["object_present"] = d.object_W.has_value();
      e["path_m"] = u.path_m;
      e["battery_left"] = u.battery_left;
      e["object_held"] = u.object_held;
      e["body_contacts"] = u.body_contacts;
      e["deepest_contact_m"] = u.deepest_contact_m;
      e["tether_true_max_m"] = d.max_true_tether_m;
    }
    if (knows_ugv_controller(side)) {
      e["outcome"] = to_string(u.outcome);
      e["grasp_attempts"] = u.grasp_attempts;
      e["decisions"] = u.decisions;
      e["tether_model_max_m"] = u.max_tether_m;
    }
    if (side == RunSide::kUgv) {
      e["final_state"] = to_string(u.final_state);
      e["object_found_m"] = u.found_W ? nlohmann::json{u.found_W->x(), u.found_W->y()} : nullptr;
    }
    deps.push_back(e);
  }
  return deps;
}

nlohmann::json transitions_json(const std::vector<Transition>& transitions) {
  nlohmann::json tr = nlohmann::json::array();
  for (const Transition& t : transitions)
    tr.push_back({{"t_s", t.t_s},
                  {"component", t.component},
                  {"from", t.from},
                  {"to", t.to},
                  {"reason", t.reason}});
  return tr;
}

// Every 0.5 s. The UAV's own samples have no true taut tether and no miniUGV battery.
void add_samples(RunSide side, const MissionRunResult& r, nlohmann::json& j) {
  const bool truth = knows_truth(side);
  auto& samples = j["samples"] = nlohmann::json::array();
  for (const MissionSample& s : r.samples) {
    nlohmann::json row = {s.t_s,     s.p_W.x(), s.p_W.y(), s.p_W.z(),
                          s.yaw_rad, s.state,   s.battery, s.released_m};
    if (truth) row.push_back(s.required_m);
    row.push_back(s.tension_n);
    if (truth) row.push_back(s.ugv_battery);
    samples.push_back(row);
  }
  j["samples_columns"] =
      truth ? nlohmann::json{"t_s",        "x_m",       "y_m",        "z_m",
                             "yaw_rad",    "state",     "battery",    "released_m",
                             "required_m", "tension_n", "ugv_battery"}
            : nlohmann::json{"t_s",   "x_m",     "y_m",        "z_m",      "yaw_rad",
                             "state", "battery", "released_m", "tension_n"};
}

constexpr const char* side_name(RunSide side) {
  switch (side) {
    case RunSide::kMission:
      return "mission";
    case RunSide::kWorld:
      return "world";
    case RunSide::kUav:
      return "uav";
    case RunSide::kUgv:
      return "ugv";
  }
  return "mission";
}

nlohmann::json report_json(const RunOutputsInput& in, const MissionRunResult& r) {
  const RunSide side = in.side;
  nlohmann::json j;
  j["schema"] = "ferret.mission_report/1";
  j["world"] = in.world_path.string();
  j["seed"] = in.seed;
  if (side != RunSide::kMission) {  // `ferret mission`'s report stays as it was
    j["side"] = side_name(side);
    j["ended_early"] = in.ended_early.empty() ? nlohmann::json() : nlohmann::json(in.ended_early);
  }
  j["backends"] = r.backends;
  if (!r.link_counters.empty()) j["link_counters"] = r.link_counters;
  if (knows_uav_mission(side)) j["outcome"] = to_string(r.outcome);
  j["time_s"] = r.time_s;
  j["summary"] = summary_json(side, r);
  // The invariants are checked where the whole mission runs in one process.
  if (side == RunSide::kMission) j["safety"] = safety_json(r.invariant_violations);
  if (knows_uav_mission(side)) {
    j["time_in_state_s"] = r.time_in_state;
    j["hidden_spaces"] = visits_json(r);
  }
  if (side != RunSide::kUav) j["ugv_deployments"] = deployments_json(side, r);
  for (const auto& [robot, said] : in.robot_summaries) {  // null: the robot said none
    const nlohmann::json summary = nlohmann::json::parse(said, nullptr, false);
    j["robot_summaries"][robot] = summary.is_discarded() ? nlohmann::json() : summary;
  }
  j["transitions"] = transitions_json(r.transitions);
  if (side != RunSide::kUgv) add_samples(side, r, j);
  return j;
}

// The aerial map: the world cut just above the ground, the flight path, each opening
// the UAV estimated, the landing points, the drop zone.
void write_aerial_png(const octomap::OcTree& tree, const WorldSpec& spec, const MissionRunResult& r,
                      const fs::path& path) {
  SliceOptions so;
  so.z_m = spec.ground.height_m + 0.35;
  const OccupancyMap2D slice = slice_octree(tree, so);
  MapCanvas c(slice);
  std::vector<Eigen::Vector2d> flight;
  for (const MissionSample& s : r.samples) flight.push_back(s.p_W.head<2>());
  c.draw_path(flight, Rgb{30, 90, 220}, 2);
  c.add_legend("flight path", Rgb{30, 90, 220}, LegendMark::kLine);
  for (const HiddenSpaceVisit& v : r.visits) {
    c.draw_marker(v.opening.p_WE.head<2>(), Rgb{230, 120, 0}, LegendMark::kDiamond, 7);
    c.draw_text(v.opening.p_WE.head<2>() + Eigen::Vector2d(0.8, 0.8),
                fmt::format("#{} {}", v.marker_id, v.object_retrieved ? "object" : v.ugv_outcome),
                Rgb{120, 60, 0});
    if (v.landing_zone)
      c.draw_marker(v.landing_zone->center_m.head<2>(), Rgb{0, 170, 0}, LegendMark::kSquare, 5);
  }
  c.add_legend("opening (from its marker)", Rgb{230, 120, 0}, LegendMark::kDiamond);
  c.add_legend("landing zone", Rgb{0, 170, 0}, LegendMark::kSquare);
  if (spec.drop_zone) {
    c.draw_circle(spec.drop_zone->center_m, spec.drop_zone->radius_m, Rgb{200, 0, 160});
    c.add_legend("drop zone", Rgb{200, 0, 160}, LegendMark::kRing);
  }
  c.set_title(fmt::format("{}: {} in {:.0f} s, {:.0f} m flown, {} of {} hidden spaces found",
                          spec.name, to_string(r.outcome), r.time_s, r.flown_m, r.visits.size(),
                          r.hidden_spaces_in_world));
  c.save_png(path);
}

// The tether over the whole mission as the tether simulation's plot draws it.
void write_tether_png(const MissionRunResult& r, const UavMissionOptions& uav,
                      double total_length_m, const fs::path& path) {
  sim::TetherSimResult t;
  t.scenario = "mission";
  t.plot_title = "The mission's tether";
  t.controller = uav.winch_controller;
  const auto& ctl = uav.winch_control;
  const double band_m = ctl.max_slack_m + ctl.max_slack_margin_m;
  t.band_label = fmt::format("allowed [0, s_max {:g} mm + the miniUGV's doubt, at most {:g} mm]",
                             1e3 * ctl.max_slack_m, 1e3 * band_m);
  // The metrics over the samples (every 0.5 s) while a miniUGV worked on the floor; the
  // tension figures are the simulation's own, from every winch step.
  double sum2 = 0.0;
  int n = 0;
  auto& m = t.metrics;
  m.min_slack_m = std::numeric_limits<double>::infinity();
  m.max_slack_m = -std::numeric_limits<double>::infinity();
  for (const MissionSample& s : r.samples) {
    sim::TetherSimSample row;
    row.t_s = s.t_s;
    row.released_m = s.released_m;
    row.required_m = s.required_m > 0 ? s.required_m : s.released_m;
    row.slack_m = row.released_m - row.required_m;
    row.winch_tension_n = row.ugv_tension_n = s.tension_n;
    t.log.push_back(row);
    if (s.required_m > 0) {
      sum2 += row.slack_m * row.slack_m;
      ++n;
      m.min_slack_m = std::min(m.min_slack_m, row.slack_m);
      m.max_slack_m = std::max(m.max_slack_m, row.slack_m);
    }
    if (s.released_m >= total_length_m - 1e-3) m.limit_active_s += 0.5;
  }
  if (n == 0) m.min_slack_m = m.max_slack_m = 0.0;
  m.slack_rms_m = n > 0 ? std::sqrt(sum2 / n) : 0.0;
  m.max_tension_n = r.max_tension_n;
  m.over_tension_events = r.over_tension_events;
  if (t.log.size() >= 2) sim::write_tether_sim_plot(t, band_m, total_length_m, path);
}

// The miniUGV lowered into a hidden space, as the UAV's visits say.
long lowered(const MissionRunResult& r) {
  return std::count_if(r.visits.begin(), r.visits.end(),
                       [](const HiddenSpaceVisit& v) { return v.deployed_s >= 0.0; });
}

// Both batteries over the mission: the UAV's with the reserve it keeps over the way home,
// the miniUGV's while it works in a hidden space (a gap while it is aboard).
void write_battery_png(const MissionRunResult& r, const UavMissionOptions& uav, bool with_ugv,
                       const fs::path& path) {
  sim::TimeSeriesPlot plot;
  plot.title = fmt::format("Batteries: the UAV's {:.0f} % left at the end", 100.0 * r.battery_left);
  plot.subtitle = fmt::format(
      "UAV endurance {:.0f} s, reserve {:.0f} % over the way home; {} miniUGV deployment(s)",
      uav.flight_endurance_s, 100.0 * uav.battery_reserve_fraction,
      with_ugv ? r.deployments.size() : static_cast<std::size_t>(lowered(r)));
  plot.y_label = "battery [%]";
  plot.y_min = 0.0;
  plot.y_max = 100.0;
  plot.levels.push_back({100.0 * uav.battery_reserve_fraction, "UAV reserve"});
  sim::TimeSeries a{"UAV", {200, 90, 20}, {}, {}},
      g{"miniUGV (while deployed)", {20, 140, 60}, {}, {}};
  for (const MissionSample& s : r.samples) {
    a.t_s.push_back(s.t_s);
    a.y.push_back(100.0 * s.battery);
    g.t_s.push_back(s.t_s);
    g.y.push_back(s.required_m > 0 ? 100.0 * s.ugv_battery
                                   : std::numeric_limits<double>::quiet_NaN());
  }
  plot.series = {a};
  if (with_ugv) plot.series.push_back(g);
  if (!r.samples.empty()) sim::write_time_series_plot(plot, path);
}

// The log in time order (Foxglove plays a topic forwards): every message is queued
// with its time, then written sorted (stable, so equal times keep their order).
std::string mission_mcap(const MissionRunResult& r, const std::vector<Transition>& transitions) {
  FoxgloveLog log;
  std::vector<std::pair<double, std::function<void()>>> queue;
  const auto at = [&](double t_s, std::function<void()> write) {
    queue.emplace_back(t_s, std::move(write));
  };
  const auto yawed = [](const Eigen::Vector3d& p, double yaw_rad) {
    Pose3 X = Pose3::Identity();
    X.translation() = p;
    X.linear() = Eigen::AngleAxisd(yaw_rad, Eigen::Vector3d::UnitZ()).toRotationMatrix();
    return X;
  };
  for (const MissionSample& s : r.samples)
    at(s.t_s, [&log, &s, yawed] { log.transform(s.t_s, "world", "uav", yawed(s.p_W, s.yaw_rad)); });
  if (!r.samples.empty())
    at(r.samples.back().t_s, [&] {
      std::vector<Eigen::Vector3d> flight;
      for (const MissionSample& s : r.samples) flight.push_back(s.p_W);
      log.line(r.samples.back().t_s, "/uav/path", "world", "flight", flight,
               RgbaColor{0.1, 0.35, 0.9, 1.0});
    });
  for (const UgvDeployment& d : r.deployments) {
    const double t0 = d.deployed_s;
    for (std::size_t k = 0; k < d.result.trajectory.size(); k += 2) {
      const double t = t0 + 0.05 * static_cast<double>(k);
      const Pose2& p = d.result.trajectory[k];
      at(t, [&log, t, &p, yawed] {
        log.transform(t, "world", "ugv", yawed({p.x_m, p.y_m, 0.03}, p.yaw_rad));
      });
    }
    if (d.result.grid && d.result.objects)
      at(t0 + d.result.time_s, [&log, &d, t0] {
        log_search_maps(log, t0 + d.result.time_s, *d.result.grid, *d.result.objects,
                        "/maps/" + (d.hidden_space.empty() ? std::string("none") : d.hidden_space),
                        "world");
      });
  }
  for (const HiddenSpaceVisit& v : r.visits)
    at(v.detected_s, [&log, &v] {
      log.marker(v.detected_s, "/detections", "world", "opening_" + std::to_string(v.marker_id),
                 v.opening.p_WE, 0.3, {1.0, 0.5, 0.0, 1.0},
                 "marker " + std::to_string(v.marker_id));
    });
  for (const Transition& t : transitions)
    at(t.t_s,
       [&log, &t] { log.log(t.t_s, t.component, t.from + " -> " + t.to + " (" + t.reason + ")"); });
  std::stable_sort(queue.begin(), queue.end(),
                   [](const auto& a, const auto& b) { return a.first < b.first; });
  for (const auto& [t_s, write] : queue) write();
  return log.finish();
}

int objects_retrieved(const MissionRunResult& r) {
  int retrieved = 0;
  for (const HiddenSpaceVisit& v : r.visits) retrieved += v.object_retrieved ? 1 : 0;
  return retrieved;
}

}  // namespace

void print_mission_summary(const MissionRunResult& r) {
  const int retrieved = objects_retrieved(r);
  std::printf(
      "outcome: %s\ntime_s: %.1f\nhidden_spaces_found: %zu of %d\nobjects_retrieved: %d of %d\n"
      "objects_dropped: %d\nflown_m: %.1f\nbattery_left: %.3f\ntether_max_m: %.2f\n"
      "tether_over_tension_events: %d\nuav_collisions: %d\nugv_body_contacts: %d\n",
      std::string(to_string(r.outcome)).c_str(), r.time_s, r.visits.size(),
      r.hidden_spaces_in_world, retrieved, r.objects_in_world, r.objects_dropped, r.flown_m,
      r.battery_left, r.max_released_m, r.over_tension_events, r.uav_collisions,
      ugv_body_contacts(r));
  for (const HiddenSpaceVisit& v : r.visits)
    std::printf("  marker %d: %s%s, miniUGV %s%s\n", v.marker_id,
                std::string(to_string(v.state)).c_str(),
                v.state == VisitState::kServiced ? (v.landed ? " (landed)" : " (hovered)") : "",
                v.ugv_outcome.empty() ? "-" : v.ugv_outcome.c_str(),
                v.object_dropped ? ", object dropped" : "");
  for (const auto& [state, n] : r.collisions_in)
    std::printf("  uav collision checks failed in %s: %d\n", state.c_str(), n);
  if (r.uav_collisions > 0)
    std::printf("  first at (%.2f, %.2f, %.2f)\n", r.first_collision_W.x(), r.first_collision_W.y(),
                r.first_collision_W.z());
  std::printf("time_per_state_s:");
  for (const auto& [state, t] : r.time_in_state) std::printf(" %s %.0f", state.c_str(), t);
  std::printf("\n");
  for (const UgvDeployment& d : r.deployments)
    std::printf(
        "  miniUGV in %s: %s in %.0f s, %.1f m driven, battery %.2f, %d body contacts (deepest "
        "%.3f m)\n",
        d.hidden_space.empty() ? "(none)" : d.hidden_space.c_str(),
        std::string(to_string(d.result.outcome)).c_str(), d.result.time_s, d.result.path_m,
        d.result.battery_left, d.result.body_contacts, d.result.deepest_contact_m);
  if (!r.link_counters.empty()) std::printf("link: %s\n", r.link_counters.c_str());
  std::printf("safety: %s\n", safety_summary(r.invariant_violations).c_str());
}

void write_mission_outputs(const fs::path& dir, const MissionOutputsInput& in,
                           const MissionRunResult& r) {
  RunOutputsInput all;
  all.world = &in.world;
  all.world_path = in.world_path;
  all.seed = in.seed;
  all.uav = &in.uav;
  all.tether_total_length_m = in.tether_total_length_m;
  write_run_outputs(dir, all, r);
}

void write_run_outputs(const fs::path& dir, const RunOutputsInput& in, const MissionRunResult& r) {
  OutputSet files(dir, OutputKind::kDirectory);
  files.write_text("report.json", report_json(in, r).dump(1) + "\n");
  const bool truth = knows_truth(in.side);
  if (in.world && truth)
    files.write("aerial.png", [&](const fs::path& p) {
      write_aerial_png(*in.world->tree, *in.world->spec, r, p);
    });
  if (in.uav && in.side != RunSide::kUgv) {
    files.write("battery.png", [&](const fs::path& p) { write_battery_png(r, *in.uav, truth, p); });
    if (truth)  // the true taut tether against l_t; the UAV has only its l_t
      files.write("tether.png", [&](const fs::path& p) {
        write_tether_png(r, *in.uav, in.tether_total_length_m, p);
      });
  }
  for (const UgvDeployment& d : r.deployments) {
    if (!truth || d.hidden_space.empty() || !d.result.grid) continue;
    EpisodeResult figure;
    figure.found = d.result.found_right;
    figure.time_s = d.result.time_s;
    figure.path_m = d.result.path_m;
    figure.decisions = d.result.decisions;
    figure.end_reason = std::string(to_string(d.result.outcome));
    figure.found_W = d.result.found_W.value_or(Eigen::Vector2d::Zero());
    figure.trajectory = d.result.trajectory;
    figure.grid = d.result.grid;
    figure.objects = d.result.objects;
    const fs::path space_dir = files.path("spaces/" + d.hidden_space + "/G.png").parent_path();
    write_exploration_images(d.truth, d.object_W.value_or(Eigen::Vector2d(-1e6, -1e6)), figure,
                             space_dir,
                             fmt::format("{}: {}", d.hidden_space, to_string(d.result.outcome)));
  }
  if (in.world && truth)
    files.write("map.bt", [&](const fs::path& p) { save_octree(*in.world->tree, p); });
  files.write_text("mission.mcap", mission_mcap(r, r.transitions));
  files.commit();
}

}  // namespace ferret
