// `ferret detect object IMAGE (--camera CAM.yaml | --robot URDF) [--json] [-o overlay.png]`:
// the miniUGV's object detector (ugv/object_detector.hpp, the orange colour patch) on a
// camera frame: bearing, distance from apparent size and confidence of every object
// found. docs/perception.md, "Object detection".

#include <fmt/format.h>

#include <filesystem>
#include <fstream>
#include <iostream>
#include <nlohmann/json.hpp>
#include <string>

#include "cli_options.hpp"
#include "cmd_detect.hpp"
#include "command.hpp"
#include "ferret/core/error.hpp"
#include "ferret/core/number.hpp"
#include "ferret/core/output_set.hpp"
#include "ferret/core/pose.hpp"
#include "ferret/perception/image.hpp"
#include "ferret/ugv/object_detector.hpp"
#include "ferret/urdf/robot_description.hpp"

namespace ferret::cli {
namespace {
namespace fs = std::filesystem;

struct DetectObjectArgs {
  std::string image, camera, robot, mission, out;
  double object_width_m = ugv::ColourObjectDetector::Options{}.object_width_m;
  double object_height_m = ugv::ColourObjectDetector::Options{}.object_height_m;
  bool json = false;
};

std::string detections_json(const std::vector<ugv::ObjectDetection>& dets) {
  nlohmann::json list = nlohmann::json::array();
  for (const auto& d : dets)
    list.push_back({{"bearing_rad", d.bearing_rad},
                    {"distance_m", d.distance_m},
                    {"confidence", d.confidence},
                    {"centroid_px", {d.centroid_px.x(), d.centroid_px.y()}},
                    {"size_px", d.apparent_size_px},
                    {"size_axis", ugv::to_string(d.size_axis)},
                    {"box_px", {d.box.x_px, d.box.y_px, d.box.width_px, d.box.height_px}},
                    {"visibility", d.visibility},
                    {"truncated", d.truncated}});
  return nlohmann::json{{"detections", list}}.dump(2) + "\n";
}

void run(const DetectObjectArgs& a) {
  // Everything the user gave is checked before the image is read.
  fs::path out;
  if (!a.out.empty()) {
    out = checked_out_file(a.out, "an overlay PNG");
    if (out.extension() != ".png")
      throw InputError("--out", "", "an overlay path ending in .png", a.out);
  }
  const MissionConfig mission = load_mission_or_defaults(a.mission);
  const CameraModel camera = resolve_camera(a.camera, a.robot, kRoleObjectCamera, mission);
  ugv::ColourObjectDetector::Options options;
  options.object_width_m =
      check_number(a.object_width_m, NumberRange::positive(100.0, "m"), "--object-width-m");
  options.object_height_m =
      check_number(a.object_height_m, NumberRange::positive(100.0, "m"), "--object-height-m");
  options.object_depth_m = options.object_width_m;  // a square footprint, as the canister's
  options.search = mission.object_search;
  options.check(a.mission.empty() ? "object detector" : a.mission);

  const RgbImage image = read_rgb_image(a.image);
  if (image.width_px != camera.width_px || image.height_px != camera.height_px)
    throw InputError(a.image, "size",
                     fmt::format("{} x {} px, the camera's size ({})", camera.width_px,
                                 camera.height_px, camera.source),
                     fmt::format("{} x {}", image.width_px, image.height_px));
  const auto dets = ugv::ColourObjectDetector(options).detect(image, camera);

  if (!out.empty()) {
    OutputSet outputs(out, OutputKind::kFile);
    const auto png = encode_png(ugv::draw_object_overlay(image, dets));
    outputs.write({}, [&](const fs::path& staged) {
      std::ofstream f(staged, std::ios::binary);
      f.write(reinterpret_cast<const char*>(png.data()), static_cast<std::streamsize>(png.size()));
      if (!f) throw InputError(staged.string(), "", "a writable file");
    });
    outputs.commit();
  }
  if (a.json) {
    std::cout << detections_json(dets);
    return;
  }
  std::cout << fmt::format("{}: {} object{} ({} x {} px, camera {})\n", a.image, dets.size(),
                           dets.size() == 1 ? "" : "s", image.width_px, image.height_px,
                           camera.name);
  for (std::size_t k = 0; k < dets.size(); ++k) {
    const auto& d = dets[k];
    std::cout << fmt::format(
        "  #{}: bearing {:+.2f} deg, distance {:.3f} m (from its {} over {:g} px), confidence "
        "{:.3f}, centroid ({:.1f}, {:.1f}) px{}\n",
        k, rad_to_deg(d.bearing_rad), d.distance_m, ugv::to_string(d.size_axis), d.apparent_size_px,
        d.confidence, d.centroid_px.x(), d.centroid_px.y(),
        d.truncated ? ", cut by the image border" : "");
  }
  if (!out.empty()) std::cout << "overlay -> " << a.out << "\n";
}

const CommandRegistration kDetectObject{
    "detect object", [](CLI::App& app) {
      auto args = std::make_shared<DetectObjectArgs>();
      auto* sub = detect_group(app).add_subcommand(
          "object",
          "Find the object (its orange colour patch) in a camera image: bearing, "
          "distance from apparent size, confidence eta / d");
      sub->add_option("IMAGE", args->image, "The camera image (PNG or JPEG)")->required();
      add_camera_option(sub, args->camera, kRoleObjectCamera);
      add_robot_option(sub, args->robot, "none: --camera gives the camera");
      add_mission_option(sub, args->mission, false);
      sub->add_option(
             "--object-width-m", args->object_width_m,
             "The object's width (and depth: a square footprint), metres (the shipped canister's)")
          ->capture_default_str();
      sub->add_option("--object-height-m", args->object_height_m,
                      "The object's height, metres: its apparent height gives the distance")
          ->capture_default_str();
      sub->add_flag("--json", args->json,
                    "JSON on stdout: {\"detections\": [{\"bearing_rad\", \"distance_m\", "
                    "\"confidence\", \"centroid_px\": [u, v], \"size_px\", ...}]}");
      add_out_option(sub, args->out, "")
          ->description(
              "overlay PNG: the image with each detection's box and values (default: none)");
      sub->callback([args, sub] {
        refuse_empty_out(sub, args->out);
        run(*args);
      });
    }};

}  // namespace
}  // namespace ferret::cli
