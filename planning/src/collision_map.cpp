#include "ferret/planning/collision_map.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>

#include "collision_map_data.hpp"
#include "ferret/core/error.hpp"

namespace ferret {
namespace {

constexpr int kTreeDepth = 16;
constexpr std::int64_t kKeySpan = 1 << kTreeDepth;  // keys per axis
const float kOccupiedLogOdds = octomap::logodds(0.97);
const float kFreeLogOdds = octomap::logodds(0.12);

std::string box_text(const Aabb3& b) {
  return fmt::format("{:g},{:g},{:g},{:g},{:g},{:g}", b.lo.x(), b.lo.y(), b.lo.z(), b.hi.x(),
                     b.hi.y(), b.hi.z());
}

struct KeyBox {  // inclusive voxel key ranges per axis
  std::array<std::int64_t, 3> lo{}, hi{};
};

// Voxels whose centres lie inside `b` (OctoMap key k has its centre at (k - 2^15 + 0.5) res).
KeyBox key_box(const Aabb3& b, double res) {
  KeyBox k;
  for (int a = 0; a < 3; ++a) {
    k.lo[a] = static_cast<std::int64_t>(std::ceil(b.lo[a] / res - 0.5)) + kKeySpan / 2;
    k.hi[a] = static_cast<std::int64_t>(std::floor(b.hi[a] / res - 0.5)) + kKeySpan / 2;
    if (k.lo[a] < 0 || k.hi[a] >= kKeySpan || k.lo[a] > k.hi[a])
      throw InputError("map", "bounds",
                       fmt::format("bounds inside OctoMap's key range (+-{:g} m at {:g} m "
                                   "resolution) holding a voxel centre",
                                   kKeySpan / 2 * res, res),
                       fmt::format("[{:g}, {:g}] on axis {}", b.lo[a], b.hi[a], "xyz"[a]));
  }
  return k;
}
}  // namespace

void check_box_in_key_range(const Aabb3& box, double resolution_m, const std::string& source,
                            const std::string& field) {
  // The key range only: a flat box (a UAV held at one altitude) is a valid geofence.
  const double reach_m = (kKeySpan / 2 - 1) * resolution_m;
  if (!(box.lo.allFinite() && box.hi.allFinite() && (box.lo.array().abs() < reach_m).all() &&
        (box.hi.array().abs() < reach_m).all()))
    throw InputError(source, field,
                     fmt::format("a box inside OctoMap's key range (+-{:g} m at {:g} m resolution)",
                                 reach_m, resolution_m),
                     box_text(box));
}

namespace {

// Fills the unknown (non-existent) part of a node's subtree that lies inside `box`
// with occupied nodes, as coarse as the box allows. `base` is the node's lowest key
// per axis and `size` its extent in keys.
void fill_unknown(octomap::OcTree& tree, octomap::OcTreeNode* node,
                  const std::array<std::int64_t, 3>& base, std::int64_t size, const KeyBox& box) {
  const std::int64_t half = size / 2;
  for (unsigned i = 0; i < 8; ++i) {
    std::array<std::int64_t, 3> cb{};
    bool overlaps = true, inside = true;
    for (int a = 0; a < 3; ++a) {
      cb[a] = base[a] + ((i >> a) & 1) * half;
      overlaps = overlaps && cb[a] <= box.hi[a] && cb[a] + half - 1 >= box.lo[a];
      inside = inside && cb[a] >= box.lo[a] && cb[a] + half - 1 <= box.hi[a];
    }
    if (!overlaps) continue;
    if (tree.nodeChildExists(node, i)) {
      octomap::OcTreeNode* child = tree.getNodeChild(node, i);
      if (tree.nodeHasChildren(child)) fill_unknown(tree, child, cb, half, box);
      continue;  // an existing leaf is known space (free or occupied)
    }
    octomap::OcTreeNode* child = tree.createNodeChild(node, i);
    child->setLogOdds(kOccupiedLogOdds);
    if (!inside) fill_unknown(tree, child, cb, half, box);
  }
}

// Felzenszwalb-Huttenlocher exact 1D squared distance transform of f (n samples,
// stride `stride` in `data`), in place. v, z, tmp are scratch buffers.
void edt_1d(float* data, int n, std::size_t stride, std::vector<int>& v, std::vector<double>& z,
            std::vector<double>& f) {
  constexpr double kInf = std::numeric_limits<double>::infinity();
  f.resize(n);
  for (int q = 0; q < n; ++q) f[q] = data[q * stride];
  v.assign(n, 0);
  z.assign(n + 1, 0.0);
  int k = 0;
  // Skip leading infinite samples: parabolas rooted at infinity do not exist.
  int first = 0;
  while (first < n && !std::isfinite(f[first])) ++first;
  if (first == n) return;  // no occupied sample on this line: leave it infinite
  v[0] = first;
  z[0] = -kInf;
  z[1] = kInf;
  for (int q = first + 1; q < n; ++q) {
    if (!std::isfinite(f[q])) continue;
    double s;
    for (;;) {
      const int p = v[k];
      s = ((f[q] + double(q) * q) - (f[p] + double(p) * p)) / (2.0 * (q - p));
      if (s <= z[k] && k > 0) {
        --k;
        continue;
      }
      if (s <= z[k]) {  // k == 0 and the new parabola dominates everywhere left
        v[0] = q;
        z[0] = -kInf;
        z[1] = kInf;
        s = kInf;
      }
      break;
    }
    if (s == kInf) continue;
    ++k;
    v[k] = q;
    z[k] = s;
    z[k + 1] = kInf;
  }
  k = 0;
  for (int q = 0; q < n; ++q) {
    while (z[k + 1] < q) ++k;
    const double d = q - v[k];
    data[q * stride] = static_cast<float>(d * d + f[v[k]]);
  }
}

DistanceField build_field(const octomap::OcTree& tree, const CollisionMapOptions& options) {
  DistanceField field;
  const double res = tree.getResolution();
  field.floor_cut_z = options.field_floor_cut_z;
  field.covers_all = !options.field_region;
  std::array<std::int64_t, 3> lo{kKeySpan, kKeySpan, kKeySpan}, hi{-1, -1, -1};
  if (options.field_region) {
    const KeyBox box = key_box(*options.field_region, res);
    lo = box.lo;
    hi = box.hi;
  }
  struct Leaf {
    std::array<std::int64_t, 3> base;
    std::int64_t size;
  };
  std::vector<Leaf> leaves;
  for (auto it = tree.begin_leafs(), end = tree.end_leafs(); it != end; ++it) {
    if (!tree.isNodeOccupied(*it)) continue;
    const std::int64_t size = std::int64_t{1} << (kTreeDepth - it.getDepth());
    if (field.floor_cut_z && it.getZ() + 0.5 * it.getSize() <= *field.floor_cut_z) continue;
    const octomap::OcTreeKey key = it.getKey();
    Leaf leaf{{key[0] - size / 2, key[1] - size / 2, key[2] - size / 2}, size};
    if (!options.field_region) {
      for (int a = 0; a < 3; ++a) {
        lo[a] = std::min(lo[a], leaf.base[a]);
        hi[a] = std::max(hi[a], leaf.base[a] + size - 1);
      }
    }
    leaves.push_back(leaf);  // with a region: clipped to the grid when marked
  }
  field.cell_m = res;
  if (leaves.empty() && field.covers_all) return field;
  field.empty = leaves.empty();
  // The finest level whose grid (with one cell of margin on every side) fits.
  std::array<std::int64_t, 3> c0{};
  for (field.level = 0;; ++field.level) {
    std::size_t cells = 1;
    for (int a = 0; a < 3; ++a) {
      c0[a] = (lo[a] >> field.level) - 1;
      field.dims[a] = static_cast<int>((hi[a] >> field.level) + 1 - c0[a] + 1);
      cells *= static_cast<std::size_t>(field.dims[a]);
    }
    if (cells <= options.max_field_cells || field.level >= kTreeDepth) break;
  }
  field.cell_m = res * static_cast<double>(std::int64_t{1} << field.level);
  for (int a = 0; a < 3; ++a)
    field.origin_m[a] = static_cast<double>((c0[a] << field.level) - kKeySpan / 2) * res;
  const std::size_t nx = field.dims.x(), ny = field.dims.y(), nz = field.dims.z();
  std::vector<float> d2(nx * ny * nz, std::numeric_limits<float>::infinity());
  for (const Leaf& leaf : leaves) {
    std::array<std::int64_t, 3> a0{}, a1{};
    for (int a = 0; a < 3; ++a) {
      a0[a] = std::max<std::int64_t>((leaf.base[a] >> field.level) - c0[a], 0);
      a1[a] = std::min<std::int64_t>(((leaf.base[a] + leaf.size - 1) >> field.level) - c0[a],
                                     field.dims[a] - 1);
    }
    for (std::int64_t z = a0[2]; z <= a1[2]; ++z)
      for (std::int64_t y = a0[1]; y <= a1[1]; ++y)
        for (std::int64_t x = a0[0]; x <= a1[0]; ++x) d2[(z * ny + y) * nx + x] = 0.0f;
  }
  // Separable exact EDT: along x, then y, then z, on squared distances.
  std::vector<int> v;
  std::vector<double> zbuf, fbuf;
  float* d = d2.data();
  for (std::size_t z = 0; z < nz; ++z)
    for (std::size_t y = 0; y < ny; ++y)
      edt_1d(d + (z * ny + y) * nx, static_cast<int>(nx), 1, v, zbuf, fbuf);
  for (std::size_t z = 0; z < nz; ++z)
    for (std::size_t x = 0; x < nx; ++x)
      edt_1d(d + z * ny * nx + x, static_cast<int>(ny), nx, v, zbuf, fbuf);
  for (std::size_t y = 0; y < ny; ++y)
    for (std::size_t x = 0; x < nx; ++x)
      edt_1d(d + y * nx + x, static_cast<int>(nz), nx * ny, v, zbuf, fbuf);
  field.dist.resize(d2.size());
  for (std::size_t k = 0; k < d2.size(); ++k)
    field.dist[k] = static_cast<std::uint16_t>(std::min(
        65535.0, std::floor(std::sqrt(static_cast<double>(d2[k])) * DistanceField::kUnitsPerCell)));
  return field;
}

BandField build_band(const octomap::OcTree& tree, const Aabb3& region, double z_lo, double z_hi) {
  BandField band;
  band.z_lo = z_lo;
  band.z_hi = z_hi;
  const double res = tree.getResolution();
  const KeyBox box = key_box(region, res);
  band.cell_m = res;
  band.dims = Eigen::Vector2i(static_cast<int>(box.hi[0] - box.lo[0] + 3),
                              static_cast<int>(box.hi[1] - box.lo[1] + 3));
  const std::int64_t c0x = box.lo[0] - 1, c0y = box.lo[1] - 1;
  band.origin_m = Eigen::Vector2d(static_cast<double>(c0x - kKeySpan / 2) * res,
                                  static_cast<double>(c0y - kKeySpan / 2) * res);
  const std::size_t nx = band.dims.x(), ny = band.dims.y();
  std::vector<float> d2(nx * ny, std::numeric_limits<float>::infinity());
  for (auto
           it = tree.begin_leafs_bbx(
               octomap::point3d(static_cast<float>(region.lo.x() - res),
                                static_cast<float>(region.lo.y() - res), static_cast<float>(z_lo)),
               octomap::point3d(static_cast<float>(region.hi.x() + res),
                                static_cast<float>(region.hi.y() + res), static_cast<float>(z_hi))),
           end = tree.end_leafs_bbx();
       it != end; ++it) {
    if (!tree.isNodeOccupied(*it)) continue;
    const double half = 0.5 * it.getSize();
    if (it.getZ() + half <= z_lo || it.getZ() - half >= z_hi)
      continue;  // touches the band only at its edge
    const std::int64_t size = std::int64_t{1} << (kTreeDepth - it.getDepth());
    const octomap::OcTreeKey key = it.getKey();
    const std::int64_t bx = key[0] - size / 2 - c0x, by = key[1] - size / 2 - c0y;
    for (std::int64_t y = std::max<std::int64_t>(by, 0); y < std::min<std::int64_t>(by + size, ny);
         ++y)
      for (std::int64_t x = std::max<std::int64_t>(bx, 0);
           x < std::min<std::int64_t>(bx + size, nx); ++x)
        d2[y * nx + x] = 0.0f;
  }
  std::vector<int> v;
  std::vector<double> zbuf, fbuf;
  for (std::size_t y = 0; y < ny; ++y)
    edt_1d(d2.data() + y * nx, static_cast<int>(nx), 1, v, zbuf, fbuf);
  for (std::size_t x = 0; x < nx; ++x)
    edt_1d(d2.data() + x, static_cast<int>(ny), nx, v, zbuf, fbuf);
  band.dist.resize(d2.size());
  for (std::size_t k = 0; k < d2.size(); ++k)
    band.dist[k] = static_cast<std::uint16_t>(std::min(
        65535.0, std::floor(std::sqrt(static_cast<double>(d2[k])) * DistanceField::kUnitsPerCell)));
  return band;
}

}  // namespace

bool BandField::disc_free(const Eigen::Vector2d& c, double r) const {
  const Eigen::Vector2d rel = (c - origin_m) / cell_m;
  const double fx = std::floor(rel.x()), fy = std::floor(rel.y());
  // The disc must lie inside the grid: columns outside it are not in the field.
  if ((c.array() - r <= origin_m.array()).any() ||
      (c.array() + r >= (origin_m + dims.cast<double>() * cell_m).array()).any())
    return false;
  const std::uint16_t d =
      dist[static_cast<std::size_t>(fy) * dims.x() + static_cast<std::size_t>(fx)];
  return cell_m * (d / DistanceField::kUnitsPerCell - std::sqrt(2.0)) - 1e-9 > r;
}

bool BandField::rect_free(const Eigen::Vector2d& lo, const Eigen::Vector2d& hi) const {
  // Cells touching the rectangle, with a hair of margin for rounding.
  const Eigen::Vector2d a = (lo - origin_m) / cell_m - Eigen::Vector2d::Constant(1e-7);
  const Eigen::Vector2d b = (hi - origin_m) / cell_m + Eigen::Vector2d::Constant(1e-7);
  if (a.x() < 0 || a.y() < 0 || b.x() >= dims.x() || b.y() >= dims.y()) return false;
  const int i0 = static_cast<int>(a.x()), j0 = static_cast<int>(a.y());
  const int i1 = static_cast<int>(b.x()), j1 = static_cast<int>(b.y());
  for (int j = j0; j <= j1; ++j)
    for (int i = i0; i <= i1; ++i)
      if (dist[static_cast<std::size_t>(j) * dims.x() + i] == 0) return false;
  return true;
}

double DistanceField::lower_bound_m(const Eigen::Vector3d& p) const {
  if (empty) return std::numeric_limits<double>::infinity();
  // One pass: the cell of p, and p's offset from the cell's centre (in cells).
  const double inv = 1.0 / cell_m;
  std::ptrdiff_t idx = 0, stride = 1;
  double off2 = 0.0;
  bool inside = true;
  for (int a = 0; a < 3; ++a) {
    const double rel = (p[a] - origin_m[a]) * inv;
    const double f = std::floor(rel);
    inside = inside && f >= 0 && f < dims[a];
    idx += static_cast<std::ptrdiff_t>(f) * stride;
    stride *= dims[a];
    off2 += (rel - f - 0.5) * (rel - f - 0.5);
  }
  if (!inside) {
    if (!covers_all) return 0.0;
    // Everything occupied lies inside the grid: the distance to the grid box bounds it.
    const Eigen::Vector3d hi = origin_m + dims.cast<double>() * cell_m;
    return (origin_m - p).cwiseMax(p - hi).cwiseMax(0.0).norm();
  }
  // |p - occupied| >= |centre(c) - centre(o)| - |p - centre(c)| - half diagonal of o.
  constexpr double kHalfDiagonal = 0.8660254037844386;
  return std::max(0.0, cell_m * (dist[static_cast<std::size_t>(idx)] / kUnitsPerCell -
                                 kHalfDiagonal - std::sqrt(off2)) -
                           1e-9);
}

bool DistanceField::sphere_free(const Eigen::Vector3d& c, double r) const {
  if (floor_cut_z && c.z() - r <= *floor_cut_z + 1e-9) return false;
  if (!covers_all) {
    // Voxels outside the region are not in the field: the ball must lie inside it.
    const Eigen::Vector3d hi = origin_m + dims.cast<double>() * cell_m;
    if (((c.array() - r) <= origin_m.array()).any() || ((c.array() + r) >= hi.array()).any())
      return false;
  }
  return lower_bound_m(c) > r;
}

int DistanceField::occupied_at(const Eigen::Vector3d& p) const {
  if (floor_cut_z && p.z() <= *floor_cut_z) return -1;
  if (empty) return covers_all ? 0 : -1;
  const std::ptrdiff_t idx = cell_index(p);
  if (idx < 0) return covers_all ? 0 : -1;
  // A cell with no occupied voxel has a non-zero distance at any level.
  if (dist[static_cast<std::size_t>(idx)] != 0) return 0;
  return level == 0 ? 1 : -1;
}

const char* to_string(UnknownPolicy policy) {
  return policy == UnknownPolicy::kFree ? "free" : "occupied";
}

std::string collision_map_options_key(const CollisionMapOptions& o) {
  const auto box = [](const std::optional<Aabb3>& b) {
    return b ? fmt::format("{:a},{:a},{:a},{:a},{:a},{:a}", b->lo.x(), b->lo.y(), b->lo.z(),
                           b->hi.x(), b->hi.y(), b->hi.z())
             : std::string("-");
  };
  return fmt::format("{}|{}|{}|{}|{}|{}|{}", to_string(o.unknown), box(o.bounds), o.max_field_cells,
                     o.max_fill_face_voxels, box(o.field_region),
                     o.field_floor_cut_z ? fmt::format("{:a}", *o.field_floor_cut_z) : "-",
                     o.ground_band_z
                         ? fmt::format("{:a},{:a}", o.ground_band_z->first, o.ground_band_z->second)
                         : "-");
}

UnknownPolicy parse_unknown_policy(const std::string& text, const std::string& source) {
  if (text == "free") return UnknownPolicy::kFree;
  if (text == "occupied") return UnknownPolicy::kOccupied;
  throw InputError(source, "", "\"free\" or \"occupied\"", text);
}

CollisionMap::CollisionMap(std::unique_ptr<Data> data) : data_(std::move(data)) {}
CollisionMap::~CollisionMap() = default;

std::shared_ptr<const CollisionMap> CollisionMap::build(const octomap::OcTree& source,
                                                        const CollisionMapOptions& options) {
  if (options.unknown == UnknownPolicy::kOccupied && !options.bounds)
    throw InputError("map", "bounds", "bounds for the unknown policy \"occupied\"");
  auto data = std::make_unique<Data>();
  data->options = options;
  const double res = source.getResolution();
  // A deep copy with binary values: occupied leaves at the upper clamp, free ones at
  // the lower, threshold 0.5, so OctoMap, FCL and the field agree on every leaf.
  data->tree = std::make_shared<octomap::OcTree>(source);
  auto& tree = *data->tree;
  // Same structure, so the two leaf iterations run in step.
  auto dst = tree.begin_leafs();
  for (auto it = source.begin_leafs(), end = source.end_leafs(); it != end; ++it, ++dst)
    dst->setLogOdds(source.isNodeOccupied(*it) ? kOccupiedLogOdds : kFreeLogOdds);
  tree.setOccupancyThres(0.5);
  tree.setClampingThresMin(0.1192);
  tree.setClampingThresMax(0.971);
  if (options.bounds) {
    const KeyBox box = key_box(*options.bounds, res);
    if (options.unknown == UnknownPolicy::kOccupied) {
      std::array<double, 3> n{};
      for (int a = 0; a < 3; ++a) n[a] = static_cast<double>(box.hi[a] - box.lo[a] + 1);
      const double faces = 2.0 * (n[0] * n[1] + n[1] * n[2] + n[0] * n[2]);
      if (faces > static_cast<double>(options.max_fill_face_voxels))
        throw InputError(
            "map", "bounds",
            fmt::format("a box whose faces hold at most {} voxels at {:g} m (unknown space in "
                        "it is filled as occupied)",
                        options.max_fill_face_voxels, res),
            fmt::format("{:g} x {:g} x {:g} m: {:.3g} voxels", n[0] * res, n[1] * res, n[2] * res,
                        faces));
      if (!tree.getRoot()) {
        octomap::OcTreeKey k(static_cast<octomap::key_type>(box.lo[0]),
                             static_cast<octomap::key_type>(box.lo[1]),
                             static_cast<octomap::key_type>(box.lo[2]));
        tree.setNodeValue(k, kOccupiedLogOdds, true);
      }
      fill_unknown(tree, tree.getRoot(), {0, 0, 0}, kKeySpan, box);
    }
  }
  tree.updateInnerOccupancy();
  tree.prune();
  for (auto it = tree.begin_leafs(), end = tree.end_leafs(); it != end; ++it)
    if (tree.isNodeOccupied(*it)) ++data->occupied_leaves;
  data->field = build_field(tree, options);
  if (options.ground_band_z) {
    if (!options.field_region)
      throw InputError("map", "field_region", "a field region for the ground band");
    data->band = build_band(tree, *options.field_region, options.ground_band_z->first,
                            options.ground_band_z->second);
  }
  data->fcl_tree =
      std::make_shared<fcl::OcTreed>(std::shared_ptr<const octomap::OcTree>(data->tree));
  return std::shared_ptr<const CollisionMap>(new CollisionMap(std::move(data)));
}

const octomap::OcTree& CollisionMap::tree() const { return *data_->tree; }
double CollisionMap::resolution_m() const { return data_->tree->getResolution(); }
UnknownPolicy CollisionMap::unknown_policy() const { return data_->options.unknown; }
const std::optional<Aabb3>& CollisionMap::bounds() const { return data_->options.bounds; }
std::size_t CollisionMap::occupied_leaf_count() const { return data_->occupied_leaves; }
double CollisionMap::field_cell_m() const { return data_->field.cell_m; }

double CollisionMap::clearance_lower_bound_m(const Eigen::Vector3d& p_W) const {
  return data_->field.lower_bound_m(p_W);
}

bool CollisionMap::sphere_free(const Eigen::Vector3d& c_W, double radius_m) const {
  return data_->field.sphere_free(c_W, radius_m);
}

bool CollisionMap::is_occupied(const Eigen::Vector3d& p_W) const {
  octomap::OcTreeKey key;
  if (!data_->tree->coordToKeyChecked(p_W.x(), p_W.y(), p_W.z(), key)) return false;
  const octomap::OcTreeNode* node = data_->tree->search(key);
  return node && data_->tree->isNodeOccupied(node);
}

}  // namespace ferret
