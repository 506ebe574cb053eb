#pragma once
// Small valid files the harnesses place beside the fuzzed one, so that an input
// naming them reaches past "file not found" into the code that uses them.

#include <string>

namespace ferret::fuzz {

/// A 16 x 12 binary PGM: a free room with an occupied border (and an unknown cell).
[[nodiscard]] inline std::string room_pgm() {
  const int w = 16, h = 12;
  std::string pixels;
  for (int r = 0; r < h; ++r)
    for (int c = 0; c < w; ++c)
      pixels += static_cast<char>(r == 0 || c == 0 || r == h - 1 || c == w - 1 ? 0
                                  : (r == 5 && c == 7)                         ? 205
                                                                               : 254);
  return "P5\n16 12\n255\n" + pixels;
}

/// The map_server YAML of room_pgm() saved as room.pgm.
[[nodiscard]] inline std::string room_yaml() {
  return "image: room.pgm\nresolution: 0.25\norigin: [0.0, 0.0, 0.0]\nnegate: 0\n"
         "occupied_thresh: 0.65\nfree_thresh: 0.196\n";
}

}  // namespace ferret::fuzz
