#include "ferret/mapping/map_render.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <opencv2/core.hpp>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>
#include <optional>

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

// 1, 2 or 5 times a power of ten: the smallest such step not below `limit`.
double nice_step_at_least(double limit) {
  const double p = std::pow(10.0, std::floor(std::log10(limit)));
  for (const double m : {1.0, 2.0, 5.0, 10.0})
    if (m * p >= limit * (1 - 1e-12)) return m * p;
  return 10 * p;
}

// A tick value with as many decimals as the step needs, never "-0".
std::string tick_label(double v, double step) {
  const int decimals = std::max(0, -static_cast<int>(std::floor(std::log10(step) + 1e-9)));
  if (std::abs(v) < 1e-6 * step) v = 0.0;
  return fmt::format("{:.{}f}", v, decimals);
}

constexpr int kFont = cv::FONT_HERSHEY_SIMPLEX;

// Draws `shape` centred at `c`: filled shapes get a dark outline so that light colours
// stay visible on white.
void draw_mark(cv::Mat& img, cv::Point c, Rgb color, LegendMark shape, int r, int line_px) {
  const cv::Scalar fill = bgr(color), edge(40, 40, 40);
  switch (shape) {
    case LegendMark::kLine:
      cv::line(img, c - cv::Point(2 * r, 0), c + cv::Point(2 * r, 0), fill, std::max(2, line_px),
               cv::LINE_AA);
      return;
    case LegendMark::kDot:
      cv::circle(img, c, r, fill, cv::FILLED, cv::LINE_AA);
      cv::circle(img, c, r, edge, 1, cv::LINE_AA);
      return;
    case LegendMark::kRing:
      cv::circle(img, c, r, fill, std::max(2, line_px), cv::LINE_AA);
      return;
    case LegendMark::kDiamond: {
      const std::vector<cv::Point> pts{c + cv::Point(0, -r), c + cv::Point(r, 0),
                                       c + cv::Point(0, r), c + cv::Point(-r, 0)};
      cv::fillConvexPoly(img, pts, fill, cv::LINE_AA);
      cv::polylines(img, pts, true, edge, 1, cv::LINE_AA);
      return;
    }
    case LegendMark::kSwatch:
    case LegendMark::kSquare:
      cv::rectangle(img, c - cv::Point(r, r), c + cv::Point(r, r), fill, cv::FILLED);
      cv::rectangle(img, c - cv::Point(r, r), c + cv::Point(r, r), edge, 1);
      return;
  }
}

cv::Mat to_bgr_mat(const RgbImage& image) {
  cv::Mat out(image.height_px, image.width_px, CV_8UC3);
  for (int r = 0; r < image.height_px; ++r)
    for (int c = 0; c < image.width_px; ++c) {
      const Rgb p = pixel(image, c, r);
      out.at<cv::Vec3b>(r, c) = {p.b, p.g, p.r};
    }
  return out;
}
RgbImage from_bgr_mat(const cv::Mat& img) {
  RgbImage out(img.cols, img.rows);
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
  cv::Mat image;  // BGR, the map alone; the frame is added by image()
  std::string title;
  struct LegendEntry {
    std::string label;
    Rgb color;
    LegendMark mark;
  };
  std::vector<LegendEntry> legend;
  std::optional<ColourBar> bar;

  // Where everything goes in the framed picture.
  struct Layout {
    cv::Rect map, legend, bar;
    cv::Size size;
    double font = 0.5;  // text scale
    int thick = 1;      // text stroke
    double k = 1.0;     // pixels grow by k with the picture
    double x_step = 1, y_step = 1;
  };
  [[nodiscard]] Layout layout() const;
  [[nodiscard]] std::vector<std::string> title_lines() const {
    std::vector<std::string> lines;
    for (std::size_t a = 0; !title.empty() && a <= title.size();) {
      const std::size_t b = std::min(title.find('\n', a), title.size());
      lines.push_back(title.substr(a, b - a));
      a = b + 1;
    }
    return lines;
  }
  void draw_frame(cv::Mat& out, const Layout& l) const;

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
    // Lines closer than 2 px are a solid fill, and a tiny spacing would loop for ever.
    const double min_step_m = 2.0 * g.resolution_m / s;
    if (!(std::isfinite(step) && step >= min_step_m))
      throw InputError(
          "render", "grid_spacing_m",
          fmt::format("a grid spacing of at least 2 pixels ({:g} m for this map)", min_step_m),
          fmt::format("{:g} m", step));
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
  const cv::Rect m = impl_->layout().map;
  return impl_->to_pixel(p_W) + Eigen::Vector2d(m.x, m.y);
}

