// PNG figures of one search, like the paper's map figure: G, O with the object's
// cells in yellow, and both together; frontiers green, the driven path blue.
#include <opencv2/core.hpp>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>
#include <stdexcept>

#include "ferret/core/atomic_file.hpp"
#include "ferret/sim/exploration_run.hpp"

namespace ferret {
namespace {

constexpr int kScale = 4;  // pixels per cell

const cv::Vec3b kUnknown(160, 160, 160), kFree(255, 255, 255), kOccupied(0, 0, 0), kFrontier(0, 200, 0),
    kObject(0, 230, 255), kTruthWall(215, 215, 215);

cv::Mat blank(const GridGeometry& g) { return cv::Mat(g.height * kScale, g.width * kScale, CV_8UC3, kUnknown); }

void fill(cv::Mat& img, const GridGeometry& g, Cell c, const cv::Vec3b& color) {
  const int row = (g.height - 1 - c.j) * kScale, col = c.i * kScale;  // row 0 of the image is the top
  img(cv::Rect(col, row, kScale, kScale)).setTo(cv::Scalar(color[0], color[1], color[2]));
}

cv::Point pixel(const GridGeometry& g, const Eigen::Vector2d& p) {
  return {static_cast<int>((p.x() - g.origin_x_m) / g.resolution_m * kScale),
          static_cast<int>((g.height - (p.y() - g.origin_y_m) / g.resolution_m) * kScale)};
}

void draw_grid(cv::Mat& img, const OccupancyMap2D& truth, const IrGrid& grid) {
  const GridGeometry& g = grid.geometry();
  for (int j = 0; j < g.height; ++j)
    for (int i = 0; i < g.width; ++i) {
      const Cell c{i, j};
      switch (grid.label(c)) {
        case GridLabel::kFree: fill(img, g, c, kFree); break;
        case GridLabel::kOccupied: fill(img, g, c, kOccupied); break;
        case GridLabel::kUnknown:
          if (truth.at(c) != CellState::kFree) fill(img, g, c, kTruthWall);  // faint truth for orientation
          break;
      }
    }
}

void draw_objects(cv::Mat& img, const ObjectMap& objects, bool background) {
  const GridGeometry& g = objects.geometry();
  for (int j = 0; j < g.height; ++j)
    for (int i = 0; i < g.width; ++i) {
      const Cell c{i, j};
      const std::size_t idx = g.index(c);
      const double p = objects.probability_at(idx);
      if (objects.label_of(p) == ObjectLabel::kObject) {
        fill(img, g, c, kObject);
      } else if (p > 0.5) {  // evidence below lambda2: orange, stronger with p
        const double w = (p - 0.5) / (objects.options().lambda2 - 0.5);
        fill(img, g, c, cv::Vec3b(0, static_cast<uchar>(200 - 80 * w), 255));
      } else if (background && objects.observed(idx)) {
        const auto shade = static_cast<uchar>(255 - 255 * std::clamp((0.5 - p) / 0.5, 0.0, 1.0) * 0.6);
        fill(img, g, c, cv::Vec3b(255, shade, shade));  // blue-ish: seen, no object
      }
    }
}

void draw_overlay(cv::Mat& img, const GridGeometry& g, const Eigen::Vector2d& object_W, const EpisodeResult& r) {
  for (const Cell& c : r.frontier) fill(img, g, c, kFrontier);
  for (std::size_t k = 1; k < r.trajectory.size(); ++k)
    cv::line(img, pixel(g, r.trajectory[k - 1].position()), pixel(g, r.trajectory[k].position()),
             cv::Scalar(200, 60, 0), 2, cv::LINE_AA);
  if (!r.trajectory.empty()) {
    cv::circle(img, pixel(g, r.trajectory.front().position()), 6, cv::Scalar(200, 60, 0), 2, cv::LINE_AA);
    const Pose2& last = r.trajectory.back();
    cv::circle(img, pixel(g, last.position()), 5, cv::Scalar(200, 60, 0), cv::FILLED, cv::LINE_AA);
  }
  cv::drawMarker(img, pixel(g, object_W), cv::Scalar(0, 0, 220), cv::MARKER_TILTED_CROSS, 14, 2);
}

void write_png(const std::filesystem::path& path, const cv::Mat& img) {
  write_file_atomically(path, [&](const std::filesystem::path& tmp) {
    if (!cv::imwrite(tmp.string() + ".png", img)) throw std::runtime_error("cannot write " + path.string());
    std::filesystem::rename(tmp.string() + ".png", tmp);
  });
}

}  // namespace

void write_exploration_images(const OccupancyMap2D& truth, const Eigen::Vector2d& object_W, const EpisodeResult& r,
                              const std::filesystem::path& dir) {
  if (!r.grid || !r.objects) throw std::invalid_argument("write_exploration_images: the run was not recorded");
  const GridGeometry& g = r.grid->geometry();
  cv::Mat img_g = blank(g), img_o = blank(g), img_go = blank(g);
  draw_grid(img_g, truth, *r.grid);
  draw_overlay(img_g, g, object_W, r);
  draw_objects(img_o, *r.objects, true);
  draw_overlay(img_o, g, object_W, r);
  draw_grid(img_go, truth, *r.grid);
  draw_objects(img_go, *r.objects, false);
  draw_overlay(img_go, g, object_W, r);
  std::filesystem::create_directories(dir);
  write_png(dir / "G.png", img_g);
  write_png(dir / "O.png", img_o);
  write_png(dir / "G_O.png", img_go);
}

}  // namespace ferret
