#include "ferret/uav/landing_zone.hpp"

#include <fmt/format.h>

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <limits>

#include "ferret/core/error.hpp"
#include "ferret/core/number.hpp"
#include "ferret/planning/mission_config.hpp"
#include "ferret/urdf/robot_description.hpp"
#include "landing_points.hpp"

namespace ferret {
namespace {

// A frame's points never span more than this many cells (10 m of range and a fov of
// 120 degrees: 0.12 million); beyond it the frame is bad input. The clearance grid has
// sixteen times as many, and the detector keeps 11 doubles for each of those (and 14 a
// coarse cell, 16 for the step test's windows): at most about 0.4 GB.
constexpr long kMaxGridCells = 250'000;

// out[t] = max of in over [t - r, t + r] (clipped to the line) along every line of a
// grid: `lines` lines of `len` elements, element t of line l at l * line_stride + t *
// stride. Van Herk's blocks of 2r + 1: a block's running maxima from its start and from
// its end, so each element costs three comparisons whatever r is.
void running_max(const std::vector<double>& in, std::vector<double>& out, int len, int lines,
                 std::size_t stride, std::size_t line_stride, int r) {
  const double kLow = -std::numeric_limits<double>::infinity();
  const int w = 2 * r + 1;
  const int n = ((len + 2 * r + w - 1) / w) * w;  // padded by r on each side, whole blocks
  std::vector<double> g(static_cast<std::size_t>(n)), h(static_cast<std::size_t>(n));
  for (int l = 0; l < lines; ++l) {
    const std::size_t base = static_cast<std::size_t>(l) * line_stride;
    const auto value = [&](int x) {  // padded coordinates
      const int t = x - r;
      return t >= 0 && t < len ? in[base + static_cast<std::size_t>(t) * stride] : kLow;
    };
    for (int b = 0; b < n; b += w) {
      g[b] = value(b);
      for (int x = b + 1; x < b + w; ++x) g[x] = std::max(g[x - 1], value(x));
      h[b + w - 1] = value(b + w - 1);
      for (int x = b + w - 2; x >= b; --x) h[x] = std::max(h[x + 1], value(x));
    }
    for (int t = 0; t < len; ++t)
      out[base + static_cast<std::size_t>(t) * stride] = std::max(h[t], g[t + 2 * r]);
  }
}

// Summed-area table: S(i, j) = sum of v over cells [0, i) x [0, j).
class Summed {
 public:
  Summed(int nx, int ny) : nx_(nx), ny_(ny), s_(static_cast<std::size_t>(nx + 1) * (ny + 1), 0.0) {}
  void build(const std::vector<double>& v) {
    for (int j = 0; j < ny_; ++j) {
      double row = 0.0;
      for (int i = 0; i < nx_; ++i) {
        row += v[static_cast<std::size_t>(j) * nx_ + i];
        at(i + 1, j + 1) = at(i + 1, j) + row;
      }
    }
  }
  // Sum over cells [i0, i1] x [j0, j1] (inclusive).
  [[nodiscard]] double sum(int i0, int j0, int i1, int j1) const {
    return at(i1 + 1, j1 + 1) - at(i0, j1 + 1) - at(i1 + 1, j0) + at(i0, j0);
  }