namespace {
PixelRect to_rect(const cv::Rect& r) { return {r.x, r.y, r.width, r.height}; }
}  // namespace
PixelRect MapCanvas::map_area() const { return to_rect(impl_->layout().map); }
PixelRect MapCanvas::legend_area() const { return to_rect(impl_->layout().legend); }
PixelRect MapCanvas::colour_bar_area() const { return to_rect(impl_->layout().bar); }

void MapCanvas::set_title(std::string title) { impl_->title = std::move(title); }
void MapCanvas::add_legend(std::string label, Rgb color, LegendMark mark) {
  impl_->legend.push_back({std::move(label), color, mark});
}
void MapCanvas::set_colour_bar(ColourBar bar) {
  for (const auto& m : bar.marks)
    if (!(m.value >= 0.0 && m.value <= 1.0))
      throw InputError("render", "colour bar mark", "a value in [0, 1]", std::to_string(m.value));
  impl_->bar = std::move(bar);
}

void MapCanvas::draw_marker(const Eigen::Vector2d& p_W, Rgb color, LegendMark shape,
                            int radius_px) {
  draw_mark(impl_->image, impl_->pixel(p_W), color, shape, radius_px, impl_->line_px());
}
int MapCanvas::pixels_per_cell() const { return impl_->scale; }
bool MapCanvas::contains(const Eigen::Vector2d& p_W, double margin_m) const {
  const GridGeometry& g = impl_->geometry;
  return p_W.x() >= g.origin_x_m - margin_m && p_W.x() <= g.origin_x_m + g.width_m() + margin_m &&
         p_W.y() >= g.origin_y_m - margin_m && p_W.y() <= g.origin_y_m + g.height_m() + margin_m;
}

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
  if (!impl_->options.frame) return from_bgr_mat(img);
  const Impl::Layout l = impl_->layout();
  cv::Mat framed(l.size, CV_8UC3, cv::Scalar(255, 255, 255));
  img.copyTo(framed(l.map));
  impl_->draw_frame(framed, l);
  return from_bgr_mat(framed);
}

MapCanvas::Impl::Layout MapCanvas::Impl::layout() const {
  Layout l;
  const int w = image.cols, h = image.rows;
  if (!options.frame) {
    l.map = cv::Rect(0, 0, w, h);
    l.size = cv::Size(w, h);
    return l;
  }
  l.k = std::max(1.0, std::max(w, h) / 1000.0);
  l.font = 0.5 * l.k;
  l.thick = std::max(1, static_cast<int>(std::lround(l.k)));
  const auto px = [&](double v) { return static_cast<int>(std::lround(v * l.k)); };
  const auto text = [&](const std::string& t, double scale = 1.0) {
    int base = 0;
    return cv::getTextSize(t, kFont, l.font * scale, l.thick, &base);
  };
  const double px_per_m = scale / geometry.resolution_m;
  // Ticks far enough apart that their labels do not touch.
  const auto step_for = [&](double lo_m, double hi_m, bool horizontal) {
    double step = nice_step_at_least(std::max(hi_m - lo_m, geometry.resolution_m) / 8.0);
    for (int guard = 0; guard < 30; ++guard) {
      const int label = horizontal ? std::max(text(tick_label(lo_m, step)).width,
                                              text(tick_label(hi_m, step)).width)
                                   : text("0").height;
      if (step * px_per_m >= label + px(12)) break;
      step = nice_step_at_least(step * 1.5);
    }
    return step;
  };
  const double x0 = geometry.origin_x_m, x1 = x0 + geometry.width_m();
  const double y0 = geometry.origin_y_m, y1 = y0 + geometry.height_m();
  l.x_step = step_for(x0, x1, true);
  l.y_step = step_for(y0, y1, false);
  int label_w = 0;
  for (double y = std::ceil(y0 / l.y_step) * l.y_step; y <= y1 + 1e-9; y += l.y_step)
    label_w = std::max(label_w, text(tick_label(y, l.y_step)).width);
  const cv::Size caption = text("y [m]");
  const int left = px(10) + caption.height + px(10) + label_w + px(10);
  const auto lines = title_lines();
  const int line_h = text("Ag", 1.2).height + px(12);
  const int top = lines.empty() ? px(14) : static_cast<int>(lines.size()) * line_h + px(14);
  const int bottom = px(8) + caption.height + px(12) + caption.height + px(14);
  l.map = cv::Rect(left, top, w, h);

  // Right panel: the legend box, then the colour bar.
  int panel_w = 0, panel_h = 0;
  const int row_h = std::max(text("Ag").height + px(10), px(22));
  if (!legend.empty()) {
    int widest = 0;
    for (const auto& e : legend) widest = std::max(widest, text(e.label).width);
    const int lw = px(12) + px(28) + px(8) + widest + px(12);
    const int lh = px(8) + static_cast<int>(legend.size()) * row_h + px(8);
    l.legend = cv::Rect(left + w + px(16), top, lw, lh);
    panel_w = lw;
    panel_h = lh;
  }
  if (bar) {
    int widest = text(bar->label).width;
    int marks_w = 0;
    for (const auto& m : bar->marks) marks_w = std::max(marks_w, text(m.label).width);
    const int tick_w = text("0.5").width;
    const int bx = left + w + px(16) + tick_w + px(10);
    const int by = top + panel_h + (panel_h ? px(20) : 0) + text(bar->label).height + px(14);
    const int bh = std::max(px(120), std::min(px(260), h - (by - top)));
    l.bar = cv::Rect(bx, by, px(22), bh);
    panel_w = std::max({panel_w, widest, (bx - (left + w + px(16))) + px(22) + px(8) + marks_w});
    panel_h = by + bh - top;
  }
  const int right = panel_w ? px(16) + panel_w + px(14) : px(14);
  int title_w = 0;
  for (const auto& line : lines) title_w = std::max(title_w, text(line, 1.2).width + 2 * px(12));
  l.size = cv::Size(std::max(left + w + right, title_w),
                    std::max(top + h + bottom, top + panel_h + px(14)));
  return l;
}

