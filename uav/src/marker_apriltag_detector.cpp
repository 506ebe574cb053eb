// AprilTag 3 (libapriltag) behind MarkerDetector.

#include <apriltag.h>

#include <algorithm>
#include <cmath>
#include <mutex>
#include <stdexcept>
#include <string_view>

#include "ferret/core/error.hpp"
#include "ferret/perception/marker_library.hpp"
#include "marker_detectors.hpp"

namespace ferret::internal {
namespace {

class AprilTagDetector final : public MarkerDetector {
 public:
  explicit AprilTagDetector(const MarkerDetectorOptions& options) : options_(options) {
    if (options.dictionary.family != MarkerFamily::kAprilTag)
      throw InputError("marker detector options", "dictionary", "an AprilTag 3 family",
                       options.dictionary.name);
    family_ = apriltag_family(options.dictionary);
    detector_ = apriltag_detector_create();
    if (detector_ == nullptr) throw std::bad_alloc();
    apriltag_detector_add_family_bits(detector_, family_.get(), options.max_hamming);
    detector_->nthreads = 1;  // one core: the UAV's computer runs more than this
    detector_->quad_decimate = static_cast<float>(options.quad_decimate);
    detector_->quad_sigma = static_cast<float>(options.quad_sigma);
    detector_->refine_edges = true;  // corners from the full-resolution edges
    detector_->decode_sharpening = options.decode_sharpening;
    detector_->debug = false;
    // Clusters shorter than the smallest marker's boundary cannot be one: skip them
    // early (most of a textured frame's clusters are small).
    detector_->qtp.min_cluster_pixels =
        std::max(5, static_cast<int>(options.min_marker_side_px / options.quad_decimate));
    detector_->qtp.min_white_black_diff = options.apriltag_min_white_black_diff;
  }
  ~AprilTagDetector() override { apriltag_detector_destroy(detector_); }
  AprilTagDetector(const AprilTagDetector&) = delete;
  AprilTagDetector& operator=(const AprilTagDetector&) = delete;

  [[nodiscard]] const MarkerDetectorOptions& options() const override { return options_; }

  [[nodiscard]] std::vector<MarkerDetection> detect(const GrayImage& image,
                                                    const CameraModel& camera) const override {
    check_frame(image, camera);
    image_u8_t im{image.width_px, image.height_px, image.width_px,
                  const_cast<std::uint8_t*>(image.data.data())};
    zarray_t* found = nullptr;
    {
      // The library's detector keeps scratch state: one detection at a time.
      const std::lock_guard lock(mutex_);
      found = apriltag_detector_detect(detector_, &im);
    }
    std::vector<MarkerDetection> out;
    const int count = zarray_size(found);
    for (int i = 0; i < count; ++i) {
      apriltag_detection_t* det = nullptr;
      zarray_get(found, i, &det);
      if (det->hamming > options_.max_hamming ||
          det->decision_margin < options_.min_decision_margin)
        continue;
      if (det->id < 0 || det->id >= static_cast<int>(family_->ncodes)) continue;
      MarkerDetection d;
      d.id = det->id;
      d.hamming = det->hamming;
      d.decision_margin = det->decision_margin;
      // AprilTag's corners wrap counter-clockwise from the tag's (-1, 1) corner in its
      // y-down tag frame: bottom-left, bottom-right, top-right, top-left of the image.
      for (int k = 0; k < 4; ++k) d.corners_px[k] = {det->p[3 - k][0], det->p[3 - k][1]};
      if (!fit_marker_pose(camera, options_.marker_size_m, d)) continue;
      if (d.reprojection_error_px > options_.max_reprojection_error_px) continue;
      out.push_back(d);
    }
    apriltag_detections_destroy(found);
    sort_detections(out);
    return out;
  }

 private:
  MarkerDetectorOptions options_;
  AprilTagFamilyPtr family_{nullptr, nullptr};
  apriltag_detector_t* detector_ = nullptr;
  mutable std::mutex mutex_;
};

}  // namespace

std::unique_ptr<MarkerDetector> make_apriltag_detector(const MarkerDetectorOptions& options) {
  return std::make_unique<AprilTagDetector>(options);
}

}  // namespace ferret::internal
