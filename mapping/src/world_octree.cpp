#include "ferret/mapping/world_octree.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <bit>
#include <charconv>
#include <cmath>
#include <cstring>
#include <fstream>
#include <limits>
#include <sstream>

#include "ferret/core/atomic_file.hpp"
#include "ferret/core/error.hpp"

namespace ferret {
namespace fs = std::filesystem;

namespace {

constexpr int kTreeDepth = 16;       // OctoMap's fixed depth
constexpr int kKeyOffset = 1 << 15;  // key of the voxel whose lower corner is 0
constexpr double kTol_m = 1e-9;      // same face tolerance as the primitives' contains()

// ---------------------------------------------------------------------------------
// Building

enum class Relation { kInside, kOutside, kPartial };

// The set of voxel centres of a cube of keys, as an axis-aligned box.
struct CentreBox {
  Eigen::Vector3d lo, hi;
  [[nodiscard]] std::array<Eigen::Vector2d, 4> xy_corners() const {
    return {Eigen::Vector2d{lo.x(), lo.y()}, {hi.x(), lo.y()}, {lo.x(), hi.y()}, {hi.x(), hi.y()}};
  }
};

// Projections of both shapes on an axis overlap (separating-axis test).
bool overlap_on(const Eigen::Vector2d& axis, const std::array<Eigen::Vector2d, 4>& a,
                const std::array<Eigen::Vector2d, 4>& b) {
  double amin = 1e300, amax = -1e300, bmin = 1e300, bmax = -1e300;
  for (const auto& p : a) amin = std::min(amin, axis.dot(p)), amax = std::max(amax, axis.dot(p));
  for (const auto& p : b) bmin = std::min(bmin, axis.dot(p)), bmax = std::max(bmax, axis.dot(p));
  return amax >= bmin && bmax >= amin;
}

Relation relate(const OrientedBox& b, const CentreBox& r) {
  const double hz = b.size_m.z() / 2 + kTol_m;
  if (r.lo.z() > b.center_m.z() + hz || r.hi.z() < b.center_m.z() - hz) return Relation::kOutside;
  const double c = std::cos(b.yaw_rad), s = std::sin(b.yaw_rad);
  const Eigen::Vector2d u{c, s}, v{-s, c};
  const double hu = b.size_m.x() / 2 + kTol_m, hv = b.size_m.y() / 2 + kTol_m;
  const Eigen::Vector2d bc = b.center_m.head<2>();
  const std::array<Eigen::Vector2d, 4> box_xy{bc + hu * u + hv * v, bc + hu * u - hv * v,
                                              bc - hu * u + hv * v, bc - hu * u - hv * v};
  const auto r_xy = r.xy_corners();
  for (const Eigen::Vector2d& axis : {Eigen::Vector2d(1, 0), Eigen::Vector2d(0, 1), u, v})
    if (!overlap_on(axis, r_xy, box_xy)) return Relation::kOutside;
  const bool z_inside = r.lo.z() >= b.center_m.z() - hz && r.hi.z() <= b.center_m.z() + hz;
  if (!z_inside) return Relation::kPartial;
  for (const auto& p : r_xy) {
    const Eigen::Vector2d d = p - bc;
    if (std::abs(d.dot(u)) > hu || std::abs(d.dot(v)) > hv) return Relation::kPartial;
  }
  return Relation::kInside;
}

Relation relate(const VerticalCylinder& cyl, const CentreBox& r) {
  const double z0 = cyl.base_z_m - kTol_m, z1 = cyl.base_z_m + cyl.height_m + kTol_m,
               rad = cyl.radius_m + kTol_m;
  if (r.lo.z() > z1 || r.hi.z() < z0) return Relation::kOutside;
  const Eigen::Vector2d nearest = cyl.center_m.cwiseMax(r.lo.head<2>()).cwiseMin(r.hi.head<2>());
  if ((nearest - cyl.center_m).norm() > rad) return Relation::kOutside;
  if (r.lo.z() < z0 || r.hi.z() > z1) return Relation::kPartial;
  for (const auto& p : r.xy_corners())
    if ((p - cyl.center_m).norm() > rad) return Relation::kPartial;
  return Relation::kInside;
}

Relation relate(const GroundSpec& g, const CentreBox& r) {
  double gmin = 1e300, gmax = -1e300;
  for (const auto& p : r.xy_corners()) {
    const double h = g.height_at(p.x(), p.y()) + kTol_m;
    gmin = std::min(gmin, h);
    gmax = std::max(gmax, h);
  }
  if (r.lo.z() > gmax) return Relation::kOutside;
  if (r.hi.z() <= gmin) return Relation::kInside;
  return Relation::kPartial;
}

// Exposes the root so the builder can grow the tree top-down, creating leaves at
// any depth. Its type on disk is still "OcTree".
class BuildableOcTree : public octomap::OcTree {
 public:
  using octomap::OcTree::OcTree;
  octomap::OcTreeNode* make_root() {
    if (root == nullptr) {
      root = new octomap::OcTreeNode();
      ++tree_size;
      size_changed = true;
    }
    return root;
  }
};

class WorldVoxelizer {
 public:
  WorldVoxelizer(const WorldSpec& world, const WorldBuildOptions& options, BuildableOcTree& tree)
      : world_(world), options_(options), tree_(tree) {
    res_ = world.resolution_m;
    for (int a = 0; a < 3; ++a) {
      // Keys whose voxel centres lie within the bounds.
      kmin_[a] =
          static_cast<long>(std::ceil(world.bounds_min_m[a] / res_ - 0.5 - 1e-9)) + kKeyOffset;
      kmax_[a] =
          static_cast<long>(std::floor(world.bounds_max_m[a] / res_ - 0.5 + 1e-9)) + kKeyOffset;
    }
    boxes_ = world.solid_boxes();
    occupied_ = tree.getClampingThresMaxLog();
    free_ = tree.getClampingThresMinLog();
    // Candidate index -1 is the ground, [0, boxes) boxes, then cylinders.
    std::vector<int> all{-1};
    for (std::size_t i = 0; i < boxes_.size() + world.cylinders.size(); ++i)
      all.push_back(static_cast<int>(i));
    candidates_.assign(kTreeDepth + 2, {});
    candidates_[0] = std::move(all);
  }

