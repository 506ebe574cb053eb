#include "hw_camera.hpp"

#include <fmt/format.h>

#include <atomic>
#include <chrono>
#include <cmath>
#include <condition_variable>
#include <cstring>
#include <filesystem>
#include <mutex>
#include <opencv2/imgproc.hpp>
#include <opencv2/videoio.hpp>
#include <thread>

#include "ferret/ugv/hw_ugv_base.hpp"

namespace ferret::ugv::internal {
namespace {

using Clock = std::chrono::steady_clock;

bool is_index(const std::string& device) {
  return !device.empty() && device.size() <= 3 &&
         device.find_first_not_of("0123456789") == std::string::npos;
}

/// A URL goes to FFmpeg as it is; anything else that is not a device is a file.
bool is_url(const std::string& device) { return device.find("://") != std::string::npos; }

bool is_video_device(const std::string& device) {
  std::error_code ec;
  return std::filesystem::is_character_file(device, ec);
}

}  // namespace

struct HwCamera::Impl {
  std::string device;
  int width_px = 0, height_px = 0;
  double frame_timeout_s = 1.0;
  bool live = false;
  cv::VideoCapture capture;

  // Live: the grabbing thread's newest frame.
  std::mutex mutex;
  std::condition_variable arrived;
  cv::Mat newest;
  std::uint64_t newest_id = 0, handed_id = 0;
  Clock::time_point newest_at = Clock::now();
  std::string problem;  ///< the last frame's fault (wrong format, size)
  std::atomic<bool> stop{false};
  std::thread grabber;
  bool file_failed = false;

  /// The frame as RGB of the camera's size, or a reason it is unusable.
  std::optional<RgbImage> convert(const cv::Mat& frame, std::string& why) const {
    if (frame.empty()) {
      why = "an empty frame";
      return std::nullopt;
    }
    if (frame.depth() != CV_8U || (frame.channels() != 3 && frame.channels() != 4)) {
      why = fmt::format("frames of {} channel(s) at {} bits: not a colour camera", frame.channels(),
                        frame.depth() == CV_8U ? 8 : 16);
      return std::nullopt;
    }
    cv::Mat rgb;
    cv::cvtColor(frame, rgb, frame.channels() == 4 ? cv::COLOR_BGRA2RGB : cv::COLOR_BGR2RGB);
    if (rgb.cols != width_px || rgb.rows != height_px) {
      // Binned or scaled frames keep the camera model's fov: scaling is exact for the
      // same aspect ratio, a guess for any other.
      const double aspect_frame = static_cast<double>(rgb.cols) / rgb.rows;
      const double aspect_model = static_cast<double>(width_px) / height_px;
      if (std::abs(aspect_frame / aspect_model - 1.0) > 0.01) {
        why = fmt::format(
            "frames of {} x {} px; the URDF's object camera is {} x {} px (another "
            "aspect ratio: set the camera's mode or the URDF)",
            rgb.cols, rgb.rows, width_px, height_px);
        return std::nullopt;
      }
      cv::Mat scaled;
      cv::resize(rgb, scaled, cv::Size(width_px, height_px), 0, 0, cv::INTER_AREA);
      rgb = scaled;
    }
    RgbImage out(width_px, height_px);
    for (int y = 0; y < height_px; ++y)
      std::memcpy(&out.at(0, y, 0), rgb.ptr(y), static_cast<std::size_t>(width_px) * 3);
    return out;
  }

