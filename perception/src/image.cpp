// Image files. PNG and JPEG are decoded with libpng and libjpeg directly (not through
// OpenCV's imdecode) for two reasons: their error and warning handlers are ferret's,
// so a corrupt file gives one InputError instead of lines on stderr, and the size in
// the header is checked before a single pixel is allocated.
#include "ferret/perception/image.hpp"

#include <fmt/format.h>
#include <jpeglib.h>
#include <png.h>

#include <cmath>
#include <csetjmp>
#include <cstring>
#include <fstream>
#include <iterator>
#include <opencv2/core.hpp>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>
#include <string>

#include "ferret/core/error.hpp"
#include "ferret/perception/colour.hpp"

namespace ferret {
namespace {

enum class Format { kPng, kJpeg, kOther };

Format sniff(const std::vector<std::uint8_t>& b) {
  static constexpr std::uint8_t kPngMagic[8] = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1a, '\n'};
  if (b.size() >= 8 && std::memcmp(b.data(), kPngMagic, 8) == 0) return Format::kPng;
  if (b.size() >= 3 && b[0] == 0xff && b[1] == 0xd8 && b[2] == 0xff) return Format::kJpeg;
  return Format::kOther;
}

std::vector<std::uint8_t> read_bytes(const std::filesystem::path& path) {
  std::error_code ec;
  if (!std::filesystem::is_regular_file(path, ec))
    throw InputError(path.string(), "file", "an existing image file",
                     std::filesystem::exists(path, ec) ? "not a regular file" : "no such file");
  const auto size = std::filesystem::file_size(path, ec);
  // A frame of 16384 x 16384 RGB compresses to far less than this; a larger file is
  // not a camera frame.
  constexpr std::uintmax_t kMaxFileBytes = 1ull << 30;
  if (ec || size > kMaxFileBytes)
    throw InputError(path.string(), "file size", "at most 1 GiB", fmt::format("{} bytes", size));
  std::ifstream in(path, std::ios::binary);
  std::vector<std::uint8_t> bytes((std::istreambuf_iterator<char>(in)),
                                  std::istreambuf_iterator<char>());
  if (!in.good() && !in.eof())
    throw InputError(path.string(), "file", "a readable file", "a read error");
  return bytes;
}

void check_size(std::uint64_t w, std::uint64_t h, const std::string& source) {
  if (w == 0 || h == 0 || w > static_cast<std::uint64_t>(kMaxImageSidePx) ||
      h > static_cast<std::uint64_t>(kMaxImageSidePx))
    throw InputError(source, "image size", fmt::format("1 to {} px a side", kMaxImageSidePx),
                     fmt::format("{} x {} px", w, h));
}

// ---- PNG ----------------------------------------------------------------------------

struct PngReader {
  const std::vector<std::uint8_t>* bytes;
  std::size_t offset = 8;  // after the signature
  std::string error;
};

void png_error_to_reader(png_structp png, png_const_charp message) {
  auto* r = static_cast<PngReader*>(png_get_error_ptr(png));
  r->error = message != nullptr ? message : "unknown libpng error";
  png_longjmp(png, 1);
}
void png_ignore_warning(png_structp, png_const_charp) {}
void png_read_from_vector(png_structp png, png_bytep out, png_size_t n) {
  auto* r = static_cast<PngReader*>(png_get_io_ptr(png));
  if (r->bytes->size() - r->offset < n) png_error(png, "the file ends inside the image data");
  std::memcpy(out, r->bytes->data() + r->offset, n);
  r->offset += n;
}

enum class PngWant { kGray8, kRgb8, kGray16 };

// libpng 1.6.39 allocates an ancillary chunk (zTXt, iCCP, ...) at the length its header
// claims before it reads a byte, whatever png_set_chunk_malloc_max says: "zTXt" read as a
// length is 2 GB (found by fuzz/image_fuzz.cpp). The whole file is in memory, so every
// chunk up to IEND is checked to fit in what is left of it first.
void check_chunk_lengths(const std::vector<std::uint8_t>& bytes, const std::string& source) {
  std::size_t at = 8;  // after the signature
  while (at + 8 <= bytes.size()) {
    const std::uint64_t length = (std::uint64_t{bytes[at]} << 24) |
                                 (std::uint64_t{bytes[at + 1]} << 16) |
                                 (std::uint64_t{bytes[at + 2]} << 8) | bytes[at + 3];
    const std::string type(reinterpret_cast<const char*>(bytes.data() + at + 4), 4);
    const std::uint64_t left = bytes.size() - at - 8;
    if (length + 4 > left)  // data and CRC
      throw InputError(source, "PNG data", "chunks that fit in the file",
                       fmt::format("a chunk of type '{}' claiming {} bytes where {} are left",
                                   printable(type), length, left >= 4 ? left - 4 : 0));
    if (type == "IEND") return;
    at += 12 + length;
  }
}

// Decodes into `channels` x `bits` samples; returns width, height in out params.
template <typename T, int C>
Image<T, C> decode_png(const std::vector<std::uint8_t>& bytes, const std::string& source,
                       PngWant want) {
  // The size straight from IHDR (always the first chunk, at byte 16): libpng would
  // refuse a size beyond its user limits with only "Invalid IHDR data".
  if (bytes.size() >= 24 && std::memcmp(bytes.data() + 12, "IHDR", 4) == 0) {
    const auto be32 = [&](std::size_t at) {
      return (std::uint64_t{bytes[at]} << 24) | (std::uint64_t{bytes[at + 1]} << 16) |
             (std::uint64_t{bytes[at + 2]} << 8) | std::uint64_t{bytes[at + 3]};
    };
    check_size(be32(16), be32(20), source);
  }
  check_chunk_lengths(bytes, source);
  PngReader reader{&bytes, 8, {}};
  png_structp png = png_create_read_struct(PNG_LIBPNG_VER_STRING, &reader, png_error_to_reader,
                                           png_ignore_warning);
  if (png == nullptr) throw std::bad_alloc();
  png_infop info = png_create_info_struct(png);
  struct Free {
    png_structp* p;
    png_infop* i;
    ~Free() { png_destroy_read_struct(p, i, nullptr); }
  } free_png{&png, &info};
  if (info == nullptr) throw std::bad_alloc();
  Image<T, C> out;
  std::vector<png_bytep> rows;
  if (setjmp(png_jmpbuf(png)) != 0)
    throw InputError(source, "PNG data", "a valid PNG file", reader.error);
  png_set_read_fn(png, &reader, png_read_from_vector);
  png_set_sig_bytes(png, 8);
  png_set_user_limits(png, kMaxImageSidePx, kMaxImageSidePx);
  png_read_info(png, info);
  png_uint_32 w = 0, h = 0;
  int bit_depth = 0, colour = 0;
  png_get_IHDR(png, info, &w, &h, &bit_depth, &colour, nullptr, nullptr, nullptr);
  check_size(w, h, source);
  if (want == PngWant::kGray16) {
    if (colour != PNG_COLOR_TYPE_GRAY || bit_depth != 16)
      throw InputError(source, "PNG format",
                       "a single-channel 16-bit PNG of millimetres (a depth frame)",
                       fmt::format("{}-bit {}", bit_depth,
                                   colour == PNG_COLOR_TYPE_GRAY         ? "grey"
                                   : colour == PNG_COLOR_TYPE_GRAY_ALPHA ? "grey with alpha"
                                   : colour == PNG_COLOR_TYPE_PALETTE    ? "palette"
                                   : colour == PNG_COLOR_TYPE_RGB        ? "RGB"
                                                                         : "RGBA"));
    png_set_swap(png);  // PNG stores 16-bit samples big-endian
  } else {
    png_set_expand(png);  // palette, low-bit grey and tRNS to 8-bit channels
    png_set_strip_16(png);
    png_set_strip_alpha(png);
    const bool gray_in = (colour & PNG_COLOR_MASK_COLOR) == 0;
    if (want == PngWant::kRgb8 && gray_in) png_set_gray_to_rgb(png);
    // BT.601 weights (perception/colour.hpp), not libpng's default BT.709: the same grey
    // as a JPEG of the same frame (libjpeg) and as to_gray().
    if (want == PngWant::kGray8 && !gray_in) png_set_rgb_to_gray_fixed(png, 1, 29900, 58700);
  }
  const int passes = png_set_interlace_handling(png);
  png_read_update_info(png, info);
  if (png_get_rowbytes(png, info) != static_cast<std::size_t>(w) * C * sizeof(T))
    throw InputError(source, "PNG format", "a PNG ferret can convert", "an unexpected row layout");
  if (passes == 1) {
    // Row by row into a buffer that grows with the rows decoded: a header that promises
    // 16384 x 16384 px in a file of a few bytes costs the memory of what it holds, not
    // 768 MiB zeroed before the first missing row (found by fuzz/depth_png_fuzz.cpp).
    out.width_px = static_cast<int>(w);
    out.height_px = static_cast<int>(h);
    const std::size_t row_values = static_cast<std::size_t>(w) * C;
    for (png_uint_32 y = 0; y < h; ++y) {
      out.data.resize((static_cast<std::size_t>(y) + 1) * row_values);
      png_read_row(png, reinterpret_cast<png_bytep>(out.data.data() + y * row_values), nullptr);
    }
    png_read_end(png, nullptr);
    return out;
  }
  // Interlaced: every pass writes into every row, so the whole frame is needed at once.
  out = Image<T, C>(static_cast<int>(w), static_cast<int>(h));
  rows.resize(h);
  for (png_uint_32 y = 0; y < h; ++y)
    rows[y] = reinterpret_cast<png_bytep>(&out.at(0, static_cast<int>(y)));
  png_read_image(png, rows.data());
  png_read_end(png, nullptr);
  return out;
}

// ---- JPEG ---------------------------------------------------------------------------

struct JpegError {
  jpeg_error_mgr mgr;
  std::jmp_buf jump;
  char message[JMSG_LENGTH_MAX];
};
void jpeg_error_exit(j_common_ptr cinfo) {
  auto* e = reinterpret_cast<JpegError*>(cinfo->err);
  (*cinfo->err->format_message)(cinfo, e->message);
  std::longjmp(e->jump, 1);
}
void jpeg_quiet(j_common_ptr) {}  // warnings ("extraneous bytes") are not printed

template <int C>
Image<std::uint8_t, C> decode_jpeg(const std::vector<std::uint8_t>& bytes,
                                   const std::string& source) {
  jpeg_decompress_struct cinfo{};
  JpegError err{};
  cinfo.err = jpeg_std_error(&err.mgr);
  err.mgr.error_exit = jpeg_error_exit;
  err.mgr.output_message = jpeg_quiet;
  Image<std::uint8_t, C> out;
  std::vector<std::uint8_t> row;
  if (setjmp(err.jump) != 0) {
    jpeg_destroy_decompress(&cinfo);
    throw InputError(source, "JPEG data", "a valid JPEG file", err.message);
  }
  jpeg_create_decompress(&cinfo);
  jpeg_mem_src(&cinfo, bytes.data(), static_cast<unsigned long>(bytes.size()));
  jpeg_read_header(&cinfo, TRUE);
  if (cinfo.image_width == 0 || cinfo.image_height == 0 ||
      cinfo.image_width > static_cast<unsigned>(kMaxImageSidePx) ||
      cinfo.image_height > static_cast<unsigned>(kMaxImageSidePx)) {
    const auto w = cinfo.image_width, h = cinfo.image_height;
    jpeg_destroy_decompress(&cinfo);
    check_size(w, h, source);
  }
  cinfo.out_color_space = C == 1 ? JCS_GRAYSCALE : JCS_RGB;
  jpeg_start_decompress(&cinfo);
  out = Image<std::uint8_t, C>(static_cast<int>(cinfo.output_width),
                               static_cast<int>(cinfo.output_height));
  while (cinfo.output_scanline < cinfo.output_height) {
    JSAMPROW r = &out.at(0, static_cast<int>(cinfo.output_scanline));
    jpeg_read_scanlines(&cinfo, &r, 1);
  }
  jpeg_finish_decompress(&cinfo);
  jpeg_destroy_decompress(&cinfo);
  return out;
}

template <int C>
Image<std::uint8_t, C> decode_colour(const std::vector<std::uint8_t>& bytes,
                                     const std::string& source) {
  switch (sniff(bytes)) {
    case Format::kPng:
      return decode_png<std::uint8_t, C>(bytes, source, C == 1 ? PngWant::kGray8 : PngWant::kRgb8);
    case Format::kJpeg:
      return decode_jpeg<C>(bytes, source);
    case Format::kOther:
      break;
  }
  throw InputError(source, "file format", "a PNG or JPEG image",
                   bytes.empty() ? "an empty file" : "neither PNG nor JPEG data");
}

std::vector<std::uint8_t> encode(const cv::Mat& m) {
  std::vector<std::uint8_t> out;
  if (!cv::imencode(".png", m, out)) throw std::runtime_error("PNG encoding failed");
  return out;
}

}  // namespace

