#include "ferret/mapping/occupancy_map_2d.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <fstream>
#include <sstream>

#include "ferret/core/error.hpp"
#include "support/cli_runner.hpp"

namespace ferret {
namespace {
using test::TempDir;
using ::testing::HasSubstr;

void write_bytes(const std::string& path, const std::string& bytes) {
  std::ofstream out(path, std::ios::binary);
  out.write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
}

std::string yaml_for(const std::string& image, const std::string& extra = "") {
  return "image: " + image + "\nresolution: 0.5\norigin: [-1.0, 2.0, 0.0]\n" + extra;
}

// Expects an InputError whose message names `source_part` and `field`.
template <class F>
void expect_input_error(F&& f, const std::string& source_part, const std::string& field) {
  try {
    f();
    FAIL() << "expected InputError for field " << field;
  } catch (const InputError& e) {
    EXPECT_THAT(e.source(), HasSubstr(source_part));
    EXPECT_EQ(e.field(), field) << e.what();
  }
}

TEST(OccupancyMap2D, ThresholdsAndRowOrderFollowMapServer) {
  TempDir dir;
  // 3 x 2 image, top row first: values chosen around the default thresholds.
  // occupancy = (255 - v) / 255: 0 -> 1.0 occupied, 254 -> 0.004 free,
  // 205 -> 0.196078 unknown (just above free_thresh 0.196), 89 -> 0.651 occupied,
  // 90 -> 0.647 unknown, 205 + 1 = 206 -> 0.192 free.
  write_bytes(dir / "m.pgm", std::string("P5\n# a comment\n3 2\n255\n") +
                                 std::string{'\x00', '\xfe', '\xcd', '\x59', '\x5a', '\xce'});
  write_bytes(dir / "m.yaml", yaml_for("m.pgm"));
  const OccupancyMap2D map = load_map_server(dir / "m.yaml");
  ASSERT_EQ(map.geometry.width, 3);
  ASSERT_EQ(map.geometry.height, 2);
  EXPECT_DOUBLE_EQ(map.geometry.origin_x_m, -1.0);
  EXPECT_DOUBLE_EQ(map.geometry.origin_y_m, 2.0);
  EXPECT_DOUBLE_EQ(map.geometry.resolution_m, 0.5);
  // The top image row is j = 1.
  EXPECT_EQ(map.at({0, 1}), CellState::kOccupied);
  EXPECT_EQ(map.at({1, 1}), CellState::kFree);
  EXPECT_EQ(map.at({2, 1}), CellState::kUnknown);
  EXPECT_EQ(map.at({0, 0}), CellState::kOccupied);
  EXPECT_EQ(map.at({1, 0}), CellState::kUnknown);
  EXPECT_EQ(map.at({2, 0}), CellState::kFree);
  // World lookup: (-1 + 0.25, 2 + 0.75) is cell (0, 1).
  EXPECT_EQ(map.state_at(-0.75, 2.75), CellState::kOccupied);
  EXPECT_EQ(map.state_at(-1.01, 2.75), CellState::kUnknown);
}

TEST(OccupancyMap2D, NegateInvertsOccupancy) {
  TempDir dir;
  write_bytes(dir / "m.pgm", std::string("P5 2 1 255 ") + std::string{'\x00', '\xff'});
  write_bytes(dir / "m.yaml", yaml_for("m.pgm", "negate: 1\n"));
  const OccupancyMap2D map = load_map_server(dir / "m.yaml");
  // With negate, occupancy = v / 255: black is free, white occupied.
  EXPECT_EQ(map.at({0, 0}), CellState::kFree);
  EXPECT_EQ(map.at({1, 0}), CellState::kOccupied);
}

TEST(OccupancyMap2D, CustomThresholds) {
  TempDir dir;
  // v = 128 -> occupancy 0.498.
  write_bytes(dir / "m.pgm", "P2\n1 1\n255\n128\n");
  write_bytes(dir / "a.yaml", yaml_for("m.pgm", "occupied_thresh: 0.4\nfree_thresh: 0.1\n"));
  write_bytes(dir / "b.yaml", yaml_for("m.pgm", "occupied_thresh: 0.9\nfree_thresh: 0.5\n"));
  write_bytes(dir / "c.yaml", yaml_for("m.pgm", "occupied_thresh: 0.9\nfree_thresh: 0.3\n"));
  EXPECT_EQ(load_map_server(dir / "a.yaml").at({0, 0}), CellState::kOccupied);
  EXPECT_EQ(load_map_server(dir / "b.yaml").at({0, 0}), CellState::kFree);
  EXPECT_EQ(load_map_server(dir / "c.yaml").at({0, 0}), CellState::kUnknown);
}

TEST(OccupancyMap2D, AsciiAndSixteenBitPgmScaleToBytes) {
  TempDir dir;
  // maxval 15: 0 -> black (occupied), 15 -> white (free).
  write_bytes(dir / "a.pgm", "P2\n2 1\n15\n0 15\n");
  const GreyImage a = read_pgm(dir / "a.pgm");
  EXPECT_EQ(a.pixels, (std::vector<std::uint8_t>{0, 255}));
  // 16-bit big-endian: 0x8000 of 65535 -> round(32768 * 255 / 65535) = 128.
  write_bytes(dir / "b.pgm", std::string("P5\n1 1\n65535\n") + std::string{'\x80', '\x00'});
  EXPECT_EQ(read_pgm(dir / "b.pgm").pixels, (std::vector<std::uint8_t>{128}));
}

TEST(OccupancyMap2D, SaveLoadRoundTrip) {
  TempDir dir;
  GridGeometry g{-3.125, 7.3, 0.05, 7, 5};
  OccupancyMap2D map = OccupancyMap2D::filled(g, CellState::kUnknown);
  for (std::size_t k = 0; k < map.cells.size(); ++k)
    map.cells[k] = static_cast<CellState>(k * 7 % 3);
  save_map_server(map, dir / "out.yaml");
  EXPECT_TRUE(std::filesystem::exists(dir / "out.pgm"));
  const OccupancyMap2D back = load_map_server(dir / "out.yaml");
  EXPECT_TRUE(back == map);
  EXPECT_EQ(back.count(CellState::kFree), map.count(CellState::kFree));
  EXPECT_EQ(dir.count(), 2u);  // no temporaries left behind
}

TEST(OccupancyMap2D, SaveRejectsNonYamlPath) {
  TempDir dir;
  const auto map = OccupancyMap2D::filled(GridGeometry{0, 0, 1, 1, 1}, CellState::kFree);
  EXPECT_THROW(save_map_server(map, dir / "out.txt"), InputError);
  EXPECT_EQ(dir.count(), 0u);
}

TEST(OccupancyMap2D, TruncatedPgmPixelData) {
  TempDir dir;
  write_bytes(dir / "m.pgm", std::string("P5\n4 4\n255\n") + std::string(15, '\xfe'));
  write_bytes(dir / "m.yaml", yaml_for("m.pgm"));
  try {
    (void)load_map_server(dir / "m.yaml");
    FAIL();
  } catch (const InputError& e) {
    EXPECT_THAT(e.source(), HasSubstr("m.pgm"));
    EXPECT_EQ(e.field(), "pixels");
    EXPECT_THAT(e.what(), HasSubstr("16 samples"));
    EXPECT_THAT(e.what(), HasSubstr("only 15 bytes"));
  }
}

TEST(OccupancyMap2D, PixelsBeyondTheHeaderSizeAreAnError) {
  // A header that says 1 x 4 over 16 bytes of raster would load as a 1-cell-wide strip.
  TempDir dir;
  write_bytes(dir / "m.pgm", std::string("P5\n1 4\n255\n") + std::string(16, '\xfe'));
  write_bytes(dir / "m.yaml", yaml_for("m.pgm"));
  try {
    (void)load_map_server(dir / "m.yaml");
    FAIL();
  } catch (const InputError& e) {
    EXPECT_THAT(e.source(), HasSubstr("m.pgm"));
    EXPECT_EQ(e.field(), "pixels");
    EXPECT_THAT(e.what(), HasSubstr("12 bytes more"));
  }
  write_bytes(dir / "a.pgm", "P2\n2 1\n15\n0 15 7\n");  // an ASCII sample too many
  write_bytes(dir / "a.yaml", yaml_for("a.pgm"));
  EXPECT_THROW((void)load_map_server(dir / "a.yaml"), InputError);
  write_bytes(dir / "b.pgm", "P2\n2 1\n15\n0 15\n# a comment after the raster\n");
  write_bytes(dir / "b.yaml", yaml_for("b.pgm"));
  EXPECT_EQ(load_map_server(dir / "b.yaml").geometry.width, 2);
}

TEST(OccupancyMap2D, TruncatedAndBrokenPgmHeaders) {
  TempDir dir;
  const std::string p = dir / "m.pgm";
  write_bytes(p, "P5\n4");
  expect_input_error([&] { (void)read_pgm(p); }, "m.pgm", "header.height");
  write_bytes(p, "P5\n4 4\n");
  expect_input_error([&] { (void)read_pgm(p); }, "m.pgm", "header.maxval");
  write_bytes(p, "P5\n4 4\n255");  // no separator before (absent) pixels
  expect_input_error([&] { (void)read_pgm(p); }, "m.pgm", "header.maxval");
  write_bytes(p, "P5\n0 4\n255\n");
  expect_input_error([&] { (void)read_pgm(p); }, "m.pgm", "header.width");
  write_bytes(p, "P5\n4 x\n255\n");
  expect_input_error([&] { (void)read_pgm(p); }, "m.pgm", "header.height");
  write_bytes(p, "P5\n4 4\n70000\n");
  expect_input_error([&] { (void)read_pgm(p); }, "m.pgm", "header.maxval");
  // A header asking for ~10^12 pixels is refused before any allocation.
  write_bytes(p, "P5\n1000000 1000000\n255\n");
  expect_input_error([&] { (void)read_pgm(p); }, "m.pgm", "header.height");
  write_bytes(p, "P6\n1 1\n255\nabc");
  expect_input_error([&] { (void)read_pgm(p); }, "m.pgm", "magic");
  write_bytes(p, "");
  expect_input_error([&] { (void)read_pgm(p); }, "m.pgm", "magic");
  write_bytes(p, "P2\n2 2\n255\n1 2 3");
  expect_input_error([&] { (void)read_pgm(p); }, "m.pgm", "pixels");
  write_bytes(p, "P2\n2 1\n10\n1 11");
  expect_input_error([&] { (void)read_pgm(p); }, "m.pgm", "pixels[1]");
  write_bytes(p, std::string("P5\n1 1\n10\n") + '\x0b');
  expect_input_error([&] { (void)read_pgm(p); }, "m.pgm", "pixels[0]");
}

TEST(OccupancyMap2D, EveryTruncationOfAPgmIsDetected) {
  TempDir dir;
  const std::string p = dir / "m.pgm";
  const std::string binary = std::string("P5\n# c\n3 2\n255\n") +
                             std::string{'\x00', '\xfe', '\xcd', '\x59', '\x5a', '\xce'};
  const std::string ascii = "P2\n3 2\n255\n0 254 205\n89 90 206\n";
  for (const std::string& full : {binary, ascii}) {
    write_bytes(p, full);
    ASSERT_EQ(read_pgm(p).pixels.size(), 6u);
    // ASCII ends with a newline and its last sample may lose digits without
    // becoming invalid: cut only before the last sample starts.
    const std::size_t last = full[1] == '5' ? full.size() : full.rfind(' ') + 1;
    for (std::size_t n = 0; n < last; ++n) {
      write_bytes(p, full.substr(0, n));
      EXPECT_THROW((void)read_pgm(p), InputError) << "prefix of " << n << " bytes";
    }
  }
}

TEST(OccupancyMap2D, BadYamlFieldsNameTheField) {
  TempDir dir;
  write_bytes(dir / "m.pgm", "P2 1 1 255 0");
  const std::string y = dir / "m.yaml";
  auto check = [&](const std::string& text, const std::string& field) {
    write_bytes(y, text);
    expect_input_error([&] { (void)load_map_server(y); }, "m.yaml", field);
  };
  check(yaml_for("missing.pgm"), "image");
  check("resolution: 0.5\norigin: [0, 0, 0]\n", "image");
  check(yaml_for("m.pgm", "mode: scale\n"), "mode");
  check(yaml_for("m.pgm", "mode: raw\n"), "mode");
  check(yaml_for("m.pgm", "negate: 2\n"), "negate");
  check(yaml_for("m.pgm", "occupied_thresh: 1.5\n"), "occupied_thresh");
  check(yaml_for("m.pgm", "occupied_thresh: 0.3\nfree_thresh: 0.5\n"), "free_thresh");
  check(yaml_for("m.pgm", "colour: red\n"), "colour");
  check("image: m.pgm\nresolution: -0.1\norigin: [0, 0, 0]\n", "resolution");
  check("image: m.pgm\nresolution: fine\norigin: [0, 0, 0]\n", "resolution");
  check("image: m.pgm\nresolution: 0.1\norigin: [0, 0]\n", "origin");
  check("image: m.pgm\nresolution: 0.1\norigin: [0, 0, 0.5]\n", "origin[2]");
  check(yaml_for("m.pgm", "search: 3\n"), "search");  // the object search's section is a mapping
  write_bytes(y, yaml_for("m.pgm", "search: {start: [1, 1, 0]}\n"));
  EXPECT_EQ(load_map_server(y).geometry.width, 1);  // whose contents ferret experiment checks
}

TEST(OccupancyMap2D, ExtraYamlIsWrittenAfterTheMapServerKeys) {
  TempDir dir;
  const OccupancyMap2D map =
      OccupancyMap2D::filled(GridGeometry{0, 0, 0.1, 3, 2}, CellState::kFree);
  save_map_server(map, dir / "s.yaml", "search:\n  start: [0.1, 0.1, 0]\n");
  EXPECT_TRUE(load_map_server(dir / "s.yaml") == map);
  std::ifstream in(dir / "s.yaml");
  std::stringstream text;
  text << in.rdbuf();
  EXPECT_NE(text.str().find("free_thresh: 0.196\nsearch:\n  start: [0.1, 0.1, 0]\n"),
            std::string::npos)
      << text.str();
}

TEST(OccupancyMap2D, CorruptPngIsInputError) {
  TempDir dir;
  write_bytes(dir / "m.png", "\x89PNG\r\n\x1a\nnot really");
  write_bytes(dir / "m.yaml", yaml_for("m.png"));
  EXPECT_THROW((void)load_map_server(dir / "m.yaml"), InputError);
}

// A request body carries the YAML and the image as bytes: the same map as from files,
// and the YAML's image key is never opened.
TEST(OccupancyMap2D, TheYamlAndImageFromBytesGiveTheSameMapAsTheFiles) {
  TempDir dir;
  const std::string pgm =
      std::string("P5\n3 2\n255\n") + std::string{'\0', '\xfe', '\xcd', '\xfe', '\0', '\0'};
  write_bytes(dir / "m.pgm", pgm);
  write_bytes(dir / "m.yaml", yaml_for("m.pgm"));
  const OccupancyMap2D from_files = load_map_server(dir / "m.yaml");
  // The YAML names a file that does not exist: parsing its text must not look for it.
  const MapServerMeta meta = parse_map_server_meta(yaml_for("/nonexistent/elsewhere.pgm"), "body");
  EXPECT_EQ(meta.image, "/nonexistent/elsewhere.pgm");
  const OccupancyMap2D from_bytes = map_from_image(meta, decode_map_image(pgm, "image"));
  EXPECT_TRUE(from_bytes == from_files);
  // Image row 0 is the top: cell (0, 1) is the first pixel (0: occupied).
  EXPECT_EQ(from_bytes.at({0, 1}), CellState::kOccupied);
  EXPECT_EQ(from_bytes.at({1, 1}), CellState::kFree);
  EXPECT_EQ(from_bytes.at({2, 1}), CellState::kUnknown);
  EXPECT_EQ(from_bytes.at({1, 0}), CellState::kOccupied);
}

TEST(OccupancyMap2D, ImageBytesAreRecognisedByTheirContentNotTheirName) {
  // The same 2 x 1 map as PGM and as PNG (written by save_map_server and OpenCV-free
  // libpng through a saved map): both decode to the same pixels.
  TempDir dir;
  OccupancyMap2D map = OccupancyMap2D::filled({0.0, 0.0, 0.1, 2, 1}, CellState::kFree);
  map.at({1, 0}) = CellState::kOccupied;
  save_map_server(map, dir / "m.yaml");
  std::ifstream in(dir / "m.pgm", std::ios::binary);
  const std::string pgm((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  const GreyImage grey = decode_map_image(pgm, "image");
  ASSERT_EQ(grey.width, 2);
  EXPECT_EQ(grey.pixels[0], 254);
  EXPECT_EQ(grey.pixels[1], 0);
  // Not an image at all, an empty body, a broken PNG: the source is named.
  expect_input_error([] { (void)decode_map_image("hello, not an image", "image"); }, "image", "");
  expect_input_error([] { (void)decode_map_image("", "image"); }, "image", "");
  expect_input_error([] { (void)decode_map_image("\x89PNG\r\n\x1a\nbroken", "image"); }, "image",
                     "");
  expect_input_error([] { (void)decode_map_image("P5\n3 2\n255\n\x01", "image"); }, "image",
                     "pixels");
  expect_input_error(
      [] {
        (void)parse_map_server_meta("image: m.pgm\nresolution: -1\norigin: [0, 0, 0]\n", "yaml");
      },
      "yaml", "resolution");
  try {
    (void)parse_map_server_meta("image: [unclosed", "yaml");
    ADD_FAILURE() << "broken YAML accepted";
  } catch (const InputError& e) {
    EXPECT_EQ(e.source(), "yaml");  // the field is where the YAML parser stopped
  }
}

TEST(OccupancyMap2D, AMapServerYamlIsToldFromAWorldYaml) {
  TempDir dir;
  write_bytes(dir / "m.yaml", yaml_for("m.pgm"));
  write_bytes(dir / "partial.yaml", "resolution: 0.05\n");  // lacks image: still map_server's
  write_bytes(dir / "w.yaml", "name: w\nresolution_m: 0.05\n");
  write_bytes(dir / "m.bt", "image: m.pgm\n");
  EXPECT_TRUE(is_map_server_yaml(dir / "m.yaml"));
  EXPECT_TRUE(is_map_server_yaml(dir / "partial.yaml"));
  EXPECT_FALSE(is_map_server_yaml(dir / "w.yaml"));
  EXPECT_FALSE(is_map_server_yaml(dir / "m.bt"));
  EXPECT_TRUE(is_map_server_yaml(FERRET_SOURCE_DIR "/examples/maps/dense.yaml"));
  EXPECT_FALSE(is_map_server_yaml(FERRET_SOURCE_DIR "/examples/worlds/default.yaml"));
}

}  // namespace
}  // namespace ferret
