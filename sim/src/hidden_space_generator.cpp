// generate_hidden_space(): obstacles are placed one at a time, each kept only if every
// place the robot could stand on before is still connected to the rest (or now under
// the obstacle), so the free space stays one piece for the robot whatever the seed.

#include "ferret/sim/hidden_space_generator.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <deque>

#include "ferret/core/error.hpp"
#include "ferret/core/random.hpp"

namespace ferret {
namespace {

struct Rect {
  double x0, y0, x1, y1;
  [[nodiscard]] bool overlaps(const Rect& o, double margin = 0.0) const {
    return x0 < o.x1 + margin && o.x0 < x1 + margin && y0 < o.y1 + margin && o.y0 < y1 + margin;
  }
};

// The paper's sensors' zones, relative to the start (x along its heading).
constexpr double kZone1Near = 1.2, kZone1Far = 3.8, kZone1HalfWidth = 0.3;
constexpr double kZone24Near = 2.0, kZone24Far = 3.2, kZone24Inner = 1.0, kZone24Outer = 1.8;
constexpr double kFarZonesFrom = 4.5;  // beyond both sensors' 4 m
constexpr double kWall = 0.1;

class Layout {
 public:
  explicit Layout(const HiddenSpaceGeneratorOptions& o) {
    g_.resolution_m = o.resolution_m;
    g_.width = static_cast<int>(std::lround(o.width_m / o.resolution_m));
    g_.height = static_cast<int>(std::lround(o.height_m / o.resolution_m));
    map_ = OccupancyMap2D::filled(g_, CellState::kFree);
    blocked_.assign(g_.size(), 0);
    seen_.assign(g_.size(), 0);
    inflate_cells_ = static_cast<int>(std::ceil(o.robot_radius_m / o.resolution_m));
    // The walls leave one rectangle for the robot: every place it can stand is one
    // connected piece, and add() keeps it so.
    add({0, 0, o.width_m, kWall}, false);
    add({0, o.height_m - kWall, o.width_m, o.height_m}, false);
    add({0, 0, kWall, o.height_m}, false);
    add({o.width_m - kWall, 0, o.width_m, o.height_m}, false);
  }

  void set_start(const Pose2& start) { start_ = g_.cell_at(start.x_m, start.y_m); }

  // Places `r` unless it would cut a place the robot can stand on off from the rest.
  bool add(const Rect& r, bool check = true) {
    const Cell lo = g_.cell_at(r.x0 + 1e-9, r.y0 + 1e-9);
    const Cell hi = g_.cell_at(r.x1 - 1e-9, r.y1 - 1e-9);
    const int k = inflate_cells_;
    // The cells the robot's centre can no longer take: the rectangle grown by its radius.
    const Cell flo{std::max(0, lo.i - k), std::max(0, lo.j - k)};
    const Cell fhi{std::min(g_.width - 1, hi.i + k), std::min(g_.height - 1, hi.j + k)};
    std::vector<std::size_t> newly;
    for (int j = flo.j; j <= fhi.j; ++j)
      for (int i = flo.i; i <= fhi.i; ++i)
        if (!blocked_[g_.index({i, j})]) newly.push_back(g_.index({i, j}));
    if (check) {
      if (start_.i >= flo.i && start_.i <= fhi.i && start_.j >= flo.j && start_.j <= fhi.j)
        return false;
      for (const std::size_t c : newly) blocked_[c] = 1;
      if (!ring_stays_connected(flo, fhi)) {
        for (const std::size_t c : newly) blocked_[c] = 0;
        return false;
      }
    }
    for (int j = std::max(0, lo.j); j <= std::min(g_.height - 1, hi.j); ++j)
      for (int i = std::max(0, lo.i); i <= std::min(g_.width - 1, hi.i); ++i)
        map_.at({i, j}) = CellState::kOccupied;
    for (const std::size_t c : newly) blocked_[c] = 1;
    return true;
  }

  [[nodiscard]] const OccupancyMap2D& map() const { return map_; }