void MapCanvas::Impl::draw_frame(cv::Mat& out, const Layout& l) const {
  const auto px = [&](double v) { return static_cast<int>(std::lround(v * l.k)); };
  const cv::Scalar ink(30, 30, 30), light(110, 110, 110);
  const auto put = [&](const std::string& t, cv::Point at, double scale = 1.0,
                       const cv::Scalar& colour = cv::Scalar(30, 30, 30)) {
    cv::putText(out, t, at, kFont, l.font * scale, colour, l.thick, cv::LINE_AA);
  };
  const auto size_of = [&](const std::string& t, double scale = 1.0) {
    int base = 0;
    return cv::getTextSize(t, kFont, l.font * scale, l.thick, &base);
  };
  const auto lines = title_lines();
  const int line_h = size_of("Ag", 1.2).height + px(12);
  for (std::size_t i = 0; i < lines.size(); ++i)
    put(lines[i], {px(12), px(4) + static_cast<int>(i + 1) * line_h - px(8)}, 1.2, ink);

  // Axes: ticks and labels in metres below and left of the map, a border round it.
  const cv::Rect m = l.map;
  cv::rectangle(out, m - cv::Point(1, 1) + cv::Size(2, 2), light, 1);
  const double px_per_m = scale / geometry.resolution_m;
  const double x0 = geometry.origin_x_m, x1 = x0 + geometry.width_m();
  const double y0 = geometry.origin_y_m, y1 = y0 + geometry.height_m();
  const int tick = px(6);
  for (double x = std::ceil(x0 / l.x_step - 1e-9) * l.x_step; x <= x1 + 1e-9; x += l.x_step) {
    const int c = m.x + static_cast<int>(std::lround((x - x0) * px_per_m));
    cv::line(out, {c, m.y + m.height}, {c, m.y + m.height + tick}, ink, 1);
    const std::string t = tick_label(x, l.x_step);
    const cv::Size ts = size_of(t);
    put(t, {c - ts.width / 2, m.y + m.height + tick + px(4) + ts.height});
  }
  const cv::Size xcap = size_of("x [m]");
  put("x [m]", {m.x + m.width / 2 - xcap.width / 2,
                m.y + m.height + tick + px(4) + 2 * xcap.height + px(12)});
  int label_w = 0;
  for (double y = std::ceil(y0 / l.y_step - 1e-9) * l.y_step; y <= y1 + 1e-9; y += l.y_step) {
    const int r = m.y + m.height - static_cast<int>(std::lround((y - y0) * px_per_m));
    cv::line(out, {m.x - tick, r}, {m.x - 1, r}, ink, 1);
    const std::string t = tick_label(y, l.y_step);
    const cv::Size ts = size_of(t);
    label_w = std::max(label_w, ts.width);
    put(t, {m.x - tick - px(4) - ts.width, r + ts.height / 2});
  }
  {  // "y [m]" turned a quarter left, centred on the left margin's outer strip
    const cv::Size ys = size_of("y [m]");
    cv::Mat strip(ys.height + px(8), ys.width + px(4), CV_8UC3, cv::Scalar(255, 255, 255));
    cv::putText(strip, "y [m]", {px(2), ys.height + px(2)}, kFont, l.font, ink, l.thick,
                cv::LINE_AA);
    cv::rotate(strip, strip, cv::ROTATE_90_COUNTERCLOCKWISE);
    const int cx = std::max(0, px(8));
    const int cy = std::clamp(m.y + m.height / 2 - strip.rows / 2, 0, out.rows - strip.rows);
    if (cx + strip.cols <= out.cols) strip.copyTo(out(cv::Rect(cx, cy, strip.cols, strip.rows)));
  }

  if (!legend.empty()) {
    const cv::Rect b = l.legend;
    cv::rectangle(out, b, cv::Scalar(250, 250, 250), cv::FILLED);
    cv::rectangle(out, b, light, 1);
    const int row_h = (b.height - 2 * px(8)) / static_cast<int>(legend.size());
    for (std::size_t i = 0; i < legend.size(); ++i) {
      const int cy = b.y + px(8) + static_cast<int>(i) * row_h + row_h / 2;
      draw_mark(out, {b.x + px(12) + px(14), cy}, legend[i].color, legend[i].mark, px(6),
                std::max(2, px(3)));
      put(legend[i].label, {b.x + px(12) + px(28) + px(8), cy + size_of("A").height / 2});
    }
  }
  if (bar) {
    const cv::Rect r = l.bar;
    put(bar->label, {r.x - size_of("0.5").width - px(10), r.y - px(10)});
    // Bottom row is value 0, top row value 1, mixed as draw_field mixes.
    for (int row = 0; row < r.height; ++row) {
      const double v = r.height > 1 ? 1.0 - static_cast<double>(row) / (r.height - 1) : 1.0;
      const auto mix = [v](std::uint8_t a, std::uint8_t b) {
        return static_cast<double>(std::lround(a + (b - a) * v));
      };
      cv::line(out, {r.x, r.y + row}, {r.x + r.width - 1, r.y + row},
               cv::Scalar(mix(bar->low.b, bar->high.b), mix(bar->low.g, bar->high.g),
                          mix(bar->low.r, bar->high.r)),
               1);
    }
    cv::rectangle(out, r - cv::Point(1, 1) + cv::Size(2, 2), light, 1);
    const auto row_of = [&](double v) {
      return r.y + static_cast<int>(std::lround((1.0 - v) * (r.height - 1)));
    };
    for (const double v : {0.0, 0.5, 1.0}) {
      const std::string t = tick_label(v, 0.1);
      const cv::Size ts = size_of(t);
      cv::line(out, {r.x - px(5), row_of(v)}, {r.x - 1, row_of(v)}, ink, 1);
      put(t, {r.x - px(8) - ts.width, row_of(v) + ts.height / 2});
    }
    for (const auto& mk : bar->marks) {
      const int y = row_of(mk.value);
      cv::line(out, {r.x - 1, y}, {r.x + r.width + px(5), y}, ink, std::max(1, px(2)));
      put(mk.label, {r.x + r.width + px(8), y + size_of("A").height / 2});
    }
  }
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
  // Legend entries only for what the picture shows (a window may cut the rest away).
  const auto any_of = [](const auto& items, const auto& shown) {
    return std::any_of(items.begin(), items.end(), shown);
  };
  if (any_of(world.hidden_spaces, [&](const auto& h) { return canvas.contains(h.p_WE.head(2)); }))
    canvas.add_legend("hidden-space entry, heading in", green, LegendMark::kLine);
  if (any_of(world.hidden_spaces,
             [&](const auto& h) { return canvas.contains(h.marker.X_WM.translation().head(2)); }))
    canvas.add_legend("marker (space #id)", blue, LegendMark::kDot);
  if (any_of(world.objects, [&](const auto& o) { return canvas.contains(o.p_WO().head(2)); }))
    canvas.add_legend("object", red, LegendMark::kDot);
  if (world.drop_zone && canvas.contains(world.drop_zone->center_m, world.drop_zone->radius_m))
    canvas.add_legend("drop zone", orange, LegendMark::kRing);
}

void write_png(const RgbImage& image, const fs::path& path) {
  check_png_path(path);
  if (image.width_px <= 0 || image.height_px <= 0 ||
      image.data.size() != static_cast<std::size_t>(image.width_px) * image.height_px * 3)
    throw InputError(path.string(), "", "a non-empty image to write");
  const cv::Mat mat = to_bgr_mat(image);
  write_file_atomically(path, [&](const fs::path& tmp) {
    bool ok = false;
    try {
      ok = cv::imwrite(tmp.string(), mat);
    } catch (const cv::Exception& e) {  // OpenCV throws for some I/O failures
      throw InputError(path.string(), "", "a writable PNG file", e.what());
    }
    if (!ok) throw InputError(path.string(), "", "a writable PNG file");
  });
}

}  // namespace ferret