  void run() {
    const std::array<long, 3> k0{0, 0, 0};
    std::vector<int>& root_cands = candidates_[0];
    // The root cube is the whole key space: always more than one state.
    fill(tree_.make_root(), k0, 1L << kTreeDepth, 0, root_cands);
  }

 private:
  enum class State { kUnknown, kFree, kOccupied, kMixed };

  Relation relate_candidate(int c, const CentreBox& r) const {
    if (c < 0) return relate(world_.ground, r);
    if (static_cast<std::size_t>(c) < boxes_.size()) return relate(boxes_[c], r);
    return relate(world_.cylinders[c - boxes_.size()], r);
  }

  // Classifies a cube of keys [k0, k0 + n) and writes the solids that cut it to `out`.
  State classify(const std::array<long, 3>& k0, long n, const std::vector<int>& cands,
                 std::vector<int>& out) const {
    bool inside_bounds = true;
    for (int a = 0; a < 3; ++a) {
      if (k0[a] > kmax_[a] || k0[a] + n - 1 < kmin_[a]) return State::kUnknown;
      inside_bounds = inside_bounds && k0[a] >= kmin_[a] && k0[a] + n - 1 <= kmax_[a];
    }
    CentreBox r;
    for (int a = 0; a < 3; ++a) {
      r.lo[a] = (static_cast<double>(k0[a] - kKeyOffset) + 0.5) * res_;
      r.hi[a] = (static_cast<double>(k0[a] + n - 1 - kKeyOffset) + 0.5) * res_;
    }
    out.clear();
    for (const int c : cands) {
      const Relation rel = relate_candidate(c, r);
      if (rel == Relation::kInside && inside_bounds) return State::kOccupied;
      if (rel != Relation::kOutside) out.push_back(c);
    }
    if (inside_bounds && out.empty()) return State::kFree;
    return State::kMixed;  // a single voxel is never mixed: its relations are inside or outside
  }

