#pragma once
// The object camera of the hardware backend (internal to ugv/): a cv::VideoCapture
// behind an interface without OpenCV types. A live device (an index, /dev/video*, a
// URL) is read by a thread that keeps the newest frame, so a slow controller never
// gets a frame from the driver's queue seconds old; a video file is read one frame a
// call and replays in a loop (the tests' camera), so every call sees the next frame.

#include <memory>
#include <optional>
#include <string>

#include "ferret/perception/image.hpp"

namespace ferret::ugv::internal {

class HwCamera {
 public:
  /// Opens `device` and waits up to first_frame_timeout_s for a valid colour frame of
  /// width x height px (a frame of another size with the same aspect ratio is scaled;
  /// another aspect ratio is refused). Throws HwUgvError kCameraMissing / kCameraNoFrames.
  HwCamera(const std::string& device, int width_px, int height_px, double first_frame_timeout_s,
           double frame_timeout_s);
  ~HwCamera();
  HwCamera(const HwCamera&) = delete;
  HwCamera& operator=(const HwCamera&) = delete;

  /// A frame not handed out before, or nullopt (none new yet, or the camera failed).
  [[nodiscard]] std::optional<RgbImage> next_frame();
  /// False when a live camera gave no frame for frame_timeout_s, or a file stopped
  /// decoding.
  [[nodiscard]] bool healthy() const;
  /// What is wrong, for diagnosis(); empty when healthy.
  [[nodiscard]] std::string problem() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace ferret::ugv::internal
