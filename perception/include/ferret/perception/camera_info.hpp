#pragma once
// ROS camera_info calibration files (the camera_calibration_parsers YAML format):
// image_width, image_height, camera_name, camera_matrix, distortion_model,
// distortion_coefficients, rectification_matrix, projection_matrix; each matrix a map
// of rows, cols and data.

#include <filesystem>
#include <string>

#include "ferret/perception/camera_model.hpp"

namespace ferret {

/// Reads a camera_info YAML. Throws InputError naming the file and the field (a
/// missing key, a matrix whose data does not have rows x cols finite numbers, an
/// unknown distortion model, sizes out of range ...).
[[nodiscard]] CameraModel load_camera_info(const std::filesystem::path& path);
[[nodiscard]] CameraModel parse_camera_info(const std::string& yaml_text,
                                            const std::string& source);
/// The camera_info YAML of a model; parse_camera_info(camera_info_yaml(m)) == m, every
/// number to the last bit. The distortion model is always written as plumb_bob (ROS
/// knows no "none"): a kNone model comes back as plumb_bob with five zeros, which
/// projects the same (has_distortion() is false for both). Throws InputError when the
/// model fails check().
[[nodiscard]] std::string camera_info_yaml(const CameraModel& model);

}  // namespace ferret