  void fill(octomap::OcTreeNode* node, const std::array<long, 3>& k0, long n, int depth,
            const std::vector<int>& cands) {
    const long half = n / 2;
    std::vector<int>& child_cands = candidates_[depth + 1];
    for (unsigned i = 0; i < 8; ++i) {
      const std::array<long, 3> kc{k0[0] + ((i & 1) ? half : 0), k0[1] + ((i & 2) ? half : 0),
                                   k0[2] + ((i & 4) ? half : 0)};
      const State s = classify(kc, half, cands, child_cands);
      if (s == State::kUnknown) continue;
      octomap::OcTreeNode* child = tree_.createNodeChild(node, i);
      if (tree_.size() > options_.max_nodes)
        throw InputError(
            world_.source.string(), "resolution_m",
            fmt::format("a resolution coarse enough for at most {} tree nodes (about {} MB); "
                        "sloped ground and tilted faces cost a leaf a voxel of surface",
                        options_.max_nodes, options_.max_nodes * 50 / 1000000),
            fmt::format("{}", world_.resolution_m));
      if (s == State::kMixed) {
        fill(child, kc, half, depth + 1, child_cands);
        child->updateOccupancyChildren();
      } else {
        child->setLogOdds(s == State::kOccupied ? occupied_ : free_);
      }
    }
  }

