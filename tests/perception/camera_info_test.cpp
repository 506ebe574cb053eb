// ROS camera_info YAML files: a file written by ROS's calibrator parses to the values
// it holds, a written file parses back to the same model bit for bit, and every
// malformed file is an InputError naming the file and the field.

#include "ferret/perception/camera_info.hpp"

#include <fmt/format.h>
#include <gtest/gtest.h>
#include <unistd.h>
#include <yaml-cpp/yaml.h>

#include <array>
#include <bit>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "ferret/core/error.hpp"
#include "ferret/core/random.hpp"

namespace ferret {
namespace {

namespace fs = std::filesystem;

// The layout of camera_calibration's ost.yaml (ROS Noetic's cameracalibrator.py), for
// a 640 x 480 camera with some barrel distortion; numbers as that tool prints them
// ("0." and "%8f" style both occur in the wild).
const char* const kRosFile = R"(image_width: 640
image_height: 480
camera_name: narrow_stereo
camera_matrix:
  rows: 3
  cols: 3
  data: [ 628.47758,    0.     ,  316.86264,
            0.     ,  628.16998,  236.4428 ,
            0.     ,    0.     ,    1.     ]
distortion_model: plumb_bob
distortion_coefficients:
  rows: 1
  cols: 5
  data: [0.145963, -0.285101, -0.000337, 0.001617, 0.000000]
rectification_matrix:
  rows: 3
  cols: 3
  data: [ 1.,  0.,  0.,
          0.,  1.,  0.,
          0.,  0.,  1.]
projection_matrix:
  rows: 3
  cols: 4
  data: [ 636.81683,    0.     ,  317.25128,    0.     ,
            0.     ,  637.0177 ,  235.31689,    0.     ,
            0.     ,    0.     ,    1.     ,    0.     ]
)";

/// `text` with the first occurrence of `from` replaced by `to` (which must occur).
std::string replaced(std::string text, const std::string& from, const std::string& to) {
  const auto at = text.find(from);
  EXPECT_NE(at, std::string::npos) << "the text does not contain " << from;
  if (at != std::string::npos) text.replace(at, from.size(), to);
  return text;
}
std::string edited(const std::string& from, const std::string& to) {
  return replaced(kRosFile, from, to);
}
/// kRosFile without the top-level key `key` and its block.
std::string without(const std::string& key) {
  std::string text = kRosFile;
  const auto start = text.find(key + ":");
  EXPECT_NE(start, std::string::npos) << key;
  auto end = start;
  do end = text.find('\n', end) + 1;
  while (end < text.size() && text[end] == ' ');
  return text.erase(start, end - start);
}

bool same_bits(double a, double b) {
  return std::bit_cast<std::uint64_t>(a) == std::bit_cast<std::uint64_t>(b);
}

void expect_same_model(const CameraModel& a, const CameraModel& b) {
  EXPECT_EQ(a.name, b.name);
  EXPECT_EQ(a.width_px, b.width_px);
  EXPECT_EQ(a.height_px, b.height_px);
  EXPECT_TRUE(same_bits(a.fx_px, b.fx_px)) << a.fx_px << " vs " << b.fx_px;
  EXPECT_TRUE(same_bits(a.fy_px, b.fy_px)) << a.fy_px << " vs " << b.fy_px;
  EXPECT_TRUE(same_bits(a.cx_px, b.cx_px)) << a.cx_px << " vs " << b.cx_px;
  EXPECT_TRUE(same_bits(a.cy_px, b.cy_px)) << a.cy_px << " vs " << b.cy_px;
  EXPECT_TRUE(same_bits(a.skew, b.skew)) << a.skew << " vs " << b.skew;
  // kNone is written as plumb_bob with zeros (ROS has no "none").
  EXPECT_EQ(b.distortion, DistortionModel::kPlumbBob);
  EXPECT_EQ(a.has_distortion(), b.has_distortion());
  for (int i = 0; i < 5; ++i)
    EXPECT_TRUE(same_bits(a.distortion_coefficients[i], b.distortion_coefficients[i])) << i;
  for (int i = 0; i < 9; ++i)
    EXPECT_TRUE(same_bits(a.rectification(i / 3, i % 3), b.rectification(i / 3, i % 3))) << i;
  for (int i = 0; i < 12; ++i)
    EXPECT_TRUE(same_bits(a.projection(i / 4, i % 4), b.projection(i / 4, i % 4))) << i;
}

/// The InputError that parsing `text` throws; fails the test when it throws none.
InputError parse_error(const std::string& text) {
  try {
    (void)parse_camera_info(text, "cam.yaml");
  } catch (const InputError& e) {
    return e;
  }
  ADD_FAILURE() << "no InputError for:\n" << text;
  return InputError("", "", "");
}

TEST(CameraInfo, RosCalibratorFileGivesItsValues) {
  const CameraModel m = parse_camera_info(kRosFile, "ost.yaml");
  EXPECT_EQ(m.name, "narrow_stereo");
  EXPECT_EQ(m.source, "ost.yaml");
  EXPECT_EQ(m.width_px, 640);
  EXPECT_EQ(m.height_px, 480);
  EXPECT_EQ(m.fx_px, 628.47758);
  EXPECT_EQ(m.fy_px, 628.16998);
  EXPECT_EQ(m.cx_px, 316.86264);
  EXPECT_EQ(m.cy_px, 236.4428);
  EXPECT_EQ(m.skew, 0.0);
  EXPECT_EQ(m.distortion, DistortionModel::kPlumbBob);
  // camera_info's order is k1, k2, p1, p2, k3, as CameraModel keeps it.
  EXPECT_EQ(m.distortion_coefficients[0], 0.145963);
  EXPECT_EQ(m.distortion_coefficients[1], -0.285101);
  EXPECT_EQ(m.distortion_coefficients[2], -0.000337);
  EXPECT_EQ(m.distortion_coefficients[3], 0.001617);
  EXPECT_EQ(m.distortion_coefficients[4], 0.0);
  EXPECT_TRUE(m.rectification.isIdentity(0.0));
  EXPECT_EQ(m.projection(0, 0), 636.81683);
  EXPECT_EQ(m.projection(1, 2), 235.31689);
  EXPECT_EQ(m.projection(2, 2), 1.0);
  // The model projects with these numbers: the principal point's ray is the axis.
  const Eigen::Vector3d axis = m.ray({316.86264, 236.4428});
  EXPECT_NEAR(axis.x(), 0.0, 1e-12);
  EXPECT_NEAR(axis.y(), 0.0, 1e-12);
}

TEST(CameraInfo, OldFilesWithoutModelOrNameAreReadAsRosReadsThem) {
  // camera_calibration_parsers: no distortion_model means plumb_bob, no camera_name
  // means "unknown".
  const std::string text =
      replaced(without("distortion_model"), "camera_name: narrow_stereo\n", "");
  const CameraModel m = parse_camera_info(text, "old.yaml");
  EXPECT_EQ(m.distortion, DistortionModel::kPlumbBob);
  EXPECT_EQ(m.name, "unknown");
  EXPECT_EQ(m.distortion_coefficients[1], -0.285101);
}

TEST(CameraInfo, StereoRightCameraWithRotatedRectificationParses) {
  // A right camera of a stereo pair: R a rotation of a few degrees, P with -fx * B.
  const double a = 0.05;  // rad about y
  const std::string r = "data: [" +
                        fmt::format("{}, 0, {}, 0, 1, 0, {}, 0, {}", std::cos(a), std::sin(a),
                                    -std::sin(a), std::cos(a)) +
                        "]";
  const std::string text =
      replaced(edited("data: [ 1.,  0.,  0.,\n          0.,  1.,  0.,\n          0.,  0.,  1.]", r),
               "317.25128,    0.     ,", "317.25128, -44.577178,");
  const CameraModel m = parse_camera_info(text, "right.yaml");
  EXPECT_EQ(m.rectification(0, 2), std::sin(a));
  EXPECT_EQ(m.projection(0, 3), -44.577178);
}

TEST(CameraInfo, WrittenFileParsesToTheSameModelBitForBit) {
  // Random models over the ranges real cameras have, with awkward doubles (no short
  // decimal form): the writer must give enough digits for every one.
  Rng rng(20261202);
  for (int trial = 0; trial < 200; ++trial) {
    CameraModel m;
    m.name = trial % 2 ? "cam_" + std::to_string(trial) : "name: with \"quotes\" #and a colon";
    m.width_px = static_cast<int>(rng.uniform_int(1, 16384));
    m.height_px = static_cast<int>(rng.uniform_int(1, 16384));
    m.fx_px = rng.uniform(1.0, 1e5);
    m.fy_px = m.fx_px * rng.uniform(0.9, 1.1);
    m.cx_px = rng.uniform(-0.5, m.width_px - 0.5);
    m.cy_px = rng.uniform(-0.5, m.height_px - 0.5);
    m.skew = trial % 3 == 0 ? rng.uniform(-1.0, 1.0) : 0.0;
    m.distortion = trial % 4 == 0 ? DistortionModel::kNone : DistortionModel::kPlumbBob;
    if (m.distortion == DistortionModel::kPlumbBob)
      for (double& d : m.distortion_coefficients) d = rng.normal(0.0, 0.3);
    const Eigen::Quaterniond q(rng.normal(0, 1), rng.normal(0, 1), rng.normal(0, 1),
                               rng.normal(0, 1));
    m.rectification = q.normalized().toRotationMatrix();
    m.projection.leftCols<3>() = m.K() * rng.uniform(0.8, 1.2);
    m.projection(2, 0) = m.projection(2, 1) = 0.0;
    m.projection(2, 2) = 1.0;
    m.projection(0, 3) = rng.uniform(-100.0, 100.0);
    m.projection(2, 3) = 0.0;
    const CameraModel back = parse_camera_info(camera_info_yaml(m), "written.yaml");
    expect_same_model(m, back);
    if (testing::Test::HasFailure()) {
      ADD_FAILURE() << "trial " << trial << ":\n" << camera_info_yaml(m);
      break;
    }
  }
  const CameraModel ros = parse_camera_info(kRosFile, "ost.yaml");
  expect_same_model(ros, parse_camera_info(camera_info_yaml(ros), "again.yaml"));
}

TEST(CameraInfo, WrittenFileHasRosLayout) {
  // What camera_calibration_parsers reads: every key, matrices as rows/cols/data.
  CameraModel m = CameraModel::from_fov("front", 640, 480, 1.5707963267948966);
  const YAML::Node doc = YAML::Load(camera_info_yaml(m));
  EXPECT_EQ(doc["image_width"].as<int>(), 640);
  EXPECT_EQ(doc["image_height"].as<int>(), 480);
  EXPECT_EQ(doc["camera_name"].as<std::string>(), "front");
  EXPECT_EQ(doc["distortion_model"].as<std::string>(), "plumb_bob");  // ROS has no "none"
  EXPECT_EQ(doc["camera_matrix"]["rows"].as<int>(), 3);
  EXPECT_EQ(doc["camera_matrix"]["data"].size(), 9u);
  // fx = (640 / 2) / tan(45 deg) = 320, cx = (640 - 1) / 2.
  EXPECT_NEAR(doc["camera_matrix"]["data"][0].as<double>(), 320.0, 1e-9);
  EXPECT_EQ(doc["camera_matrix"]["data"][2].as<double>(), 319.5);
  EXPECT_EQ(doc["distortion_coefficients"]["rows"].as<int>(), 1);
  EXPECT_EQ(doc["distortion_coefficients"]["cols"].as<int>(), 5);
  EXPECT_EQ(doc["rectification_matrix"]["data"].size(), 9u);
  EXPECT_EQ(doc["projection_matrix"]["cols"].as<int>(), 4);
  EXPECT_EQ(doc["projection_matrix"]["data"].size(), 12u);
  EXPECT_EQ(doc["projection_matrix"]["data"][10].as<double>(), 1.0);
  // A model without distortion writes zeros whatever its coefficients hold.
  m.distortion_coefficients = {0.1, 0.2, 0.3, 0.4, 0.5};
  const CameraModel back = parse_camera_info(camera_info_yaml(m), "w.yaml");
  EXPECT_FALSE(back.has_distortion());
  EXPECT_EQ(back.distortion_coefficients, (std::array<double, 5>{0, 0, 0, 0, 0}));
}

TEST(CameraInfo, NoneModelAcceptsNoCoefficientsOrZeros) {
  const std::string none = edited("distortion_model: plumb_bob", "distortion_model: none");
  const std::string coefficients = "data: [0.145963, -0.285101, -0.000337, 0.001617, 0.000000]";
  for (const std::string& d :
       {std::string("cols: 0\n  data: []"), std::string("cols: 5\n  data: [0, 0, 0, 0, 0]")}) {
    const CameraModel m =
        parse_camera_info(replaced(none, "cols: 5\n  " + coefficients, d), "none.yaml");
    EXPECT_EQ(m.distortion, DistortionModel::kNone);
    EXPECT_FALSE(m.has_distortion());
    EXPECT_EQ(m.distortion_coefficients, (std::array<double, 5>{0, 0, 0, 0, 0}));
  }
}

TEST(CameraInfo, LoadReadsTheFileAndNamesIt) {
  const fs::path dir = fs::temp_directory_path() / ("ferret_caminfo_" + std::to_string(::getpid()));
  fs::create_directories(dir);
  const fs::path file = dir / "ost.yaml";
  std::ofstream(file) << kRosFile;
  const CameraModel m = load_camera_info(file);
  EXPECT_EQ(m.source, file.string());
  EXPECT_EQ(m.fx_px, 628.47758);
  std::ofstream(file) << edited("628.16998", "-628.16998");
  try {
    (void)load_camera_info(file);
    ADD_FAILURE() << "negative fy accepted";
  } catch (const InputError& e) {
    EXPECT_EQ(e.source(), file.string());
    EXPECT_EQ(e.field(), "camera_matrix.data[4]");
  }
  // A calibration is a few hundred bytes; a file of megabytes is refused unread.
  std::ofstream(file) << kRosFile << std::string(1u << 20, '#') << "\n";
  try {
    (void)load_camera_info(file);
    ADD_FAILURE() << "a 1 MiB file accepted";
  } catch (const InputError& e) {
    EXPECT_EQ(e.source(), file.string());
    EXPECT_NE(std::string(e.what()).find("1 MiB"), std::string::npos) << e.what();
  }
  EXPECT_THROW((void)load_camera_info(dir), InputError);  // a directory
  try {
    (void)load_camera_info(dir / "missing.yaml");
    ADD_FAILURE() << "missing file accepted";
  } catch (const InputError& e) {
    EXPECT_EQ(e.source(), (dir / "missing.yaml").string());
  }
  fs::remove_all(dir);
}

struct Malformed {
  const char* what;
  std::string text;
  const char* field;  ///< the field the error must name (a prefix for YAML syntax errors)
};

TEST(CameraInfo, EveryMalformedFileNamesFileAndField) {
  std::string binary = "\x89PNG\r\n\x1a\n";
  // sizeof - 1: the literal holds NULs, so its length cannot come from strlen.
  static constexpr char kChunk[] = "\0\0\0\rIHDR\xff\xfe";
  binary += std::string(kChunk, sizeof kChunk - 1);
  const std::string r_scaled =
      "data: [ 2.,  0.,  0.,\n          0.,  1.,  0.,\n          0.,  0.,  1.]";
  const std::string r_mirror =
      "data: [ -1.,  0.,  0.,\n          0.,  1.,  0.,\n          0.,  0.,  1.]";
  const std::string r_old =
      "data: [ 1.,  0.,  0.,\n          0.,  1.,  0.,\n          0.,  0.,  1.]";
  const std::vector<Malformed> cases{
      {"missing image_width", edited("image_width: 640\n", ""), "image_width"},
      {"missing image_height", without("image_height"), "image_height"},
      {"missing camera_matrix", without("camera_matrix"), "camera_matrix"},
      {"missing distortion_coefficients", without("distortion_coefficients"),
       "distortion_coefficients"},
      {"missing rectification_matrix", without("rectification_matrix"), "rectification_matrix"},
      {"missing projection_matrix", without("projection_matrix"), "projection_matrix"},
      {"missing data", edited("  data: [0.145963, -0.285101, -0.000337, 0.001617, 0.000000]\n", ""),
       "distortion_coefficients.data"},
      {"missing rows", edited("  rows: 3\n", ""), "camera_matrix.rows"},
      {"a misspelt key", edited("camera_matrix:", "camera_matrixx:"), "camera_matrixx"},
      {"K with 2 rows", edited("rows: 3", "rows: 2"), "camera_matrix.rows"},
      {"D cols 4 for 5 numbers", edited("cols: 5", "cols: 4"), "distortion_coefficients.data"},
      {"8 numbers for 9", edited("  316.86264,\n", "\n"), "camera_matrix.data"},
      {"NaN", edited("628.47758", ".nan"), "camera_matrix.data[0]"},
      {"infinity", edited("628.16998", "1e999"), "camera_matrix.data[4]"},
      {"text for a number", edited("628.16998", "six hundred"), "camera_matrix.data[4]"},
      {"K(2,0) not zero",
       edited("0.     ,    0.     ,    1.     ]", "0.5    ,    0.     ,    1.     ]"),
       "camera_matrix.data[6]"},
      {"K(2,2) not one",
       edited("0.     ,    0.     ,    1.     ]", "0.     ,    0.     ,    2.     ]"),
       "camera_matrix.data[8]"},
      {"negative fx", edited("628.47758", "-628.47758"), "camera_matrix.data[0]"},
      {"cx outside the image", edited("316.86264", "700"), "camera_matrix.data[2]"},
      {"cy outside the image", edited("236.4428", "-3"), "camera_matrix.data[5]"},
      {"R scaled", edited(r_old, r_scaled), "rectification_matrix"},
      {"R a reflection", edited(r_old, r_mirror), "rectification_matrix"},
      {"rational_polynomial",
       edited("distortion_model: plumb_bob", "distortion_model: rational_polynomial"),
       "distortion_model"},
      {"equidistant", edited("distortion_model: plumb_bob", "distortion_model: equidistant"),
       "distortion_model"},
      {"none with coefficients", edited("distortion_model: plumb_bob", "distortion_model: none"),
       "distortion_coefficients.data[0]"},
      {"plumb_bob with 4 numbers",
       edited("cols: 5\n  data: [0.145963, -0.285101, -0.000337, 0.001617, 0.000000]",
              "cols: 4\n  data: [0.145963, -0.285101, -0.000337, 0.001617]"),
       "distortion_coefficients.data"},
      {"width 0", edited("image_width: 640", "image_width: 0"), "image_width"},
      {"height 20000", edited("image_height: 480", "image_height: 20000"), "image_height"},
      {"width 640.5", edited("image_width: 640", "image_width: 640.5"), "image_width"},
      {"a typo'd key", edited("camera_name:", "camera_nmae:"), "camera_nmae"},
      {"a key twice", edited("image_height: 480\n", "image_height: 480\nimage_height: 481\n"),
       "image_height"},
      {"P's last row", edited("1.     ,    0.     ]", "2.     ,    0.     ]"),
       "projection_matrix.data[10]"},
      {"P 3 x 3", edited("cols: 4", "cols: 3"), "projection_matrix.cols"},
      {"data a mapping",
       edited("data: [0.145963, -0.285101, -0.000337, 0.001617, 0.000000]", "data: {a: 1}"),
       "distortion_coefficients.data"},
      {"matrix a number", without("rectification_matrix") + "rectification_matrix: 3\n",
       "rectification_matrix"},
      {"rows a list", edited("rows: 3", "rows: [3]"), "camera_matrix.rows"},
      {"not YAML", "image_width: [640\nimage_height: 480\n", "line "},
      {"empty file", "", "(document)"},
      {"a list", "- 1\n- 2\n", "(document)"},
      {"binary garbage", binary, "line "},
  };
  for (const auto& c : cases) {
    SCOPED_TRACE(c.what);
    const InputError e = parse_error(c.text);
    EXPECT_EQ(e.source(), "cam.yaml");
    EXPECT_EQ(e.field().rfind(c.field, 0), 0u)
        << "field '" << e.field() << "' is not " << c.field << "; message: " << e.what();
  }
  // The refusal of another lens model says what is supported.
  const InputError e =
      parse_error(edited("distortion_model: plumb_bob", "distortion_model: rational_polynomial"));
  EXPECT_NE(std::string(e.what()).find("plumb_bob"), std::string::npos) << e.what();
  EXPECT_NE(std::string(e.what()).find("rational_polynomial"), std::string::npos) << e.what();
}

}  // namespace
}  // namespace ferret