 private:
  [[nodiscard]] double& at(int i, int j) { return s_[static_cast<std::size_t>(j) * (nx_ + 1) + i]; }
  [[nodiscard]] double at(int i, int j) const {
    return s_[static_cast<std::size_t>(j) * (nx_ + 1) + i];
  }
  int nx_, ny_;
  std::vector<double> s_;
};

struct Plane {
  double a = 0.0, b = 0.0, c = 0.0;  // z = a x + b y + c, in grid-local coordinates
  [[nodiscard]] double at(double x, double y) const { return a * x + b * y + c; }
};

}  // namespace

const char* to_string(LandingReject reason) {
  switch (reason) {
    case LandingReject::kNone:
      return "safe";
    case LandingReject::kUnobserved:
      return "unobserved";
    case LandingReject::kSlope:
      return "slope";
    case LandingReject::kRoughness:
      return "roughness";
    case LandingReject::kStep:
      return "step";
    case LandingReject::kClearance:
      return "clearance";
    case LandingReject::kOutOfReach:
      return "out of reach";
  }
  return "?";
}

LandingZoneDetector::Options LandingZoneDetector::Options::for_robot(const RobotDescription& robot,
                                                                     const MissionConfig* mission) {
  Options o;
  o.footprint_radius_m = robot.circumscribed_radius_m;
  // The tether leaves the UAV where it is attached (or at the spool); that point, not
  // the body's centre, must be within l_0 of the point above the opening.
  if (!robot.tether_attachments.empty())
    o.p_ZW_xy_m = robot.tether_attachments.front().X_BF.translation().head<2>();
  else if (robot.winch_spool)
    o.p_ZW_xy_m = robot.winch_spool->X_BF.translation().head<2>();
  if (mission != nullptr) o.reach_m = mission->tether.entry_offset_m;
  return o;
}

void LandingZoneDetector::Options::check(const std::string& source) const {
  check_number(footprint_radius_m, NumberRange::positive(20.0, "m"), source, "footprint_radius_m");
  check_number(margin_m, NumberRange::non_negative(10.0, "m"), source, "margin_m");
  check_number(max_slope_deg, NumberRange::closed(0.0, 89.0, "deg"), source, "max_slope_deg");
  check_number(slope_sigmas, NumberRange::closed(0.0, 10.0, ""), source, "slope_sigmas");
  check_number(slope_allowance_deg, NumberRange::closed(0.0, 89.0, "deg"), source,
               "slope_allowance_deg");
  check_number(max_roughness_m, NumberRange::positive(10.0, "m"), source, "max_roughness_m");
  check_number(max_step_m, NumberRange::positive(10.0, "m"), source, "max_step_m");
  check_number(step_allowance_m, NumberRange::non_negative(10.0, "m"), source, "step_allowance_m");
  if (step_allowance_m >= max_step_m)
    throw InputError(source, "step_allowance_m", "less than max_step_m",
                     fmt::format("{} >= {}", step_allowance_m, max_step_m));
  check_number(min_clearance_m, NumberRange::non_negative(20.0, "m"), source, "min_clearance_m");
  check_number(taller_than_m, NumberRange::positive(10.0, "m"), source, "taller_than_m");
  check_number(taller_allowance_m, NumberRange::non_negative(10.0, "m"), source,
               "taller_allowance_m");
  if (taller_allowance_m >= taller_than_m)
    throw InputError(source, "taller_allowance_m", "less than taller_than_m",
                     fmt::format("{} >= {}", taller_allowance_m, taller_than_m));
  check_number(cell_size_m, NumberRange::closed(0.01, 2.0, "m"), source, "cell_size_m");
  if (hover_cell_size_m != 0.0)
    check_number(hover_cell_size_m, NumberRange::closed(0.01, 2.0, "m"), source,
                 "hover_cell_size_m");
  check_number(hover_min_frames, NumberRange::closed(1, kMaxHoverFrames), source,
               "hover_min_frames");
  check_number(min_points_per_cell, NumberRange::closed(1, 1e6), source, "min_points_per_cell");
  check_number(min_depth_m, NumberRange::non_negative(100.0, "m"), source, "min_depth_m");
  check_number(max_depth_m, NumberRange::positive(100.0, "m"), source, "max_depth_m");
  if (max_depth_m <= min_depth_m)
    throw InputError(source, "max_depth_m", "a depth above min_depth_m",
                     fmt::format("{} <= {}", max_depth_m, min_depth_m));
  check_number(reach_m, NumberRange::positive(1000.0, "m"), source, "reach_m");
  if (p_WE)
    for (int k = 0; k < 3; ++k)
      check_number((*p_WE)[k], NumberRange::closed(-1e5, 1e5, "m"), source, "opening");
  check_number(max_zones, NumberRange::closed(1, 10000), source, "max_zones");
  // A disc and its clearance of more than 250 cells' radius (25 m at the default 0.1 m)
  // is not a landing-zone question, and its clearance windows (16 a cell) would not fit.
  for (const auto& [cell, field] :
       {std::pair{cell_size_m, "cell_size_m"}, std::pair{hover_cell_size_m, "hover_cell_size_m"}})
    if (cell > 0.0 && (footprint_radius_m + margin_m + min_clearance_m) / cell > 250.0)
      throw InputError(source, field, "at most 250 cells in the radius of a disc and its clearance",
                       fmt::format("{}", cell));
}

LandingZoneDetector::LandingZoneDetector(Options options) : options_(std::move(options)) {
  options_.check("landing-zone options");
  const double radius = options_.footprint_radius_m + options_.margin_m;
  ring_ = window_offsets(0.25 * options_.cell_size_m, radius + options_.min_clearance_m + 0.5);
  step_disc_ = window_offsets(0.5 * options_.cell_size_m, radius);
  if (options_.hover_cell_size_m > 0.0 && options_.hover_cell_size_m != options_.cell_size_m) {
    Options hover = options_;
    const double ratio = options_.hover_cell_size_m / options_.cell_size_m;
    hover.margin_m = options_.margin_m * ratio;
    hover.step_allowance_m =
        std::min(options_.step_allowance_m * ratio, 0.99 * options_.max_step_m);
    hover.slope_allowance_deg = std::min(options_.slope_allowance_deg * ratio, 89.0);
    hover.taller_allowance_m =
        std::min(options_.taller_allowance_m * ratio, 0.99 * options_.taller_than_m);
    hover.cell_size_m = options_.hover_cell_size_m;
    hover.hover_cell_size_m = 0.0;
    hover_ = std::make_shared<const LandingZoneDetector>(std::move(hover));
  }
}

const LandingZoneDetector& LandingZoneDetector::for_frames(std::size_t frames) const {
  return hover_ && frames >= static_cast<std::size_t>(options_.hover_min_frames) ? *hover_ : *this;
}

std::vector<LandingZoneDetector::WindowOffset> LandingZoneDetector::window_offsets(double unit,
                                                                                   double limit) {
  const int r = static_cast<int>(std::ceil(limit / unit)) + 1;
  std::vector<WindowOffset> out;
  for (int b = -r - 2; b <= r; ++b)
    for (int a = -r - 2; a <= r; ++a) {
      const double dist = unit * std::hypot(std::max({0, a, -a - 2}), std::max({0, b, -b - 2}));
      if (dist < limit) out.push_back({a, b, dist});
    }
  std::stable_sort(out.begin(), out.end(),
                   [](const WindowOffset& x, const WindowOffset& y) { return x.dist < y.dist; });
  return out;
}

LandingResult LandingZoneDetector::detect(const std::vector<PosedDepthFrame>& frames,
                                          const CameraModel& camera) const {
  const LandingZoneDetector& judge = for_frames(frames.size());
  if (frames.size() == 1 && frames.front().depth != nullptr)
    return judge.detect(*frames.front().depth, camera, frames.front().X_WC);
  // Fused first: it refuses an empty list before front() is read.
  const DepthImageMm fused = fuse_depth_frames(frames, camera);
  return judge.detect(fused, camera, frames.front().X_WC);
}

LandingResult LandingZoneDetector::detect(const DepthFrameFusion& frames) const {
  return for_frames(frames.frames()).detect(frames.fused(), frames.camera(), frames.X_WC());
}

LandingResult LandingZoneDetector::detect(const DepthImageMm& depth, const CameraModel& camera,
                                          const Pose3& X_WC) const {
  const Options& o = options_;
  LandingResult result;
  std::vector<Eigen::Vector3d> border;
  const std::vector<Eigen::Vector3d> points =
      internal::depth_to_world_points(depth, camera, X_WC, o.min_depth_m, o.max_depth_m, &border);
  if (points.empty()) {
    result.reason = "no safe zone in view: no depth returns in the frame";
    return result;
  }

  // The height grid, aligned with the world axes, over the points' extent.
  Eigen::Vector2d lo = points.front().head<2>(), hi = lo;
  for (const auto& p : points) {
    lo = lo.cwiseMin(p.head<2>());
    hi = hi.cwiseMax(p.head<2>());
  }
  const double cell = o.cell_size_m;
  const int nx = static_cast<int>(std::floor((hi.x() - lo.x()) / cell)) + 1;
  const int ny = static_cast<int>(std::floor((hi.y() - lo.y()) / cell)) + 1;
  if (static_cast<long>(nx) * ny > kMaxGridCells)
    throw InputError("depth frame", "extent",
                     fmt::format("at most {} cells of {} m", kMaxGridCells, cell),
                     fmt::format("{} x {} cells", nx, ny));
  const auto idx = [nx](int i, int j) { return static_cast<std::size_t>(j) * nx + i; };
  const std::size_t n_cells = static_cast<std::size_t>(nx) * ny;
  // The clearance test's grid: windows of half a cell, at a quarter cell's stride
  // (window p covers quarter cells p and p + 1; quarter cells 4i to 4i + 3 make coarse
  // cell i). Something taller beside the disc is judged in these: a pole or a block that
  // covers part of a cell at the ring's edge raises that cell's mean by only the part it
  // covers, and slipped under the taller-than test in coarse cells (seeds 1-3 of the
  // evaluation, with the margin off: six unsafe choices) and, at the ring's outer edge,
  // in half-size cells side by side (a rubble corner at the ring's edge, seen first 7 cm
  // farther out, on a frame without noise). Overlapping windows halve how far beyond a
  // thing's edge the first window it covers enough may lie. A window with too few returns
  // of its own takes the highest mean of the coarse cells it touches.
  const double quarter = 0.25 * cell;
  const int qnx = 4 * nx, qny = 4 * ny;
  const auto qidx = [qnx](int i, int j) { return static_cast<std::size_t>(j) * qnx + i; };
  const std::size_t n_quarter = static_cast<std::size_t>(qnx) * qny;
  // Per quarter cell: count and sums of the points (x, y relative to the grid origin, z
  // minus a reference height, to keep the sums well conditioned). (x / quarter is exactly
  // four times x / cell, so a point's quarter cell lies in its coarse cell.)
  const double z_ref = points.front().z();
  std::vector<double> qcnt(n_quarter, 0.0), qsx(n_quarter, 0.0), qsy(n_quarter, 0.0),
      qsz(n_quarter, 0.0);
  for (const auto& p : points) {
    const int i = std::min(qnx - 1, static_cast<int>((p.x() - lo.x()) / quarter));
    const int j = std::min(qny - 1, static_cast<int>((p.y() - lo.y()) / quarter));
    const std::size_t k = qidx(i, j);
    qcnt[k] += 1.0;
    qsx[k] += p.x() - lo.x();
    qsy[k] += p.y() - lo.y();
    qsz[k] += p.z() - z_ref;
  }
  // A window of `size` x `size` quarter cells from (i0, j0): its count and sums.
  struct WindowSum {
    double n = 0.0, x = 0.0, y = 0.0, z = 0.0;
  };
  const auto window_sum = [&](int i0, int j0, int size) {
    WindowSum w;
    for (int j = j0; j < j0 + size; ++j)
      for (int i = i0; i < i0 + size; ++i) {
        const std::size_t k = qidx(i, j);
        w.n += qcnt[k];
        w.x += qsx[k];
        w.y += qsy[k];
        w.z += qsz[k];
      }
    return w;
  };
  // Per coarse cell: the sums of its sixteen quarter cells.
  std::vector<double> cnt(n_cells, 0.0), sx(n_cells, 0.0), sy(n_cells, 0.0), sz(n_cells, 0.0);
  for (int j = 0; j < qny; ++j)
    for (int i = 0; i < qnx; ++i) {
      const std::size_t f = qidx(i, j), k = idx(i / 4, j / 4);
      cnt[k] += qcnt[f];
      sx[k] += qsx[f];
      sy[k] += qsy[f];
      sz[k] += qsz[f];
    }
  // A cell the image's edge runs through is seen only in part: what stands in its
  // unseen part is unknown, so the cell counts as unobserved.
  for (const auto& p : border) {
    const int i = static_cast<int>(std::floor((p.x() - lo.x()) / cell));
    const int j = static_cast<int>(std::floor((p.y() - lo.y()) / cell));
    if (i >= 0 && j >= 0 && i < nx && j < ny) cnt[idx(i, j)] = 0.0;
  }
  // Cell means; the plane is fitted to them (not to the points) so that a cell counts
  // once however close it is to the camera, and the depth noise averages out first.
  std::vector<double> obs(n_cells, 0.0), mx(n_cells, 0.0), my(n_cells, 0.0), mz(n_cells, 0.0);
  std::vector<double> xx(n_cells, 0.0), xy(n_cells, 0.0), yy(n_cells, 0.0), xz(n_cells, 0.0),
      yz(n_cells, 0.0), zz(n_cells, 0.0);
  for (std::size_t k = 0; k < n_cells; ++k) {
    if (cnt[k] < o.min_points_per_cell) continue;
    obs[k] = 1.0;
    mx[k] = sx[k] / cnt[k];
    my[k] = sy[k] / cnt[k];
    mz[k] = sz[k] / cnt[k];
    xx[k] = mx[k] * mx[k];
    xy[k] = mx[k] * my[k];
    yy[k] = my[k] * my[k];
    xz[k] = mx[k] * mz[k];
    yz[k] = my[k] * mz[k];
    zz[k] = mz[k] * mz[k];
  }
  // Windows: their own mean with enough returns, else the highest of the coarse cells
  // they touch; unobserved when a coarse cell they touch is (too few returns, or the
  // image's edge runs through it). The last window of a row or column has no second
  // quarter cell and stays unobserved.
  // (A window sees only what its coarse cells see: all of them must be observed.)
  const auto touches_unobserved = [&](int i0, int j0, int size) {
    const int ci0 = i0 / 4, ci1 = (i0 + size - 1) / 4, cj0 = j0 / 4, cj1 = (j0 + size - 1) / 4;
    return obs[idx(ci0, cj0)] <= 0.0 || obs[idx(ci1, cj0)] <= 0.0 || obs[idx(ci0, cj1)] <= 0.0 ||
           obs[idx(ci1, cj1)] <= 0.0;
  };
  constexpr double kMinWindowPoints = 4.0;
  std::vector<double> fobs(n_quarter, 0.0), fmx(n_quarter, 0.0), fmy(n_quarter, 0.0),
      fmz(n_quarter, 0.0);
  for (int j = 0; j + 1 < qny; ++j)
    for (int i = 0; i + 1 < qnx; ++i) {
      if (touches_unobserved(i, j, 2)) continue;
      const std::size_t f = qidx(i, j);
      fobs[f] = 1.0;
      const WindowSum w = window_sum(i, j, 2);
      if (w.n >= kMinWindowPoints) {
        fmx[f] = w.x / w.n;
        fmy[f] = w.y / w.n;
        fmz[f] = w.z / w.n;
      } else {
        const int ci0 = i / 4, ci1 = (i + 1) / 4, cj0 = j / 4, cj1 = (j + 1) / 4;
        std::size_t hk = idx(ci0, cj0);
        for (const std::size_t k : {idx(ci1, cj0), idx(ci0, cj1), idx(ci1, cj1)})
          if (mz[k] > mz[hk]) hk = k;
        fmx[f] = mx[hk];
        fmy[f] = my[hk];
        fmz[f] = mz[hk];
      }
    }
  // Observed cells per window (summed-area table); the plane's sums are taken over
  // each disc's cells.
  Summed observed(nx, ny);
  observed.build(obs);
  enum { kN, kX, kY, kZ, kXX, kXY, kYY, kXZ, kYZ, kZZ };

  const double radius = o.footprint_radius_m + o.margin_m;
  const int h =
      static_cast<int>(std::ceil(radius / cell - 0.5));  // cells whose centre may lie in the disc
  const double ring_outer = radius + o.min_clearance_m;
  const double clearance_cap = o.min_clearance_m + 0.5;  // reported up to this
  // Windows (quarter cells) from a centre to the end of the clearance looked for.
  const int hc = static_cast<int>(std::ceil((radius + clearance_cap) / quarter)) + 2;
  const int hr = static_cast<int>(std::ceil(ring_outer / cell));
  // Disc mask offsets: every cell that overlaps the disc (centre within radius + half a
  // cell diagonal), so that nothing under the footprint escapes the step test.
  const double overlap = radius + cell * std::sqrt(0.5);
  std::vector<Eigen::Vector2i> disc;
  for (int dj = -h - 1; dj <= h + 1; ++dj)
    for (int di = -h - 1; di <= h + 1; ++di)
      if (std::hypot(di * cell, dj * cell) <= overlap) disc.emplace_back(di, dj);
  int hd = 0;
  for (const auto& d : disc) hd = std::max({hd, std::abs(d.x()), std::abs(d.y())});
  const int h_window = std::max(h, hd);
  const double max_step = o.max_step_m - o.step_allowance_m;
  const double taller = o.taller_than_m - o.taller_allowance_m;

  // The step test's windows: a cell's size every half cell (window p covers half cells p
  // and p + 1, quarter cells 2p to 2p + 3), so that they overlap by half. A block that
  // reaches over the footprint's rim from outside covers the cells the rim cuts in part
  // and lifts their means by the part it covers: a 0.105 m block 1 cm from the rim
  // measured 0.066 m in the cells (a 1280 x 720 frame of the evaluation), where the
  // margin was to show it whole. Some window that overlaps the disc holds a straight
  // edge whole. The plane is still fitted to the cells.
  // (Offsets in step_disc_: a candidate's centre is half-cell boundary 2i + 1.)
  const int hnx = 2 * nx, hny = 2 * ny;
  const auto hidx = [hnx](int i, int j) { return static_cast<std::size_t>(j) * hnx + i; };
  const std::size_t n_half = static_cast<std::size_t>(hnx) * hny;
  std::vector<double> sobs(n_half, 0.0), smx(n_half, 0.0), smy(n_half, 0.0), smz(n_half, 0.0);
  for (int q = 0; q + 1 < hny; ++q)
    for (int p = 0; p + 1 < hnx; ++p) {
      if (touches_unobserved(2 * p, 2 * q, 4)) continue;
      const WindowSum w = window_sum(2 * p, 2 * q, 4);
      if (w.n < o.min_points_per_cell) continue;  // its cells, all observed, stand for it
      const std::size_t k = hidx(p, q);
      sobs[k] = 1.0;
      smx[k] = w.x / w.n;
      smy[k] = w.y / w.n;
      smz[k] = w.z / w.n;
    }

  // Upper envelope for the clearance test: the highest window mean within hc windows of
  // every window, by two passes of a running maximum (rows, then columns; van Herk's
  // blocks, so the cost does not grow with hc).
  const double kLow = -std::numeric_limits<double>::infinity();
  std::vector<double> top(n_quarter, kLow);
  for (std::size_t k = 0; k < n_quarter; ++k)
    if (fobs[k] > 0.0) top[k] = fmz[k];
  std::vector<double> row_max(n_quarter, kLow), win_max(n_quarter, kLow);
  running_max(top, row_max, qnx, qny, 1, static_cast<std::size_t>(qnx), hc);
  running_max(row_max, win_max, qny, qnx, static_cast<std::size_t>(qnx), 1, hc);
  // The clearance's windows (ring_) are offsets from a coarse cell's centre, quarter
  // boundary 4i + 2; every one the walk below reaches lies within hc of window 4i + 1.

  const Eigen::Vector2d nadir = X_WC.translation().head<2>();
  std::vector<LandingZone> safe;
  int counts[7] = {0, 0, 0, 0, 0, 0, 0};
  int n_candidates = 0;
  const int stride = std::max(1, static_cast<int>(std::round(0.3 / cell)));
  const auto reject = [&](LandingZone z, LandingReject why, int i, int j) {
    ++counts[static_cast<int>(why)];
    if (i % stride == 0 && j % stride == 0 && result.rejected.size() < 4000) {
      z.reject = why;
      result.rejected.push_back(z);
    }
  };

  for (int j = h_window; j < ny - h_window; ++j)
    for (int i = h_window; i < nx - h_window; ++i) {
      ++n_candidates;
      const double cxl = (i + 0.5) * cell, cyl = (j + 0.5) * cell;  // grid-local centre
      LandingZone z;
      z.center_m = {lo.x() + cxl, lo.y() + cyl, z_ref + (obs[idx(i, j)] > 0 ? mz[idx(i, j)] : 0.0)};
      const int i0 = i - h_window, i1 = i + h_window, j0 = j - h_window, j1 = j + h_window;
      const double n = observed.sum(i0, j0, i1, j1);
      // The disc's own cells must all be observed (checked below); the square around
      // it, which the plane is fitted over, may miss its corners at the image's edge.
      const double full = static_cast<double>((2 * h_window + 1) * (2 * h_window + 1));
      if (n < 0.7 * full) {
        reject(z, LandingReject::kUnobserved, i, j);
        continue;
      }
      // Least squares z = a x + b y + c over the cell means of the disc's own cells,
      // every one of them observed: the plane the footprint stands on. (Fitted over the
      // square window around the disc, a plane that also took in a step's top beyond
      // the disc came out flatter than the slope under the footprint: seed 2 of the
      // evaluation chose two zones on a 15.2 degree slope that way.)
      double m[10] = {0, 0, 0, 0, 0, 0, 0, 0, 0, 0};
      bool disc_seen = true;
      for (const auto& d : disc) {
        const std::size_t k = idx(i + d.x(), j + d.y());
        if (obs[k] <= 0.0) {
          disc_seen = false;
          break;
        }
        m[kN] += 1.0;
        m[kX] += mx[k];
        m[kY] += my[k];
        m[kZ] += mz[k];
        m[kXX] += xx[k];
        m[kXY] += xy[k];
        m[kYY] += yy[k];
        m[kXZ] += xz[k];
        m[kYZ] += yz[k];
        m[kZZ] += zz[k];
      }
      if (!disc_seen) {
        reject(z, LandingReject::kUnobserved, i, j);
        continue;
      }
      const double nd = m[kN];
      const double ex = m[kX] / nd, ey = m[kY] / nd, ez = m[kZ] / nd;
      const double cxx = m[kXX] / nd - ex * ex;
      const double cxy = m[kXY] / nd - ex * ey;
      const double cyy = m[kYY] / nd - ey * ey;
      const double cxz = m[kXZ] / nd - ex * ez;
      const double cyz = m[kYZ] / nd - ey * ez;
      const double czz = m[kZZ] / nd - ez * ez;
      const double det = cxx * cyy - cxy * cxy;
      if (!(det > 1e-12 * cell * cell * cell * cell)) {  // cells collapsed onto a line (a wall)
        reject(z, LandingReject::kUnobserved, i, j);
        continue;
      }
      Plane pl;
      pl.a = (cyy * cxz - cxy * cyz) / det;
      pl.b = (cxx * cyz - cxy * cxz) / det;
      pl.c = ez - pl.a * ex - pl.b * ey;
      z.center_m.z() = z_ref + pl.at(cxl, cyl);
      const double grad = std::hypot(pl.a, pl.b);
      z.slope_deg = rad_to_deg(std::atan(grad));
      const double residual_var = std::max(0.0, czz - pl.a * cxz - pl.b * cyz);
      z.roughness_m = std::sqrt(residual_var);
      // The gradient's standard error from the residuals (taken as independent; real
      // relief under the disc only widens it), along the direction the cells constrain
      // least: sigma^2 (X^T X)^-1 with sigma^2 = nd residual_var / (nd - 3) and
      // X^T X = nd cov, whose inverse's largest eigenvalue is inv_cov_max / nd.
      const double inv_cov_max = 0.5 * (cxx + cyy + std::hypot(cxx - cyy, 2.0 * cxy)) / det;
      const double grad_sigma = std::sqrt(residual_var / std::max(1.0, nd - 3.0) * inv_cov_max);
      z.slope_sigma_deg = rad_to_deg(grad_sigma / (1.0 + grad * grad));
      if (o.p_WE) {
        const Eigen::Vector2d winch = z.center_m.head<2>() + o.p_ZW_xy_m;
        z.distance_to_opening_m = (winch - o.p_WE->head<2>()).norm();
      } else {
        z.distance_to_opening_m = std::numeric_limits<double>::quiet_NaN();
      }
      const double slope_margin_deg =
          std::max(o.slope_sigmas * z.slope_sigma_deg, o.slope_allowance_deg);
      if (z.slope_deg + slope_margin_deg > o.max_slope_deg) {
        reject(z, LandingReject::kSlope, i, j);
        continue;
      }
      if (z.roughness_m > o.max_roughness_m) {
        reject(z, LandingReject::kRoughness, i, j);
        continue;
      }
      // The step: peak-to-peak of the cell means about the plane over the disc. (A
      // difference of neighbouring cells would miss a step whose edge halves a cell.)
      double rmin = std::numeric_limits<double>::infinity(), rmax = -rmin;
      bool unobserved = false;
      for (const auto& d : disc) {
        const std::size_t k = idx(i + d.x(), j + d.y());
        if (obs[k] <= 0.0) {
          unobserved = true;
          break;
        }
        const double r = mz[k] - pl.at(mx[k], my[k]);
        rmin = std::min(rmin, r);
        rmax = std::max(rmax, r);
      }
      if (unobserved) {
        reject(z, LandingReject::kUnobserved, i, j);
        continue;
      }
      // (The cells' peak-to-peak above, and the windows' that overlap the disc.)
      for (const WindowOffset& d : step_disc_) {
        const int p = 2 * i + 1 + d.di, q = 2 * j + 1 + d.dj;
        if (p < 0 || q < 0 || p >= hnx || q >= hny) continue;
        const std::size_t k = hidx(p, q);
        if (sobs[k] <= 0.0) continue;
        const double r = smz[k] - pl.at(smx[k], smy[k]);
        rmin = std::min(rmin, r);
        rmax = std::max(rmax, r);
      }
      z.step_m = rmax - rmin;
      if (z.step_m > max_step) {
        reject(z, LandingReject::kStep, i, j);
        continue;
      }
      // Clearance: the nearest cell beyond the disc that is taller than the plane (or,
      // within the required clearance, not observed: unknown is not free).
      z.clearance_m = clearance_cap;
      const double plane_low =
          pl.at(cxl, cyl) - (std::abs(pl.a) + std::abs(pl.b)) * (hc + 2) * quarter;
      const bool ring_observed =
          i - hr >= 0 && j - hr >= 0 && i + hr < nx && j + hr < ny &&
          observed.sum(i - hr, j - hr, i + hr, j + hr) >= (2.0 * hr + 1) * (2.0 * hr + 1);
      // (Window 4i + 1 is centred on the candidate.)
      if (!ring_observed || win_max[qidx(4 * i + 1, 4 * j + 1)] > plane_low + taller) {
        double nearest = radius + clearance_cap;
        for (const WindowOffset& f : ring_) {
          const int ci = 4 * i + 2 + f.di, cj = 4 * j + 2 + f.dj;
          const bool inside = ci >= 0 && cj >= 0 && ci < qnx && cj < qny;
          if (!inside || fobs[qidx(ci, cj)] <= 0.0) {
            if (f.dist < ring_outer) {
              nearest = f.dist;
              break;
            }
            continue;
          }
          const std::size_t k = qidx(ci, cj);
          if (fmz[k] > pl.at(fmx[k], fmy[k]) + taller) {
            nearest = f.dist;
            break;
          }
        }
        z.clearance_m = std::max(0.0, nearest - radius);
      }
      if (z.clearance_m < o.min_clearance_m) {
        reject(z, LandingReject::kClearance, i, j);
        continue;
      }
      if (o.p_WE && z.distance_to_opening_m > o.reach_m) {
        reject(z, LandingReject::kOutOfReach, i, j);
        continue;
      }
      // Safety margin: the tightest of the criteria, each as the fraction of its limit
      // left (clearance: of the extra clearance looked for beyond the minimum).
      double margin =
          std::min({1.0 - (z.slope_deg + slope_margin_deg) / std::max(o.max_slope_deg, 1e-9),
                    1.0 - z.roughness_m / o.max_roughness_m, 1.0 - z.step_m / max_step,
                    (z.clearance_m - o.min_clearance_m) / (clearance_cap - o.min_clearance_m)});
      margin = std::clamp(margin, 0.0, 1.0);
      // Distance: to the opening within the reach when there is one (the miniUGV's
      // tether is what matters), else to the point below the camera (less flying).
      const double distance_term = o.p_WE ? 0.5 * z.distance_to_opening_m / o.reach_m
                                          : 0.05 * (z.center_m.head<2>() - nadir).norm();
      z.score = margin - distance_term;
      ++counts[0];
      safe.push_back(z);
    }

  std::sort(safe.begin(), safe.end(), [](const LandingZone& a, const LandingZone& b) {
    if (a.score != b.score) return a.score > b.score;
    if (a.center_m.x() != b.center_m.x()) return a.center_m.x() < b.center_m.x();
    return a.center_m.y() < b.center_m.y();
  });
  // Distinct zones: a zone suppresses the others within a footprint of it.
  for (const auto& z : safe) {
    bool near = false;
    for (const auto& kept : result.zones)
      if ((kept.center_m.head<2>() - z.center_m.head<2>()).norm() < o.footprint_radius_m) {
        near = true;
        break;
      }
    if (near) continue;
    result.zones.push_back(z);
    if (static_cast<int>(result.zones.size()) >= o.max_zones) break;
  }
  result.no_safe_zone = result.zones.empty();
  if (result.no_safe_zone) {
    if (n_candidates == 0) {
      result.reason = fmt::format(
          "no safe zone in view: the observed ground ({:.2f} x {:.2f} m) is smaller than a "
          "{:.2f} m disc",
          hi.x() - lo.x(), hi.y() - lo.y(), 2 * radius);
    } else {
      std::string parts;
      for (int r = 1; r < 7; ++r)
        if (counts[r] > 0)
          parts += fmt::format("{}{} {}", parts.empty() ? "" : ", ", counts[r],
                               to_string(static_cast<LandingReject>(r)));
      result.reason =
          fmt::format("no safe zone in view: {} candidates rejected ({})", n_candidates, parts);
    }
  }
  return result;
}

}  // namespace ferret