  const WorldSpec& world_;
  const WorldBuildOptions& options_;
  BuildableOcTree& tree_;
  double res_ = 0.05;
  std::array<long, 3> kmin_{}, kmax_{};
  std::vector<OrientedBox> boxes_;
  float occupied_ = 0, free_ = 0;
  std::vector<std::vector<int>> candidates_;  // one buffer a depth, reused by siblings
};

// ---------------------------------------------------------------------------------
// Reading

std::string slurp(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in || fs::is_directory(path))
    throw InputError(path.string(), "", "a readable OctoMap file", "cannot open");
  std::ostringstream data;
  data << in.rdbuf();
  return std::move(data).str();
}

struct OctreeHeader {
  std::string id;
  std::uint64_t size = 0;
  double resolution_m = 0.0;
  std::size_t data_offset = 0;
};

// Parses the text header OctoMap writes ("# Octomap OcTree [binary ]file", then
// "id", "size", "res" and "data" lines), strictly.
OctreeHeader parse_header(const std::string& bytes, const std::string& source, bool binary) {
  const std::string magic = binary ? "# Octomap OcTree binary file" : "# Octomap OcTree file";
  if (bytes.compare(0, magic.size(), magic) != 0)
    throw InputError(
        source, "header", "a first line '" + magic + "'",
        bytes.empty() ? "an empty file"
                      : "'" + bytes.substr(0, std::min<std::size_t>(bytes.find('\n'), 40)) + "'");
  OctreeHeader h;
  bool have_size = false, have_res = false;
  std::size_t pos = bytes.find('\n');
  // The header is a few short lines; a file without "data" in its first 4 KiB is not OctoMap's.
  constexpr std::size_t kMaxHeader = 4096;
  while (pos != std::string::npos && pos < kMaxHeader) {
    const std::size_t start = pos + 1;
    const std::size_t end = bytes.find('\n', start);
    if (end == std::string::npos) break;
    std::istringstream line(bytes.substr(start, end - start));
    std::string key, value, extra;
    line >> key;
    pos = end;
    if (key.empty() || key[0] == '#') continue;
    if (key == "data") {
      h.data_offset = end + 1;
      if (h.id.empty()) throw InputError(source, "header.id", "an 'id OcTree' line before 'data'");
      if (!have_size) throw InputError(source, "header.size", "a 'size N' line before 'data'");
      if (!have_res) throw InputError(source, "header.res", "a 'res R' line before 'data'");
      return h;
    }
    line >> value;
    if (value.empty() || (line >> extra))
      throw InputError(source, "header." + key, "one value", "'" + line.str() + "'");
    if (key == "id") {
      h.id = value == "1" ? "OcTree" : value;  // "1" is OctoMap's deprecated id of OcTree
      if (h.id != "OcTree") throw InputError(source, "header.id", "OcTree", "'" + value + "'");
    } else if (key == "size") {
      const auto [p, ec] = std::from_chars(value.data(), value.data() + value.size(), h.size);
      if (ec != std::errc() || p != value.data() + value.size())
        throw InputError(source, "header.size", "a node count (non-negative integer)",
                         "'" + value + "'");
      have_size = true;
    } else if (key == "res") {
      char* endp = nullptr;
      h.resolution_m = std::strtod(value.c_str(), &endp);
      // Below 0.1 mm OctoMap's key range (+-2^15 voxels) would not reach a metre.
      if (*endp != '\0' || !std::isfinite(h.resolution_m) || h.resolution_m < 1e-4 ||
          h.resolution_m > 1000)
        throw InputError(source, "header.res", "a resolution in [0.0001, 1000] m",
                         "'" + printable(value) + "'");
      have_res = true;
    } else {
      throw InputError(source, "header", "id, size, res or data lines", "'" + key + "'");
    }
  }
  throw InputError(source, "header", "a 'data' line ending the header",
                   "none (truncated or not an OctoMap file)");
}

// Walks the serialized node structure exactly as OctoMap will read it, without
// recursion, so that OctoMap only ever sees a well-formed stream. Returns the
// number of nodes. Binary (.bt) nodes are two bytes of 2-bit child codes (01
// occupied leaf, 10 free leaf, 11 inner); full (.ot) nodes are a float log-odds
// and a byte of child-exists bits.
std::uint64_t validate_nodes(const std::string& bytes, std::size_t pos, const std::string& source,
                             bool binary) {
  std::uint64_t nodes = 1;
  std::vector<int> pending;  // inner children still to read, one entry a depth
  auto read_node = [&](int depth) {
    const std::size_t need = binary ? 2 : sizeof(float) + 1;
    if (pos + need > bytes.size())
      throw InputError(source, "data",
                       fmt::format("{} more bytes for a node at depth {}", need, depth),
                       fmt::format("end of file at byte {} (truncated)", bytes.size()));
    int inner = 0, children = 0;
    if (binary) {
      const auto lo = static_cast<unsigned char>(bytes[pos]),
                 hi = static_cast<unsigned char>(bytes[pos + 1]);
      for (int i = 0; i < 8; ++i) {
        const unsigned byte = i < 4 ? lo : hi;
        const unsigned code = (byte >> ((i % 4) * 2)) & 3u;
        children += code != 0;
        inner += code == 3;
      }
    } else {
      float value = 0;
      std::memcpy(&value, bytes.data() + pos, sizeof(float));
      if (!std::isfinite(value))
        throw InputError(source, fmt::format("data (byte {})", pos), "a finite log-odds value",
                         "NaN or infinity");
      const auto mask = static_cast<unsigned char>(bytes[pos + sizeof(float)]);
      children = inner = std::popcount(mask);
    }
    if (binary && children == 0)
      throw InputError(source, fmt::format("data (byte {})", pos),
                       "an inner node with at least one child", "a node without children");
    if (inner > 0 && depth >= kTreeDepth - (binary ? 1 : 0))
      throw InputError(source, fmt::format("data (byte {})", pos),
                       fmt::format("a tree at most {} levels deep", kTreeDepth),
                       "deeper nodes (corrupt file)");
    nodes += static_cast<std::uint64_t>(children);
    pos += need;
    pending.push_back(inner);
  };
  read_node(0);
  while (!pending.empty()) {
    if (pending.back() == 0) {
      pending.pop_back();
      continue;
    }
    --pending.back();
    read_node(static_cast<int>(pending.size()));
  }
  if (pos != bytes.size())
    throw InputError(source, "data", "the file to end after the tree",
                     fmt::format("{} trailing bytes", bytes.size() - pos));
  return nodes;
}

bool has_ext(const fs::path& p, std::string_view ext) { return p.extension() == ext; }

}  // namespace

std::unique_ptr<octomap::OcTree> build_world_octree(const WorldSpec& world,
                                                    const WorldBuildOptions& options) {
  auto tree = std::make_unique<BuildableOcTree>(world.resolution_m);
  WorldVoxelizer(world, options, *tree).run();
  // The conservative cube tests can split a cube whose children all agree; merge them.
  tree->prune();
  tree->updateInnerOccupancy();
  return tree;
}

