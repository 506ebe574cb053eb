// `ferret render MAP -o out.png`: draws a 2D map to PNG. MAP is a map_server YAML,
// or a world YAML / .bt / .ot file sliced at --z (world YAMLs also get their
// hidden-space entries, markers, objects and drop zone drawn on top).

#include <fmt/format.h>

#include <filesystem>
#include <iostream>
#include <optional>
#include <string>
#include <vector>

#include "command.hpp"
#include "ferret/core/error.hpp"
#include "ferret/core/yaml_config.hpp"
#include "ferret/mapping/map_render.hpp"
#include "ferret/mapping/world_octree.hpp"

namespace ferret::cli {
namespace {
namespace fs = std::filesystem;

struct RenderArgs {
  std::string input, output, space;
  std::vector<double> window;
  SliceOptions slice;
  RenderOptions render;
  bool annotate = true;
};

// A map_server YAML has keys a world YAML never has (image, resolution, origin),
// so a map_server file that lacks one of them still gets map_server's messages.
bool is_map_server_yaml(const fs::path& path) {
  const std::string ext = path.extension().string();
  if (ext != ".yaml" && ext != ".yml") return false;
  const YAML::Node doc = yaml::load_file(path);
  if (!doc.IsMap()) return false;
  for (const char* key : {"image", "resolution", "origin"})
    if (doc[key].IsDefined()) return true;
  return false;
}

void run(const RenderArgs& a) {
  if (fs::path(a.output).extension() != ".png")
    throw InputError("-o", "", "an output path ending in .png", a.output);
  if (a.render.pixels_per_cell < 0 || a.render.pixels_per_cell > 64)
    throw InputError("--scale", "", "pixels per cell in [0, 64] (0: automatic)",
                     std::to_string(a.render.pixels_per_cell));
  if (!(a.render.grid_spacing_m >= 0)) throw InputError("--grid", "", "a spacing >= 0 m");
  std::optional<WorldSpec> world;
  OccupancyMap2D map;
  if (is_map_server_yaml(a.input)) {
    map = load_map_server(a.input);
  } else {
    const auto tree = load_or_build_octree(a.input, &world);
    SliceOptions slice = a.slice;
    slice.window_m = requested_slice_window(a.window, a.space, world);
    map = slice_octree(*tree, slice);
  }
  MapCanvas canvas(map, a.render);
  if (world && a.annotate) draw_world_annotations(canvas, *world);
  canvas.save_png(a.output);
  const RgbImage img = canvas.image();
  std::cout << fmt::format("rendered {} x {} cells at {} px/cell ({} x {} px) -> {}\n",
                           map.geometry.width, map.geometry.height, canvas.pixels_per_cell(),
                           img.width, img.height, a.output);
}

void setup(CLI::App& app) {
  auto args = std::make_shared<RenderArgs>();
  auto* sub = app.add_subcommand("render",
                                 "Draw a map to PNG: occupied black, free white, unknown grey "
                                 "(map_server YAML, world YAML, .bt, .ot)");
  sub->add_option("map", args->input, "map_server YAML, world YAML, or OctoMap .bt/.ot")
      ->required();
  sub->add_option("-o,--output", args->output, "output PNG")->required();
  sub->add_option("--z", args->slice.z_m, "slice height for 3D maps, m")->capture_default_str();
  sub->add_option("--band", args->slice.half_band_m, "slice half band for 3D maps, m")
      ->capture_default_str();
  sub->add_option("--window", args->window, "3D maps: cut to x0,y0,x1,y1 (m)")
      ->expected(4)
      ->delimiter(',');
  sub->add_option("--space", args->space,
                  "world YAML: cut to a hidden space (and 0.5 m around it)");
  sub->add_option("--scale", args->render.pixels_per_cell,
                  "pixels per cell (0: at least 800 px a side)")
      ->capture_default_str();
  sub->add_option("--grid", args->render.grid_spacing_m, "grid line spacing, m (0: none)")
      ->capture_default_str();
  sub->add_flag("!--no-scale-bar", args->render.scale_bar, "leave out the scale bar");
  sub->add_flag("!--no-annotations", args->annotate,
                "leave out a world's entries, markers, objects, drop zone");
  sub->callback([args] { run(*args); });
}

const CommandRegistration kRender{"render", setup};

}  // namespace
}  // namespace ferret::cli
