// PNG figures of one search, like the paper's map figure: G, O as a probability per
// cell with its colour bar, and both together; frontiers green, the driven path
// magenta. Drawn with the mapping module's MapCanvas (title, metre axes, legend).
#include <fmt/format.h>

#include <algorithm>
#include <stdexcept>

#include "ferret/core/output_set.hpp"
#include "ferret/mapping/map_render.hpp"
#include "ferret/mission/exploration_run.hpp"

namespace ferret {
namespace {

const Rgb kFrontier{0, 190, 0}, kObject{255, 220, 0}, kEvidence{255, 140, 0}, kPath{210, 0, 150},
    kTruthWall{215, 215, 215}, kTruthObject{220, 0, 0}, kProbLow{50, 80, 200},
    kProbHigh{255, 220, 0}, kUnknown{160, 160, 160},
    kUnseen{228, 228, 228};  // lighter than the bar's grey-green middle (p = 0.5)

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

// O as what it is, a probability per observed cell, on the colour bar's scale.
void draw_probability(MapCanvas& canvas, const ObjectMap& objects) {
  const GridGeometry& g = objects.geometry();
  std::vector<double> values(g.size(), -1.0);  // unobserved cells stay grey
  for (std::size_t idx = 0; idx < values.size(); ++idx)
    if (objects.observed(idx)) values[idx] = objects.probability_at(idx);
  canvas.draw_field(g, values, kProbLow, kProbHigh, 1.0);
  const auto& o = objects.options();
  canvas.set_colour_bar(ColourBar{"P(object) per cell",
                                  kProbLow,
                                  kProbHigh,
                                  {{o.lambda1, fmt::format("lambda1 = {:.2f}", o.lambda1)},
                                   {o.lambda2, fmt::format("lambda2 = {:.2f}", o.lambda2)}}});
  canvas.add_legend("not seen by the camera (prior 0.5)", kUnseen, LegendMark::kSwatch);
}

// O's evidence on G: cells above 0.5 in orange, above lambda2 in yellow.
void draw_evidence(MapCanvas& canvas, const ObjectMap& objects) {
  const GridGeometry& g = objects.geometry();
  std::vector<Cell> object, evidence;
  for (const std::size_t idx : objects.evidence_cells())
    (objects.label_of(objects.probability_at(idx)) == ObjectLabel::kObject ? object : evidence)
        .push_back(g.cell_of_index(idx));
  canvas.draw_cells(g, evidence, kEvidence);
  canvas.draw_cells(g, object, kObject);
  const auto& o = objects.options();
  canvas.add_legend(fmt::format("O: evidence, 0.5 < p <= lambda2 = {:.2f}", o.lambda2), kEvidence,
                    LegendMark::kSwatch);
  canvas.add_legend(fmt::format("O: object, p > lambda2 = {:.2f}", o.lambda2), kObject,
                    LegendMark::kSwatch);
}

void legend_for_g(MapCanvas& canvas) {
  canvas.add_legend("G: free", Rgb{255, 255, 255}, LegendMark::kSwatch);
  canvas.add_legend("G: occupied", Rgb{0, 0, 0}, LegendMark::kSwatch);
  canvas.add_legend("G: unknown", kUnknown, LegendMark::kSwatch);
  canvas.add_legend("walls G has not seen (truth)", kTruthWall, LegendMark::kSwatch);
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
  canvas.add_legend("frontier cells of G at the end", kFrontier, LegendMark::kSwatch);
  canvas.add_legend("driven path", kPath, LegendMark::kLine);
  canvas.add_legend("start", kPath, LegendMark::kRing);
  canvas.add_legend("end pose (dot, heading line)", kPath, LegendMark::kDot);
  canvas.add_legend("object (ground truth)", kTruthObject, LegendMark::kRing);
}

std::string outcome(const EpisodeResult& r) {
  if (r.found)
    return fmt::format("found in {:.1f} s, {:.1f} m, {} decisions", r.time_s, r.path_m,
                       r.decisions);
  return fmt::format("not found ({}) after {:.1f} s, {:.1f} m", r.end_reason, r.time_s, r.path_m);
}

}  // namespace

void write_exploration_images(const OccupancyMap2D& truth, const Eigen::Vector2d& object_W,
                              const EpisodeResult& r, const std::filesystem::path& dir,
                              const std::string& what) {
  if (!r.grid || !r.objects)
    throw std::invalid_argument("write_exploration_images: the run was not recorded");
  const GridGeometry& g = r.grid->geometry();
  const OccupancyMap2D g_map = grid_as_map(*r.grid);

  const std::string result = (what.empty() ? "" : what + ": ") + outcome(r);

  MapCanvas img_g(g_map);
  img_g.set_title("G, IR occupancy grid; " + result);
  draw_truth_walls(img_g, truth, *r.grid);
  legend_for_g(img_g);
  draw_run(img_g, g, object_W, r);

  RenderOptions o_options;
  o_options.unknown = kUnseen;
  MapCanvas img_o(observed_as_map(*r.objects), o_options);
  img_o.set_title("O, object map; " + result);
  draw_probability(img_o, *r.objects);
  draw_run(img_o, g, object_W, r);

  MapCanvas img_go(g_map);
  img_go.set_title("G and O's evidence; " + result);
  draw_truth_walls(img_go, truth, *r.grid);
  legend_for_g(img_go);
  draw_evidence(img_go, *r.objects);
  draw_run(img_go, g, object_W, r);

  OutputSet out(dir, OutputKind::kDirectory);
  img_g.save_png(out.path("G.png"));
  img_o.save_png(out.path("O.png"));
  img_go.save_png(out.path("G_O.png"));
  out.commit();
}

}  // namespace ferret
