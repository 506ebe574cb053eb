// `ferret sense --world W --robot URDF --sensor camera|depth|ir --pose x,y,z,r,p,y -o FILE`:
// one simulated sensor frame of a robot in a world (sim/sensor_sim.hpp): an RGB PNG
// from its colour camera, a 16-bit depth PNG (millimetres) from its depth camera, or
// the JSON of its IR beams' ranges.

#include <fmt/format.h>

#include <filesystem>
#include <iostream>
#include <nlohmann/json.hpp>
#include <string>

#include "cli_options.hpp"
#include "command.hpp"
#include "ferret/core/error.hpp"
#include "ferret/core/output_set.hpp"
#include "ferret/planning/planning_world.hpp"
#include "ferret/sim/sensor_sim.hpp"

namespace ferret::cli {
namespace {
namespace fs = std::filesystem;

struct SenseArgs {
  std::string world, robot, mission, sensor = "camera", pose, role, out;
  std::uint64_t seed = 1;
};

void write_bytes(OutputSet& files, const std::vector<std::uint8_t>& bytes) {
  files.write_text("", std::string_view(reinterpret_cast<const char*>(bytes.data()), bytes.size()));
}

void run(const SenseArgs& a) {
  check_choice("--sensor", a.sensor, {"camera", "depth", "ir"});
  const fs::path out = checked_out_file(a.out, "the frame (PNG) or IR ranges (JSON)");
  const std::string ext = a.sensor == "ir" ? ".json" : ".png";
  if (out.extension() != ext)
    throw InputError("--out", "", fmt::format("a path ending in {} for --sensor {}", ext, a.sensor),
                     a.out);
  const std::string world_ext = fs::path(a.world).extension().string();
  if (world_ext != ".yaml" && world_ext != ".yml")
    throw InputError("--world", "", "a world YAML (frames are rendered from its geometry)",
                     a.world);
  if (!a.role.empty() && a.sensor == "ir")
    throw InputError("--camera-role", "", "no camera role for --sensor ir", a.role);
  const auto p = parse_number_list(a.pose, 6, "--pose");
  const Pose3 X_WB = pose_from_xyz_rpy({p[0], p[1], p[2]}, p[3], p[4], p[5]);
  const MissionConfig mission = load_mission_or_defaults(a.mission);
  const RobotDescription robot = load_robot_description(resolve_robot(a.robot, ""), mission);
  const WorldSpec world = load_world(a.world);
  const SensorSimulator sim(world);

  OutputSet files(out, OutputKind::kFile);
  if (a.sensor == "ir") {
    const auto readings = sim.ir_ranges(robot, X_WB, SensorOptions{}, a.seed);
    nlohmann::json j;
    j["robot"] = robot.name;
    j["seed"] = a.seed;
    j["pose"] = p;
    for (const IrReading& r : readings)
      j["beams"].push_back(
          {{"sensor", r.sensor},
           {"origin_m", {r.p_WO.x(), r.p_WO.y(), r.p_WO.z()}},
           {"direction", {r.direction_W.x(), r.direction_W.y(), r.direction_W.z()}},
           {"range_m", r.range_m},
           {"range_max_m", r.range_max_m},
           {"hit", r.hit}});
    files.write_text("", j.dump(1) + "\n");
    files.commit();
    std::cout << fmt::format("ir: {} beams of {} -> {}\n", readings.size(), robot.name, a.out);
    return;
  }
  const bool depth = a.sensor == "depth";
  const CameraSensor& sensor = camera_for(robot, depth, a.role);
  const CameraModel camera = camera_model(sensor, robot.source);
  const Pose3 X_WC = optical_pose(X_WB, sensor);
  if (depth) {
    write_bytes(files, encode_png(sim.render_depth(camera, X_WC, DepthFrameOptions{}, a.seed)));
  } else {
    write_bytes(files, encode_png(sim.render_camera(camera, X_WC, CameraFrameOptions{}, a.seed)));
  }
  files.commit();
  std::string markers;
  for (const VisibleMarker& m : sim.visible_markers(camera, X_WC))
    markers += fmt::format("{}{} {} ({:.0f} % visible, {:.2f} m)", markers.empty() ? "" : ", ",
                           m.dictionary.name, m.id, 100 * m.visible_fraction, m.distance_m);
  std::cout << fmt::format("{}: {} ({} x {} px) -> {}; markers in view: {}\n", a.sensor,
                           sensor.name, camera.width_px, camera.height_px, a.out,
                           markers.empty() ? "none" : markers);
}

const CommandRegistration kSense{
    "sense", [](CLI::App& app) {
      auto o = std::make_shared<SenseArgs>();
      auto* sub = app.add_subcommand(
          "sense",
          "Render one simulated sensor frame: camera (RGB PNG), depth (16-bit PNG, mm) or ir "
          "(JSON of beam ranges)");
      add_world_option(sub, o->world, true, "world YAML");
      add_robot_option(sub, o->robot, "required")->required();
      add_mission_option(sub, o->mission, false);
      sub->add_option("--sensor", o->sensor, "camera, depth or ir")->capture_default_str();
      sub->add_option("--pose", o->pose,
                      "Pose of the robot's base link in the world: x,y,z,roll,pitch,yaw (metres, "
                      "radians)")
          ->required();
      sub->add_option(
          "--camera-role", o->role,
          "The camera to render: marker_camera, object_camera or depth_camera (default: "
          "marker_camera for a UAV, object_camera for a UGV; depth_camera for depth)");
      add_seed_option(sub, o->seed, "Seed of the sensor noise");
      add_out_option(sub, o->out, "Output file: .png for camera and depth, .json for ir");
      sub->callback([o] { run(*o); });
    }};

}  // namespace
}  // namespace ferret::cli
