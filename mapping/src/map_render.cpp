#include "ferret/mapping/map_render.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <opencv2/core.hpp>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include "ferret/core/atomic_file.hpp"
#include "ferret/core/error.hpp"
#include "ferret/mapping/world_spec.hpp"

namespace ferret {
namespace fs = std::filesystem;

namespace {
cv::Scalar bgr(Rgb c) {
  return {static_cast<double>(c.b), static_cast<double>(c.g), static_cast<double>(c.r)};
}

// 1, 2 or 5 times a power of ten: the longest such length not above `limit`.
double nice_length(double limit) {
  const double p = std::pow(10.0, std::floor(std::log10(limit)));
  for (const double m : {5.0, 2.0, 1.0})
    if (m * p <= limit) return m * p;
  return p;
}

std::string metres_label(double m) {
  return m >= 1.0 ? fmt::format("{:g} m", m) : fmt::format("{:g} cm", m * 100);
}

void check_png_path(const fs::path& path) {
  if (path.extension() != ".png")
    throw InputError(path.string(), "", "an output path ending in .png");
}

cv::Mat to_bgr_mat(const RgbImage& image) {
  cv::Mat out(image.height, image.width, CV_8UC3);
  for (int r = 0; r < image.height; ++r)
    for (int c = 0; c < image.width; ++c) {
      const Rgb p = image.at(c, r);
      out.at<cv::Vec3b>(r, c) = {p.b, p.g, p.r};
    }
  return out;
}
RgbImage from_bgr_mat(const cv::Mat& img) {
  RgbImage out{img.cols, img.rows, std::vector<std::uint8_t>(img.total() * 3)};
  for (int r = 0; r < img.rows; ++r)
    for (int c = 0; c < img.cols; ++c) {
      const cv::Vec3b p = img.at<cv::Vec3b>(r, c);
      const std::size_t k = (static_cast<std::size_t>(r) * img.cols + c) * 3;
      out.data[k] = p[2], out.data[k + 1] = p[1], out.data[k + 2] = p[0];
    }
  return out;
}
}  // namespace

struct MapCanvas::Impl {
  GridGeometry geometry;
  RenderOptions options;
  int scale = 1;
  cv::Mat image;  // BGR

  // Text and marks grow with the picture so they stay legible when it is shrunk for viewing.
  [[nodiscard]] double text_scale() const {
    return 0.5 * std::max(1.0, std::max(image.cols, image.rows) / 1000.0);
  }
  [[nodiscard]] int line_px() const {
    return std::max(1, static_cast<int>(std::lround(text_scale() * 2)));
  }