RgbImage decode_rgb_image(const std::vector<std::uint8_t>& bytes, const std::string& source) {
  return decode_colour<3>(bytes, source);
}
GrayImage decode_gray_image(const std::vector<std::uint8_t>& bytes, const std::string& source) {
  return decode_colour<1>(bytes, source);
}
DepthImageMm decode_depth_png(const std::vector<std::uint8_t>& bytes, const std::string& source) {
  if (sniff(bytes) != Format::kPng)
    throw InputError(source, "file format",
                     "a single-channel 16-bit PNG of millimetres (a depth frame)",
                     bytes.empty() ? "an empty file" : "not PNG data");
  return decode_png<std::uint16_t, 1>(bytes, source, PngWant::kGray16);
}

GrayImage read_gray_image(const std::filesystem::path& path) {
  return decode_gray_image(read_bytes(path), path.string());
}
RgbImage read_rgb_image(const std::filesystem::path& path) {
  return decode_rgb_image(read_bytes(path), path.string());
}
DepthImageMm read_depth_png(const std::filesystem::path& path) {
  return decode_depth_png(read_bytes(path), path.string());
}

GrayImage to_gray(const RgbImage& rgb) {
  GrayImage g(rgb.width_px, rgb.height_px);
  for (std::size_t i = 0; i < g.data.size(); ++i)
    g.data[i] = static_cast<std::uint8_t>(std::lround(
        0.299 * rgb.data[3 * i] + 0.587 * rgb.data[3 * i + 1] + 0.114 * rgb.data[3 * i + 2]));
  return g;
}

std::vector<std::uint8_t> encode_png(const GrayImage& image) {
  return encode(cv::Mat(image.height_px, image.width_px, CV_8UC1,
                        const_cast<std::uint8_t*>(image.data.data())));
}
std::vector<std::uint8_t> encode_png(const RgbImage& image) {
  cv::Mat rgb(image.height_px, image.width_px, CV_8UC3,
              const_cast<std::uint8_t*>(image.data.data()));
  cv::Mat bgr;
  cv::cvtColor(rgb, bgr, cv::COLOR_RGB2BGR);
  return encode(bgr);
}
std::vector<std::uint8_t> encode_png(const DepthImageMm& image) {
  return encode(cv::Mat(image.height_px, image.width_px, CV_16UC1,
                        const_cast<std::uint16_t*>(image.data.data())));
}

}  // namespace ferret
