#include "ferret/mapping/world_spec.hpp"

#include <fmt/format.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <array>
#include <cmath>
#include <numbers>

#include "ferret/core/error.hpp"
#include "ferret/core/random.hpp"
#include "ferret/core/yaml_config.hpp"

namespace ferret {

namespace {

constexpr double kPi = std::numbers::pi;
// Points exactly on a face count as inside; the tolerance absorbs rounding of
// voxel centres that sit on a face by construction.
constexpr double kFaceTolerance_m = 1e-9;

Eigen::Vector2d rotate(const Eigen::Vector2d& v, double yaw_rad) {
  const double c = std::cos(yaw_rad), s = std::sin(yaw_rad);
  return {c * v.x() - s * v.y(), s * v.x() + c * v.y()};
}

// An axis-aligned box in the frame H of a hidden space, as a world OrientedBox.
OrientedBox box_in_h(const HiddenSpace& h, double x0, double x1, double y0, double y1, double z0,
                     double z1) {
  const Eigen::Vector2d c_W =
      h.X_WH.position() + rotate({(x0 + x1) / 2, (y0 + y1) / 2}, h.X_WH.yaw_rad);
  return OrientedBox{
      {c_W.x(), c_W.y(), h.floor_z_m + (z0 + z1) / 2}, {x1 - x0, y1 - y0, z1 - z0}, h.X_WH.yaw_rad};
}

Eigen::Vector3d to_h(const HiddenSpace& h, const Eigen::Vector3d& p_W) {
  const Eigen::Vector2d d = rotate(p_W.head<2>() - h.X_WH.position(), -h.X_WH.yaw_rad);
  return {d.x(), d.y(), p_W.z() - h.floor_z_m};
}

// Outward unit normal of the opening wall, and the along-wall axis, in H.
Eigen::Vector2d wall_normal_h(WallSide side) {
  switch (side) {
    case WallSide::kPlusX:
      return {1, 0};
    case WallSide::kMinusX:
      return {-1, 0};
    case WallSide::kPlusY:
      return {0, 1};
    case WallSide::kMinusY:
      return {0, -1};
  }
  return {1, 0};
}
bool wall_is_x(WallSide side) { return side == WallSide::kPlusX || side == WallSide::kMinusX; }

Pose3 pose_from_axes(const Eigen::Vector3d& p, const Eigen::Vector3d& x, const Eigen::Vector3d& y,
                     const Eigen::Vector3d& z) {
  Pose3 X = Pose3::Identity();
  X.linear().col(0) = x.normalized();
  X.linear().col(1) = y.normalized();
  X.linear().col(2) = z.normalized();
  X.translation() = p;
  return X;
}

}  // namespace

bool OrientedBox::contains(const Eigen::Vector3d& p_W) const {
  const Eigen::Vector2d d = rotate(p_W.head<2>() - center_m.head<2>(), -yaw_rad);
  return std::abs(d.x()) <= size_m.x() / 2 + kFaceTolerance_m &&
         std::abs(d.y()) <= size_m.y() / 2 + kFaceTolerance_m &&
         std::abs(p_W.z() - center_m.z()) <= size_m.z() / 2 + kFaceTolerance_m;
}

bool VerticalCylinder::contains(const Eigen::Vector3d& p_W) const {
  return (p_W.head<2>() - center_m).norm() <= radius_m + kFaceTolerance_m &&
         p_W.z() >= base_z_m - kFaceTolerance_m &&
         p_W.z() <= base_z_m + height_m + kFaceTolerance_m;
}

std::vector<OrientedBox> HiddenSpace::solids() const {
  const double hx = interior_size_m.x() / 2, hy = interior_size_m.y() / 2, lz = interior_size_m.z();
  const double t = wall_thickness_m;
  std::vector<OrientedBox> out;
  out.push_back(box_in_h(*this, -hx, hx, -hy, hy, lz, lz + t));  // roof
  out.push_back(box_in_h(*this, -hx, hx, -hy, hy, -t, 0));       // floor slab
  // Walls reach from below the floor slab to the roof's top; the x walls cover the corners.
  struct Wall {
    WallSide side;
    double x0, x1, y0, y1;
  };
  const Wall walls[] = {{WallSide::kPlusX, hx, hx + t, -hy - t, hy + t},
                        {WallSide::kMinusX, -hx - t, -hx, -hy - t, hy + t},
                        {WallSide::kPlusY, -hx, hx, hy, hy + t},
                        {WallSide::kMinusY, -hx, hx, -hy - t, -hy}};
  for (const Wall& w : walls) {
    if (w.side != opening_wall) {
      out.push_back(box_in_h(*this, w.x0, w.x1, w.y0, w.y1, -t, lz + t));
      continue;
    }
    // Cut the opening (floor level, centred at opening_offset_m along the wall):
    // below-floor strip, the two sides, and the lintel above.
    const double c = opening_offset_m, half_w = opening_width_m / 2, h = opening_height_m;
    out.push_back(box_in_h(*this, w.x0, w.x1, w.y0, w.y1, -t, 0));
    if (wall_is_x(w.side)) {
      out.push_back(box_in_h(*this, w.x0, w.x1, w.y0, c - half_w, 0, lz + t));
      out.push_back(box_in_h(*this, w.x0, w.x1, c + half_w, w.y1, 0, lz + t));
      out.push_back(box_in_h(*this, w.x0, w.x1, c - half_w, c + half_w, h, lz + t));
    } else {
      out.push_back(box_in_h(*this, w.x0, c - half_w, w.y0, w.y1, 0, lz + t));
      out.push_back(box_in_h(*this, c + half_w, w.x1, w.y0, w.y1, 0, lz + t));
      out.push_back(box_in_h(*this, c - half_w, c + half_w, w.y0, w.y1, h, lz + t));
    }
  }
  return out;
}

bool HiddenSpace::interior_contains(const Eigen::Vector3d& p_W) const {
  const Eigen::Vector3d p = to_h(*this, p_W);
  const double hx = interior_size_m.x() / 2, hy = interior_size_m.y() / 2, t = wall_thickness_m;
  if (p.z() < 0 || p.z() > interior_size_m.z()) return false;
  if (std::abs(p.x()) <= hx && std::abs(p.y()) <= hy) return true;
  // The tunnel through the opening wall.
  if (p.z() > opening_height_m) return false;
  const Eigen::Vector2d n = wall_normal_h(opening_wall);
  const double across = wall_is_x(opening_wall) ? p.y() : p.x();
  const double depth = n.dot(p.head<2>()) - (wall_is_x(opening_wall) ? hx : hy);
  return std::abs(across - opening_offset_m) <= opening_width_m / 2 && depth >= 0 && depth <= t;
}

Eigen::AlignedBox3d HiddenSpace::outer_bounds_m() const {
  Eigen::AlignedBox3d out;
  for (const auto& s : solids()) {
    // Half extents of the yawed box along the world axes.
    const double c = std::abs(std::cos(s.yaw_rad)), sn = std::abs(std::sin(s.yaw_rad));
    const Eigen::Vector3d half{(c * s.size_m.x() + sn * s.size_m.y()) / 2,
                               (sn * s.size_m.x() + c * s.size_m.y()) / 2, s.size_m.z() / 2};
    out.extend(s.center_m - half);
    out.extend(s.center_m + half);
  }
  return out;
}

Eigen::Vector3d HiddenSpace::to_world(const Eigen::Vector3d& p_H) const {
  const Eigen::Vector2d xy = X_WH.position() + rotate(p_H.head<2>(), X_WH.yaw_rad);
  return {xy.x(), xy.y(), floor_z_m + p_H.z()};
}

bool WorldSpec::in_bounds(const Eigen::Vector3d& p) const {
  return (p.array() >= bounds_min_m.array()).all() && (p.array() <= bounds_max_m.array()).all();
}

std::vector<OrientedBox> WorldSpec::solid_boxes() const {
  std::vector<OrientedBox> out = boxes;
  out.insert(out.end(), rubble.begin(), rubble.end());
  for (const auto& o : objects) out.push_back(o.box);
  for (const auto& h : hidden_spaces) {
    const auto s = h.solids();
    out.insert(out.end(), s.begin(), s.end());
  }
  return out;
}

bool WorldSpec::is_solid(const Eigen::Vector3d& p) const {
  if (!in_bounds(p)) return false;
  if (p.z() <= ground.height_at(p.x(), p.y()) + kFaceTolerance_m) return true;
  for (const auto& c : cylinders)
    if (c.contains(p)) return true;
  for (const auto& b : solid_boxes())
    if (b.contains(p)) return true;
  return false;
}

int WorldSpec::find_hidden_space(const std::string& name) const {
  for (std::size_t i = 0; i < hidden_spaces.size(); ++i)
    if (hidden_spaces[i].name == name) return static_cast<int>(i);
  return -1;
}

// ---------------------------------------------------------------------------------
// Parsing

namespace {

using yaml::MapReader;

double positive(const MapReader& r, std::string_view key) {
  const auto v = r.get<double>(key);
  if (!std::isfinite(v) || v <= 0) r.fail(key, "a number > 0", fmt::format("{}", v));
  return v;
}
double positive_or(const MapReader& r, std::string_view key, double fallback) {
  return r.has(key) ? positive(r, key) : fallback;
}
double finite_or(const MapReader& r, std::string_view key, double fallback) {
  const double v = r.get_or<double>(key, fallback);
  if (!std::isfinite(v)) r.fail(key, "a finite number", fmt::format("{}", v));
  return v;
}

template <int N>
Eigen::Matrix<double, N, 1> vec(const MapReader& r, std::string_view key) {
  const auto v = r.get_list<double>(key, N);
  Eigen::Matrix<double, N, 1> out;
  for (int i = 0; i < N; ++i) {
    if (!std::isfinite(v[i])) r.fail(key, fmt::format("{} finite numbers", N));
    out[i] = v[i];
  }
  return out;
}

template <int N>
Eigen::Matrix<double, N, 1> positive_vec(const MapReader& r, std::string_view key) {
  const auto v = vec<N>(r, key);
  for (int i = 0; i < N; ++i)
    if (v[i] <= 0)
      throw InputError(r.source(), r.field_path(key) + "[" + std::to_string(i) + "]", "a size > 0",
                       fmt::format("{}", v[i]));
  return v;
}

std::vector<MapReader> optional_list(const MapReader& r, std::string_view key) {
  return r.has(key) ? r.child_list(key) : std::vector<MapReader>{};
}

WallSide parse_wall(const MapReader& r, std::string_view key) {
  const auto s = r.get<std::string>(key);
  if (s == "+x") return WallSide::kPlusX;
  if (s == "-x") return WallSide::kMinusX;
  if (s == "+y") return WallSide::kPlusY;
  if (s == "-y") return WallSide::kMinusY;
  r.fail(key, "one of +x, -x, +y, -y", "'" + s + "'");
}

void place_marker(HiddenSpace& h, const MapReader& m) {
  m.allow_only({"id", "size_m", "family", "dictionary", "placement", "position_m", "rpy_deg"});
  FiducialMarker& marker = h.marker;
  if (m.has("family")) {
    marker.dictionary.family =
        parse_marker_family(m.get<std::string>("family"), m.source(), m.field_path("family"));
    // Each family's default dictionary: the paper's tag36h11 for AprilTag.
    if (marker.dictionary.family == MarkerFamily::kAprilTag) marker.dictionary.name = "tag36h11";
  }
  marker.dictionary.name = m.get_or<std::string>("dictionary", marker.dictionary.name);
  check_marker_dictionary(marker.dictionary, m.source(), m.field_path("dictionary"));
  const int ids = marker_id_count(marker.dictionary);
  marker.id = m.get<int>("id");
  if (marker.id < 0 || marker.id >= ids)
    m.fail("id", fmt::format("an id in [0, {}] of {}", ids - 1, marker.dictionary.name),
           std::to_string(marker.id));
  marker.size_m = positive_or(m, "size_m", marker.size_m);
  const Eigen::Vector3d up_W = Eigen::Vector3d::UnitZ();
  const Eigen::Vector2d n2 = rotate(wall_normal_h(h.opening_wall), h.X_WH.yaw_rad);
  const Eigen::Vector3d n_W{n2.x(), n2.y(), 0};  // outward normal of the opening wall
  const double s = marker.size_m, lz = h.interior_size_m.z(), t = h.wall_thickness_m;
  // Markers sit 1 mm off their surface so they never fall inside a solid voxel's test.
  constexpr double kStandOff_m = 0.001;
  if (m.has("position_m") || m.has("rpy_deg")) {
    const auto p = vec<3>(m, "position_m");
    const auto rpy = vec<3>(m, "rpy_deg");
    marker.X_WM = Pose3::Identity();
    marker.X_WM.translation() = p;
    marker.X_WM.linear() = (Eigen::AngleAxisd(deg_to_rad(rpy.z()), Eigen::Vector3d::UnitZ()) *
                            Eigen::AngleAxisd(deg_to_rad(rpy.y()), Eigen::Vector3d::UnitY()) *
                            Eigen::AngleAxisd(deg_to_rad(rpy.x()), Eigen::Vector3d::UnitX()))
                               .toRotationMatrix();
    if (m.has("placement"))
      m.fail("placement", "no placement when position_m and rpy_deg are given");
    return;
  }
  const std::string placement = m.get_or<std::string>("placement", "wall");
  if (placement == "wall") {
    // Upright on the outer face, centred in the wall above the opening.
    const double room = lz + t - h.opening_height_m;
    if (s > room)
      m.fail("size_m",
             fmt::format("a marker that fits the {:.3f} m of wall above the opening", room),
             fmt::format("{}", s));
    const Eigen::Vector3d p = h.p_WE + n_W * kStandOff_m + up_W * (h.opening_height_m + room / 2);
    marker.X_WM = pose_from_axes(p, up_W.cross(n_W), up_W, n_W);
  } else if (placement == "roof") {
    // Flat on the roof at the opening wall, image "up" pointing out of the wall.
    const Eigen::Vector3d p = h.p_WE - n_W * (s / 2) + up_W * (lz + t + kStandOff_m);
    marker.X_WM = pose_from_axes(p, n_W.cross(up_W), n_W, up_W);
  } else if (placement == "ground") {
    // Flat on the ground in front of the opening, image "up" pointing at it.
    const Eigen::Vector3d p = h.p_WE + n_W * (s / 2 + 0.05) + up_W * kStandOff_m;
    marker.X_WM = pose_from_axes(p, (-n_W).cross(up_W), -n_W, up_W);
  } else {
    m.fail("placement", "wall, roof or ground", "'" + placement + "'");
  }
}

HiddenSpace parse_hidden_space(const MapReader& r, const GroundSpec& ground) {
  r.allow_only({"name", "center_m", "yaw_deg", "floor_z_m", "interior_size_m", "wall_thickness_m",
                "opening", "marker"});
  HiddenSpace h;
  h.name = r.get<std::string>("name");
  const auto c = vec<2>(r, "center_m");
  h.X_WH = Pose2{c.x(), c.y(), wrap_angle_rad(deg_to_rad(finite_or(r, "yaw_deg", 0.0)))};
  h.floor_z_m = finite_or(r, "floor_z_m", ground.height_at(c.x(), c.y()));
  h.interior_size_m = positive_vec<3>(r, "interior_size_m");
  h.wall_thickness_m = positive_or(r, "wall_thickness_m", h.wall_thickness_m);
  const MapReader o = r.child("opening");
  o.allow_only({"wall", "width_m", "height_m", "offset_m"});
  h.opening_wall = parse_wall(o, "wall");
  h.opening_width_m = positive(o, "width_m");
  h.opening_height_m = positive(o, "height_m");
  h.opening_offset_m = finite_or(o, "offset_m", 0.0);
  const double wall_len = wall_is_x(h.opening_wall) ? h.interior_size_m.y() : h.interior_size_m.x();
  if (std::abs(h.opening_offset_m) + h.opening_width_m / 2 > wall_len / 2)
    o.fail("width_m",
           fmt::format("an opening within the {} m interior wall (with offset_m)", wall_len),
           fmt::format("{}", h.opening_width_m));
  if (h.opening_height_m > h.interior_size_m.z())
    o.fail("height_m", fmt::format("at most the interior height {}", h.interior_size_m.z()),
           fmt::format("{}", h.opening_height_m));
  // Ground inside the interior would cut into the space (sloped ground: raise floor_z_m).
  const double hx = h.interior_size_m.x() / 2, hy = h.interior_size_m.y() / 2;
  for (const double sx : {-hx, hx})
    for (const double sy : {-hy, hy}) {
      const Eigen::Vector3d p = h.to_world({sx, sy, 0});
      if (ground.height_at(p.x(), p.y()) > h.floor_z_m + 1e-6)
        r.fail(
            "floor_z_m", "a floor at or above the ground under the whole interior",
            fmt::format("{} (ground reaches {:.3f})", h.floor_z_m, ground.height_at(p.x(), p.y())));
    }
  // Entry E: bottom centre of the opening on the outer face; entering heads along -n.
  const Eigen::Vector2d n = wall_normal_h(h.opening_wall);
  const double reach = (wall_is_x(h.opening_wall) ? hx : hy) + h.wall_thickness_m;
  const Eigen::Vector2d along =
      wall_is_x(h.opening_wall) ? Eigen::Vector2d{0, 1} : Eigen::Vector2d{1, 0};
  const Eigen::Vector2d e_H = n * reach + along * h.opening_offset_m;
  h.p_WE = h.to_world({e_H.x(), e_H.y(), 0});
  h.entry_yaw_rad = wrap_angle_rad(h.X_WH.yaw_rad + std::atan2(-n.y(), -n.x()));
  place_marker(h, r.child("marker"));
  return h;
}

// Corners of a box in plan.
std::array<Eigen::Vector2d, 4> plan_corners(const OrientedBox& b) {
  std::array<Eigen::Vector2d, 4> out;
  int k = 0;
  for (const double sx : {-0.5, 0.5})
    for (const double sy : {-0.5, 0.5})
      out[k++] = b.center_m.head<2>() + rotate({sx * b.size_m.x(), sy * b.size_m.y()}, b.yaw_rad);
  return out;
}

// Separating-axis test of two boxes that share the vertical axis; touching is not overlapping.
bool boxes_overlap(const OrientedBox& a, const OrientedBox& b) {
  if (std::abs(a.center_m.z() - b.center_m.z()) >= (a.size_m.z() + b.size_m.z()) / 2) return false;
  const auto ca = plan_corners(a), cb = plan_corners(b);
  for (const double yaw : {a.yaw_rad, b.yaw_rad})
    for (const Eigen::Vector2d& axis : {rotate({1, 0}, yaw), rotate({0, 1}, yaw)}) {
      double amin = 1e300, amax = -1e300, bmin = 1e300, bmax = -1e300;
      for (const auto& p : ca)
        amin = std::min(amin, axis.dot(p)), amax = std::max(amax, axis.dot(p));
      for (const auto& p : cb)
        bmin = std::min(bmin, axis.dot(p)), bmax = std::max(bmax, axis.dot(p));
      if (amax <= bmin || bmax <= amin) return false;
    }
  return true;
}

bool box_meets_cylinder(const OrientedBox& b, const VerticalCylinder& c) {
  if (b.center_m.z() + b.size_m.z() / 2 <= c.base_z_m ||
      b.center_m.z() - b.size_m.z() / 2 >= c.base_z_m + c.height_m)
    return false;
  const Eigen::Vector2d d = rotate(c.center_m - b.center_m.head<2>(), -b.yaw_rad);
  const Eigen::Vector2d half = b.size_m.head<2>() / 2;
  return (d - d.cwiseMax(-half).cwiseMin(half)).norm() < c.radius_m;
}

// The whole enclosure (interior and walls) as one box.
OrientedBox outer_box(const HiddenSpace& h) {
  const double t = h.wall_thickness_m;
  const Eigen::Vector3d size = h.interior_size_m + Eigen::Vector3d::Constant(2 * t);
  return OrientedBox{
      {h.X_WH.x_m, h.X_WH.y_m, h.floor_z_m + h.interior_size_m.z() / 2}, size, h.X_WH.yaw_rad};
}

WorldObject parse_object(const MapReader& r, const WorldSpec& w) {
  r.allow_only({"name", "hidden_space", "position_m", "size_m", "yaw_deg"});
  WorldObject o;
  o.name = r.get<std::string>("name");
  const auto xy = vec<2>(r, "position_m");
  const Eigen::Vector3d size = positive_vec<3>(r, "size_m");
  const double yaw = deg_to_rad(finite_or(r, "yaw_deg", 0.0));
  if (r.has("hidden_space")) {
    const auto hs = r.get<std::string>("hidden_space");
    o.hidden_space = w.find_hidden_space(hs);
    if (o.hidden_space < 0)
      r.fail("hidden_space", "the name of a hidden space listed above", "'" + hs + "'");
    const HiddenSpace& h = w.hidden_spaces[o.hidden_space];
    // position_m is in the space's frame H; the object rests on its floor.
    o.box = OrientedBox{h.to_world({xy.x(), xy.y(), size.z() / 2}), size,
                        wrap_angle_rad(h.X_WH.yaw_rad + yaw)};
    const double r_xy = size.head<2>().norm() / 2;
    if (std::abs(xy.x()) + r_xy > h.interior_size_m.x() / 2 ||
        std::abs(xy.y()) + r_xy > h.interior_size_m.y() / 2 || size.z() > h.interior_size_m.z())
      r.fail("position_m",
             fmt::format(
                 "an object wholly inside hidden space '{}' (interior {} x {} m, centred at 0)",
                 h.name, h.interior_size_m.x(), h.interior_size_m.y()));
  } else {
    o.box =
        OrientedBox{{xy.x(), xy.y(), w.ground.height_at(xy.x(), xy.y()) + size.z() / 2}, size, yaw};
  }
  return o;
}

RubbleSpec parse_rubble(const MapReader& r) {
  r.allow_only({"seed", "count", "region_m", "size_min_m", "size_max_m", "clearance_m"});
  RubbleSpec s;
  s.seed = r.get<std::uint64_t>("seed");
  s.count = r.get<int>("count");
  if (s.count < 0 || s.count > 100000)
    r.fail("count", "an integer in [0, 100000]", std::to_string(s.count));
  const MapReader region = r.child("region_m");
  region.allow_only({"min", "max"});
  s.region_min_m = vec<2>(region, "min");
  s.region_max_m = vec<2>(region, "max");
  if ((s.region_max_m.array() <= s.region_min_m.array()).any())
    region.fail("max", "a corner above and right of min");
  s.size_min_m = positive_vec<3>(r, "size_min_m");
  s.size_max_m = positive_vec<3>(r, "size_max_m");
  if ((s.size_max_m.array() < s.size_min_m.array()).any())
    r.fail("size_max_m", "sizes >= size_min_m");
  s.clearance_m = r.get_or<double>("clearance_m", s.clearance_m);
  if (!std::isfinite(s.clearance_m) || s.clearance_m < 0) r.fail("clearance_m", "a number >= 0");
  return s;
}

// Seeded rubble: boxes drawn uniformly in the region, resting on the ground,
// redrawn when they would crowd a hidden space or the drop zone.
std::vector<OrientedBox> generate_rubble(const WorldSpec& w, const RubbleSpec& s,
                                         const std::string& field) {
  Rng rng(s.seed);
  std::vector<OrientedBox> out;
  const double slope = std::abs(w.ground.slope_x) + std::abs(w.ground.slope_y);
  auto crowds = [&](const Eigen::Vector2d& c, double radius) {
    for (const auto& h : w.hidden_spaces) {
      const Eigen::Vector3d p = to_h(h, {c.x(), c.y(), 0});
      const double mx = h.interior_size_m.x() / 2 + h.wall_thickness_m + s.clearance_m + radius;
      const double my = h.interior_size_m.y() / 2 + h.wall_thickness_m + s.clearance_m + radius;
      if (std::abs(p.x()) < mx && std::abs(p.y()) < my) return true;
    }
    return w.drop_zone &&
           (c - w.drop_zone->center_m).norm() < w.drop_zone->radius_m + s.clearance_m + radius;
  };
  constexpr int kTriesPerBox = 200;
  for (int k = 0; k < s.count; ++k) {
    bool placed = false;
    for (int attempt = 0; attempt < kTriesPerBox && !placed; ++attempt) {
      const Eigen::Vector3d size{rng.uniform(s.size_min_m.x(), s.size_max_m.x()),
                                 rng.uniform(s.size_min_m.y(), s.size_max_m.y()),
                                 rng.uniform(s.size_min_m.z(), s.size_max_m.z())};
      const Eigen::Vector2d c{rng.uniform(s.region_min_m.x(), s.region_max_m.x()),
                              rng.uniform(s.region_min_m.y(), s.region_max_m.y())};
      const double yaw = rng.uniform(-kPi / 2, kPi / 2);
      const double radius = size.head<2>().norm() / 2;
      if (crowds(c, radius)) continue;
      if (c.x() - radius < w.bounds_min_m.x() || c.x() + radius > w.bounds_max_m.x() ||
          c.y() - radius < w.bounds_min_m.y() || c.y() + radius > w.bounds_max_m.y())
        continue;
      // Sunk by the slope over its half-diagonal so no corner floats on sloped ground.
      const double bottom = w.ground.height_at(c.x(), c.y()) - slope * radius;
      out.push_back(OrientedBox{{c.x(), c.y(), bottom + size.z() / 2}, size, yaw});
      placed = true;
    }
    if (!placed)
      throw InputError(
          w.source.string(), field + ".count",
          fmt::format("a region with room for {} boxes clear of hidden spaces and the drop zone",
                      s.count),
          fmt::format("only {} fit", out.size()));
  }
  return out;
}

void check_inside_bounds(const WorldSpec& w, const MapReader& r, std::string_view key,
                         const Eigen::Vector3d& lo, const Eigen::Vector3d& hi) {
  if ((lo.array() < w.bounds_min_m.array()).any() || (hi.array() > w.bounds_max_m.array()).any())
    r.fail(key, "geometry inside bounds_m");
}

WorldSpec parse_world_node(const YAML::Node& root, const std::string& source) {
  const MapReader r(root, source);
  r.allow_only({"name", "resolution_m", "bounds_m", "ground", "boxes", "cylinders", "hidden_spaces",
                "objects", "drop_zone", "rubble"});
  WorldSpec w;
  w.source = source;
  w.name = r.get_or<std::string>("name", std::filesystem::path(source).stem().string());
  w.resolution_m = r.get_in_range("resolution_m", 0.005, 10.0);
  const MapReader b = r.child("bounds_m");
  b.allow_only({"min", "max"});
  w.bounds_min_m = vec<3>(b, "min");
  w.bounds_max_m = vec<3>(b, "max");
  for (int i = 0; i < 3; ++i)
    if (w.bounds_max_m[i] <= w.bounds_min_m[i] + w.resolution_m)
      throw InputError(source, fmt::format("bounds_m.max[{}]", i),
                       "more than one voxel above bounds_m.min",
                       fmt::format("{}", w.bounds_max_m[i]));
  // OctoMap keys are 16 bit: coordinates must stay within [-2^15, 2^15 - 1] voxels (octomap#289).
  const double key_limit_m = 32767.0 * w.resolution_m;
  for (const char* corner : {"min", "max"}) {
    const Eigen::Vector3d& v = std::string(corner) == "min" ? w.bounds_min_m : w.bounds_max_m;
    if (v.cwiseAbs().maxCoeff() >= key_limit_m)
      b.fail(corner,
             fmt::format("coordinates within +-{} m (OctoMap's key range at this resolution)",
                         key_limit_m));
  }

  if (const auto g = r.optional_child("ground")) {
    g->allow_only({"height_m", "slope"});
    w.ground.height_m = finite_or(*g, "height_m", 0.0);
    if (g->has("slope")) {
      const auto s = vec<2>(*g, "slope");
      w.ground.slope_x = s.x();
      w.ground.slope_y = s.y();
    }
  }

  const auto boxes = optional_list(r, "boxes");
  for (const auto& br : boxes) {
    br.allow_only({"name", "center_m", "size_m", "yaw_deg"});
    OrientedBox box;
    box.size_m = positive_vec<3>(br, "size_m");
    box.yaw_rad = wrap_angle_rad(deg_to_rad(finite_or(br, "yaw_deg", 0.0)));
    const auto c = br.get_list<double>("center_m");
    if (c.size() == 2) {  // resting on the ground
      box.center_m = {c[0], c[1], w.ground.height_at(c[0], c[1]) + box.size_m.z() / 2};
    } else if (c.size() == 3) {
      box.center_m = {c[0], c[1], c[2]};
    } else {
      br.fail("center_m", "[x, y] (resting on the ground) or [x, y, z]",
              fmt::format("{} values", c.size()));
    }
    if (!box.center_m.allFinite()) br.fail("center_m", "finite numbers");
    w.boxes.push_back(box);
  }
  for (const auto& cr : optional_list(r, "cylinders")) {
    cr.allow_only({"name", "center_m", "base_z_m", "radius_m", "height_m"});
    VerticalCylinder c;
    c.center_m = vec<2>(cr, "center_m");
    c.base_z_m = finite_or(cr, "base_z_m", w.ground.height_at(c.center_m.x(), c.center_m.y()));
    c.radius_m = positive(cr, "radius_m");
    c.height_m = positive(cr, "height_m");
    w.cylinders.push_back(c);
  }
  const auto spaces = optional_list(r, "hidden_spaces");
  for (const auto& hr : spaces) {
    HiddenSpace h = parse_hidden_space(hr, w.ground);
    if (w.find_hidden_space(h.name) >= 0)
      hr.fail("name", "a name not used by another hidden space", "'" + h.name + "'");
    const Eigen::AlignedBox3d extent = h.outer_bounds_m();
    check_inside_bounds(w, hr, "center_m", extent.min(), extent.max());
    for (const auto& other : w.hidden_spaces)
      if (boxes_overlap(outer_box(h), outer_box(other)))
        hr.fail("center_m",
                fmt::format("a hidden space clear of '{}' (their walls overlap)", other.name));
    w.hidden_spaces.push_back(std::move(h));
  }
  for (const auto& orr : optional_list(r, "objects")) {
    w.objects.push_back(parse_object(orr, w));
    // An object buried in an obstacle could never be reached.
    const OrientedBox& o = w.objects.back().box;
    for (std::size_t i = 0; i < w.boxes.size(); ++i)
      if (boxes_overlap(o, w.boxes[i]))
        orr.fail("position_m", fmt::format("an object clear of boxes[{}]", i));
    for (std::size_t i = 0; i < w.cylinders.size(); ++i)
      if (box_meets_cylinder(o, w.cylinders[i]))
        orr.fail("position_m", fmt::format("an object clear of cylinders[{}]", i));
  }
  if (const auto d = r.optional_child("drop_zone")) {
    d->allow_only({"center_m", "radius_m"});
    w.drop_zone = DropZone{vec<2>(*d, "center_m"), positive(*d, "radius_m")};
  }
  const auto rubble = optional_list(r, "rubble");
  for (std::size_t i = 0; i < rubble.size(); ++i) {
    w.rubble_specs.push_back(parse_rubble(rubble[i]));
    const auto more = generate_rubble(w, w.rubble_specs.back(), fmt::format("rubble[{}]", i));
    w.rubble.insert(w.rubble.end(), more.begin(), more.end());
  }
  return w;
}

}  // namespace

WorldSpec parse_world(const std::string& yaml_text, const std::string& source) {
  return parse_world_node(yaml::load_string(yaml_text, source), source);
}

WorldSpec load_world(const std::filesystem::path& yaml_path) {
  return parse_world_node(yaml::load_file(yaml_path), yaml_path.string());
}

}  // namespace ferret
