#pragma once
// Object detection on the miniUGV's camera frames (paper sect. IV-A: a detector whose
// confidence falls with distance, conf = eta / d, d = k_c / gamma from the object's
// apparent size).
//
// The object's visual feature is a colour patch (kObjectColourRgb, orange): at the
// few pixels an 8 cm object spans at metres in the miniUGV's camera a fiducial marker
// cannot be decoded (it needs ~20 px), a colour patch is still there, it looks the same
// from every side, and its extent in pixels gives the distance (docs/perception.md,
// "Object detection").
//
// ColourObjectDetector: HSV threshold around the colour's hue (hue wraps at 0/360),
// morphological opening (drops isolated noise pixels), connected components; a blob
// becomes a detection when its area, fill ratio (area / bounding box) and colour
// purity pass. Its distance comes from the extent of the blob through the camera model
// (undistorted rays), its confidence from the one formula of the codebase
// (detection_confidence, mapping/object_map.hpp) scaled by a visibility term for blobs
// that are small or cut by the image border.

#include <Eigen/Core>
#include <array>
#include <cstdint>
#include <vector>

#include "ferret/mapping/object_map.hpp"
#include "ferret/mapping/object_search_params.hpp"
#include "ferret/perception/camera_model.hpp"
#include "ferret/perception/image.hpp"
#include "ferret/perception/object_appearance.hpp"

namespace ferret::ugv {

/// A pixel rectangle: columns [x_px, x_px + width_px), rows [y_px, y_px + height_px).
struct PixelBox {
  int x_px = 0;
  int y_px = 0;
  int width_px = 0;
  int height_px = 0;
};

/// Which of the object's sizes the distance came from.
enum class SizeAxis { kHeight, kWidth };
[[nodiscard]] const char* to_string(SizeAxis axis);  ///< "height" / "width"

/// One object found in one image.
struct ObjectDetection {
  /// Angle of the blob's centroid from the optical axis in the camera's horizontal
  /// plane (x-z of the optical frame), + to the left: atan2(-x, z) of the undistorted
  /// ray through the centroid.
  double bearing_rad = 0.0;
  /// Range from the camera to the object's centre: the near face's depth z = size_m /
  /// (normalised extent) times the length of the centroid's ray at z = 1, plus the
  /// mean distance from the near face to the centre (Options::object_depth_m).
  double distance_m = 0.0;
  /// clip(visibility * eta / d, conf_floor, conf_cap): what the object map fuses.
  double confidence = 0.0;
  Eigen::Vector2d centroid_px = Eigen::Vector2d::Zero();
  /// The blob's extent along `size_axis` in pixels (the apparent size d came from).
  double apparent_size_px = 0.0;
  SizeAxis size_axis = SizeAxis::kHeight;
  PixelBox box;
  int area_px = 0;
  double fill_ratio = 0.0;  ///< area / box area
  double purity = 0.0;      ///< 1 - mean |hue - object hue| / hue tolerance, in [0, 1]
  /// In (0, 1]: 1 for a whole blob of at least full_visibility_px; less for a small
  /// blob or one cut by the image border.
  double visibility = 1.0;
  bool truncated = false;  ///< the blob touches the image border
};

/// The form the object map takes (mapping/object_map.hpp).
[[nodiscard]] ::ferret::ObjectDetection to_map_detection(const ObjectDetection& detection);

/// Finds the object in camera frames.
class ObjectDetector {
 public:
  virtual ~ObjectDetector() = default;
  /// Every object found in `image` (taken by `camera`), best confidence first.
  /// @pre image size == camera size (InputError otherwise).
  [[nodiscard]] virtual std::vector<ObjectDetection> detect(const RgbImage& image,
                                                            const CameraModel& camera) const = 0;
};

class ColourObjectDetector final : public ObjectDetector {
 public:
  struct Options {
    std::array<std::uint8_t, 3> colour_rgb = kObjectColourRgb;
    /// A pixel is the object's when its hue is within this of the colour's hue ...
    double hue_tolerance_deg = 12.0;
    /// ... and it is saturated and bright enough (fractions of full scale). Shading
    /// and exposure scale brightness but keep hue and saturation.
    double min_saturation = 0.45;
    double min_value = 0.2;
    /// The object's real size (the shipped canister: 8 x 8 x 5 cm). Height is its
    /// vertical extent: for a level camera, the same from every side.
    double object_width_m = 0.08;
    double object_height_m = 0.05;
    /// The side of its (square) footprint: the blob's extent gives the range to the
    /// object's near face, and the centre lies half the footprint's projected depth
    /// further, 2 depth / pi on average over the object's yaw. 0 for a flat patch.
    double object_depth_m = 0.08;
    /// Side of the square opening kernel (odd; 1: no opening).
    int open_kernel_px = 3;
    int min_area_px = 6;
    double min_fill_ratio = 0.35;
    double min_purity = 0.3;
    /// A blob whose apparent size is at least this has full visibility; smaller ones
    /// scale it down linearly (a few pixels are weak evidence of a colour patch).
    double full_visibility_px = 8.0;
    /// Detections whose distance is beyond this are dropped: the camera's detection
    /// range D_cam (a URDF camera's far clip). 0: no limit.
    double max_distance_m = 0.0;
    /// eta_m, conf_floor, conf_cap (the mission YAML's object_search).
    ObjectSearchParams search;

    /// Throws InputError(source, "object_detector.FIELD", ...) for values out of range.
    void check(const std::string& source) const;
  };

  ColourObjectDetector() : ColourObjectDetector(Options{}) {}
  explicit ColourObjectDetector(Options options);

  [[nodiscard]] std::vector<ObjectDetection> detect(const RgbImage& image,
                                                    const CameraModel& camera) const override;
  [[nodiscard]] const Options& options() const { return options_; }

 private:
  Options options_;
};

/// An image with each detection's box, centroid and values drawn on it (a person's
/// view of what the detector saw).
[[nodiscard]] RgbImage draw_object_overlay(const RgbImage& image,
                                           const std::vector<ObjectDetection>& detections);

}  // namespace ferret::ugv