 private:
  // Any path that crossed the footprint [flo, fhi] entered and left it through the
  // ring of cells around it. If the ring's open cells are one run along the ring, every
  // such path goes round instead; otherwise the runs must still meet elsewhere, which
  // a flood from one of them tells (stopping once it has met them all).
  bool ring_stays_connected(Cell flo, Cell fhi) {
    std::vector<Cell> ring;  // the loop, each cell 4-adjacent to the next
    for (int i = flo.i - 1; i <= fhi.i + 1; ++i) ring.push_back({i, flo.j - 1});
    for (int j = flo.j; j <= fhi.j + 1; ++j) ring.push_back({fhi.i + 1, j});
    for (int i = fhi.i; i >= flo.i - 1; --i) ring.push_back({i, fhi.j + 1});
    for (int j = fhi.j; j >= flo.j; --j) ring.push_back({flo.i - 1, j});
    const auto open = [&](Cell c) { return g_.contains(c) && !blocked_[g_.index(c)]; };
    // One cell of each run of open ring cells (the loop is cyclic).
    std::vector<Cell> runs;
    const std::size_t n = ring.size();
    std::size_t first_closed = n;
    for (std::size_t q = 0; q < n; ++q)
      if (!open(ring[q])) {
        first_closed = q;
        break;
      }
    if (first_closed == n) return true;  // all open: one run
    for (std::size_t q = 1; q <= n; ++q) {
      const Cell c = ring[(first_closed + q) % n], prev = ring[(first_closed + q - 1) % n];
      if (open(c) && !open(prev)) runs.push_back(c);
    }
    if (runs.size() <= 1) return true;
    // Flood from the first run until every other run's cell is met.
    ++stamp_;
    std::size_t left = runs.size() - 1;
    std::deque<Cell> queue{runs[0]};
    seen_[g_.index(runs[0])] = stamp_;
    std::vector<std::size_t> targets;
    for (std::size_t r = 1; r < runs.size(); ++r) targets.push_back(g_.index(runs[r]));
    while (!queue.empty() && left > 0) {
      const Cell c = queue.front();
      queue.pop_front();
      for (const Cell d :
           {Cell{c.i + 1, c.j}, Cell{c.i - 1, c.j}, Cell{c.i, c.j + 1}, Cell{c.i, c.j - 1}}) {
        if (!open(d) || seen_[g_.index(d)] == stamp_) continue;
        seen_[g_.index(d)] = stamp_;
        if (std::find(targets.begin(), targets.end(), g_.index(d)) != targets.end()) --left;
        queue.push_back(d);
      }
    }
    return left == 0;
  }

