#include "ferret/perception/marker_family.hpp"

#include <apriltag.h>
#include <fmt/format.h>
#include <tag16h5.h>
#include <tag25h9.h>
#include <tag36h10.h>
#include <tag36h11.h>
#include <tagCircle21h7.h>
#include <tagCircle49h12.h>
#include <tagCustom48h12.h>
#include <tagStandard41h12.h>
#include <tagStandard52h13.h>

#include <memory>
#include <opencv2/aruco.hpp>
#include <opencv2/core.hpp>
#include <string_view>
#include <utility>

#include "ferret/core/error.hpp"
#include "ferret/perception/marker_library.hpp"

namespace ferret {
namespace {

struct ArucoName {
  const char* name;
  cv::aruco::PREDEFINED_DICTIONARY_NAME id;
};
constexpr ArucoName kArucoNames[] = {
    {"DICT_4X4_50", cv::aruco::DICT_4X4_50},
    {"DICT_4X4_100", cv::aruco::DICT_4X4_100},
    {"DICT_4X4_250", cv::aruco::DICT_4X4_250},
    {"DICT_4X4_1000", cv::aruco::DICT_4X4_1000},
    {"DICT_5X5_50", cv::aruco::DICT_5X5_50},
    {"DICT_5X5_100", cv::aruco::DICT_5X5_100},
    {"DICT_5X5_250", cv::aruco::DICT_5X5_250},
    {"DICT_5X5_1000", cv::aruco::DICT_5X5_1000},
    {"DICT_6X6_50", cv::aruco::DICT_6X6_50},
    {"DICT_6X6_100", cv::aruco::DICT_6X6_100},
    {"DICT_6X6_250", cv::aruco::DICT_6X6_250},
    {"DICT_6X6_1000", cv::aruco::DICT_6X6_1000},
    {"DICT_7X7_50", cv::aruco::DICT_7X7_50},
    {"DICT_7X7_100", cv::aruco::DICT_7X7_100},
    {"DICT_7X7_250", cv::aruco::DICT_7X7_250},
    {"DICT_7X7_1000", cv::aruco::DICT_7X7_1000},
    {"DICT_ARUCO_ORIGINAL", cv::aruco::DICT_ARUCO_ORIGINAL},
    {"DICT_APRILTAG_16h5", cv::aruco::DICT_APRILTAG_16h5},
    {"DICT_APRILTAG_25h9", cv::aruco::DICT_APRILTAG_25h9},
    {"DICT_APRILTAG_36h10", cv::aruco::DICT_APRILTAG_36h10},
    {"DICT_APRILTAG_36h11", cv::aruco::DICT_APRILTAG_36h11},
};

// AprilTag 3's families, created and destroyed through the library's own functions.
struct AprilTagName {
  const char* name;
  apriltag_family_t* (*create)();
  void (*destroy)(apriltag_family_t*);
};
constexpr AprilTagName kAprilTagNames[] = {
    {"tag36h11", tag36h11_create, tag36h11_destroy},
    {"tag36h10", tag36h10_create, tag36h10_destroy},
    {"tag25h9", tag25h9_create, tag25h9_destroy},
    {"tag16h5", tag16h5_create, tag16h5_destroy},
    {"tagCircle21h7", tagCircle21h7_create, tagCircle21h7_destroy},
    {"tagCircle49h12", tagCircle49h12_create, tagCircle49h12_destroy},
    {"tagStandard41h12", tagStandard41h12_create, tagStandard41h12_destroy},
    {"tagStandard52h13", tagStandard52h13_create, tagStandard52h13_destroy},
    {"tagCustom48h12", tagCustom48h12_create, tagCustom48h12_destroy},
};

const ArucoName* find_aruco(std::string_view name) {
  for (const auto& a : kArucoNames)
    if (name == a.name) return &a;
  return nullptr;
}
const AprilTagName* find_apriltag(std::string_view name) {
  for (const auto& a : kAprilTagNames)
    if (name == a.name) return &a;
  return nullptr;
}

std::string joined_names(MarkerFamily family) {
  std::string out;
  for (const auto& n : marker_dictionary_names(family)) out += (out.empty() ? "" : ", ") + n;
  return out;
}

}  // namespace

const char* to_string(MarkerFamily family) {
  return family == MarkerFamily::kAruco ? "aruco" : "apriltag";
}

MarkerFamily parse_marker_family(const std::string& text, const std::string& source,
                                 const std::string& field) {
  if (text == "aruco") return MarkerFamily::kAruco;
  if (text == "apriltag") return MarkerFamily::kAprilTag;
  throw InputError(source, field, "aruco or apriltag", "'" + text + "'");
}

const std::vector<std::string>& marker_dictionary_names(MarkerFamily family) {
  static const std::vector<std::string> aruco = [] {
    std::vector<std::string> v;
    for (const auto& a : kArucoNames) v.emplace_back(a.name);
    return v;
  }();
  static const std::vector<std::string> apriltag = [] {
    std::vector<std::string> v;
    for (const auto& a : kAprilTagNames) v.emplace_back(a.name);
    return v;
  }();
  return family == MarkerFamily::kAruco ? aruco : apriltag;
}

void check_marker_dictionary(const MarkerDictionary& dictionary, const std::string& source,
                             const std::string& field) {
  const bool known = dictionary.family == MarkerFamily::kAruco
                         ? find_aruco(dictionary.name) != nullptr
                         : find_apriltag(dictionary.name) != nullptr;
  if (!known)
    throw InputError(source, field,
                     fmt::format("a {} dictionary ({})", to_string(dictionary.family),
                                 joined_names(dictionary.family)),
                     "'" + dictionary.name + "'");
}

cv::Ptr<cv::aruco::Dictionary> aruco_dictionary(const MarkerDictionary& dictionary) {
  const ArucoName* a =
      dictionary.family == MarkerFamily::kAruco ? find_aruco(dictionary.name) : nullptr;
  if (a == nullptr)
    throw InputError("marker dictionary", "name",
                     "an OpenCV ArUco dictionary (" + joined_names(MarkerFamily::kAruco) + ")",
                     "'" + dictionary.name + "'");
  return cv::aruco::getPredefinedDictionary(a->id);
}

AprilTagFamilyPtr apriltag_family(const MarkerDictionary& dictionary) {
  const AprilTagName* a =
      dictionary.family == MarkerFamily::kAprilTag ? find_apriltag(dictionary.name) : nullptr;
  if (a == nullptr)
    throw InputError("marker dictionary", "name",
                     "an AprilTag 3 family (" + joined_names(MarkerFamily::kAprilTag) + ")",
                     "'" + dictionary.name + "'");
  AprilTagFamilyPtr family(a->create(), a->destroy);
  if (family == nullptr) throw std::bad_alloc();
  return family;
}

int marker_id_count(const MarkerDictionary& dictionary) {
  check_marker_dictionary(dictionary, "marker dictionary", "name");
  if (dictionary.family == MarkerFamily::kAruco) {
    return aruco_dictionary(dictionary)->bytesList.rows;
  }
  return static_cast<int>(apriltag_family(dictionary)->ncodes);
}

MarkerBitmap marker_bitmap(const MarkerDictionary& dictionary, int id) {
  const int count = marker_id_count(dictionary);
  if (id < 0 || id >= count)
    throw InputError("marker dictionary " + dictionary.name, "id",
                     fmt::format("an id in [0, {}]", count - 1), std::to_string(id));
  MarkerBitmap out;
  if (dictionary.family == MarkerFamily::kAruco) {
    const auto dict = aruco_dictionary(dictionary);
    const int cells = dict->markerSize + 2;  // the data bits inside a one-cell black border
    cv::Mat image;
    cv::aruco::drawMarker(dict, id, cells, image, 1);
    out.cells = GrayImage(cells, cells);
    for (int y = 0; y < cells; ++y)
      for (int x = 0; x < cells; ++x) out.cells.at(x, y) = image.at<std::uint8_t>(y, x);
    out.black_square_cells = cells;
    out.black_square_offset = 0;
    return out;
  }
  const auto family = apriltag_family(dictionary);
  image_u8_t* image = apriltag_to_image(family.get(), id);
  const int total = static_cast<int>(family->total_width);
  out.cells = GrayImage(total, total);
  for (int y = 0; y < total; ++y)
    for (int x = 0; x < total; ++x)
      out.cells.at(x, y) =
          image->buf[static_cast<std::size_t>(y) * static_cast<std::size_t>(image->stride) +
                     static_cast<std::size_t>(x)];
  image_u8_destroy(image);
  // The tag size AprilTag's pose estimate uses is the side of the square at the border
  // between the black and white rings (width_at_border cells), centred in the bitmap.
  out.black_square_cells = family->width_at_border;
  out.black_square_offset = (total - family->width_at_border) / 2;
  return out;
}

}  // namespace ferret
