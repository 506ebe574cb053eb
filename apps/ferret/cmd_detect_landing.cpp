// `ferret detect landing DEPTH.png [DEPTH.png ...] --robot URDF --pose
// x,y,z,roll,pitch,yaw [--opening x,y,z] [--mission M] [--json] [-o overlay.png]`: landing
// zones in a depth frame of the robot's depth camera, or in several frames of one hover
// fused (LandingZoneDetector, fuse_depth_frames; docs/perception.md, "Landing zones").
#include <fmt/format.h>

#include <fstream>
#include <iostream>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "cli_options.hpp"
#include "cmd_detect.hpp"
#include "command.hpp"
#include "ferret/core/error.hpp"
#include "ferret/core/output_set.hpp"
#include "ferret/perception/camera_model.hpp"
#include "ferret/perception/image.hpp"
#include "ferret/planning/planning_world.hpp"
#include "ferret/sim/sensor_sim.hpp"
#include "ferret/uav/landing_zone.hpp"
#include "ferret/urdf/robot_description.hpp"

namespace ferret::cli {
namespace {

struct LandingArgs {
  std::vector<std::string> depth;
  std::string robot, pose, opening, mission, out;
  bool json = false;
};

void run(const LandingArgs& a, const CLI::App* cmd) {
  refuse_empty_out(cmd, a.out);
  std::optional<std::filesystem::path> overlay_path;
  if (!a.out.empty()) {
    overlay_path = checked_out_file(a.out, "the overlay PNG");
    if (overlay_path->extension() != ".png")
      throw InputError("--out", "", "an overlay path ending in .png", a.out);
  }
  // Range: a UAV's pose within OctoMap's reach of any world ferret builds, angles in
  // radians within one turn either way.
  const auto p = parse_number_list(a.pose, 6, "--pose");
  for (int k = 0; k < 3; ++k)
    if (std::abs(p[k]) > 1e5)
      throw InputError("--pose", "", "x,y,z within +-100000 m and roll,pitch,yaw in radians",
                       a.pose);
  for (int k = 3; k < 6; ++k)
    if (std::abs(p[k]) > 2 * std::numbers::pi)
      throw InputError("--pose", "", "roll,pitch,yaw in radians within [-2 pi, 2 pi]", a.pose);
  const MissionConfig mission = load_mission_or_defaults(a.mission);
  const RobotDescription robot = load_robot(resolve_robot(a.robot, "m100.urdf").string(), mission);
  const CameraSensor& sensor = robot.depth_camera();
  const CameraModel camera = camera_model(sensor, robot.source);

  LandingZoneDetector::Options options = LandingZoneDetector::Options::for_robot(robot, &mission);
  if (!a.opening.empty()) {
    const auto e = parse_number_list(a.opening, 3, "--opening");
    for (const double v : e)
      if (std::abs(v) > 1e5)
        throw InputError("--opening", "", "x,y,z within +-100000 m", a.opening);
    options.p_WE = Eigen::Vector3d(e[0], e[1], e[2]);
  }
  if (a.depth.size() > static_cast<std::size_t>(kMaxHoverFrames))
    throw InputError("DEPTH", "", fmt::format("at most {} frames of one hover", kMaxHoverFrames),
                     fmt::format("{} frames", a.depth.size()));
  std::vector<DepthImageMm> frames;
  for (const std::string& path : a.depth) {
    frames.push_back(read_depth_png(path));
    const DepthImageMm& d = frames.back();
    if (d.width_px != camera.width_px || d.height_px != camera.height_px)
      throw InputError(path, "",
                       fmt::format("a {} x {} px frame of the robot's depth camera '{}'",
                                   camera.width_px, camera.height_px, sensor.name),
                       fmt::format("{} x {} px", d.width_px, d.height_px));
  }

  const Pose3 X_WB = pose_from_xyz_rpy({p[0], p[1], p[2]}, p[3], p[4], p[5]);
  const Pose3 X_WC = optical_pose(X_WB, sensor);
  // Several frames are one hover's, all at --pose: fused pixel by pixel (one frame
  // comes out as it went in), and the overlay shows what was judged.
  std::vector<PosedDepthFrame> posed;
  for (const DepthImageMm& d : frames) posed.push_back({&d, X_WC});
  const DepthImageMm depth = fuse_depth_frames(posed, camera);
  const LandingZoneDetector detector(options);
  const LandingResult result = detector.detect(depth, camera, X_WC);

  if (overlay_path) {
    const RgbImage img = landing_overlay(depth, camera, X_WC, result, options.footprint_radius_m);
    const std::vector<std::uint8_t> png = encode_png(img);
    OutputSet files(*overlay_path, OutputKind::kFile);
    {
      std::ofstream f(files.path(), std::ios::binary);
      f.write(reinterpret_cast<const char*>(png.data()), static_cast<std::streamsize>(png.size()));
      if (!f) throw InputError(a.out, "", "a writable overlay file");
    }
    files.commit();
  }

  if (a.json) {
    nlohmann::json zones = nlohmann::json::array();
    for (const auto& z : result.zones) {
      nlohmann::json j;
      j["center_m"] = {z.center_m.x(), z.center_m.y(), z.center_m.z()};
      j["slope_deg"] = z.slope_deg;
      j["roughness_m"] = z.roughness_m;
      j["clearance_m"] = z.clearance_m;
      j["score"] = z.score;
      zones.push_back(j);
    }
    nlohmann::json out;
    out["zones"] = zones;
    if (result.zones.empty()) out["reason"] = result.reason;
    std::cout << out.dump(2) << "\n";
    return;
  }
  if (result.zones.empty()) {
    std::cout << result.reason << "\n";
  } else {
    const auto& z = result.zones.front();
    std::cout << fmt::format(
        "{} landing zone{}; best at ({:.3f}, {:.3f}, {:.3f}) m: slope {:.1f} deg, roughness "
        "{:.3f} m, step {:.3f} m, clearance {:.2f} m, score {:.3f}{}\n",
        result.zones.size(), result.zones.size() == 1 ? "" : "s", z.center_m.x(), z.center_m.y(),
        z.center_m.z(), z.slope_deg, z.roughness_m, z.step_m, z.clearance_m, z.score,
        options.p_WE ? fmt::format(", {:.2f} m from the opening", z.distance_to_opening_m) : "");
  }
  if (overlay_path) std::cout << "overlay -> " << a.out << "\n";
}

const CommandRegistration kDetectLanding{
    "detect landing", [](CLI::App& app) {
      auto args = std::make_shared<LandingArgs>();
      auto* sub = detect_group(app).add_subcommand(
          "landing",
          "Landing zones in a depth frame (16-bit PNG, mm along the optical axis, 0 = no "
          "return) of the robot's depth camera, or in several frames of one hover fused");
      sub->add_option("DEPTH", args->depth,
                      "the depth frame (16-bit PNG of millimetres); several: frames of one "
                      "hover at --pose, fused pixel by pixel before the zones are judged (at "
                      "most " +
                          std::to_string(kMaxHoverFrames) + ")")
          ->required();
      add_robot_option(sub, args->robot, "m100");
      sub->add_option("--pose", args->pose,
                      "the robot's base_link in the world when the frame was taken: "
                      "x,y,z,roll,pitch,yaw (metres, radians)")
          ->required();
      sub->add_option(
          "--opening", args->opening,
          "the hidden space's opening p_WE, x,y,z (metres): zones must have the "
          "winch within l_0 (the mission's tether.entry_offset_m) of the point above it "
          "(default: none; zones are then ranked by distance from the point under the "
          "camera)");
      add_mission_option(sub, args->mission, false);
      sub->add_flag("--json", args->json,
                    "print {\"zones\": [{\"center_m\", \"slope_deg\", \"roughness_m\", "
                    "\"clearance_m\", \"score\"}]} (best first; empty, with \"reason\", when "
                    "nothing in view is safe)");
      // Optional here: the shared helper words -o as required, so its help is replaced.
      add_out_option(sub, args->out, "")
          ->description(
              "the overlay PNG to write: zones on the false-coloured depth frame (default: none)");
      sub->callback([args, sub] { run(*args, sub); });
    }};

}  // namespace
}  // namespace ferret::cli