  GridGeometry g_;
  OccupancyMap2D map_;
  std::vector<char> blocked_;
  std::vector<std::uint32_t> seen_;
  std::uint32_t stamp_ = 0;
  int inflate_cells_ = 2;
  Cell start_{0, 0};
};

void check_option(double v, double lo, double hi, const char* option, const char* unit) {
  if (!(std::isfinite(v) && v >= lo && v <= hi))
    throw InputError(option, "", fmt::format("{} in [{:g}, {:g}]", unit, lo, hi),
                     fmt::format("{}", v));
}

}  // namespace

const char* to_string(HiddenSpaceClutter clutter) {
  return clutter == HiddenSpaceClutter::kSparse ? "sparse" : "dense";
}

std::optional<HiddenSpaceClutter> parse_hidden_space_clutter(const std::string& text) {
  if (text == "sparse") return HiddenSpaceClutter::kSparse;
  if (text == "dense") return HiddenSpaceClutter::kDense;
  return std::nullopt;
}

GeneratedHiddenSpace generate_hidden_space(const HiddenSpaceGeneratorOptions& o) {
  check_option(o.width_m, 8.0, 64.0, "--size", "a width in metres");
  check_option(o.height_m, 5.0, 64.0, "--size", "a height in metres");
  check_option(o.resolution_m, 0.02, 0.2, "--resolution", "metres");
  check_option(o.robot_radius_m, 0.02, 0.5, "robot_radius_m", "metres");
  GeneratedHiddenSpace out;
  out.options = o;
  Rng rng(derive_seed(o.seed, {stable_hash("generate-hidden")}));
  const bool dense = o.clutter == HiddenSpaceClutter::kDense;
  const double W = o.width_m, H = o.height_m;

  // The start: 1 m from the left wall, anywhere across that leaves room for zones 2 and 4.
  const double margin_y = kZone24Outer + 0.5;
  const double y_lo = std::max(margin_y, 0.35 * H), y_hi = std::min(H - margin_y, 0.65 * H);
  // On a 0.1 m step (inside [y_lo, y_hi]), so the file's numbers read well.
  out.start = {1.0, std::clamp(std::round(rng.uniform(y_lo, y_hi) * 10.0) / 10.0, y_lo, y_hi), 0.0};
  const double xs = out.start.x_m, ys = out.start.y_m;
  const Rect z1{xs + kZone1Near, ys - kZone1HalfWidth, xs + kZone1Far, ys + kZone1HalfWidth};
  const Rect z2{xs + kZone24Near, ys + kZone24Inner, xs + kZone24Far, ys + kZone24Outer};
  const Rect z4{xs + kZone24Near, ys - kZone24Outer, xs + kZone24Far, ys - kZone24Inner};
  const Rect z3{xs + kFarZonesFrom, ys + 0.2, W - 0.5, H - 0.5};
  const Rect z5{xs + kFarZonesFrom, 0.5, W - 0.5, ys - 0.2};
  for (const auto& [id, z] : {std::pair{1, z1}, {2, z2}, {3, z3}, {4, z4}, {5, z5}})
    out.zones.push_back({id, z.x0, z.y0, z.x1, z.y1});

  Layout layout(o);
  layout.set_start(out.start);
  // What the start sees of zones 1, 2 and 4 stays open (dense: but thin pillars).
  const Rect near{0.0, ys - kZone24Outer - 0.3, xs + kFarZonesFrom - 0.2, ys + kZone24Outer + 0.3};
  const double far_x0 = xs + kFarZonesFrom;
  const double far_area = (W - far_x0) * H;
  const double area = W * H;
  const auto count = [&](double per_m2, double a) {
    return static_cast<int>(std::lround(per_m2 * a * rng.uniform(0.75, 1.25)));
  };

  // Rooms: partitions across the far part, each with a door or two; dense spaces get
  // more, and walls along them that split a room in two.
  const int partitions = dense
                             ? static_cast<int>(rng.uniform_int(
                                   1, std::max<std::int64_t>(1, std::lround((W - far_x0) / 4.0))))
                             : static_cast<int>(rng.uniform_int(
                                   0, std::max<std::int64_t>(1, std::lround((W - far_x0) / 7.0))));
  std::vector<double> walls_x;
  for (int p = 0; p < partitions; ++p) {
    const double x = rng.uniform(far_x0 + 0.8, W - 1.5);
    if (std::any_of(walls_x.begin(), walls_x.end(),
                    [&](double w) { return std::abs(w - x) < 2.0; }))
      continue;
    walls_x.push_back(x);
  }
  std::sort(walls_x.begin(), walls_x.end());
  const auto wall_with_doors = [&](bool vertical, double at, double from, double to) {
    const double t = rng.uniform(0.1, 0.2);
    const int doors = 1 + (rng.bernoulli(0.5) ? 1 : 0);
    std::vector<std::pair<double, double>> gaps;
    for (int d = 0; d < doors; ++d) {
      const double w = rng.uniform(0.7, 1.2);
      const double c = rng.uniform(from + w / 2 + 0.2, to - w / 2 - 0.2);
      gaps.emplace_back(c - w / 2, c + w / 2);
    }
    std::sort(gaps.begin(), gaps.end());
    double s = from;
    for (const auto& [g0, g1] : gaps) {
      if (g0 > s) (void)layout.add(vertical ? Rect{at, s, at + t, g0} : Rect{s, at, g0, at + t});
      s = std::max(s, g1);
    }
    if (s < to) (void)layout.add(vertical ? Rect{at, s, at + t, to} : Rect{s, at, to, at + t});
  };
  for (std::size_t w = 0; w < walls_x.size(); ++w) {
    wall_with_doors(true, walls_x[w], kWall, H - kWall);
    if (dense && rng.bernoulli(0.6)) {
      const double x1 = w + 1 < walls_x.size() ? walls_x[w + 1] : W - kWall;
      if (x1 - walls_x[w] > 2.5)
        wall_with_doors(false, rng.uniform(0.3 * H, 0.7 * H), walls_x[w] + 0.2, x1);
    }
  }

  // Boxes, pillars and debris, anywhere but the start's view of its zones.
  const Rect inside{kWall, kWall, W - kWall, H - kWall};
  const auto scatter = [&](int n, double min_side, double max_side, const Rect& region,
                           bool near_allowed) {
    for (int k = 0, tries = 0; k < n && tries < 20 * n; ++tries) {
      const double sx = rng.uniform(min_side, max_side), sy = rng.uniform(min_side, max_side);
      const double x = rng.uniform(region.x0, region.x1 - sx),
                   y = rng.uniform(region.y0, region.y1 - sy);
      const Rect r{x, y, x + sx, y + sy};
      if (r.overlaps(near) && !near_allowed) continue;
      if (r.overlaps(z1, 0.3) || r.overlaps(z2, 0.3) || r.overlaps(z4, 0.3)) continue;
      if (std::hypot(r.x0 + sx / 2 - xs, r.y0 + sy / 2 - ys) < 0.8) continue;
      if (layout.add(r)) ++k;
    }
  };
  scatter(count(dense ? 0.13 : 0.055, far_area), 0.3, 1.0, inside, false);  // boxes
  scatter(count(dense ? 0.04 : 0.01, area), 0.15, 0.25, inside, false);     // pillars
  if (dense)  // thin pillars in the start's view, beside its zones
    scatter(2 + static_cast<int>(rng.uniform_int(0, 2)), 0.15, 0.2,
            Rect{near.x0 + kWall, std::max(near.y0, kWall), near.x1, std::min(near.y1, H - kWall)},
            true);
  scatter(count(dense ? 0.2 : 0.05, area), 0.05, 0.15, inside, false);  // debris
  out.map = layout.map();
  return out;
}

std::string GeneratedHiddenSpace::search_yaml() const {
  std::string y = fmt::format("search:\n  start: [{}, {}, {}]\n  zones:\n", start.x_m, start.y_m,
                              start.yaw_rad);
  for (const ZoneSpec& z : zones)
    y += fmt::format("    {}: [{}, {}, {}, {}]\n", z.id, z.xmin_m, z.ymin_m, z.xmax_m, z.ymax_m);
  y += fmt::format("  generator: {{seed: {}, size_m: [{}, {}], resolution_m: {}, clutter: {}}}\n",
                   options.seed, options.width_m, options.height_m, options.resolution_m,
                   to_string(options.clutter));
  return y;
}

}  // namespace ferret
