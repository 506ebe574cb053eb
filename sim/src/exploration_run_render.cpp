// PNG figures of one search, like the paper's map figure: G, O with the object's
// cells in yellow, and both together; frontiers green, the driven path blue. Drawn
// with the mapping module's MapCanvas (scale bar included).
#include <algorithm>
#include <stdexcept>

#include "ferret/mapping/map_render.hpp"
#include "ferret/sim/exploration_run.hpp"

namespace ferret {
namespace {

const Rgb kFrontier{0, 190, 0}, kObject{255, 220, 0}, kEvidence{255, 140, 0}, kPath{0, 70, 210},
    kTruthWall{215, 215, 215}, kTruthObject{220, 0, 0}, kSeenLow{255, 255, 255},
    kSeenHigh{90, 90, 255};

// G as a map: free, occupied, unknown.
OccupancyMap2D grid_as_map(const IrGrid& grid) {
  OccupancyMap2D m;
  m.geometry = grid.geometry();
  m.cells.resize(m.geometry.size());
  for (std::size_t idx = 0; idx < m.cells.size(); ++idx) {
    switch (grid.label_at(idx)) {
      case GridLabel::kFree:
        m.cells[idx] = CellState::kFree;
        break;
      case GridLabel::kOccupied:
        m.cells[idx] = CellState::kOccupied;
        break;
      case GridLabel::kUnknown:
        m.cells[idx] = CellState::kUnknown;
        break;
    }
  }
  return m;
}

// O's footprint as a map: cells the camera has measured are "free", the rest unknown.
OccupancyMap2D observed_as_map(const ObjectMap& objects) {
  OccupancyMap2D m;
  m.geometry = objects.geometry();
  m.cells.resize(m.geometry.size());
  for (std::size_t idx = 0; idx < m.cells.size(); ++idx)
    m.cells[idx] = objects.observed(idx) ? CellState::kFree : CellState::kUnknown;
  return m;
}

void draw_truth_walls(MapCanvas& canvas, const OccupancyMap2D& truth, const IrGrid& grid) {
  std::vector<Cell> hidden;  // walls G has not seen, faintly, for orientation
  for (std::size_t idx = 0; idx < truth.cells.size(); ++idx)
    if (truth.cells[idx] != CellState::kFree && grid.label_at(idx) == GridLabel::kUnknown)
      hidden.push_back(truth.geometry.cell_of_index(idx));
  canvas.draw_cells(truth.geometry, hidden, kTruthWall);
}

void draw_objects(MapCanvas& canvas, const ObjectMap& objects, bool seen_field) {
  const GridGeometry& g = objects.geometry();
  if (seen_field) {  // seen without the object: white (p = 0.5) to blue (p = 0)
    std::vector<double> values(g.size(), -1.0);
    for (std::size_t idx = 0; idx < values.size(); ++idx) {
      const double p = objects.probability_at(idx);
      if (objects.observed(idx) && p <= 0.5) values[idx] = (0.5 - p) / 0.5;
    }
    canvas.draw_field(g, values, kSeenLow, kSeenHigh, 0.8);
  }
  std::vector<Cell> object, evidence;
  for (const std::size_t idx : objects.evidence_cells())
    (objects.label_of(objects.probability_at(idx)) == ObjectLabel::kObject ? object : evidence)
        .push_back(g.cell_of_index(idx));
  canvas.draw_cells(g, evidence, kEvidence);
  canvas.draw_cells(g, object, kObject);
}

void draw_run(MapCanvas& canvas, const GridGeometry& g, const Eigen::Vector2d& object_W,
              const EpisodeResult& r) {
  canvas.draw_cells(g, r.frontier, kFrontier);
  std::vector<Eigen::Vector2d> path;
  path.reserve(r.trajectory.size());
  for (const Pose2& p : r.trajectory) path.push_back(p.position());
  canvas.draw_path(path, kPath);
  if (!r.trajectory.empty()) {
    canvas.draw_circle(r.trajectory.front().position(), 0.15, kPath);
    canvas.draw_pose(r.trajectory.back(), kPath, 0.4);
  }
  canvas.draw_circle(object_W, 0.12, kTruthObject);
}

}  // namespace

void write_exploration_images(const OccupancyMap2D& truth, const Eigen::Vector2d& object_W,
                              const EpisodeResult& r, const std::filesystem::path& dir) {
  if (!r.grid || !r.objects)
    throw std::invalid_argument("write_exploration_images: the run was not recorded");
  const GridGeometry& g = r.grid->geometry();
  const OccupancyMap2D g_map = grid_as_map(*r.grid);

  MapCanvas img_g(g_map);
  draw_truth_walls(img_g, truth, *r.grid);
  draw_run(img_g, g, object_W, r);

  MapCanvas img_o(observed_as_map(*r.objects));
  draw_objects(img_o, *r.objects, true);
  draw_run(img_o, g, object_W, r);

  MapCanvas img_go(g_map);
  draw_truth_walls(img_go, truth, *r.grid);
  draw_objects(img_go, *r.objects, false);
  draw_run(img_go, g, object_W, r);

  std::filesystem::create_directories(dir);
  img_g.save_png(dir / "G.png");
  img_o.save_png(dir / "O.png");
  img_go.save_png(dir / "G_O.png");
}

}  // namespace ferret
