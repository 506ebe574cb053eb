// The world as ray-castable primitives and the per-pixel frame cast.
//
// Why ray casting and not rasterised triangles or sphere tracing: every primitive of a
// WorldSpec (plane, yawed box, upright cylinder, marker square) has a closed-form ray
// intersection, so each pixel's depth and normal are exact, lens distortion costs
// nothing (each pixel's ray comes from the camera model once, cached), and there is no
// near-plane clipping of triangles. Cost is kept down like a rasteriser's: a primitive
// is tested only in the 16 x 16 pixel tiles its hull projects to, and only for pixels
// whose ray lies inside that projection.

#include "sensor_sim_scene.hpp"

#include <algorithm>
#include <cmath>
#include <system_error>
#include <thread>

namespace ferret::internal {
namespace {

constexpr double kNearClip_m = 1e-3;  // hull vertices nearer than this are clipped

Hull hull_of(const BoxPrim& b) {
  Hull h;
  h.center = b.center;
  h.axes << b.cos_yaw, -b.sin_yaw, 0, b.sin_yaw, b.cos_yaw, 0, 0, 0, 1;
  h.half = b.half;
  return h;
}
Hull hull_of(const CylinderPrim& c) {
  Hull h;
  h.center = {c.center.x(), c.center.y(), (c.z0 + c.z1) / 2};
  h.half = {c.radius, c.radius, (c.z1 - c.z0) / 2};
  return h;
}
Hull hull_of(const MarkerPrim& m) {
  Hull h;
  h.center = m.p_W;
  h.axes = m.X_MW.linear().transpose();
  h.half = {m.quad_half_m, m.quad_half_m, 0.0};
  return h;
}

/// The hull's projection in normalised image coordinates (x0, x1, y0, y1), clipped to
/// z >= kNearClip_m in C, and its nearest z (a lower bound of any hit's depth: rays
/// have z = 1); false when nothing of it lies in front of the camera.
bool projected_rect(const Hull& h, const Pose3& X_CW, std::array<double, 4>& rect, double& z_min) {
  std::array<Eigen::Vector3d, 8> v;
  for (int i = 0; i < 8; ++i) {
    const Eigen::Vector3d s{(i & 1) ? 1.0 : -1.0, (i & 2) ? 1.0 : -1.0, (i & 4) ? 1.0 : -1.0};
    v[i] = X_CW * (h.center + h.axes * s.cwiseProduct(h.half));
  }
  rect = {kInf, -kInf, kInf, -kInf};
  z_min = kInf;
  bool any = false;
  const auto add = [&](const Eigen::Vector3d& p) {
    rect[0] = std::min(rect[0], p.x() / p.z());
    rect[1] = std::max(rect[1], p.x() / p.z());
    rect[2] = std::min(rect[2], p.y() / p.z());
    rect[3] = std::max(rect[3], p.y() / p.z());
    z_min = std::min(z_min, p.z());
    any = true;
  };
  for (const auto& p : v)
    if (p.z() >= kNearClip_m) add(p);
  // Edges crossing the near plane: corners differing in one bit.
  for (int i = 0; i < 8; ++i)
    for (int bit = 1; bit < 8; bit <<= 1) {
      const int j = i | bit;
      if (j == i) continue;
      const double zi = v[i].z() - kNearClip_m, zj = v[j].z() - kNearClip_m;
      if ((zi < 0) == (zj < 0)) continue;
      const double s = zi / (zi - zj);
      add(v[i] + s * (v[j] - v[i]));
    }
  return any;
}

[[gnu::always_inline]] inline double hit_box(const BoxPrim& b, const Eigen::Vector3d& o_B,
                                             double dx, double dy, double dz, int& face) {
  const double d[3] = {b.cos_yaw * dx + b.sin_yaw * dy, -b.sin_yaw * dx + b.cos_yaw * dy, dz};
  double t_near = -kInf, t_far = kInf;
  for (int i = 0; i < 3; ++i) {
    if (d[i] == 0.0) {
      if (o_B[i] < -b.half[i] || o_B[i] > b.half[i]) return kInf;
      continue;
    }
    const double inv = 1.0 / d[i];
    double t1 = (-b.half[i] - o_B[i]) * inv, t2 = (b.half[i] - o_B[i]) * inv;
    if (t1 > t2) std::swap(t1, t2);
    if (t1 > t_near) {
      t_near = t1;
      face = 2 * i + (d[i] < 0 ? 1 : 0);
    }
    t_far = std::min(t_far, t2);
  }
  // A ray starting inside the box sees nothing of it (a camera is never in a solid).
  if (t_near > t_far || t_near <= kMinHitT) return kInf;
  return t_near;
}

[[gnu::always_inline]] inline double hit_cylinder(const CylinderPrim& c, const Eigen::Vector3d& o,
                                                  double dx, double dy, double dz, int& face) {
  const double ox = o.x() - c.center.x(), oy = o.y() - c.center.y();
  double best = kInf;
  const double a = dx * dx + dy * dy;
  if (a > 0) {
    const double b = ox * dx + oy * dy, cc = ox * ox + oy * oy - c.radius * c.radius;
    const double disc = b * b - a * cc;
    if (disc >= 0) {
      const double t = (-b - std::sqrt(disc)) / a;
      const double z = o.z() + t * dz;
      if (t > kMinHitT && z >= c.z0 && z <= c.z1) {
        best = t;
        face = 0;
      }
    }
  }
  if (dz != 0) {
    const bool from_above = dz < 0;
    const double zc = from_above ? c.z1 : c.z0;
    const double t = (zc - o.z()) / dz;
    if (t > kMinHitT && t < best) {
      const double x = ox + t * dx, y = oy + t * dy;
      if (x * x + y * y <= c.radius * c.radius) {
        best = t;
        face = from_above ? 1 : 2;
      }
    }
  }
  return best;
}

double hit_marker(const MarkerPrim& m, const Eigen::Vector3d& o, const Eigen::Vector3d& d) {
  const double den = m.n_W.dot(d);
  if (!(den < 0)) return kInf;  // seen from behind or edge-on
  const double t = m.n_W.dot(m.p_W - o) / den;
  if (!(t > kMinHitT)) return kInf;
  const Eigen::Vector3d q = m.X_MW * (o + t * d);
  if (std::abs(q.x()) > m.quad_half_m || std::abs(q.y()) > m.quad_half_m) return kInf;
  return t;
}

double hit_ground(const Scene& s, const Eigen::Vector3d& o, const Eigen::Vector3d& d) {
  const GroundSpec& g = s.ground;
  const double den = d.z() - g.slope_x * d.x() - g.slope_y * d.y();
  if (den == 0.0) return kInf;
  const double t = (g.height_at(o.x(), o.y()) - o.z()) / den;
  if (!(t > kMinHitT)) return kInf;
  const double x = o.x() + t * d.x(), y = o.y() + t * d.y();
  // The ground ends at the world's bounds: beyond is sky.
  if (x < s.xy_min.x() || x > s.xy_max.x() || y < s.xy_min.y() || y > s.xy_max.y()) return kInf;
  return t;
}

/// The ground's hit, pushed back by a hair: a floor slab or a box top lying in the ground
/// plane (a hidden space's floor at ground level) wins the tie instead of striping
/// with it pixel by pixel. 1e-7 relative is a micrometre at 10 m, far below a depth
/// frame's millimetre.
double ground_hit_for_ties(double t) { return t * (1 + 1e-7) + 1e-9; }

bool same_camera(const CameraModel& a, const CameraModel& b) {
  return a.width_px == b.width_px && a.height_px == b.height_px && a.fx_px == b.fx_px &&
         a.fy_px == b.fy_px && a.cx_px == b.cx_px && a.cy_px == b.cy_px && a.skew == b.skew &&
         a.distortion == b.distortion && a.distortion_coefficients == b.distortion_coefficients;
}

}  // namespace

float MarkerPrim::reflectance(double x_m, double y_m) const {
  constexpr float kWhite = 0.9f, kBlack = 0.04f;  // matte print on white paper
  const int n = bitmap.cells.width_px;
  const double col = std::floor((x_m + bitmap_half_m) / cell_m);
  const double row = std::floor((bitmap_half_m - y_m) / cell_m);  // row 0 at the top (+y)
  if (col < 0 || row < 0 || col >= n || row >= n) return kWhite;  // quiet zone
  return bitmap.cells.at(static_cast<int>(col), static_cast<int>(row)) < 128 ? kBlack : kWhite;
}

Scene::Scene(const WorldSpec& world) : ground(world.ground) {
  ground_normal = Eigen::Vector3d(-ground.slope_x, -ground.slope_y, 1.0).normalized();
  xy_min = world.bounds_min_m.head<2>();
  xy_max = world.bounds_max_m.head<2>();
  z_min = world.bounds_min_m.z();
  const auto add_box = [&](const OrientedBox& b, Material m) {
    BoxPrim p;
    p.center = b.center_m;
    p.half = b.size_m / 2;
    p.cos_yaw = std::cos(b.yaw_rad);
    p.sin_yaw = std::sin(b.yaw_rad);
    p.material = m;
    boxes.push_back(p);
  };
  for (const auto& b : world.boxes) add_box(b, Material::kStructure);
  for (const auto& b : world.rubble) add_box(b, Material::kRubble);
  for (const auto& o : world.objects) add_box(o.box, Material::kObject);
  for (std::size_t i = 0; i < world.hidden_spaces.size(); ++i) {
    const HiddenSpace& h = world.hidden_spaces[i];
    for (const auto& b : h.solids()) add_box(b, Material::kEnclosure);
    MarkerPrim m;
    m.hidden_space = static_cast<int>(i);
    m.marker = h.marker;
    m.bitmap = marker_bitmap(h.marker.dictionary, h.marker.id);
    m.X_MW = h.marker.X_WM.inverse();
    m.p_W = h.marker.X_WM.translation();
    m.n_W = h.marker.X_WM.linear().col(2);
    m.cell_m = h.marker.size_m / m.bitmap.black_square_cells;
    m.bitmap_half_m = m.cell_m * m.bitmap.cells.width_px / 2;
    m.quad_half_m = m.bitmap_half_m + m.cell_m;
    markers.push_back(std::move(m));
  }
  for (const auto& c : world.cylinders)
    cylinders.push_back({c.center_m, c.base_z_m, c.base_z_m + c.height_m, c.radius_m});
}

std::shared_ptr<const RayTable> Scene::rays(const CameraModel& camera) const {
  {
    const std::lock_guard lock(cache_mutex);
    for (const auto& [model, table] : ray_cache)
      if (same_camera(model, camera)) return table;
  }
  auto table = std::make_shared<RayTable>();
  const int w = camera.width_px, h = camera.height_px;
  table->width = w;
  table->height = h;
  table->x.resize(static_cast<std::size_t>(w) * h);
  table->y.resize(table->x.size());
  for (int v = 0; v < h; ++v)
    for (int u = 0; u < w; ++u) {
      const Eigen::Vector3d r = camera.ray({u, v});
      table->x[static_cast<std::size_t>(v) * w + u] = static_cast<float>(r.x());
      table->y[static_cast<std::size_t>(v) * w + u] = static_cast<float>(r.y());
    }
  table->tiles_x = (w + RayTable::kTile - 1) / RayTable::kTile;
  table->tiles_y = (h + RayTable::kTile - 1) / RayTable::kTile;
  table->tile_rect.assign(static_cast<std::size_t>(table->tiles_x) * table->tiles_y,
                          {INFINITY, -INFINITY, INFINITY, -INFINITY});
  for (int v = 0; v < h; ++v)
    for (int u = 0; u < w; ++u) {
      auto& r = table->tile_rect[static_cast<std::size_t>(v / RayTable::kTile) * table->tiles_x +
                                 u / RayTable::kTile];
      const float x = table->x[static_cast<std::size_t>(v) * w + u];
      const float y = table->y[static_cast<std::size_t>(v) * w + u];
      r = {std::min(r[0], x), std::max(r[1], x), std::min(r[2], y), std::max(r[3], y)};
    }
  table->column_x.assign(table->tiles_x, {INFINITY, -INFINITY});
  table->row_y.assign(table->tiles_y, {INFINITY, -INFINITY});
  for (int ty = 0; ty < table->tiles_y; ++ty)
    for (int tx = 0; tx < table->tiles_x; ++tx) {
      const auto& r = table->tile_rect[static_cast<std::size_t>(ty) * table->tiles_x + tx];
      auto& cx = table->column_x[tx];
      auto& ry = table->row_y[ty];
      cx = {std::min(cx[0], r[0]), std::max(cx[1], r[1])};
      ry = {std::min(ry[0], r[2]), std::max(ry[1], r[3])};
    }
  const std::lock_guard lock(cache_mutex);
  if (ray_cache.size() >= 8) ray_cache.erase(ray_cache.begin());
  ray_cache.emplace_back(camera, table);
  return table;
}

void for_each_interleaved(int n, const std::function<void(int)>& body) {
  static const int threads =
      static_cast<int>(std::clamp(std::thread::hardware_concurrency(), 1u, 4u));
  const int t_count = std::min(threads, n);
  if (t_count <= 1) {
    for (int k = 0; k < n; ++k) body(k);
    return;
  }
  const auto run = [&](int first) {
    for (int k = first; k < n; k += t_count) body(k);
  };
  std::vector<std::thread> workers;
  workers.reserve(static_cast<std::size_t>(t_count - 1));
  try {
    for (int t = 1; t < t_count; ++t) workers.emplace_back(run, t);
  } catch (const std::system_error&) {
    // No thread to be had: this one does the rest of the items too.
    for (int t = static_cast<int>(workers.size()) + 1; t < t_count; ++t) run(t);
  }
  run(0);
  for (auto& w : workers) w.join();
}

namespace {

/// Calls f(k) for every tile k whose rays' bounds overlap `rect` (normalised image
/// coordinates) until f returns false; false then, else true.
template <typename F>
bool for_each_tile_under(const RayTable& rays, const std::array<double, 4>& rect, F&& f) {
  std::vector<int> columns;
  for (int tx = 0; tx < rays.tiles_x; ++tx)
    if (rays.column_x[tx][1] >= rect[0] && rays.column_x[tx][0] <= rect[1]) columns.push_back(tx);
  for (int ty = 0; ty < rays.tiles_y && !columns.empty(); ++ty) {
    if (rays.row_y[ty][1] < rect[2] || rays.row_y[ty][0] > rect[3]) continue;
    for (const int tx : columns) {
      const std::size_t k = static_cast<std::size_t>(ty) * rays.tiles_x + tx;
      const auto& tr = rays.tile_rect[k];
      if (tr[1] < rect[0] || tr[0] > rect[1] || tr[3] < rect[2] || tr[2] > rect[3]) continue;
      if (!f(k)) return false;
    }
  }
  return true;
}

}  // namespace

bool Scene::markers_in_frame(const RayTable& rays, const Pose3& X_WC) const {
  const Pose3 X_CW = X_WC.inverse();
  for (const MarkerPrim& m : markers) {
    std::array<double, 4> rect{};
    double z_min = 0.0;
    if (!projected_rect(hull_of(m), X_CW, rect, z_min)) continue;
    if (!for_each_tile_under(rays, rect, [](std::size_t) { return false; })) return true;
  }
  return false;
}

void Scene::cast_frame(const RayTable& rays, const Pose3& X_WC, bool with_markers,
                       CastBuffers& out) const {
  const int w = rays.width, h = rays.height;
  const std::size_t n = static_cast<std::size_t>(w) * h;
  out.t.resize(n);
  out.code.resize(n);
  const Eigen::Matrix3d R = X_WC.linear();
  const Eigen::Vector3d o = X_WC.translation();
  const Pose3 X_CW = X_WC.inverse();

  // The primitives in front of the camera, nearest first, each with its projection
  // and a lower bound of its depth: a pixel that already has a nearer hit stops there.
  struct FramePrim {
    PrimKind kind;
    std::size_t index;
    double z_min;
    std::array<double, 4> rect;
    Eigen::Vector3d o_B;  // boxes: the camera centre in the box's frame
  };
  std::vector<FramePrim> solids, marks;
  const auto add = [&](std::vector<FramePrim>& list, PrimKind kind, std::size_t index,
                       const Hull& hull) {
    FramePrim p{kind, index, 0.0, {}, Eigen::Vector3d::Zero()};
    if (projected_rect(hull, X_CW, p.rect, p.z_min)) list.push_back(p);
  };
  for (std::size_t b = 0; b < boxes.size(); ++b) add(solids, PrimKind::kBox, b, hull_of(boxes[b]));
  for (std::size_t c = 0; c < cylinders.size(); ++c)
    add(solids, PrimKind::kCylinder, c, hull_of(cylinders[c]));
  if (with_markers)
    for (std::size_t m = 0; m < markers.size(); ++m)
      add(marks, PrimKind::kMarker, m, hull_of(markers[m]));
  const auto nearer = [](const FramePrim& a, const FramePrim& b) {
    return a.z_min < b.z_min || (a.z_min == b.z_min && a.index < b.index);
  };
  std::sort(solids.begin(), solids.end(), nearer);
  std::sort(marks.begin(), marks.end(), nearer);
  for (auto& p : solids)
    if (p.kind == PrimKind::kBox) {
      const BoxPrim& box = boxes[p.index];
      const Eigen::Vector3d rel = o - box.center;
      p.o_B = {box.cos_yaw * rel.x() + box.sin_yaw * rel.y(),
               -box.sin_yaw * rel.x() + box.cos_yaw * rel.y(), rel.z()};
    }

  // Bins: the primitives whose projection overlaps each tile, nearest first.
  const std::size_t tiles = static_cast<std::size_t>(rays.tiles_x) * rays.tiles_y;
  std::vector<std::vector<const FramePrim*>> solid_bins(tiles), mark_bins(tiles);
  const auto bin = [&](const std::vector<FramePrim>& list,
                       std::vector<std::vector<const FramePrim*>>& bins) {
    for (const FramePrim& p : list)
      for_each_tile_under(rays, p.rect, [&](std::size_t k) {
        bins[k].push_back(&p);
        return true;
      });
  };
  bin(solids, solid_bins);
  bin(marks, mark_bins);

  // Row by row across a band of tiles (not tile by tile): the per-pixel tables and
  // buffers are then read and written in order, which the cache prefetches; tile by
  // tile touched 16 rows' worth of streams at once and waited on memory.
  for_each_interleaved(rays.tiles_y, [&](int ty) {
    const int v1 = std::min(h, (ty + 1) * RayTable::kTile);
    for (int v = ty * RayTable::kTile; v < v1; ++v)
      for (int tx = 0; tx < rays.tiles_x; ++tx) {
        const std::size_t k = static_cast<std::size_t>(ty) * rays.tiles_x + tx;
        const auto& sb = solid_bins[k];
        const auto& mb = mark_bins[k];
        const int u1 = std::min(w, (tx + 1) * RayTable::kTile);
        for (int u = tx * RayTable::kTile; u < u1; ++u) {
          const std::size_t i = static_cast<std::size_t>(v) * w + u;
          const double x = rays.x[i], y = rays.y[i];
          const Eigen::Vector3d d = ray_direction(R, rays, i);
          const double t_ground = hit_ground(*this, o, d);
          double best = ground_hit_for_ties(t_ground);
          std::int32_t code = best < kInf ? hit_code(PrimKind::kGround, 0, 0) : -1;
          for (const FramePrim* p : sb) {
            if (best <= p->z_min) break;  // this and every later one lie behind the hit
            if (x < p->rect[0] || x > p->rect[1] || y < p->rect[2] || y > p->rect[3]) continue;
            int face = 0;
            const double t = p->kind == PrimKind::kBox
                                 ? hit_box(boxes[p->index], p->o_B, d.x(), d.y(), d.z(), face)
                                 : hit_cylinder(cylinders[p->index], o, d.x(), d.y(), d.z(), face);
            if (t < best) {
              best = t;
              code = hit_code(p->kind, p->index, face);
            }
          }
          for (const FramePrim* p : mb) {
            // Markers are printed on a surface (1 mm off it): they win a tie with it.
            if (p->z_min > (best + 1e-3) / (1 - 1e-4)) break;
            if (x < p->rect[0] || x > p->rect[1] || y < p->rect[2] || y > p->rect[3]) continue;
            const double t = hit_marker(markers[p->index], o, d);
            if (t < kInf && t <= best + 1e-3 + 1e-4 * t) {
              best = t;
              code = hit_code(PrimKind::kMarker, p->index, 0);
            }
          }
          out.t[i] = static_cast<float>(code >= 0 && code_kind(code) == PrimKind::kGround ? t_ground
                                                                                          : best);
          out.code[i] = code;
        }
      }
  });
}

double Scene::cast(const Eigen::Vector3d& o, const Eigen::Vector3d& d, std::int32_t* code) const {
  const double t_ground = hit_ground(*this, o, d);
  double best = ground_hit_for_ties(t_ground);
  std::int32_t best_code = best < kInf ? hit_code(PrimKind::kGround, 0, 0) : -1;
  for (std::size_t b = 0; b < boxes.size(); ++b) {
    const BoxPrim& box = boxes[b];
    const Eigen::Vector3d rel = o - box.center;
    const Eigen::Vector3d o_B{box.cos_yaw * rel.x() + box.sin_yaw * rel.y(),
                              -box.sin_yaw * rel.x() + box.cos_yaw * rel.y(), rel.z()};
    int face = 0;
    const double t = hit_box(box, o_B, d.x(), d.y(), d.z(), face);
    if (t < best) {
      best = t;
      best_code = hit_code(PrimKind::kBox, b, face);
    }
  }
  for (std::size_t c = 0; c < cylinders.size(); ++c) {
    int face = 0;
    const double t = hit_cylinder(cylinders[c], o, d.x(), d.y(), d.z(), face);
    if (t < best) {
      best = t;
      best_code = hit_code(PrimKind::kCylinder, c, face);
    }
  }
  if (best_code >= 0 && code_kind(best_code) == PrimKind::kGround) best = t_ground;
  if (code) *code = best_code;
  return best;
}

Eigen::Vector3d Scene::normal(std::int32_t code, const Eigen::Vector3d& p_W,
                              const Eigen::Vector3d& d) const {
  Eigen::Vector3d n = Eigen::Vector3d::UnitZ();
  const std::size_t i = code_index(code);
  const int face = code_face(code);
  switch (code_kind(code)) {
    case PrimKind::kGround:
      n = ground_normal;
      break;
    case PrimKind::kBox: {
      const BoxPrim& b = boxes[i];
      const double sign = (face & 1) ? 1.0 : -1.0;
      const int axis = face / 2;
      n = axis == 0   ? Eigen::Vector3d(b.cos_yaw, b.sin_yaw, 0)
          : axis == 1 ? Eigen::Vector3d(-b.sin_yaw, b.cos_yaw, 0)
                      : Eigen::Vector3d::UnitZ();
      n *= sign;
      break;
    }
    case PrimKind::kCylinder: {
      const CylinderPrim& c = cylinders[i];
      if (face == 0)
        n = Eigen::Vector3d(p_W.x() - c.center.x(), p_W.y() - c.center.y(), 0).normalized();
      else
        n = Eigen::Vector3d(0, 0, face == 1 ? 1.0 : -1.0);
      break;
    }
    case PrimKind::kMarker:
      n = markers[i].n_W;
      break;
  }
  if (n.dot(d) > 0) n = -n;
  return n;
}

}  // namespace ferret::internal
