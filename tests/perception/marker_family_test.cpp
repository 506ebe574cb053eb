#include "ferret/perception/marker_family.hpp"

#include <apriltag.h>
#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <tag36h11.h>
#include <tagStandard41h12.h>

#include <opencv2/aruco.hpp>
#include <opencv2/core.hpp>
#include <opencv2/imgproc.hpp>

#include "ferret/core/error.hpp"

namespace ferret {
namespace {
using ::testing::HasSubstr;

// The bitmap scaled up, with a white quiet zone, as a printed marker would be seen
// head-on by a camera.
cv::Mat printed(const MarkerBitmap& b, int px_per_cell, int quiet_cells) {
  const int n = b.cells.width_px;
  cv::Mat cells(n, n, CV_8UC1);
  for (int y = 0; y < n; ++y)
    for (int x = 0; x < n; ++x) cells.at<std::uint8_t>(y, x) = b.cells.at(x, y);
  cv::Mat big;
  cv::resize(cells, big, {n * px_per_cell, n * px_per_cell}, 0, 0, cv::INTER_NEAREST);
  cv::Mat out;
  const int q = quiet_cells * px_per_cell;
  cv::copyMakeBorder(big, out, q, q, q, q, cv::BORDER_CONSTANT, 255);
  return out;
}

bool black_ring(const MarkerBitmap& b) {
  const int lo = b.black_square_offset, hi = lo + b.black_square_cells - 1;
  for (int i = lo; i <= hi; ++i)
    if (b.cells.at(i, lo) != 0 || b.cells.at(i, hi) != 0 || b.cells.at(lo, i) != 0 ||
        b.cells.at(hi, i) != 0)
      return false;
  return true;
}

TEST(MarkerFamily, ArucoBitmapIsReadBackByOpenCv) {
  const MarkerDictionary dict{MarkerFamily::kAruco, "DICT_4X4_50"};
  EXPECT_EQ(marker_id_count(dict), 50);
  for (const int id : {0, 11, 23, 49}) {
    const MarkerBitmap b = marker_bitmap(dict, id);
    ASSERT_EQ(b.cells.width_px, 6);  // 4 x 4 bits inside a one-cell black border
    EXPECT_EQ(b.black_square_cells, 6);
    EXPECT_EQ(b.black_square_offset, 0);
    EXPECT_TRUE(black_ring(b));
    std::vector<int> ids;
    std::vector<std::vector<cv::Point2f>> corners;
    cv::aruco::detectMarkers(printed(b, 20, 2),
                             cv::aruco::getPredefinedDictionary(cv::aruco::DICT_4X4_50), corners,
                             ids);
    ASSERT_EQ(ids.size(), 1u) << id;
    EXPECT_EQ(ids[0], id);
    // The detected square spans the black border: 6 cells of 20 px.
    EXPECT_NEAR(cv::norm(corners[0][1] - corners[0][0]), 120.0, 2.0);
  }
}

int detect_apriltag(const cv::Mat& image, apriltag_family_t* family, double* side_px) {
  apriltag_detector_t* td = apriltag_detector_create();
  apriltag_detector_add_family(td, family);
  image_u8_t im{image.cols, image.rows, static_cast<int32_t>(image.step), image.data};
  zarray_t* detections = apriltag_detector_detect(td, &im);
  int id = -1;
  if (zarray_size(detections) == 1) {
    apriltag_detection_t* det = nullptr;
    zarray_get(detections, 0, &det);
    id = det->id;
    *side_px = std::hypot(det->p[1][0] - det->p[0][0], det->p[1][1] - det->p[0][1]);
  }
  apriltag_detections_destroy(detections);
  apriltag_detector_destroy(td);
  return id;
}

TEST(MarkerFamily, AprilTagBitmapIsReadBackByAprilTag) {
  const MarkerDictionary dict{MarkerFamily::kAprilTag, "tag36h11"};
  EXPECT_EQ(marker_id_count(dict), 587);
  apriltag_family_t* family = tag36h11_create();
  for (const int id : {0, 7, 586}) {
    const MarkerBitmap b = marker_bitmap(dict, id);
    ASSERT_EQ(b.cells.width_px, 10);  // 6 x 6 bits, a black ring, a white ring
    EXPECT_EQ(b.black_square_cells, 8);
    EXPECT_EQ(b.black_square_offset, 1);
    EXPECT_TRUE(black_ring(b));
    EXPECT_EQ(b.cells.at(0, 0), 255);  // the outer ring is white
    double side_px = 0;
    EXPECT_EQ(detect_apriltag(printed(b, 16, 1), family, &side_px), id);
    EXPECT_NEAR(side_px, 8 * 16, 2.0);  // the tag size is the black square's side
  }
  tag36h11_destroy(family);
}

TEST(MarkerFamily, NewerAprilTagLayoutsPutTheBlackSquareInside) {
  const MarkerDictionary dict{MarkerFamily::kAprilTag, "tagStandard41h12"};
  const MarkerBitmap b = marker_bitmap(dict, 5);
  EXPECT_EQ(b.cells.width_px, 9);
  EXPECT_EQ(b.black_square_cells, 5);
  EXPECT_EQ(b.black_square_offset, 2);
  apriltag_family_t* family = tagStandard41h12_create();
  double side_px = 0;
  EXPECT_EQ(detect_apriltag(printed(b, 16, 1), family, &side_px), 5);
  EXPECT_NEAR(side_px, 5 * 16, 2.0);
  tagStandard41h12_destroy(family);
}

// OpenCV 4.6's DICT_APRILTAG_36h11 holds the tag36h11 codes, but each bitmap is the
// AprilTag library's turned by 180 degrees: OpenCV reads a tag printed by AprilTag with
// the same id and its marker frame turned half a turn about z (corners two places on).
TEST(MarkerFamily, OpenCvsAprilTagDictionaryIsAprilTagTurnedHalfATurn) {
  for (const int id : {0, 1, 100, 586}) {
    const MarkerBitmap tag = marker_bitmap({MarkerFamily::kAprilTag, "tag36h11"}, id);
    const MarkerBitmap cv = marker_bitmap({MarkerFamily::kAruco, "DICT_APRILTAG_36h11"}, id);
    const int s = tag.black_square_cells, o = tag.black_square_offset;
    ASSERT_EQ(cv.cells.width_px, s);
    int same = 0, turned = 0;
    for (int y = 0; y < s; ++y)
      for (int x = 0; x < s; ++x) {
        same += tag.cells.at(x + o, y + o) == cv.cells.at(x, y);
        turned += tag.cells.at(x + o, y + o) == cv.cells.at(s - 1 - x, s - 1 - y);
      }
    EXPECT_EQ(turned, s * s) << id;
    EXPECT_LT(same, s * s) << id;
  }
}

TEST(MarkerFamily, BadNamesAndIds) {
  try {
    check_marker_dictionary({MarkerFamily::kAprilTag, "DICT_4X4_50"}, "w.yaml",
                            "marker.dictionary");
    FAIL();
  } catch (const InputError& e) {
    EXPECT_EQ(e.source(), "w.yaml");
    EXPECT_EQ(e.field(), "marker.dictionary");
    EXPECT_THAT(e.what(), HasSubstr("tag36h11"));
  }
  EXPECT_NO_THROW(check_marker_dictionary({MarkerFamily::kAruco, "DICT_APRILTAG_36h11"}, "w", "d"));
  EXPECT_EQ(marker_id_count({MarkerFamily::kAruco, "DICT_APRILTAG_36h11"}), 587);
  EXPECT_THROW((void)marker_bitmap({MarkerFamily::kAruco, "DICT_4X4_50"}, 50), InputError);
  EXPECT_THROW((void)marker_bitmap({MarkerFamily::kAruco, "DICT_4X4_50"}, -1), InputError);
  EXPECT_EQ(parse_marker_family("apriltag", "m.yaml", "f"), MarkerFamily::kAprilTag);
  EXPECT_THROW((void)parse_marker_family("AprilTag", "m.yaml", "f"), InputError);
  EXPECT_EQ(marker_dictionary_names(MarkerFamily::kAprilTag).front(), "tag36h11");
}

}  // namespace
}  // namespace ferret