  [[nodiscard]] cv::Point pixel(const Eigen::Vector2d& p_W) const {
    const Eigen::Vector2d px = to_pixel(p_W);
    return {static_cast<int>(std::lround(px.x())), static_cast<int>(std::lround(px.y()))};
  }
  [[nodiscard]] Eigen::Vector2d to_pixel(const Eigen::Vector2d& p_W) const {
    const double s = scale / geometry.resolution_m;
    return {(p_W.x() - geometry.origin_x_m) * s,
            (geometry.origin_y_m + geometry.height_m() - p_W.y()) * s};
  }
  // Pixel rectangle of a cell of any grid.
  [[nodiscard]] cv::Rect cell_rect(const GridGeometry& g, Cell c) const {
    const Eigen::Vector2d lo =
        to_pixel({g.origin_x_m + c.i * g.resolution_m, g.origin_y_m + (c.j + 1) * g.resolution_m});
    const Eigen::Vector2d hi =
        to_pixel({g.origin_x_m + (c.i + 1) * g.resolution_m, g.origin_y_m + c.j * g.resolution_m});
    const int x0 = static_cast<int>(std::lround(lo.x())),
              y0 = static_cast<int>(std::lround(lo.y()));
    const int x1 = std::max(x0 + 1, static_cast<int>(std::lround(hi.x())));
    const int y1 = std::max(y0 + 1, static_cast<int>(std::lround(hi.y())));
    return cv::Rect(x0, y0, x1 - x0, y1 - y0) & cv::Rect(0, 0, image.cols, image.rows);
  }
  void blend(const cv::Rect& r, Rgb color, double alpha) {
    if (r.empty()) return;
    cv::Mat roi = image(r);
    if (alpha >= 1.0) {
      roi.setTo(bgr(color));
    } else {
      cv::Mat solid(roi.size(), roi.type(), bgr(color));
      cv::addWeighted(solid, alpha, roi, 1.0 - alpha, 0.0, roi);
    }
  }
};

MapCanvas::MapCanvas(const OccupancyMap2D& map, const RenderOptions& options)
    : impl_(std::make_unique<Impl>()) {
  const GridGeometry& g = map.geometry;
  if (g.width <= 0 || g.height <= 0 || map.cells.size() != g.size())
    throw InputError("map", "", "a non-empty map whose cell count matches its geometry");
  impl_->geometry = g;
  impl_->options = options;
  int s = options.pixels_per_cell;
  if (s <= 0)
    s = std::clamp(
        (options.min_size_px + std::max(g.width, g.height) - 1) / std::max(g.width, g.height), 1,
        16);
  if (static_cast<double>(g.width) * s * g.height * s > 1.2e8)
    throw InputError("render", "pixels_per_cell", "a picture of at most 120 megapixels",
                     fmt::format("{} x {} px", g.width * s, g.height * s));
  impl_->scale = s;
  cv::Mat cells(g.height, g.width, CV_8UC3);
  for (int j = 0; j < g.height; ++j)
    for (int i = 0; i < g.width; ++i) {
      const CellState st = map.at({i, j});
      const Rgb c = st == CellState::kOccupied ? options.occupied
                    : st == CellState::kFree   ? options.free
                                               : options.unknown;
      cells.at<cv::Vec3b>(g.height - 1 - j, i) = {c.b, c.g, c.r};
    }
  cv::resize(cells, impl_->image, cv::Size(g.width * s, g.height * s), 0, 0, cv::INTER_NEAREST);
  if (options.grid_spacing_m > 0) {
    const double step = options.grid_spacing_m;
    const cv::Scalar grid_colour(200, 170, 140);
    for (double x = std::ceil(g.origin_x_m / step) * step; x <= g.origin_x_m + g.width_m();
         x += step) {
      const int px = impl_->pixel({x, g.origin_y_m}).x;
      cv::line(impl_->image, {px, 0}, {px, impl_->image.rows - 1}, grid_colour, 1);
    }
    for (double y = std::ceil(g.origin_y_m / step) * step; y <= g.origin_y_m + g.height_m();
         y += step) {
      const int py = impl_->pixel({g.origin_x_m, y}).y;
      cv::line(impl_->image, {0, py}, {impl_->image.cols - 1, py}, grid_colour, 1);
    }
  }
}

MapCanvas::~MapCanvas() = default;
MapCanvas::MapCanvas(MapCanvas&&) noexcept = default;
MapCanvas& MapCanvas::operator=(MapCanvas&&) noexcept = default;

void MapCanvas::draw_path(const std::vector<Eigen::Vector2d>& points_W, Rgb color,
                          int thickness_px) {
  for (std::size_t k = 1; k < points_W.size(); ++k)
    cv::line(impl_->image, impl_->pixel(points_W[k - 1]), impl_->pixel(points_W[k]), bgr(color),
             thickness_px, cv::LINE_AA);
  if (points_W.size() == 1) draw_point(points_W[0], color, thickness_px);
}

void MapCanvas::draw_cells(const GridGeometry& grid, const std::vector<Cell>& cells, Rgb color,
                           double alpha) {
  for (const Cell c : cells)
    impl_->blend(impl_->cell_rect(grid, c), color, std::clamp(alpha, 0.0, 1.0));
}

void MapCanvas::draw_field(const GridGeometry& grid, const std::vector<double>& values, Rgb low,
                           Rgb high, double alpha) {
  if (values.size() != grid.size())
    throw InputError("render", "field", fmt::format("{} values (one a cell)", grid.size()),
                     std::to_string(values.size()));
  for (std::size_t k = 0; k < values.size(); ++k) {
    const double v = values[k];
    if (!(v >= 0.0 && v <= 1.0)) continue;
    auto mix = [v](std::uint8_t a, std::uint8_t b) {
      return static_cast<std::uint8_t>(std::lround(a + (b - a) * v));
    };
    impl_->blend(impl_->cell_rect(grid, grid.cell_of_index(k)),
                 Rgb{mix(low.r, high.r), mix(low.g, high.g), mix(low.b, high.b)},
                 std::clamp(alpha, 0.0, 1.0));
  }
}

void MapCanvas::draw_point(const Eigen::Vector2d& p_W, Rgb color, int radius_px) {
  cv::circle(impl_->image, impl_->pixel(p_W), radius_px, bgr(color), cv::FILLED, cv::LINE_AA);
}

void MapCanvas::draw_circle(const Eigen::Vector2d& center_W, double radius_m, Rgb color,
                            int thickness_px) {
  const int r = std::max(
      1, static_cast<int>(std::lround(radius_m / impl_->geometry.resolution_m * impl_->scale)));
  cv::circle(impl_->image, impl_->pixel(center_W), r, bgr(color), thickness_px, cv::LINE_AA);
}

void MapCanvas::draw_pose(const Pose2& X_W, Rgb color, double length_m) {
  const Eigen::Vector2d tip =
      X_W.position() + length_m * Eigen::Vector2d(std::cos(X_W.yaw_rad), std::sin(X_W.yaw_rad));
  cv::line(impl_->image, impl_->pixel(X_W.position()), impl_->pixel(tip), bgr(color), 2,
           cv::LINE_AA);
  draw_point(X_W.position(), color, 4);
}

void MapCanvas::draw_text(const Eigen::Vector2d& p_W, const std::string& text, Rgb color) {
  const double scale = impl_->text_scale();
  const int thickness = impl_->line_px() / 2 + 1;
  int baseline = 0;
  const cv::Size size =
      cv::getTextSize(text, cv::FONT_HERSHEY_SIMPLEX, scale, thickness, &baseline);
  // Right of the point, or left of it when the label would leave the picture.
  cv::Point at = impl_->pixel(p_W) + cv::Point(6, -6);
  if (at.x + size.width > impl_->image.cols) at.x -= size.width + 12;
  if (at.y - size.height < 0) at.y += size.height + 12;
  cv::putText(impl_->image, text, at, cv::FONT_HERSHEY_SIMPLEX, scale, bgr(color), thickness,
              cv::LINE_AA);
}

Eigen::Vector2d MapCanvas::to_pixel(const Eigen::Vector2d& p_W) const {
  return impl_->to_pixel(p_W);
}
int MapCanvas::pixels_per_cell() const { return impl_->scale; }

RgbImage MapCanvas::image() const {
  cv::Mat img = impl_->image.clone();
  if (impl_->options.scale_bar) {
    // About a fifth of the width, rounded down to 1, 2 or 5 x 10^k metres.
    const double px_per_m = impl_->scale / impl_->geometry.resolution_m;
    const double len_m = nice_length(img.cols / 5.0 / px_per_m);
    const int len_px = static_cast<int>(std::lround(len_m * px_per_m));
    const double k = impl_->text_scale() / 0.5;  // 1 up to 1000 px, growing beyond
    const auto px = [k](double v) { return static_cast<int>(std::lround(v * k)); };
    const cv::Point a(px(12), img.rows - px(14)), b(px(12) + len_px, img.rows - px(14));
    cv::rectangle(img, a + cv::Point(-px(6), -px(26)), b + cv::Point(px(60), px(8)),
                  cv::Scalar(255, 255, 255), cv::FILLED);
    cv::line(img, a, b, cv::Scalar(0, 0, 0), px(3));
    cv::line(img, a + cv::Point(0, -px(6)), a + cv::Point(0, px(6)), cv::Scalar(0, 0, 0), px(2));
    cv::line(img, b + cv::Point(0, -px(6)), b + cv::Point(0, px(6)), cv::Scalar(0, 0, 0), px(2));
    cv::putText(img, metres_label(len_m), a + cv::Point(0, -px(10)), cv::FONT_HERSHEY_SIMPLEX,
                0.45 * k, cv::Scalar(0, 0, 0), std::max(1, px(1)), cv::LINE_AA);
  }
  return from_bgr_mat(img);
}

void MapCanvas::save_png(const fs::path& path) const { write_png(image(), path); }

void draw_world_annotations(MapCanvas& canvas, const WorldSpec& world) {
  const Rgb green{0, 160, 0}, blue{30, 80, 230}, red{220, 20, 20}, orange{255, 140, 0};
  for (const auto& h : world.hidden_spaces) {
    canvas.draw_pose(Pose2{h.p_WE.x(), h.p_WE.y(), h.entry_yaw_rad}, green, 0.6);
    const Eigen::Vector2d m = h.marker.X_WM.translation().head<2>();
    canvas.draw_point(m, blue, 3);
    canvas.draw_text(m, fmt::format("{} #{}", h.name, h.marker.id), blue);
  }
  for (const auto& o : world.objects) {
    canvas.draw_point(o.p_WO().head<2>(), red, 4);
    canvas.draw_text(o.p_WO().head<2>(), o.name, red);
  }
  if (world.drop_zone) {
    canvas.draw_circle(world.drop_zone->center_m, world.drop_zone->radius_m, orange, 2);
    canvas.draw_text(world.drop_zone->center_m, "drop zone", orange);
  }
}

void write_png(const RgbImage& image, const fs::path& path) {
  check_png_path(path);
  if (image.width <= 0 || image.height <= 0 ||
      image.data.size() != static_cast<std::size_t>(image.width) * image.height * 3)
    throw InputError(path.string(), "", "a non-empty image to write");
  const cv::Mat mat = to_bgr_mat(image);
  write_file_atomically(path, [&](const fs::path& tmp) {
    if (!cv::imwrite(tmp.string(), mat)) throw InputError(path.string(), "", "a writable PNG file");
  });
}

RgbImage read_rgb_image(const fs::path& path) {
  const cv::Mat img = cv::imread(path.string(), cv::IMREAD_COLOR);
  if (img.empty())
    throw InputError(path.string(), "", "an image OpenCV can read", "unreadable or corrupt");
  return from_bgr_mat(img);
}

}  // namespace ferret
