#include "ferret/perception/camera_info.hpp"

#include <fmt/format.h>
#include <yaml-cpp/yaml.h>

#include <cmath>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

#include "ferret/core/error.hpp"
#include "ferret/core/number.hpp"
#include "ferret/core/yaml_config.hpp"

namespace ferret {
namespace {

constexpr int kMaxSidePx = 16384;
// A matrix in a calibration file is at most 3 x 4 (P); the bound keeps a hostile
// rows/cols pair from asking for a huge product before the data is looked at.
constexpr int kMaxMatrixSide = 16;

const char* const kSupportedModels = "plumb_bob or none";

/// A camera_info matrix: {rows, cols, data}; rows x cols must match what the field is
/// (3 x 3 for K and R, 3 x 4 for P) and data must hold that many finite numbers.
std::vector<double> read_matrix(const yaml::MapReader& doc, std::string_view key, int rows,
                                int cols) {
  const yaml::MapReader m = doc.child(key);
  m.allow_only({"rows", "cols", "data"});
  const auto read_dim = [&](std::string_view dim, int want) {
    if (!m.has(dim)) m.fail(dim, fmt::format("{} (required field missing)", want));
    const YAML::Node n = m.node()[std::string(dim)];
    if (!n.IsScalar()) m.fail(dim, std::to_string(want), yaml::internal::describe(n));
    const auto v = parse_integer(n.Scalar(), 0, kMaxMatrixSide, m.source(), m.field_path(dim));
    if (v != want) m.fail(dim, std::to_string(want), std::to_string(v));
  };
  read_dim("rows", rows);
  read_dim("cols", cols);
  const auto n = static_cast<std::size_t>(rows) * static_cast<std::size_t>(cols);
  const std::vector<double> data = m.get_list<double>("data");
  if (data.size() != n)
    m.fail("data", fmt::format("a list of {} numbers (rows x cols = {} x {})", n, rows, cols),
           fmt::format("a list of {}", data.size()));
  return data;
}

int read_size(const yaml::MapReader& doc, std::string_view key) {
  if (!doc.has(key))
    doc.fail(key, fmt::format("an integer in [1, {}] px (required field missing)", kMaxSidePx));
  const YAML::Node n = doc.node()[std::string(key)];
  if (!n.IsScalar())
    doc.fail(key, fmt::format("an integer in [1, {}] px", kMaxSidePx), yaml::internal::describe(n));
  return static_cast<int>(
      parse_integer(n.Scalar(), 1, kMaxSidePx, doc.source(), doc.field_path(key)));
}

DistortionModel read_distortion(const yaml::MapReader& doc, std::array<double, 5>& coefficients) {
  // camera_calibration_parsers assumes plumb_bob when the key is absent (old files).
  DistortionModel model = DistortionModel::kPlumbBob;
  if (doc.has("distortion_model") || doc.given_empty("distortion_model")) {
    const YAML::Node n = doc.node()["distortion_model"];
    if (!n.IsScalar()) doc.fail("distortion_model", kSupportedModels, yaml::internal::describe(n));
    const std::string name = n.Scalar();
    if (name == "plumb_bob") {
      model = DistortionModel::kPlumbBob;
    } else if (name == "none") {
      model = DistortionModel::kNone;
    } else {
      doc.fail("distortion_model",
               fmt::format("{} (ferret's camera model; rational_polynomial and equidistant "
                           "lenses are not supported: recalibrate with plumb_bob)",
                           kSupportedModels),
               "'" + printable(name, 60) + "'");
    }
  }

  const yaml::MapReader d = doc.child("distortion_coefficients");
  d.allow_only({"rows", "cols", "data"});
  // ROS writes D as 1 x N; the count is what matters, and it must fit the model.
  const auto dim = [&](std::string_view key) {
    if (!d.has(key)) d.fail(key, "an integer (required field missing)");
    const YAML::Node n = d.node()[std::string(key)];
    if (!n.IsScalar()) d.fail(key, "an integer", yaml::internal::describe(n));
    return parse_integer(n.Scalar(), 0, kMaxMatrixSide, d.source(), d.field_path(key));
  };
  const auto rows = dim("rows");
  const auto cols = dim("cols");
  const std::vector<double> data = d.get_list<double>("data");
  if (data.size() != static_cast<std::size_t>(rows * cols))
    d.fail("data",
           fmt::format("a list of {} numbers (rows x cols = {} x {})", rows * cols, rows, cols),
           fmt::format("a list of {}", data.size()));
  const bool none = model == DistortionModel::kNone;
  if (data.size() != 5 && !(none && data.empty()))
    d.fail("data",
           none ? "no coefficients or 5 zeros (distortion_model none)"
                : "5 coefficients k1, k2, p1, p2, k3 (distortion_model plumb_bob)",
           fmt::format("a list of {}", data.size()));
  coefficients = {0.0, 0.0, 0.0, 0.0, 0.0};
  for (std::size_t i = 0; i < data.size(); ++i) {
    if (none && data[i] != 0.0)
      d.fail(fmt::format("data[{}]", i), "0 (distortion_model none)", fmt::format("{}", data[i]));
    coefficients[i] = data[i];
  }
  return model;
}

std::string number(double v) {
  // fmt's shortest form reads back to the same double (from_chars is correctly
  // rounded), so a written file parses to the model it came from, bit for bit.
  return fmt::format("{}", v);
}

void emit_matrix(std::string& out, const char* key, int rows, int cols,
                 const std::vector<double>& data) {
  std::string list;
  for (std::size_t i = 0; i < data.size(); ++i) {
    if (i > 0) list += ", ";
    list += number(data[i]);
  }
  out += fmt::format("{}:\n  rows: {}\n  cols: {}\n  data: [{}]\n", key, rows, cols, list);
}

}  // namespace

CameraModel parse_camera_info(const std::string& yaml_text, const std::string& source) {
  const YAML::Node root = yaml::load_string(yaml_text, source);
  const yaml::MapReader doc(root, source);
  doc.allow_only({"image_width", "image_height", "camera_name", "camera_matrix", "distortion_model",
                  "distortion_coefficients", "rectification_matrix", "projection_matrix"});

  CameraModel m;
  m.source = source;
  // camera_calibration_parsers names a camera without a name "unknown".
  m.name = doc.get_or<std::string>("camera_name", "unknown");
  m.width_px = read_size(doc, "image_width");
  m.height_px = read_size(doc, "image_height");

  const std::vector<double> k = read_matrix(doc, "camera_matrix", 3, 3);
  const auto k_field = [](int i) { return fmt::format("camera_matrix.data[{}]", i); };
  // K = [fx s cx; 0 fy cy; 0 0 1]: anything else is not a pinhole calibration.
  for (const int i : {3, 6, 7})
    if (k[i] != 0.0)
      throw InputError(source, k_field(i), "0 (K = [fx s cx; 0 fy cy; 0 0 1])", number(k[i]));
  if (k[8] != 1.0)
    throw InputError(source, k_field(8), "1 (K = [fx s cx; 0 fy cy; 0 0 1])", number(k[8]));
  const NumberRange focal = NumberRange::positive(1e7, "px");
  m.fx_px = check_number(k[0], focal, source, k_field(0));
  m.fy_px = check_number(k[4], focal, source, k_field(4));
  m.skew = k[1];
  m.cx_px = check_number(k[2], NumberRange::closed(-0.5, m.width_px - 0.5, "px (inside the image)"),
                         source, k_field(2));
  m.cy_px =
      check_number(k[5], NumberRange::closed(-0.5, m.height_px - 0.5, "px (inside the image)"),
                   source, k_field(5));

  m.distortion = read_distortion(doc, m.distortion_coefficients);

  const std::vector<double> r = read_matrix(doc, "rectification_matrix", 3, 3);
  for (int i = 0; i < 9; ++i) m.rectification(i / 3, i % 3) = r[i];
  const Eigen::Matrix3d rrt = m.rectification * m.rectification.transpose();
  if ((rrt - Eigen::Matrix3d::Identity()).norm() >= 1e-6 ||
      std::abs(m.rectification.determinant() - 1.0) >= 1e-6)
    throw InputError(
        source, "rectification_matrix.data",
        "a rotation (orthonormal rows, determinant +1, within 1e-6)",
        fmt::format("|R R^T - I| = {:.3g}, det R = {:.9g}",
                    (rrt - Eigen::Matrix3d::Identity()).norm(), m.rectification.determinant()));

  const std::vector<double> p = read_matrix(doc, "projection_matrix", 3, 4);
  for (int i = 0; i < 12; ++i) m.projection(i / 4, i % 4) = p[i];
  // P's last row is [0 0 1 0] for every camera, rectified or stereo.
  for (const int i : {8, 9, 11})
    if (p[i] != 0.0)
      throw InputError(source, fmt::format("projection_matrix.data[{}]", i),
                       "0 (P's last row is [0 0 1 0])", number(p[i]));
  if (p[10] != 1.0)
    throw InputError(source, "projection_matrix.data[10]", "1 (P's last row is [0 0 1 0])",
                     number(p[10]));

  m.check();
  return m;
}

CameraModel load_camera_info(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::error_code ec;
  if (!in || std::filesystem::is_directory(path, ec))
    throw InputError(path.string(), "", "a readable camera_info YAML file", "cannot open");
  std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  // A calibration file is a few hundred bytes; megabytes are not one.
  if (text.size() > (1u << 20))
    throw InputError(path.string(), "", "a camera_info YAML file of at most 1 MiB",
                     fmt::format("{} bytes", text.size()));
  return parse_camera_info(text, path.string());
}

std::string camera_info_yaml(const CameraModel& model) {
  model.check();
  YAML::Emitter name;
  name << YAML::DoubleQuoted << model.name;
  std::string out;
  out += fmt::format("image_width: {}\n", model.width_px);
  out += fmt::format("image_height: {}\n", model.height_px);
  out += fmt::format("camera_name: {}\n", name.c_str());
  emit_matrix(out, "camera_matrix", 3, 3,
              {model.fx_px, model.skew, model.cx_px, 0.0, model.fy_px, model.cy_px, 0.0, 0.0, 1.0});
  // Always plumb_bob: ROS knows no "none" (image_geometry calls another model's
  // distortion unknown and will not rectify), and five zeros is how ROS writes an ideal
  // lens (camera_info_manager, gazebo_ros_camera). A model without distortion ignores
  // its coefficients, so it writes zeros.
  out += "distortion_model: plumb_bob\n";
  std::vector<double> d(model.distortion_coefficients.begin(), model.distortion_coefficients.end());
  if (model.distortion == DistortionModel::kNone) d.assign(5, 0.0);
  emit_matrix(out, "distortion_coefficients", 1, 5, d);
  std::vector<double> r, p;
  for (int i = 0; i < 9; ++i) r.push_back(model.rectification(i / 3, i % 3));
  for (int i = 0; i < 12; ++i) p.push_back(model.projection(i / 4, i % 4));
  emit_matrix(out, "rectification_matrix", 3, 3, r);
  emit_matrix(out, "projection_matrix", 3, 4, p);
  return out;
}

}  // namespace ferret