std::unique_ptr<octomap::OcTree> extrude_map_2d(const OccupancyMap2D& map,
                                                const std::string& source,
                                                const Map2DExtrusion& options) {
  const GridGeometry& g = map.geometry;
  const double res = g.resolution_m;
  if (!(std::isfinite(res) && res >= 0.001 && res <= 100.0))
    throw InputError(source, "resolution", "metres per cell in [0.001, 100]",
                     fmt::format("{}", res));
  if (!(std::isfinite(options.height_m) && options.height_m > 0.0 && options.height_m <= 100.0))
    throw InputError(source, "height_m", "a wall height in (0, 100] m",
                     fmt::format("{}", options.height_m));
  if (g.width < 1 || g.height < 1 || map.cells.size() != g.size())
    throw InputError(source, "", "a non-empty map whose cell count matches its geometry");
  if (!(std::isfinite(g.origin_x_m) && std::isfinite(g.origin_y_m)))
    throw InputError(source, "origin", "a finite origin");
  // Voxel index (key - kKeyOffset) of cell (0, 0): the origin snapped onto the voxel grid.
  const double ix = std::round(g.origin_x_m / res), iy = std::round(g.origin_y_m / res);
  const double reach = kKeyOffset - 1;
  if (ix < -reach || iy < -reach || ix + g.width > reach || iy + g.height > reach)
    throw InputError(
        source, "origin",
        fmt::format("a map within OctoMap's key range, +-{:g} m at {:g} m cells", reach * res, res),
        fmt::format("[{:g}, {:g}] to [{:g}, {:g}]", g.origin_x_m, g.origin_y_m,
                    g.origin_x_m + g.width * res, g.origin_y_m + g.height * res));
  const long layers = std::max(1L, static_cast<long>(std::ceil(options.height_m / res - 1e-9)));
  if (layers >= kKeyOffset) throw InputError(source, "height_m", "fewer than 2^15 voxel layers");
  const std::size_t known = map.count(CellState::kFree) + map.count(CellState::kOccupied);
  if (static_cast<double>(known) * static_cast<double>(layers + 1) >
      static_cast<double>(options.max_voxels))
    throw InputError(source, "resolution",
                     fmt::format("a map of at most {} voxels (known cells x {} layers)",
                                 options.max_voxels, layers + 1),
                     fmt::format("{} known cells", known));
  auto tree = std::make_unique<octomap::OcTree>(res);
  const float occupied = tree->getClampingThresMaxLog(), free = tree->getClampingThresMinLog();
  const long x0 = static_cast<long>(ix) + kKeyOffset, y0 = static_cast<long>(iy) + kKeyOffset;
  const auto key = [](long v) { return static_cast<octomap::key_type>(v); };
  for (int j = 0; j < g.height; ++j) {
    for (int i = 0; i < g.width; ++i) {
      const CellState s = map.at({i, j});
      if (s == CellState::kUnknown) continue;
      const long x = x0 + i, y = y0 + j;
      tree->setNodeValue(octomap::OcTreeKey(key(x), key(y), key(kKeyOffset - 1)), occupied, true);
      const float v = s == CellState::kOccupied ? occupied : free;
      for (long k = 0; k < layers; ++k)
        tree->setNodeValue(octomap::OcTreeKey(key(x), key(y), key(kKeyOffset + k)), v, true);
    }
  }
  tree->prune();
  tree->updateInnerOccupancy();
  return tree;
}

std::unique_ptr<octomap::OcTree> load_octree(const fs::path& path) {
  const bool binary = has_ext(path, ".bt");
  if (!binary && !has_ext(path, ".ot"))
    throw InputError(path.string(), "", "an OctoMap file ending in .bt or .ot");
  return parse_octree(slurp(path), binary, path.string());
}

std::unique_ptr<octomap::OcTree> parse_octree(const std::string& bytes, bool binary,
                                              const std::string& source) {
  const OctreeHeader h = parse_header(bytes, source, binary);
  auto tree = std::make_unique<octomap::OcTree>(h.resolution_m);
  if (h.size == 0) {
    if (h.data_offset != bytes.size())
      throw InputError(source, "data", "no data for a tree of size 0",
                       fmt::format("{} bytes", bytes.size() - h.data_offset));
    return tree;
  }
  const std::uint64_t nodes = validate_nodes(bytes, h.data_offset, source, binary);
  if (nodes != h.size)
    throw InputError(source, "header.size",
                     fmt::format("the number of nodes in the data ({})", nodes),
                     std::to_string(h.size));
  std::istringstream in(bytes);
  in.seekg(static_cast<std::streamoff>(h.data_offset));
  if (binary)
    tree->readBinaryData(in);
  else
    tree->readData(in);
  if (tree->size() != h.size)
    throw InputError(source, "data", fmt::format("{} nodes", h.size), std::to_string(tree->size()));
  return tree;
}

