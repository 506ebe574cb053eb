// `ferret detect marker`: fiducial markers (AprilTag 3 or OpenCV ArUco) in a camera
// image, with each marker's pose in the camera's optical frame. The `detect` group
// itself is shared with `detect landing` and `detect object` (cmd_detect.hpp).

#include "cmd_detect.hpp"

#include <fmt/format.h>

#include <iostream>
#include <memory>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>

#include "cli_options.hpp"
#include "command.hpp"
#include "ferret/core/error.hpp"
#include "ferret/core/number.hpp"
#include "ferret/core/output_set.hpp"
#include "ferret/perception/camera_model.hpp"
#include "ferret/perception/image.hpp"
#include "ferret/uav/marker_detector.hpp"
#include "ferret/urdf/robot_description.hpp"

namespace ferret::cli {

CLI::App& detect_group(CLI::App& app) {
  for (CLI::App* sub : app.get_subcommands([](CLI::App*) { return true; }))
    if (sub->get_name() == "detect") return *sub;
  auto* detect =
      app.add_subcommand("detect", "Detect markers, landing zones and objects in frames");
  detect->require_subcommand(1);
  return *detect;
}

namespace {
namespace fs = std::filesystem;

struct MarkerArgs {
  std::string image, camera, robot, family, dictionary, out;
  double marker_size_m = 0.0;
  bool json = false;
};

nlohmann::json to_json(const std::vector<MarkerDetection>& detections) {
  nlohmann::json list = nlohmann::json::array();
  for (const auto& d : detections) {
    nlohmann::json corners = nlohmann::json::array();
    for (const auto& c : d.corners_px) corners.push_back({c.x(), c.y()});
    const Eigen::Matrix3d R = d.X_CM.linear();
    const Eigen::Vector3d t = d.X_CM.translation();
    list.push_back(
        {{"id", d.id},
         {"corners_px", corners},
         {"t_CM_m", {t.x(), t.y(), t.z()}},
         {"R_CM",
          {{R(0, 0), R(0, 1), R(0, 2)}, {R(1, 0), R(1, 1), R(1, 2)}, {R(2, 0), R(2, 1), R(2, 2)}}},
         {"reprojection_error_px", d.reprojection_error_px}});
  }
  return {{"detections", list}};
}

void run_marker(const MarkerArgs& a) {
  // Every option first, then the output target, then the work.
  MarkerDetectorOptions options;
  options.dictionary.family = parse_marker_family(a.family, "--family", "");
  options.dictionary.name =
      a.dictionary.empty() ? default_marker_dictionary(options.dictionary.family) : a.dictionary;
  check_marker_dictionary(options.dictionary, "--dictionary", "");
  options.marker_size_m =
      check_number(a.marker_size_m, NumberRange::positive(100.0, "m"), "--marker-size-m");
  std::optional<OutputSet> files;
  if (!a.out.empty()) {
    const fs::path target = checked_out_file(a.out, "an overlay PNG");
    if (target.extension() != ".png")
      throw InputError("--out", "", "an overlay path ending in .png", a.out);
    files.emplace(target, OutputKind::kFile);
  }
  const CameraModel camera = resolve_camera(a.camera, a.robot, kRoleMarkerCamera);
  const GrayImage image = read_gray_image(a.image);
  if (image.width_px != camera.width_px || image.height_px != camera.height_px)
    throw InputError(
        a.image, "size",
        fmt::format("the camera's {}x{} px ({})", camera.width_px, camera.height_px, camera.source),
        fmt::format("{}x{} px", image.width_px, image.height_px));
  const auto detections = make_marker_detector(options)->detect(image, camera);
  if (files) {
    const auto png =
        encode_png(draw_marker_overlay(image, camera, detections, options.marker_size_m / 2));
    files->write_text("", std::string_view(reinterpret_cast<const char*>(png.data()), png.size()));
    files->commit();
  }
  if (a.json) {
    std::cout << to_json(detections).dump(2) << "\n";
    return;
  }
  std::cout << fmt::format("{} marker(s) of {} {}\n", detections.size(),
                           to_string(options.dictionary.family), options.dictionary.name);
  for (const auto& d : detections) {
    const Eigen::Vector3d t = d.X_CM.translation();
    std::cout << fmt::format(
        "  id {}: t_CM_m [{:.4f}, {:.4f}, {:.4f}], distance {:.3f} m, reprojection {:.2f} px\n",
        d.id, t.x(), t.y(), t.z(), t.norm(), d.reprojection_error_px);
  }
}

const CommandRegistration kDetectMarker{
    "detect marker", [](CLI::App& app) {
      auto args = std::make_shared<MarkerArgs>();
      auto* sub = detect_group(app).add_subcommand(
          "marker", "Fiducial markers in a camera image, with their poses in the optical frame");
      sub->add_option("IMAGE", args->image, "camera image (PNG or JPEG)")->required();
      add_camera_option(sub, args->camera, kRoleMarkerCamera);
      add_robot_option(sub, args->robot, "none: --camera or --robot; the URDF's marker_camera");
      sub->add_option("--family", args->family, "marker family: apriltag or aruco")->required();
      sub->add_option("--dictionary", args->dictionary,
                      "dictionary (AprilTag family or OpenCV ArUco name); default: tag36h11 for "
                      "apriltag, DICT_4X4_50 for aruco");
      sub->add_option("--marker-size-m", args->marker_size_m,
                      "side of the marker's black square, metres")
          ->required();
      sub->add_flag("--json", args->json,
                    "JSON on stdout: {\"detections\": [...]} (docs/perception.md)");
      add_out_option(sub, args->out, "overlay PNG: outlines, ids, axes (default: none)");
      sub->callback([sub, args] {
        refuse_empty_out(sub, args->out);
        run_marker(*args);
      });
    }};

}  // namespace
}  // namespace ferret::cli