  void grab_loop() {
    cv::Mat frame;
    while (!stop) {
      if (!capture.read(frame) || frame.empty()) {
        std::this_thread::sleep_for(std::chrono::milliseconds(10));
        continue;
      }
      std::lock_guard lock(mutex);
      newest = frame.clone();
      ++newest_id;
      newest_at = Clock::now();
      arrived.notify_all();
    }
  }
};

HwCamera::HwCamera(const std::string& device, int width_px, int height_px,
                   double first_frame_timeout_s, double frame_timeout_s)
    : impl_(std::make_unique<Impl>()) {
  Impl& m = *impl_;
  m.device = device;
  m.width_px = width_px;
  m.height_px = height_px;
  m.frame_timeout_s = frame_timeout_s;
  using Kind = HwUgvError::Kind;
  const std::string name = fmt::format("camera '{}'", device);
  if (is_index(device)) {
    m.live = true;
    m.capture.open(std::stoi(device), cv::CAP_V4L2);
  } else if (is_url(device)) {
    m.live = true;
    m.capture.open(device, cv::CAP_FFMPEG);
  } else if (is_video_device(device)) {
    m.live = true;
    m.capture.open(device, cv::CAP_V4L2);
  } else {
    std::error_code ec;
    if (!std::filesystem::exists(device, ec))
      throw HwUgvError(Kind::kCameraMissing,
                       fmt::format("{}: no such device or file (ls /dev/video* lists the cameras; "
                                   "is it plugged in and the camera interface enabled?)",
                                   name));
    if (!std::filesystem::is_regular_file(device, ec))
      throw HwUgvError(Kind::kCameraMissing,
                       fmt::format("{}: not a camera device or a video file", name));
    m.capture.open(device, cv::CAP_FFMPEG);
  }
  if (!m.capture.isOpened())
    throw HwUgvError(Kind::kCameraMissing,
                     fmt::format("{}: cannot open ({}; busy with another program, or not a "
                                 "video OpenCV can read?)",
                                 name, m.live ? "a V4L2 or stream device" : "a video file"));
  if (m.live) {
    // Ask for the model's size; a camera that ignores it is scaled (same aspect) or refused.
    m.capture.set(cv::CAP_PROP_FRAME_WIDTH, width_px);
    m.capture.set(cv::CAP_PROP_FRAME_HEIGHT, height_px);
    m.grabber = std::thread([&m] { m.grab_loop(); });
  }

  // The first valid frame, within the timeout: a device that opens but gives no colour
  // frames (a V4L2 metadata node, a wrong index) is the wrong device.
  const auto deadline = Clock::now() + std::chrono::duration_cast<Clock::duration>(
                                           std::chrono::duration<double>(first_frame_timeout_s));
  std::string why = "no frame";
  if (m.live) {
    std::unique_lock lock(m.mutex);
    while (Clock::now() < deadline) {
      if (m.newest_id > 0) {
        if (m.convert(m.newest, why)) break;
        m.newest_id = 0;  // an unusable frame: wait for the next
      }
      m.arrived.wait_until(lock, deadline);
    }
    const bool ok = m.newest_id > 0;
    lock.unlock();
    if (!ok) {
      m.stop = true;
      m.grabber.join();
      throw HwUgvError(
          Kind::kCameraNoFrames,
          fmt::format("{}: opened, but {} within {} s (the capture node? "
                      "v4l2-ctl --list-devices shows each camera's nodes)",
                      name, why == "no frame" ? "no frame" : why, first_frame_timeout_s));
    }
  } else {
    cv::Mat frame;
    if (!m.capture.read(frame) || !m.convert(frame, why))
      throw HwUgvError(Kind::kCameraNoFrames,
                       fmt::format("{}: opened, but {} (not a video OpenCV can decode?)", name,
                                   why == "no frame" ? "no frame decodes" : why));
    m.capture.set(cv::CAP_PROP_POS_FRAMES, 0);  // hand out the first frame first
  }
}

HwCamera::~HwCamera() {
  impl_->stop = true;
  if (impl_->grabber.joinable()) impl_->grabber.join();
}

std::optional<RgbImage> HwCamera::next_frame() {
  Impl& m = *impl_;
  std::string why;
  if (!m.live) {
    cv::Mat frame;
    if (!m.capture.read(frame) || frame.empty()) {
      // The end of the file: replay it from the start.
      m.capture.set(cv::CAP_PROP_POS_FRAMES, 0);
      if (!m.capture.read(frame) || frame.empty()) {
        std::lock_guard lock(m.mutex);
        m.file_failed = true;
        m.problem = "the video file stopped decoding";
        return std::nullopt;
      }
    }
    auto image = m.convert(frame, why);
    std::lock_guard lock(m.mutex);
    m.problem = image ? std::string() : why;
    return image;
  }
  cv::Mat frame;
  {
    std::lock_guard lock(m.mutex);
    if (m.newest_id == m.handed_id) return std::nullopt;
    m.handed_id = m.newest_id;
    frame = m.newest;
  }
  auto image = m.convert(frame, why);
  std::lock_guard lock(m.mutex);
  m.problem = image ? std::string() : why;
  return image;
}

bool HwCamera::healthy() const { return problem().empty(); }

std::string HwCamera::problem() const {
  Impl& m = *impl_;
  std::lock_guard lock(m.mutex);
  if (!m.problem.empty()) return m.problem;
  if (m.live) {
    const double age_s = std::chrono::duration<double>(Clock::now() - m.newest_at).count();
    if (age_s > m.frame_timeout_s) return fmt::format("no frame for {:.1f} s", age_s);
  }
  return {};
}

}  // namespace ferret::ugv::internal
