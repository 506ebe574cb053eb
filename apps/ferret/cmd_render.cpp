// `ferret render MAP -o out.png [--plan PLAN]`: draws a 2D map to PNG. MAP is a
// map_server YAML, or a world YAML / .bt / .ot file sliced at --z (world YAMLs also
// get their hidden-space entries, markers, objects and drop zone drawn on top); a
// plan is drawn over it. docs/maps_and_worlds.md describes the picture.

#include <fmt/format.h>

#include <cmath>
#include <filesystem>
#include <iostream>
#include <optional>
#include <string>
#include <vector>

#include "cli_options.hpp"
#include "command.hpp"
#include "ferret/core/error.hpp"
#include "ferret/mapping/map_render.hpp"
#include "ferret/mapping/world_octree.hpp"
#include "ferret/planning/plan_overlay.hpp"

namespace ferret::cli {
namespace {
namespace fs = std::filesystem;

struct RenderArgs {
  std::string input, output, space, plan;
  std::vector<double> window;
  SliceOptions slice;
  RenderOptions render;
  bool annotate = true;
};

std::string slice_caption(const SliceOptions& s) {
  return s.half_band_m > 0 ? fmt::format("slice z = {:g} m +- {:g} m", s.z_m, s.half_band_m)
                           : fmt::format("slice z = {:g} m", s.z_m);
}

void run(const RenderArgs& a) {
  (void)checked_out_file(a.output, "an output PNG");
  if (fs::path(a.output).extension() != ".png")
    throw InputError("--out", "", "an output path ending in .png", a.output);
  if (a.render.pixels_per_cell < 0 || a.render.pixels_per_cell > 64)
    throw InputError("--scale", "", "pixels per cell in [0, 64] (0: automatic)",
                     std::to_string(a.render.pixels_per_cell));
  if (!(a.render.grid_spacing_m >= 0)) throw InputError("--grid", "", "a spacing >= 0 m");
  if (!std::isfinite(a.slice.z_m)) throw InputError("--z", "", "a finite height in metres");
  if (!(a.slice.half_band_m >= 0 && a.slice.half_band_m < 1e3))
    throw InputError("--band", "", "a half band in [0, 1000) m");
  // The plan first: a bad plan file is bad input before anything is drawn.
  std::optional<PlanFile> plan;
  std::string plan_line;
  if (!a.plan.empty()) plan = load_plan(a.plan);
  std::optional<WorldSpec> world;
  OccupancyMap2D map;
  std::string title;
  std::optional<OccupancyMap2D> whole;  // the unwindowed slice, for a tether to wrap on
  if (is_map_server_yaml(a.input)) {
    // A 2D map has no slice to cut: options that only 3D inputs take are mistakes.
    if (!a.space.empty())
      throw InputError("--space", "", "a world YAML input (a map_server map has no hidden spaces)",
                       a.input);
    if (!a.window.empty())
      throw InputError("--window", "",
                       "a world YAML or .bt/.ot input (a map_server map is drawn whole)", a.input);
    map = load_map_server(a.input);
    title = fmt::format("{} (map_server map, {:g} m cells)", fs::path(a.input).filename().string(),
                        map.geometry.resolution_m);
  } else {
    const auto tree = load_or_build_octree(a.input, &world);
    SliceOptions slice = a.slice;
    slice.window_m = requested_slice_window(a.window, a.space, world);
    map = slice_octree(*tree, slice);
    if (plan && slice.window_m) {
      slice.window_m.reset();
      whole = slice_octree(*tree, slice);
    }
    title = world ? fmt::format("{} world", world->name) : fs::path(a.input).filename().string();
    if (!a.space.empty()) title += ", hidden space " + a.space;
    title += ", " + slice_caption(slice);
  }
  MapCanvas canvas = [&] {
    try {
      return MapCanvas(map, a.render);
    } catch (const InputError& e) {
      // The renderer names its own fields; the user gave them as options.
      if (e.field() == "grid_spacing_m")
        throw InputError("--grid", "", e.expected(), fmt::format("{:g}", a.render.grid_spacing_m));
      if (e.field() == "pixels_per_cell")
        throw InputError("--scale", "", e.expected(), std::to_string(a.render.pixels_per_cell));
      throw;
    }
  }();
  if (world && a.annotate) draw_world_annotations(canvas, *world);
  if (plan) {
    const PlanOverlaySummary s = draw_plan(canvas, *plan, whole ? *whole : map);
    title += fmt::format("\nplan {} ({}): {}", fs::path(a.plan).filename().string(),
                         plan->robot_known ? to_string(plan->robot) : "CSV", s.describe());
    if (s.outside == s.states) title += " (none inside: nothing drawn)";
    plan_line = "plan: " + s.describe() + "\n";
  }
  canvas.set_title(title);
  canvas.save_png(a.output);
  const RgbImage img = canvas.image();
  std::cout << fmt::format("rendered {} x {} cells at {} px/cell ({} x {} px) -> {}\n",
                           map.geometry.width, map.geometry.height, canvas.pixels_per_cell(),
                           img.width_px, img.height_px, a.output)
            << plan_line;
}

void setup(CLI::App& app) {
  auto args = std::make_shared<RenderArgs>();
  auto* sub = app.add_subcommand("render",
                                 "Draw a map to PNG: occupied black, free white, unknown grey "
                                 "(map_server YAML, world YAML, .bt, .ot)");
  sub->add_option("map", args->input, "map_server YAML, world YAML, or OctoMap .bt/.ot")
      ->required();
  add_out_option(sub, args->output, "output PNG");
  sub->add_option(
      "--plan", args->plan,
      "a plan to draw over the map: ferret plan's JSON or a CSV with a header t,x,y,z,yaw "
      "(default: none)");
  sub->add_option("--z", args->slice.z_m, "slice height for 3D maps, m")->capture_default_str();
  sub->add_option("--band", args->slice.half_band_m, "slice half band for 3D maps, m")
      ->capture_default_str();
  sub->add_option("--window", args->window, "3D maps: cut to x0,y0,x1,y1 (m)")
      ->expected(4)
      ->delimiter(',')
      ->description("3D maps: cut to x0,y0,x1,y1 (m) (default: the map's known extent)");
  sub->add_option("--space", args->space,
                  "world YAML: cut to a hidden space (and 0.5 m around it) (default: the whole "
                  "world)");
  sub->add_option("--scale", args->render.pixels_per_cell,
                  "pixels per cell (0: at least 800 px a side)")
      ->capture_default_str();
  sub->add_option("--grid", args->render.grid_spacing_m, "grid line spacing, m (0: none)")
      ->capture_default_str();
  sub->add_flag("!--no-scale-bar", args->render.scale_bar, "leave out the scale bar");
  sub->add_flag("!--no-frame", args->render.frame,
                "the map alone: no title, metre axes or legend (pixel for pixel)");
  sub->add_flag("!--no-annotations", args->annotate,
                "leave out a world's entries, markers, objects, drop zone");
  sub->callback([args] { run(*args); });
}

const CommandRegistration kRender{"render", setup};

}  // namespace
}  // namespace ferret::cli
