// Camera, depth, IR and IMU frames of a world (sensor_sim.hpp). The geometry and the
// per-pixel cast are in sensor_sim_scene.cpp; this file turns hits into frames.

#include "ferret/sim/sensor_sim.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <numbers>
#include <vector>

#include "ferret/core/error.hpp"
#include "ferret/core/random.hpp"
#include "ferret/perception/object_appearance.hpp"
#include "sensor_sim_scene.hpp"

namespace ferret {
namespace {

using internal::CastBuffers;
using internal::Material;
using internal::PrimKind;

// Streams of derive_seed, so the sensors' noise never shares draws.
constexpr std::uint64_t kCameraStream = 1, kDepthStream = 2, kIrStream = 3, kImuStream = 4;

/// 65536 standard normal draws (core/random.hpp's Box-Muller, fixed seed): per-pixel
/// noise picks one with 16 random bits, a quarter of a 64-bit draw instead of a log,
/// a sqrt and a sine per value, and the same numbers on every machine.
const std::vector<float>& normal_table() {
  static const std::vector<float> table = [] {
    std::vector<float> t(65536);
    Rng rng(0x5e45e7ab1eULL);
    for (auto& v : t) v = static_cast<float>(rng.normal(0.0, 1.0));
    return t;
  }();
  return table;
}

// Albedos (linear RGB in [0, 1]); a fixed sun, with enough ambient light that faces
// turned away from it still show their edges.
struct Rgb {
  float r, g, b;
};
constexpr Rgb kSky{0.78f, 0.84f, 0.92f};
Rgb albedo(Material m, bool draw_objects) {
  switch (m) {
    case Material::kGround:
      return {0.50f, 0.46f, 0.40f};
    case Material::kStructure:
      return {0.62f, 0.62f, 0.60f};
    case Material::kEnclosure:
      return {0.58f, 0.56f, 0.52f};
    case Material::kRubble:
      return {0.52f, 0.48f, 0.44f};
    case Material::kCylinder:
      return {0.55f, 0.55f, 0.58f};
    case Material::kObject:
      if (!draw_objects) return {0.62f, 0.62f, 0.60f};
      return {kObjectColourRgb[0] / 255.0f, kObjectColourRgb[1] / 255.0f,
              kObjectColourRgb[2] / 255.0f};
  }
  return {0.5f, 0.5f, 0.5f};
}
const Eigen::Vector3d& sun_W() {
  static const Eigen::Vector3d l = Eigen::Vector3d(0.35, 0.25, 0.9).normalized();
  return l;
}
double lambert(const Eigen::Vector3d& n) { return 0.45 + 0.55 * std::max(0.0, n.dot(sun_W())); }

// Rounds half up and clamps (NaN-free inputs: radiance is finite).
std::uint8_t to_u8(double v) {
  return v <= 0.0 ? 0 : v >= 255.0 ? 255 : static_cast<std::uint8_t>(static_cast<int>(v + 0.5));
}

/// The reflectance of a marker pixel: 3 x 3 samples over the pixel (rays interpolated
/// from the neighbours' in the ray table), so that cell edges are anti-aliased.
float marker_pixel(const internal::MarkerPrim& m, const internal::RayTable& rays,
                   const Eigen::Matrix3d& R, const Eigen::Vector3d& o, int u, int v) {
  const int w = rays.width, h = rays.height;
  const auto at = [&](int uu, int vv) {
    const std::size_t i = static_cast<std::size_t>(vv) * w + uu;
    return Eigen::Vector2d(rays.x[i], rays.y[i]);
  };
  const Eigen::Vector2d c = at(u, v);
  const Eigen::Vector2d du = (at(std::min(u + 1, w - 1), v) - at(std::max(u - 1, 0), v)) /
                             (u > 0 && u < w - 1 ? 2.0 : 1.0);
  const Eigen::Vector2d dv = (at(u, std::min(v + 1, h - 1)) - at(u, std::max(v - 1, 0))) /
                             (v > 0 && v < h - 1 ? 2.0 : 1.0);
  float sum = 0.0f;
  for (int a = -1; a <= 1; ++a)
    for (int b = -1; b <= 1; ++b) {
      const Eigen::Vector2d xy = c + du * (a / 3.0) + dv * (b / 3.0);
      const Eigen::Vector3d d = R * Eigen::Vector3d(xy.x(), xy.y(), 1.0);
      const double den = m.n_W.dot(d);
      if (!(den < 0)) {
        sum += m.reflectance(1e9, 0.0);
        continue;
      }
      const Eigen::Vector3d q = m.X_MW * (o + (m.n_W.dot(m.p_W - o) / den) * d);
      sum += m.reflectance(q.x(), q.y());
    }
  return sum / 9.0f;
}

/// Separable Gaussian blur of an interleaved buffer of `channels` bytes a pixel in fixed
/// point: weights in 1/256 (sum exactly 256, so a pass's sum fits 16 bits), each pass
/// rounded back to 8 bits, borders replicated. Integer arithmetic gives the same bytes
/// on every machine; 16-bit lanes keep it fast on one core.
void gaussian_blur(std::vector<std::uint8_t>& img, int w, int h, int channels, double sigma_px) {
  const int r = std::max(1, static_cast<int>(std::ceil(3.0 * sigma_px)));
  std::vector<double> wd(2 * r + 1);
  double sum = 0;
  for (int k = -r; k <= r; ++k) sum += wd[k + r] = std::exp(-0.5 * k * k / (sigma_px * sigma_px));
  std::vector<std::uint16_t> wk(2 * r + 1);
  int total = 0;
  for (int k = 0; k <= 2 * r; ++k)
    total += wk[k] = static_cast<std::uint16_t>(std::lround(256 * wd[k] / sum));
  wk[r] = static_cast<std::uint16_t>(wk[r] + 256 - total);  // the weights sum to 256
  const std::size_t c = static_cast<std::size_t>(channels);
  const std::size_t stride = static_cast<std::size_t>(w) * c;
  // Rows are independent in each pass (several threads; the same bytes for any number).
  // Horizontal, row by row, from a copy padded with the border pixels.
  internal::for_each_interleaved(h, [&](int y) {
    std::vector<std::uint16_t> acc(stride, 0);
    std::vector<std::uint8_t> padded(stride + 2 * c * static_cast<std::size_t>(r));
    std::uint8_t* row = img.data() + static_cast<std::size_t>(y) * stride;
    for (int x = -r; x < w + r; ++x)
      for (std::size_t ch = 0; ch < c; ++ch)
        padded[c * static_cast<std::size_t>(x + r) + ch] =
            row[c * static_cast<std::size_t>(std::clamp(x, 0, w - 1)) + ch];
    for (int k = 0; k <= 2 * r; ++k) {
      const std::uint8_t* p = padded.data() + c * static_cast<std::size_t>(k);
      const std::uint16_t wt = wk[k];
      for (std::size_t i = 0; i < stride; ++i)
        acc[i] = static_cast<std::uint16_t>(acc[i] + wt * p[i]);
    }
    for (std::size_t i = 0; i < stride; ++i)
      row[i] = static_cast<std::uint8_t>((acc[i] + 128u) >> 8);
  });
  // Vertical, from a copy of the horizontally blurred frame.
  const std::vector<std::uint8_t> src = img;
  internal::for_each_interleaved(h, [&](int y) {
    std::vector<std::uint16_t> acc(stride, 0);
    for (int k = -r; k <= r; ++k) {
      const std::uint8_t* p =
          src.data() + static_cast<std::size_t>(std::clamp(y + k, 0, h - 1)) * stride;
      const std::uint16_t wt = wk[k + r];
      for (std::size_t i = 0; i < stride; ++i)
        acc[i] = static_cast<std::uint16_t>(acc[i] + wt * p[i]);
    }
    std::uint8_t* row = img.data() + static_cast<std::size_t>(y) * stride;
    for (std::size_t i = 0; i < stride; ++i)
      row[i] = static_cast<std::uint8_t>((acc[i] + 128u) >> 8);
  });
}

/// The per-pixel noise in 1/16 grey levels for one frame's sigma: integer additions in
/// the pixel loops.
std::vector<std::int32_t> noise_q4(double sigma) {
  const auto& table = normal_table();
  std::vector<std::int32_t> q(table.size());
  for (std::size_t k = 0; k < table.size(); ++k)
    q[k] = static_cast<std::int32_t>(std::lround(16.0 * sigma * table[k]));
  return q;
}

std::uint8_t noisy(std::uint8_t v, std::int32_t noise_q4) {
  return static_cast<std::uint8_t>(
      std::clamp((16 * v + noise_q4 + 8) >> 4, 0, 255));  // round half up
}

}  // namespace

Pose3 pose_from_xyz_rpy(const Eigen::Vector3d& p_m, double roll_rad, double pitch_rad,
                        double yaw_rad) {
  Pose3 X = Pose3::Identity();
  X.translation() = p_m;
  X.linear() = (Eigen::AngleAxisd(yaw_rad, Eigen::Vector3d::UnitZ()) *
                Eigen::AngleAxisd(pitch_rad, Eigen::Vector3d::UnitY()) *
                Eigen::AngleAxisd(roll_rad, Eigen::Vector3d::UnitX()))
                   .toRotationMatrix();
  return X;
}

ImuReading rpy_of(const Eigen::Matrix3d& R) {
  ImuReading r;
  r.pitch_rad = std::asin(std::clamp(-R(2, 0), -1.0, 1.0));
  r.roll_rad = std::atan2(R(2, 1), R(2, 2));
  r.yaw_rad = std::atan2(R(1, 0), R(0, 0));
  return r;
}

Pose3 optical_pose(const Pose3& X_WB, const CameraSensor& camera) {
  return X_WB * camera.X_BS * X_SC();
}

const CameraSensor& camera_for(const RobotDescription& robot, bool depth, const std::string& role,
                               const std::string& option) {
  const std::vector<std::string> roles{std::string(kRoleMarkerCamera),
                                       std::string(kRoleObjectCamera),
                                       std::string(kRoleDepthCamera)};
  std::string r = role;
  if (r.empty()) r = depth ? roles[2] : robot.kind == RobotKind::kUav ? roles[0] : roles[1];
  if (std::find(roles.begin(), roles.end(), r) == roles.end())
    throw InputError(option, "", "one of marker_camera, object_camera, depth_camera",
                     "'" + r + "'");
  const auto it = robot.roles.find(r);
  if (it == robot.roles.end() || it->second.empty())
    robot.missing_role(r, depth ? "depth frames" : "camera frames");
  const CameraSensor& camera = robot.camera(it->second.front());
  if (depth && !camera.depth)
    throw InputError(option, "", "the role of a depth camera for depth frames",
                     "'" + r + "' (" + camera.name + ", a colour camera)");
  return camera;
}

SensorSimulator::SensorSimulator(const WorldSpec& world)
    : scene_(std::make_unique<internal::Scene>(world)) {}
SensorSimulator::~SensorSimulator() = default;
SensorSimulator::SensorSimulator(SensorSimulator&&) noexcept = default;
SensorSimulator& SensorSimulator::operator=(SensorSimulator&&) noexcept = default;
namespace {

// The shaded frame, `C` bytes a pixel: RGB (3) or its BT.601 luminance (1), before
// blur and noise.
template <int C>
std::vector<std::uint8_t> shade_frame(const internal::Scene& scene, const internal::RayTable& rays,
                                      const CastBuffers& cast, const Pose3& X_WC,
                                      const CameraFrameOptions& options) {
  const int w = rays.width, h = rays.height;
  const Eigen::Matrix3d R = X_WC.linear();
  const Eigen::Vector3d o = X_WC.translation();
  std::vector<std::uint8_t> frame(static_cast<std::size_t>(w) * h * C);
  const double scale = 255.0 * options.exposure_gain;
  // Rows are shaded independently (on several threads); along a row, neighbouring
  // pixels mostly see the same flat face: its colour is computed once.
  internal::for_each_interleaved(h, [&](int v) {
    std::int32_t last_code = -2;
    std::array<std::uint8_t, C> last{};
    std::uint8_t* row = frame.data() + static_cast<std::size_t>(v) * w * C;
    for (int u = 0; u < w; ++u) {
      const std::size_t i = static_cast<std::size_t>(v) * w + u;
      const std::int32_t code = cast.code[i];
      const PrimKind kind = internal::code_kind(code);
      const bool flat =
          !(code >= 0 && (kind == PrimKind::kMarker ||
                          (kind == PrimKind::kCylinder && internal::code_face(code) == 0)));
      if (!flat || code != last_code) {
        Rgb c = kSky;
        double shade = 1.0;
        if (code >= 0) {
          const Eigen::Vector3d d = internal::ray_direction(R, rays, i);
          const Eigen::Vector3d p = o + static_cast<double>(cast.t[i]) * d;
          shade = lambert(scene.normal(code, p, d));
          switch (kind) {
            case PrimKind::kGround:
              c = albedo(Material::kGround, options.draw_objects);
              break;
            case PrimKind::kBox:
              c = albedo(scene.boxes[internal::code_index(code)].material, options.draw_objects);
              break;
            case PrimKind::kCylinder:
              c = albedo(Material::kCylinder, options.draw_objects);
              break;
            case PrimKind::kMarker: {
              const float r =
                  marker_pixel(scene.markers[internal::code_index(code)], rays, R, o, u, v);
              c = {r, r, r};
              break;
            }
          }
        }
        if constexpr (C == 3) {
          last = {to_u8(c.r * shade * scale), to_u8(c.g * shade * scale),
                  to_u8(c.b * shade * scale)};
        } else {
          last = {to_u8((0.299 * c.r + 0.587 * c.g + 0.114 * c.b) * shade * scale)};
        }
        last_code = flat ? code : -2;
      }
      for (int ch = 0; ch < C; ++ch) row[C * u + ch] = last[ch];
    }
  });
  return frame;
}

}  // namespace

RgbImage SensorSimulator::render_camera(const CameraModel& camera, const Pose3& X_WC,
                                        const CameraFrameOptions& options,
                                        std::uint64_t seed) const {
  camera.check();
  const auto rays = scene_->rays(camera);
  thread_local CastBuffers cast;  // reused: a frame's buffers are megabytes
  scene_->cast_frame(*rays, X_WC, true, cast);
  const int w = camera.width_px, h = camera.height_px;
  std::vector<std::uint8_t> frame = shade_frame<3>(*scene_, *rays, cast, X_WC, options);
  if (options.blur_sigma_px > 0) gaussian_blur(frame, w, h, 3, options.blur_sigma_px);
  RgbImage out(w, h);
  if (!(options.noise_sigma > 0)) {
    out.data = std::move(frame);
    return out;
  }
  Rng rng(derive_seed(seed, {kCameraStream}));
  const std::vector<std::int32_t> noise = noise_q4(options.noise_sigma);
  std::uint8_t* dst = out.data.data();
  const std::uint8_t* src = frame.data();
  for (std::size_t k = 0; k < frame.size(); k += 3) {
    const std::uint64_t bits = rng.next_u64();  // one draw a pixel: 16 bits a channel
    for (int ch = 0; ch < 3; ++ch)
      dst[k + ch] = noisy(src[k + ch], noise[(bits >> (16 * ch)) & 0xffff]);
  }
  return out;
}

GrayImage SensorSimulator::render_gray(const CameraModel& camera, const Pose3& X_WC,
                                       const CameraFrameOptions& options,
                                       std::uint64_t seed) const {
  camera.check();
  const auto rays = scene_->rays(camera);
  thread_local CastBuffers cast;
  scene_->cast_frame(*rays, X_WC, true, cast);
  const int w = camera.width_px, h = camera.height_px;
  GrayImage out(w, h);
  out.data = shade_frame<1>(*scene_, *rays, cast, X_WC, options);
  if (options.blur_sigma_px > 0) gaussian_blur(out.data, w, h, 1, options.blur_sigma_px);
  if (!(options.noise_sigma > 0)) return out;
  // The luminance of three independent channels' noise: sigma * |(0.299, 0.587, 0.114)|.
  constexpr double kLumaNoise = 0.66780;
  Rng rng(derive_seed(seed, {kCameraStream}));
  const std::vector<std::int32_t> noise = noise_q4(kLumaNoise * options.noise_sigma);
  std::uint8_t* px = out.data.data();
  const std::size_t n = out.data.size();
  for (std::size_t k = 0; k < n; k += 4) {
    const std::uint64_t bits = rng.next_u64();  // one draw four pixels: 16 bits each
    for (std::size_t q = 0; q < 4 && k + q < n; ++q)
      px[k + q] = noisy(px[k + q], noise[(bits >> (16 * q)) & 0xffff]);
  }
  return out;
}

DepthImageMm SensorSimulator::render_depth(const CameraModel& camera, const Pose3& X_WC,
                                           const DepthFrameOptions& options,
                                           std::uint64_t seed) const {
  camera.check();
  const auto rays = scene_->rays(camera);
  thread_local CastBuffers cast;
  scene_->cast_frame(*rays, X_WC, false, cast);  // markers are paper: the wall's depth
  const int w = camera.width_px, h = camera.height_px;
  const Eigen::Matrix3d R = X_WC.linear();
  const Eigen::Vector3d o = X_WC.translation();
  const double cos_max = std::cos(options.max_incidence_deg * std::numbers::pi / 180.0);
  const auto dropout =
      static_cast<std::uint64_t>(std::clamp(options.dropout_fraction, 0.0, 1.0) * 65536.0);
  DepthImageMm out(w, h);
  Rng rng(derive_seed(seed, {kDepthStream}));
  const auto& table = normal_table();
  for (std::size_t i = 0; i < out.data.size(); ++i) {
    const std::uint64_t bits = rng.next_u64();  // drawn for every pixel: hits never shift the noise
    const std::int32_t code = cast.code[i];
    if (code < 0) continue;
    const double z = cast.t[i];  // rays have z = 1 in C: the ray parameter is the depth
    if (z < options.min_range_m || z > options.max_range_m) continue;
    const Eigen::Vector3d d = internal::ray_direction(R, *rays, i);
    const Eigen::Vector3d n = scene_->normal(code, o + z * d, d);
    if (-n.dot(d) < cos_max * d.norm()) continue;  // grazing: the stereo match fails
    if ((bits & 0xffff) < dropout) continue;
    const double z_noisy =
        z + options.noise_coefficient_per_m * z * z * table[(bits >> 16) & 0xffff];
    out.data[i] =
        static_cast<std::uint16_t>(std::clamp(std::floor(z_noisy * 1000.0 + 0.5), 1.0, 65535.0));
  }
  return out;
}

bool SensorSimulator::markers_in_frame(const CameraModel& camera, const Pose3& X_WC) const {
  camera.check();
  return scene_->markers_in_frame(*scene_->rays(camera), X_WC);
}

std::vector<VisibleMarker> SensorSimulator::visible_markers(const CameraModel& camera,
                                                            const Pose3& X_WC) const {
  camera.check();
  const Pose3 X_CW = X_WC.inverse();
  const Eigen::Vector3d o = X_WC.translation();
  std::vector<VisibleMarker> out;
  for (const auto& m : scene_->markers) {
    const FiducialMarker& fm = m.marker;
    VisibleMarker vm;
    vm.hidden_space = m.hidden_space;
    vm.id = fm.id;
    vm.dictionary = fm.dictionary;
    vm.X_CM = X_CW * fm.X_WM;
    const double s = fm.size_m / 2;
    const Eigen::Vector2d corners_M[4] = {{-s, s}, {s, s}, {s, -s}, {-s, -s}};
    for (int k = 0; k < 4; ++k) {
      const auto px =
          camera.project(vm.X_CM * Eigen::Vector3d(corners_M[k].x(), corners_M[k].y(), 0));
      vm.corners_px[k] = px ? *px : Eigen::Vector2d::Constant(std::nan(""));
    }
    const Eigen::Vector3d to_camera = o - m.p_W;
    vm.distance_m = to_camera.norm();
    vm.off_axis_rad = std::acos(std::clamp(m.n_W.dot(to_camera) / vm.distance_m, -1.0, 1.0));
    // Samples over the black square: in the image, facing the camera, nothing between.
    constexpr int kSamples = 16;
    int seen = 0;
    for (int a = 0; a < kSamples; ++a)
      for (int b = 0; b < kSamples; ++b) {
        const Eigen::Vector3d p_M{-s + (a + 0.5) * 2 * s / kSamples,
                                  -s + (b + 0.5) * 2 * s / kSamples, 0};
        const Eigen::Vector3d p_W = fm.X_WM * p_M;
        const auto px = camera.project(X_CW * p_W);
        if (!px || !camera.in_image(*px)) continue;
        const Eigen::Vector3d ray = p_W - o;
        const double dist = ray.norm();
        if (!(m.n_W.dot(-ray) > 0)) continue;
        // The marker stands 1 mm off its surface: stop short of both.
        if (scene_->cast(o, ray / dist, nullptr) < dist - 2e-3) continue;
        ++seen;
      }
    vm.visible_fraction = static_cast<double>(seen) / (kSamples * kSamples);
    if (seen > 0) out.push_back(vm);
  }
  return out;
}

std::optional<double> SensorSimulator::cast_ray(const Eigen::Vector3d& p_W,
                                                const Eigen::Vector3d& direction_W,
                                                double max_range_m,
                                                Eigen::Vector3d* normal_W) const {
  std::int32_t code = -1;
  const double t = scene_->cast(p_W, direction_W, &code);
  if (!(t <= max_range_m)) return std::nullopt;
  if (normal_W) *normal_W = scene_->normal(code, p_W + t * direction_W, direction_W);
  return t;
}

std::vector<IrReading> SensorSimulator::ir_ranges(const RobotDescription& robot, const Pose3& X_WB,
                                                  const SensorOptions& noise,
                                                  std::uint64_t seed) const {
  const auto role = robot.roles.find(std::string(kRoleIr));
  if (role == robot.roles.end() || role->second.empty()) robot.missing_role(kRoleIr, "IR ranges");
  Rng rng(derive_seed(seed, {kIrStream}));
  std::vector<IrReading> out;
  for (const std::string& name : role->second) {
    const RangeSensor* sensor = robot.find_range_sensor(name);
    if (!sensor) continue;  // the loader guarantees the role's sensors exist
    const Pose3 X_WS = X_WB * sensor->X_BS;
    for (int k = 0; k < sensor->samples; ++k) {
      const double a = sensor->beam_angle_rad(k);
      IrReading r;
      r.sensor = name;
      r.p_WO = X_WS.translation();
      r.direction_W = X_WS.linear() * Eigen::Vector3d(std::cos(a), std::sin(a), 0.0);
      r.range_max_m = sensor->range_max_m;
      r.range_m = sensor->range_max_m;
      // Both draws for every beam, so one beam's outcome never shifts another's noise.
      const bool dropped = rng.bernoulli(noise.ir_dropout);
      const double e = rng.normal(0.0, noise.ir_noise_m);
      const auto t = cast_ray(r.p_WO, r.direction_W, sensor->range_max_m);
      // Nearer than range_min the sensor reads nothing usable (a Sharp IR's fold-back).
      if (t && *t >= sensor->range_min_m && !dropped) {
        r.hit = true;
        r.range_m = std::clamp(*t + e, sensor->range_min_m, sensor->range_max_m);
      }
      out.push_back(r);
    }
  }
  return out;
}

std::optional<Pose3> SensorSimulator::resting_pose(const Eigen::Vector2d& p_W, double yaw_rad,
                                                   double from_z_m, double ground_offset_m) const {
  const Eigen::Vector3d o{p_W.x(), p_W.y(), from_z_m};
  const Eigen::Vector3d down = -Eigen::Vector3d::UnitZ();
  Eigen::Vector3d n;
  const auto t = cast_ray(o, down, from_z_m - scene_->z_min + 1e3, &n);
  if (!t) return std::nullopt;
  const Eigen::Vector3d heading{std::cos(yaw_rad), std::sin(yaw_rad), 0.0};
  const Eigen::Vector3d x = (heading - heading.dot(n) * n).normalized();
  Pose3 X = Pose3::Identity();
  X.linear().col(0) = x;
  X.linear().col(1) = n.cross(x);
  X.linear().col(2) = n;
  X.translation() = o + *t * down + ground_offset_m * n;
  return X;
}

ImuReading SensorSimulator::imu(const Pose3& X_WB, const ImuOptions& options,
                                std::uint64_t seed) const {
  Rng rng(derive_seed(seed, {kImuStream}));
  ImuReading r = rpy_of(X_WB.linear());
  r.roll_rad += rng.normal(0.0, options.tilt_noise_rad);
  r.pitch_rad += rng.normal(0.0, options.tilt_noise_rad);
  r.yaw_rad = wrap_angle_rad(r.yaw_rad + rng.normal(0.0, options.yaw_noise_rad));
  return r;
}

}  // namespace ferret
