#include "ferret/mapping/occupancy_map_2d.hpp"

#include <fmt/format.h>
#include <png.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <fstream>
#include <limits>
#include <opencv2/core.hpp>
#include <opencv2/imgcodecs.hpp>
#include <sstream>

#include "ferret/core/atomic_file.hpp"
#include "ferret/core/error.hpp"
#include "ferret/core/output_set.hpp"
#include "ferret/core/yaml_config.hpp"

namespace ferret {
namespace fs = std::filesystem;

namespace {

// Images larger than this are refused before allocating (a corrupt header must
// not ask for gigabytes): 2^28 cells is a 16384 x 16384 map.
constexpr std::uint64_t kMaxPixels = std::uint64_t{1} << 28;
constexpr std::uint64_t kMaxSide = std::uint64_t{1} << 20;

std::string read_binary_file(const fs::path& path, const char* what) {
  std::ifstream in(path, std::ios::binary);
  if (!in || fs::is_directory(path)) throw InputError(path.string(), "", what, "cannot open");
  std::ostringstream data;
  data << in.rdbuf();
  return std::move(data).str();
}

// Bytes of a header as a quoted, printable snippet (ferret::printable escapes them).
std::string quoted_bytes(std::string_view bytes) {
  return fmt::format("'{}'", printable(bytes.substr(0, 16)));
}

// Netpbm header/ASCII-raster tokenizer: whitespace and '#' comments separate
// decimal numbers; every failure names the field being read.
class PgmReader {
 public:
  PgmReader(std::string data, std::string source)
      : data_(std::move(data)), source_(std::move(source)) {}

  [[nodiscard]] std::string_view data() const { return data_; }
  [[nodiscard]] std::size_t pos() const { return pos_; }
  void skip(std::size_t n) { pos_ += n; }
  [[nodiscard]] bool at_end() const { return pos_ >= data_.size(); }
  [[nodiscard]] char peek() const { return data_[pos_]; }

  void skip_space_and_comments() {
    while (pos_ < data_.size()) {
      const char c = data_[pos_];
      if (c == '#') {
        while (pos_ < data_.size() && data_[pos_] != '\n' && data_[pos_] != '\r') ++pos_;
      } else if (std::isspace(static_cast<unsigned char>(c))) {
        ++pos_;
      } else {
        break;
      }
    }
  }

  /// Reads an unsigned decimal in [lo, hi].
  std::uint64_t number(const std::string& field, std::uint64_t lo, std::uint64_t hi) {
    skip_space_and_comments();
    const std::string expected = fmt::format("an integer in [{}, {}]", lo, hi);
    if (at_end()) fail(field, expected, "end of file (truncated)");
    if (!std::isdigit(static_cast<unsigned char>(peek())))
      fail(field, expected, quoted_bytes(data_.substr(pos_, 8)));
    std::uint64_t value = 0;
    while (!at_end() && std::isdigit(static_cast<unsigned char>(peek()))) {
      value = value * 10 + static_cast<std::uint64_t>(peek() - '0');
      if (value > hi) fail(field, expected, "a larger number");
      ++pos_;
    }
    if (value < lo) fail(field, expected, std::to_string(value));
    return value;
  }

  [[noreturn]] void fail(const std::string& field, const std::string& expected,
                         const std::string& got) const {
    throw InputError(source_, field, expected, got);
  }