std::unique_ptr<octomap::OcTree> load_or_build_octree(const fs::path& path,
                                                      std::optional<WorldSpec>* world) {
  if (world != nullptr) world->reset();
  if (has_ext(path, ".yaml") || has_ext(path, ".yml")) {
    WorldSpec spec = load_world(path);
    auto tree = build_world_octree(spec);
    if (world != nullptr) *world = std::move(spec);
    return tree;
  }
  if (!has_ext(path, ".bt") && !has_ext(path, ".ot"))
    throw InputError(path.string(), "", "a world YAML (.yaml) or an OctoMap file (.bt, .ot)");
  return load_octree(path);
}

void save_octree(const octomap::OcTree& tree, const fs::path& path) {
  const bool binary = has_ext(path, ".bt");
  if (!binary && !has_ext(path, ".ot"))
    throw InputError(path.string(), "", "an output path ending in .bt or .ot");
  write_file_atomically(path, [&](const fs::path& tmp) {
    std::ofstream out(tmp, std::ios::binary);
    // OctoMap's header, written here because the packaged library's writers print
    // debug chatter to stderr; the resolution keeps all its digits.
    out << (binary ? "# Octomap OcTree binary file\n" : "# Octomap OcTree file\n")
        << "# (feel free to add / change comments, but leave the first line as it is!)\n#\n"
        << fmt::format("id {}\nsize {}\nres {}\ndata\n", tree.getTreeType(), tree.size(),
                       tree.getResolution());
    if (binary)
      tree.writeBinaryData(out);
    else
      tree.writeData(out);
    out.close();
    if (!out) throw InputError(path.string(), "", "a writable file");
  });
}

Eigen::Vector4d hidden_space_window(const WorldSpec& world, const std::string& name,
                                    double margin_m, const std::string& option) {
  const int index = world.find_hidden_space(name);
  if (index < 0) {
    std::string names;
    for (const auto& h : world.hidden_spaces) names += (names.empty() ? "" : ", ") + h.name;
    throw InputError(option, "",
                     fmt::format("the name of a hidden space of {} ({})", world.source.string(),
                                 names.empty() ? "it has none" : "one of: " + names),
                     "'" + name + "'");
  }
  const Eigen::AlignedBox3d b = world.hidden_spaces[index].outer_bounds_m();
  return {b.min().x() - margin_m, b.min().y() - margin_m, b.max().x() + margin_m,
          b.max().y() + margin_m};
}

std::optional<Eigen::Vector4d> requested_slice_window(const std::vector<double>& window,
                                                      const std::string& space,
                                                      const std::optional<WorldSpec>& world) {
  if (!window.empty() && !space.empty())
    throw InputError("--space", "", "either --space or --window, not both");
  if (!window.empty()) {
    if (window.size() != 4) throw InputError("--window", "", "four numbers x0,y0,x1,y1");
    return Eigen::Vector4d(window[0], window[1], window[2], window[3]);
  }
  if (space.empty()) return std::nullopt;
  if (!world) throw InputError("--space", "", "a world YAML input (hidden spaces are named there)");
  return hidden_space_window(*world, space, 0.5, "--space");
}

