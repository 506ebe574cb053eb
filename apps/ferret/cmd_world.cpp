// `ferret world build | slice | info | generate-hidden`: a world YAML becomes an
// OctoMap (.bt/.ot), an OctoMap (or world YAML) becomes a 2D map_server slice, `info`
// summarises either, and `generate-hidden` writes a hidden space for the object
// search. docs/maps_and_worlds.md describes the formats.

#include <fmt/format.h>

#include <chrono>
#include <cmath>
#include <filesystem>
#include <iostream>
#include <optional>
#include <string>
#include <vector>

#include "cli_options.hpp"
#include "command.hpp"
#include "ferret/core/error.hpp"
#include "ferret/mapping/world_octree.hpp"
#include "ferret/sim/hidden_space_generator.hpp"

namespace ferret::cli {
namespace {
namespace fs = std::filesystem;

void require_extension(const std::string& path, std::initializer_list<const char*> exts,
                       const std::string& what) {
  const std::string ext = fs::path(path).extension().string();
  for (const char* e : exts)
    if (ext == e) return;
  throw InputError("--out", "", what, path);
}

std::string vec3(const Eigen::Vector3d& v) {
  return fmt::format("[{:.4g}, {:.4g}, {:.4g}]", v.x(), v.y(), v.z());
}

void print_summary(const OctreeSummary& s) {
  std::cout << fmt::format("resolution_m: {}\n", s.resolution_m)
            << fmt::format("known_min_m: {}\nknown_max_m: {}\n", vec3(s.min_m), vec3(s.max_m))
            << fmt::format("nodes: {}\nleaves: {}\noccupied_leaves: {}\nfree_leaves: {}\n", s.nodes,
                           s.leaves, s.occupied_leaves, s.free_leaves)
            << fmt::format("occupied_volume_m3: {:.3f}\nfree_volume_m3: {:.3f}\n",
                           s.occupied_volume_m3, s.free_volume_m3)
            << fmt::format("memory_mib: {:.1f}\n", s.memory_bytes / 1048576.0);
}

void print_world(const WorldSpec& w) {
  std::cout << fmt::format("world: {}\nbounds_m: {{min: {}, max: {}}}\n", w.name,
                           vec3(w.bounds_min_m), vec3(w.bounds_max_m))
            << fmt::format("boxes: {}\ncylinders: {}\nrubble_boxes: {}\n", w.boxes.size(),
                           w.cylinders.size(), w.rubble.size());
  std::cout << "hidden_spaces:\n";
  for (const auto& h : w.hidden_spaces) {
    const Eigen::Vector3d m = h.marker.X_WM.translation(), n = h.marker.X_WM.linear().col(2);
    std::cout
        << fmt::format(
               "  - name: {}\n    interior_size_m: {}\n    p_WE: {}\n    entry_yaw_deg: {:.1f}\n",
               h.name, vec3(h.interior_size_m), vec3(h.p_WE), rad_to_deg(h.entry_yaw_rad))
        << fmt::format(
               "    opening_m: [{}, {}]\n    marker: {{id: {}, size_m: {}, position_m: {}, normal: "
               "{}}}\n",
               h.opening_width_m, h.opening_height_m, h.marker.id, h.marker.size_m, vec3(m),
               vec3(n));
  }
  std::cout << "objects:\n";
  for (const auto& o : w.objects)
    std::cout << fmt::format("  - {{name: {}, hidden_space: {}, p_WO: {}}}\n", o.name,
                             o.hidden_space >= 0 ? w.hidden_spaces[o.hidden_space].name : "none",
                             vec3(o.p_WO()));
  if (w.drop_zone)
    std::cout << fmt::format("drop_zone: {{center_m: [{}, {}], radius_m: {}}}\n",
                             w.drop_zone->center_m.x(), w.drop_zone->center_m.y(),
                             w.drop_zone->radius_m);
}

void add_build(CLI::App& world) {
  struct Args {
    std::string input, output;
  };
  auto args = std::make_shared<Args>();
  auto* build =
      world.add_subcommand("build", "Voxelize a world YAML into an OctoMap .bt or .ot file");
  build->add_option("world", args->input, "world YAML")->required();
  add_out_option(build, args->output, "output .bt (max-likelihood) or .ot (log-odds)");
  build->callback([args] {
    (void)checked_out_file(args->output, "an output .bt or .ot");
    require_extension(args->output, {".bt", ".ot"}, "an output path ending in .bt or .ot");
    const auto t0 = std::chrono::steady_clock::now();
    const WorldSpec w = load_world(args->input);
    const auto tree = build_world_octree(w);
    const double build_s =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    save_octree(*tree, args->output);
    const OctreeSummary s = summarize_octree(*tree);
    std::cout << fmt::format(
        "built '{}' in {:.2f} s: {} leaves ({} occupied, {} free) at {} m -> {}\n", w.name, build_s,
        s.leaves, s.occupied_leaves, s.free_leaves, s.resolution_m, args->output);
  });
}

void add_slice(CLI::App& world) {
  struct Args {
    std::string input, output, space;
    std::vector<double> window;
    SliceOptions options;
  };
  auto args = std::make_shared<Args>();
  auto* slice = world.add_subcommand(
      "slice", "Cut a 2D map_server map (YAML + PGM) out of a world at a height");
  slice->add_option("map", args->input, "OctoMap .bt/.ot, or a world YAML (built in memory)")
      ->required();
  slice->add_option("--z", args->options.z_m, "height of the slice, m")->capture_default_str();
  slice
      ->add_option("--band", args->options.half_band_m,
                   "voxel layers within +-band of z count (occupied if any is)")
      ->capture_default_str();
  slice
      ->add_option("--window", args->window,
                   "cut to x0,y0,x1,y1 (m) (default: the map's known extent)")
      ->expected(4)
      ->delimiter(',');
  slice->add_option("--space", args->space,
                    "cut to a hidden space (and 0.5 m around it); world YAML input (default: "
                    "the whole world)");
  add_out_option(slice, args->output, "output map_server YAML (the PGM is written beside it)");
  slice->callback([args] {
    (void)checked_out_file(args->output, "an output map_server YAML");
    if (!std::isfinite(args->options.z_m)) throw InputError("--z", "", "a finite height in metres");
    if (!(args->options.half_band_m >= 0 && args->options.half_band_m < 1e3))
      throw InputError("--band", "", "a half band in [0, 1000) m");
    require_extension(args->output, {".yaml"}, "an output path ending in .yaml");
    (void)checked_out_file(fs::path(args->output).replace_extension(".pgm").string(),
                           "the PGM beside the YAML");
    std::optional<WorldSpec> spec;
    const auto tree = load_or_build_octree(args->input, &spec);
    SliceOptions options = args->options;
    options.window_m = requested_slice_window(args->window, args->space, spec);
    const OccupancyMap2D map = slice_octree(*tree, options);
    save_map_server(map, args->output);
    std::cout << fmt::format(
        "slice at z = {} m: {} x {} cells ({} occupied, {} free, {} unknown) -> {}\n", options.z_m,
        map.geometry.width, map.geometry.height, map.count(CellState::kOccupied),
        map.count(CellState::kFree), map.count(CellState::kUnknown), args->output);
  });
}

void add_info(CLI::App& world) {
  auto input = std::make_shared<std::string>();
  auto* info =
      world.add_subcommand("info", "Summarise a world YAML or an OctoMap file (YAML on stdout)");
  info->add_option("file", *input, "world YAML, .bt or .ot")->required();
  info->callback([input] {
    std::optional<WorldSpec> spec;
    const auto tree = load_or_build_octree(*input, &spec);
    std::cout << fmt::format("file: {}\n", *input);
    if (spec) print_world(*spec);
    print_summary(summarize_octree(*tree));
  });
}

void add_generate_hidden(CLI::App& world) {
  struct Args {
    std::string output, clutter = "sparse";
    std::vector<double> size{12.0, 8.0};
    HiddenSpaceGeneratorOptions options;
  };
  auto args = std::make_shared<Args>();
  auto* gen = world.add_subcommand("generate-hidden",
                                   "Write a generated hidden space (map_server YAML + PGM) with "
                                   "the object search's start and zones");
  add_seed_option(gen, args->options.seed, "seed of the layout");
  gen->add_option("--size", args->size,
                  "width (along the start's heading), height in metres: [8, 64] x [5, 64]")
      ->expected(2)
      ->delimiter(',')
      ->capture_default_str();
  gen->add_option("--clutter", args->clutter, "sparse or dense")->capture_default_str();
  gen->add_option("--resolution", args->options.resolution_m, "cell size, metres")
      ->capture_default_str();
  add_out_option(gen, args->output, "output map_server YAML (the PGM is written beside it)");
  gen->callback([args] {
    (void)checked_out_file(args->output, "an output map_server YAML");
    require_extension(args->output, {".yaml"}, "an output path ending in .yaml");
    (void)checked_out_file(fs::path(args->output).replace_extension(".pgm").string(),
                           "the PGM beside the YAML");
    const auto clutter = parse_hidden_space_clutter(args->clutter);
    if (!clutter) throw InputError("--clutter", "", "sparse or dense", args->clutter);
    HiddenSpaceGeneratorOptions o = args->options;
    o.clutter = *clutter;
    o.width_m = args->size[0];
    o.height_m = args->size[1];
    const GeneratedHiddenSpace h = generate_hidden_space(o);
    save_map_server(h.map, args->output, h.search_yaml());
    std::cout << fmt::format(
        "{} hidden space, seed {}: {} x {} cells ({} occupied, {} free), start ({}, {}) -> {}\n",
        to_string(o.clutter), o.seed, h.map.geometry.width, h.map.geometry.height,
        h.map.count(CellState::kOccupied), h.map.count(CellState::kFree), h.start.x_m, h.start.y_m,
        args->output);
  });
}

void setup(CLI::App& app) {
  auto* world = app.add_subcommand("world",
                                   "Build 3D worlds (OctoMap) from YAML, slice them to 2D, "
                                   "summarise them, generate hidden spaces");
  world->require_subcommand(1);
  add_build(*world);
  add_slice(*world);
  add_info(*world);
  add_generate_hidden(*world);
}

const CommandRegistration kWorld{"world", setup};

}  // namespace
}  // namespace ferret::cli