 private:
  std::string data_;
  std::string source_;
  std::size_t pos_ = 0;
};

std::uint8_t scale_to_byte(std::uint64_t v, std::uint64_t maxval) {
  return static_cast<std::uint8_t>((v * 255 + maxval / 2) / maxval);
}

GreyImage read_with_opencv(const std::string& data, const std::string& source) {
  if (data.size() > std::numeric_limits<int>::max())
    throw InputError(source, "", "an image of at most 2 GiB", "a larger file");
  const cv::Mat bytes(1, static_cast<int>(data.size()), CV_8U, const_cast<char*>(data.data()));
  const cv::Mat img = data.empty() ? cv::Mat() : cv::imdecode(bytes, cv::IMREAD_UNCHANGED);
  if (img.empty())
    throw InputError(source, "", "an image OpenCV can read (PGM, PNG, ...)",
                     "unreadable or corrupt");
  if (img.depth() != CV_8U && img.depth() != CV_16U)
    throw InputError(source, "", "an 8- or 16-bit image", "another pixel depth");
  if (static_cast<std::uint64_t>(img.cols) * static_cast<std::uint64_t>(img.rows) > kMaxPixels)
    throw InputError(source, "", fmt::format("at most {} pixels", kMaxPixels), "a larger image");
  const int channels = img.channels();
  // Grey+alpha and BGRA: the alpha channel does not count towards the grey value.
  const int colour = (channels == 2 || channels == 4) ? channels - 1 : channels;
  const double full = img.depth() == CV_8U ? 255.0 : 65535.0;
  GreyImage out{img.cols, img.rows, std::vector<std::uint8_t>(img.total())};
  for (int r = 0; r < img.rows; ++r) {
    for (int c = 0; c < img.cols; ++c) {
      double sum = 0.0;
      for (int k = 0; k < colour; ++k) {
        sum += img.depth() == CV_8U ? img.ptr<std::uint8_t>(r)[c * channels + k]
                                    : img.ptr<std::uint16_t>(r)[c * channels + k];
      }
      out.pixels[static_cast<std::size_t>(r) * img.cols + c] =
          static_cast<std::uint8_t>(std::lround(sum / colour / full * 255.0));
    }
  }
  return out;
}

// PNG through libpng's simplified API: its errors and warnings come back as text in
// png_image::message instead of being printed to stderr (as OpenCV's use of libpng
// does), so a broken PNG gives ferret's one line and nothing else.
GreyImage read_png(const std::string& data, const std::string& source) {
  png_image image{};
  image.version = PNG_IMAGE_VERSION;
  struct Free {
    png_image* i;
    ~Free() { png_image_free(i); }
  } free_on_exit{&image};
  if (png_image_begin_read_from_memory(&image, data.data(), data.size()) == 0)
    throw InputError(source, "", "a PNG image", image.message);
  if (static_cast<std::uint64_t>(image.width) * image.height > kMaxPixels)
    throw InputError(source, "", fmt::format("at most {} pixels", kMaxPixels),
                     fmt::format("{} x {} pixels", image.width, image.height));
  // RGBA, 8 bits: grey, grey+alpha, palette and 16-bit images all arrive as sRGB bytes;
  // the grey value is the mean of R, G and B, alpha does not count (as for OpenCV).
  image.format = PNG_FORMAT_RGBA;
  std::vector<std::uint8_t> rgba(PNG_IMAGE_SIZE(image));
  if (png_image_finish_read(&image, nullptr, rgba.data(), 0, nullptr) == 0)
    throw InputError(source, "", "a PNG image", image.message);
  const int w = static_cast<int>(image.width), h = static_cast<int>(image.height);
  GreyImage out{w, h, std::vector<std::uint8_t>(static_cast<std::size_t>(w) * h)};
  for (std::size_t k = 0; k < out.pixels.size(); ++k) {
    const unsigned sum = rgba[4 * k] + rgba[4 * k + 1] + rgba[4 * k + 2];
    out.pixels[k] = static_cast<std::uint8_t>((sum + 1) / 3);
  }
  return out;
}

bool is_png(std::string_view data) {
  return data.substr(0, 8) == std::string_view("\x89PNG\r\n\x1a\n", 8);
}

bool has_extension(const fs::path& p, std::string_view ext) {
  std::string e = p.extension().string();
  std::transform(e.begin(), e.end(), e.begin(), [](unsigned char c) { return std::tolower(c); });
  return e == ext;
}

}  // namespace

OccupancyMap2D OccupancyMap2D::filled(const GridGeometry& geometry, CellState fill) {
  return OccupancyMap2D{geometry, std::vector<CellState>(geometry.size(), fill)};
}

std::size_t OccupancyMap2D::count(CellState state) const {
  return static_cast<std::size_t>(std::count(cells.begin(), cells.end(), state));
}

bool operator==(const OccupancyMap2D& a, const OccupancyMap2D& b) {
  const GridGeometry &ga = a.geometry, &gb = b.geometry;
  return ga.origin_x_m == gb.origin_x_m && ga.origin_y_m == gb.origin_y_m &&
         ga.resolution_m == gb.resolution_m && ga.width == gb.width && ga.height == gb.height &&
         a.cells == b.cells;
}

GreyImage read_pgm(const fs::path& path) {
  return parse_pgm(read_binary_file(path, "a readable PGM file"), path.string());
}

GreyImage parse_pgm(std::string bytes, const std::string& source) {
  PgmReader in(std::move(bytes), source);
  const std::string_view data = in.data();
  if (data.size() < 2 || data[0] != 'P' || (data[1] != '5' && data[1] != '2'))
    in.fail("magic", "'P5' (binary PGM) or 'P2' (ASCII PGM)",
            data.empty() ? "an empty file" : quoted_bytes(data.substr(0, 2)));
  const bool binary = data[1] == '5';
  in.skip(2);
  if (in.at_end() || !std::isspace(static_cast<unsigned char>(in.peek())))
    in.fail("magic", "whitespace after the magic number",
            in.at_end() ? "end of file (truncated)" : quoted_bytes(data.substr(2, 4)));
  const auto width = in.number("header.width", 1, kMaxSide);
  const auto height = in.number("header.height", 1, kMaxSide);
  if (width * height > kMaxPixels)
    in.fail("header.height", fmt::format("at most {} pixels in all", kMaxPixels),
            fmt::format("{} x {}", width, height));
  const auto maxval = in.number("header.maxval", 1, 65535);
  const std::uint64_t samples = width * height;
  GreyImage out{static_cast<int>(width), static_cast<int>(height),
                std::vector<std::uint8_t>(samples)};

  if (binary) {
    // Exactly one whitespace byte separates maxval from the raster.
    if (in.at_end() || !std::isspace(static_cast<unsigned char>(in.peek())))
      in.fail("header.maxval", "one whitespace byte before the pixel data",
              in.at_end() ? "end of file (truncated)" : quoted_bytes(data.substr(in.pos(), 4)));
    in.skip(1);
    const std::uint64_t bytes_per_sample = maxval < 256 ? 1 : 2;
    const std::uint64_t needed = samples * bytes_per_sample;
    const std::uint64_t available = data.size() - in.pos();
    if (available < needed)
      in.fail("pixels",
              fmt::format("{} x {} = {} samples ({} bytes)", width, height, samples, needed),
              fmt::format("only {} bytes: truncated", available));
    // One image: bytes past the raster mean the header's size is wrong (a width of 1
    // for a 240-wide map would otherwise load as a thin strip).
    if (available > needed)
      in.fail("pixels",
              fmt::format("{} x {} = {} samples ({} bytes) and nothing after them", width, height,
                          samples, needed),
              fmt::format("{} bytes more", available - needed));
    const auto* raster = reinterpret_cast<const unsigned char*>(data.data() + in.pos());
    for (std::uint64_t k = 0; k < samples; ++k) {
      // 16-bit samples are big-endian (Netpbm).
      const std::uint64_t v = bytes_per_sample == 1
                                  ? raster[k]
                                  : (std::uint64_t{raster[2 * k]} << 8) | raster[2 * k + 1];
      if (v > maxval)
        in.fail(fmt::format("pixels[{}]", k), fmt::format("a sample <= maxval {}", maxval),
                std::to_string(v));
      out.pixels[k] = scale_to_byte(v, maxval);
    }
  } else {
    for (std::uint64_t k = 0; k < samples; ++k) {
      in.skip_space_and_comments();
      if (in.at_end())
        in.fail("pixels", fmt::format("{} x {} = {} samples", width, height, samples),
                fmt::format("only {}: truncated", k));
      out.pixels[k] = scale_to_byte(in.number(fmt::format("pixels[{}]", k), 0, maxval), maxval);
    }
    in.skip_space_and_comments();
    if (!in.at_end())
      in.fail("pixels",
              fmt::format("{} x {} = {} samples and nothing after them", width, height, samples),
              "more samples");
  }
  return out;
}

void write_pgm(const GreyImage& image, const fs::path& path) {
  write_file_atomically(path, [&](const fs::path& tmp) {
    std::ofstream out(tmp, std::ios::binary);
    out << "P5\n" << image.width << ' ' << image.height << "\n255\n";
    out.write(reinterpret_cast<const char*>(image.pixels.data()),
              static_cast<std::streamsize>(image.pixels.size()));
    out.close();
    if (!out) throw InputError(path.string(), "", "a writable file");
  });
}

namespace {

MapServerMeta map_server_meta_from(const YAML::Node& doc, const std::string& source) {
  const yaml::MapReader r(doc, source);
  // `search`: ferret's object-search setup (start and zones) for `ferret experiment`,
  // which reads it; map_server ignores keys it does not know.
  r.allow_only({"image", "resolution", "origin", "negate", "occupied_thresh", "free_thresh", "mode",
                "search"});
  if (r.has("search") && !r.node()["search"].IsMap())
    r.fail("search", "a mapping (start and zones of the object search, docs/object_search.md)");
  MapServerMeta meta;
  const auto image = r.get<std::string>("image");
  if (image.empty()) r.fail("image", "a non-empty image path");
  meta.image = image;
  meta.resolution_m = r.get<double>("resolution");
  if (!std::isfinite(meta.resolution_m) || meta.resolution_m <= 0.0)
    r.fail("resolution", "a number > 0 (metres per cell)",
           yaml::internal::describe(r.node()["resolution"]));
  const auto origin = r.get_list<double>("origin", 3);
  meta.origin_x_m = origin[0];
  meta.origin_y_m = origin[1];
  meta.origin_yaw_rad = origin[2];
  if (!std::isfinite(origin[0]) || !std::isfinite(origin[1])) r.fail("origin", "finite x and y");
  if (origin[2] != 0.0)
    throw InputError(r.source(), "origin[2]", "a yaw of 0 (rotated maps are not supported)",
                     fmt::format("{}", origin[2]));
  if (r.has("negate")) {
    // map_server writes negate as 0/1; YAML booleans are accepted too.
    const std::string v = r.get<std::string>("negate");
    if (v == "0" || v == "false" || v == "False")
      meta.negate = false;
    else if (v == "1" || v == "true" || v == "True")
      meta.negate = true;
    else
      r.fail("negate", "0, 1, true or false", "'" + v + "'");
  }
  meta.occupied_thresh = r.get_in_range_or("occupied_thresh", 0.0, 1.0, meta.occupied_thresh);
  meta.free_thresh = r.get_in_range_or("free_thresh", 0.0, 1.0, meta.free_thresh);
  if (meta.free_thresh > meta.occupied_thresh)
    r.fail("free_thresh", fmt::format("a value <= occupied_thresh ({})", meta.occupied_thresh),
           fmt::format("{}", meta.free_thresh));
  meta.mode = r.get_or<std::string>("mode", "trinary");
  if (meta.mode != "trinary")
    r.fail("mode",
           "'trinary' (scale and raw maps hold graded values, which a three-state map cannot keep)",
           "'" + meta.mode + "'");
  return meta;
}

}  // namespace

MapServerMeta load_map_server_meta(const fs::path& yaml_path) {
  return map_server_meta_from(yaml::load_file(yaml_path), yaml_path.string());
}

MapServerMeta parse_map_server_meta(const std::string& yaml_text, const std::string& source) {
  return map_server_meta_from(yaml::load_string(yaml_text, source), source);
}

OccupancyMap2D load_map_server(const fs::path& yaml_path) {
  const MapServerMeta meta = load_map_server_meta(yaml_path);
  const fs::path image_path =
      meta.image.is_absolute() ? meta.image : yaml_path.parent_path() / meta.image;
  std::error_code ec;
  if (!fs::is_regular_file(image_path, ec))
    throw InputError(yaml_path.string(), "image", "an existing image file", image_path.string());
  // A file called .pgm is read as PGM whatever it holds, so a broken one gets the PGM
  // reader's message naming the header field.
  const GreyImage img =
      has_extension(image_path, ".pgm")
          ? read_pgm(image_path)
          : decode_map_image(read_binary_file(image_path, "a readable image file"),
                             image_path.string());
  return map_from_image(meta, img);
}

GreyImage decode_map_image(std::string bytes, const std::string& source) {
  if (bytes.size() >= 2 && bytes[0] == 'P' && (bytes[1] == '5' || bytes[1] == '2'))
    return parse_pgm(std::move(bytes), source);
  if (is_png(bytes)) return read_png(bytes, source);
  return read_with_opencv(bytes, source);
}

OccupancyMap2D map_from_image(const MapServerMeta& meta, const GreyImage& img) {
  OccupancyMap2D map;
  map.geometry =
      GridGeometry{meta.origin_x_m, meta.origin_y_m, meta.resolution_m, img.width, img.height};
  map.cells.resize(map.geometry.size());
  for (int row = 0; row < img.height; ++row) {
    const int j = img.height - 1 - row;  // image row 0 is the top of the map
    for (int i = 0; i < img.width; ++i) {
      const double v = img.pixels[static_cast<std::size_t>(row) * img.width + i];
      const double occupancy = meta.negate ? v / 255.0 : (255.0 - v) / 255.0;
      CellState s = CellState::kUnknown;
      if (occupancy > meta.occupied_thresh)
        s = CellState::kOccupied;
      else if (occupancy < meta.free_thresh)
        s = CellState::kFree;
      map.at({i, j}) = s;
    }
  }
  return map;
}

bool is_map_server_yaml(const fs::path& path) {
  if (!has_extension(path, ".yaml") && !has_extension(path, ".yml")) return false;
  const YAML::Node doc = yaml::load_file(path);
  if (!doc.IsMap()) return false;
  for (const char* key : {"image", "resolution", "origin"})
    if (doc[key].IsDefined()) return true;
  return false;
}

void save_map_server(const OccupancyMap2D& map, const fs::path& yaml_path,
                     const std::string& extra_yaml) {
  if (!has_extension(yaml_path, ".yaml"))
    throw InputError(yaml_path.string(), "", "an output path ending in .yaml");
  const GridGeometry& g = map.geometry;
  if (g.width <= 0 || g.height <= 0 || map.cells.size() != g.size())
    throw InputError(yaml_path.string(), "",
                     "a non-empty map whose cell count matches its geometry");
  GreyImage img{g.width, g.height, std::vector<std::uint8_t>(g.size())};
  for (int j = 0; j < g.height; ++j) {
    for (int i = 0; i < g.width; ++i) {
      const CellState s = map.at({i, j});
      img.pixels[static_cast<std::size_t>(g.height - 1 - j) * g.width + i] =
          s == CellState::kOccupied ? 0
          : s == CellState::kFree   ? 254
                                    : 205;
    }
  }
  fs::path pgm_path = yaml_path;
  pgm_path.replace_extension(".pgm");
  // The YAML and its PGM are one set: both appear, or neither (a map without its image,
  // or an image the old YAML does not describe, would be worse than no map).
  check_output_target(yaml_path, OutputKind::kFile);
  check_output_target(pgm_path, OutputKind::kFile);
  OutputSet out(yaml_path.parent_path().empty() ? fs::path(".") : yaml_path.parent_path(),
                OutputKind::kDirectory);
  write_pgm(img, out.path(pgm_path.filename()));
  std::string name = pgm_path.filename().string();
  std::string quoted = "\"";
  for (const char c : name)
    quoted += (c == '"' || c == '\\') ? std::string{'\\', c} : std::string(1, c);
  quoted += '"';
  // fmt's "{}" prints the shortest text that reads back as the same double.
  out.write_text(yaml_path.filename(),
                 fmt::format("image: {}\nmode: trinary\nresolution: {}\norigin: [{}, {}, 0]\n"
                             "negate: 0\noccupied_thresh: 0.65\nfree_thresh: 0.196\n",
                             quoted, g.resolution_m, g.origin_x_m, g.origin_y_m) +
                     extra_yaml);
  out.commit();
}

}  // namespace ferret