OccupancyMap2D slice_octree(const octomap::OcTree& tree, const SliceOptions& options) {
  if (tree.size() == 0) throw InputError("octree", "", "a non-empty tree to slice");
  if (!std::isfinite(options.z_m) || !std::isfinite(options.half_band_m) || options.half_band_m < 0)
    throw InputError("--z", "", "a finite height and a band >= 0");
  const double res = tree.getResolution();
  double x0, y0, z0, x1, y1, z1;
  tree.getMetricMin(x0, y0, z0);
  tree.getMetricMax(x1, y1, z1);
  if (options.window_m) {
    const Eigen::Vector4d& w = *options.window_m;
    if (!w.allFinite() || w[2] <= w[0] || w[3] <= w[1] || w[0] >= x1 || w[2] <= x0 || w[1] >= y1 ||
        w[3] <= y0)
      throw InputError("--window", "",
                       fmt::format("x0 < x1 and y0 < y1 overlapping the known extent [{:.4g}, "
                                   "{:.4g}] x [{:.4g}, {:.4g}]",
                                   x0, x1, y0, y1),
                       fmt::format("[{}, {}, {}, {}]", w[0], w[1], w[2], w[3]));
    // Whole voxels: the cells the window touches (a window edge on a voxel edge,
    // up to rounding, does not pull in the next voxel).
    x0 = std::max(x0, std::floor(w[0] / res + 1e-9) * res);
    y0 = std::max(y0, std::floor(w[1] / res + 1e-9) * res);
    x1 = std::min(x1, std::ceil(w[2] / res - 1e-9) * res);
    y1 = std::min(y1, std::ceil(w[3] / res - 1e-9) * res);
  }
  octomap::OcTreeKey kmin, kmax;
  if (!tree.coordToKeyChecked(x0 + res / 2, y0 + res / 2, options.z_m - options.half_band_m,
                              kmin) ||
      !tree.coordToKeyChecked(x1 - res / 2, y1 - res / 2, options.z_m + options.half_band_m, kmax))
    throw InputError("--z", "",
                     fmt::format("a height within the tree's key range (+-{} m)", 32767 * res),
                     fmt::format("{}", options.z_m));
  OccupancyMap2D map;
  map.geometry =
      GridGeometry{tree.keyToCoord(kmin[0]) - res / 2, tree.keyToCoord(kmin[1]) - res / 2, res,
                   kmax[0] - kmin[0] + 1, kmax[1] - kmin[1] + 1};
  const int layers = kmax[2] - kmin[2] + 1;
  std::vector<std::uint8_t> occupied(map.geometry.size(), 0);
  std::vector<int> free_layers(map.geometry.size(), 0);
  for (auto it = tree.begin_leafs_bbx(kmin, kmax), end = tree.end_leafs_bbx(); it != end; ++it) {
    // A leaf above the finest depth covers a cube of keys; clip it to the slice.
    const int span = 1 << (kTreeDepth - it.getDepth());
    const octomap::OcTreeKey c = tree.coordToKey(it.getCoordinate());
    std::array<int, 3> lo{}, hi{};
    for (int a = 0; a < 3; ++a) {
      const int first = (c[a] / span) * span;  // cubes at a depth are aligned to their span
      lo[a] = std::max<int>(first, kmin[a]);
      hi[a] = std::min<int>(first + span - 1, kmax[a]);
    }
    if (lo[0] > hi[0] || lo[1] > hi[1] || lo[2] > hi[2]) continue;
    const bool occ = tree.isNodeOccupied(*it);
    for (int j = lo[1]; j <= hi[1]; ++j)
      for (int i = lo[0]; i <= hi[0]; ++i) {
        const std::size_t idx = map.geometry.index({i - kmin[0], j - kmin[1]});
        if (occ)
          occupied[idx] = 1;
        else
          free_layers[idx] += hi[2] - lo[2] + 1;
      }
  }
  map.cells.resize(map.geometry.size());
  for (std::size_t k = 0; k < map.cells.size(); ++k)
    map.cells[k] = occupied[k]                ? CellState::kOccupied
                   : free_layers[k] == layers ? CellState::kFree
                                              : CellState::kUnknown;
  return map;
}

OctreeSummary summarize_octree(const octomap::OcTree& tree) {
  OctreeSummary s;
  s.resolution_m = tree.getResolution();
  s.nodes = tree.size();
  s.memory_bytes = tree.memoryUsage();
  if (s.nodes == 0) return s;
  tree.getMetricMin(s.min_m.x(), s.min_m.y(), s.min_m.z());
  tree.getMetricMax(s.max_m.x(), s.max_m.y(), s.max_m.z());
  for (auto it = tree.begin_leafs(), end = tree.end_leafs(); it != end; ++it) {
    const double v = std::pow(it.getSize(), 3);
    ++s.leaves;
    if (tree.isNodeOccupied(*it)) {
      ++s.occupied_leaves;
      s.occupied_volume_m3 += v;
    } else {
      ++s.free_leaves;
      s.free_volume_m3 += v;
    }
  }
  return s;
}

}  // namespace ferret
