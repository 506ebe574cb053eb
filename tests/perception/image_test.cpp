// Image files: every PNG colour type and bit depth a camera or a tool writes decodes to
// the pixels it holds, JPEG too; depth frames must be 16-bit grey; and every bad file
// (not an image, the wrong bit depth, a size beyond the limit in the header, cut
// short) is an InputError naming the file. The test writes its PNG and JPEG files
// itself, from first principles, so a decoder bug cannot hide behind a shared encoder.

#include "ferret/perception/image.hpp"

#include <gtest/gtest.h>
#include <unistd.h>

#include <array>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "ferret/core/error.hpp"
#include "ferret/core/random.hpp"

namespace ferret {
namespace {

namespace fs = std::filesystem;
using Bytes = std::vector<std::uint8_t>;

std::uint32_t crc32(const std::uint8_t* p, std::size_t n, std::uint32_t crc = 0) {
  crc = ~crc;
  for (std::size_t i = 0; i < n; ++i) {
    crc ^= p[i];
    for (int k = 0; k < 8; ++k) crc = (crc >> 1) ^ (0xEDB88320u & (0u - (crc & 1u)));
  }
  return ~crc;
}

void put32(Bytes& out, std::uint32_t v) {
  for (int s = 24; s >= 0; s -= 8) out.push_back(static_cast<std::uint8_t>(v >> s));
}

void chunk(Bytes& out, const char* kind, const Bytes& body) {
  put32(out, static_cast<std::uint32_t>(body.size()));
  Bytes typed(kind, kind + 4);
  typed.insert(typed.end(), body.begin(), body.end());
  out.insert(out.end(), typed.begin(), typed.end());
  put32(out, crc32(typed.data(), typed.size()));
}

/// zlib stream of `data` in stored (uncompressed) deflate blocks.
Bytes zlib_stored(const Bytes& data) {
  Bytes out{0x78, 0x01};
  std::size_t at = 0;
  do {
    const std::size_t n = std::min<std::size_t>(65535, data.size() - at);
    out.push_back(at + n == data.size() ? 1 : 0);
    out.push_back(static_cast<std::uint8_t>(n));
    out.push_back(static_cast<std::uint8_t>(n >> 8));
    out.push_back(static_cast<std::uint8_t>(~n));
    out.push_back(static_cast<std::uint8_t>(~n >> 8));
    out.insert(out.end(), data.begin() + static_cast<std::ptrdiff_t>(at),
               data.begin() + static_cast<std::ptrdiff_t>(at + n));
    at += n;
  } while (at < data.size());
  std::uint32_t a = 1, b = 0;
  for (const auto v : data) {
    a = (a + v) % 65521;
    b = (b + a) % 65521;
  }
  put32(out, (b << 16) | a);
  return out;
}

struct Png {
  std::uint32_t width, height;
  std::uint8_t colour, depth;  ///< PNG colour type (0 grey, 2 RGB, 3 palette, 4 grey+alpha, 6 RGBA)
  std::vector<Bytes> rows;     ///< raw scanlines, without filter bytes
  Bytes plte, trns;
};

Bytes png_bytes(const Png& p, bool header_only = false) {
  Bytes out{0x89, 'P', 'N', 'G', '\r', '\n', 0x1a, '\n'};
  Bytes ihdr;
  put32(ihdr, p.width);
  put32(ihdr, p.height);
  ihdr.insert(ihdr.end(), {p.depth, p.colour, 0, 0, 0});
  chunk(out, "IHDR", ihdr);
  if (header_only) return out;
  if (!p.plte.empty()) chunk(out, "PLTE", p.plte);
  if (!p.trns.empty()) chunk(out, "tRNS", p.trns);
  Bytes raw;
  for (const auto& r : p.rows) {
    raw.push_back(0);  // filter: none
    raw.insert(raw.end(), r.begin(), r.end());
  }
  chunk(out, "IDAT", zlib_stored(raw));
  chunk(out, "IEND", {});
  return out;
}

/// The same image Adam7-interlaced (8-bit samples only: `bytes_per_pixel` a pixel).
Bytes png_interlaced(const Png& p, int bytes_per_pixel) {
  Bytes out{0x89, 'P', 'N', 'G', '\r', '\n', 0x1a, '\n'};
  Bytes ihdr;
  put32(ihdr, p.width);
  put32(ihdr, p.height);
  ihdr.insert(ihdr.end(), {p.depth, p.colour, 0, 0, 1});
  chunk(out, "IHDR", ihdr);
  const int passes[7][4] = {{0, 0, 8, 8}, {4, 0, 8, 8}, {0, 4, 4, 8}, {2, 0, 4, 4},
                            {0, 2, 2, 4}, {1, 0, 2, 2}, {0, 1, 1, 2}};
  Bytes raw;
  for (const auto& [x0, y0, dx, dy] : passes) {
    for (int y = y0; y < static_cast<int>(p.height); y += dy) {
      if (x0 >= static_cast<int>(p.width)) break;  // an empty pass has no rows
      raw.push_back(0);
      for (int x = x0; x < static_cast<int>(p.width); x += dx)
        for (int b = 0; b < bytes_per_pixel; ++b)
          raw.push_back(p.rows[static_cast<std::size_t>(y)]
                              [static_cast<std::size_t>(x * bytes_per_pixel + b)]);
    }
  }
  chunk(out, "IDAT", zlib_stored(raw));
  chunk(out, "IEND", {});
  return out;
}

/// A baseline JPEG whose Huffman tables hold one symbol each (DC difference 0, end of
/// block): every 8 x 8 block is flat mid-grey (128) in every component.
Bytes flat_jpeg(std::uint16_t width, std::uint16_t height, int components) {
  Bytes out{0xff, 0xd8};
  auto segment = [&](std::uint8_t marker, const Bytes& body) {
    out.insert(out.end(), {0xff, marker, static_cast<std::uint8_t>((body.size() + 2) >> 8),
                           static_cast<std::uint8_t>(body.size() + 2)});
    out.insert(out.end(), body.begin(), body.end());
  };
  Bytes dqt{0x00};
  dqt.insert(dqt.end(), 64, 1);
  segment(0xdb, dqt);
  Bytes sof{8,
            static_cast<std::uint8_t>(height >> 8),
            static_cast<std::uint8_t>(height),
            static_cast<std::uint8_t>(width >> 8),
            static_cast<std::uint8_t>(width),
            static_cast<std::uint8_t>(components)};
  for (int c = 0; c < components; ++c)
    sof.insert(sof.end(), {static_cast<std::uint8_t>(c + 1), 0x11, 0});
  segment(0xc0, sof);
  for (const std::uint8_t table : {0x00, 0x10}) {
    Bytes dht{table, 1};
    dht.insert(dht.end(), 15, 0);
    dht.push_back(0);  // the one symbol: DC category 0 / AC end of block, code "0"
    segment(0xc4, dht);
  }
  Bytes sos{static_cast<std::uint8_t>(components)};
  for (int c = 0; c < components; ++c)
    sos.insert(sos.end(), {static_cast<std::uint8_t>(c + 1), 0x00});
  sos.insert(sos.end(), {0x00, 0x3f, 0x00});
  segment(0xda, sos);
  const std::size_t blocks = ((width + 7u) / 8u) * ((height + 7u) / 8u) * components;
  const std::size_t bits = 2 * blocks;
  out.insert(out.end(), bits / 8, 0x00);
  if (bits % 8 != 0) out.push_back(static_cast<std::uint8_t>((1u << (8 - bits % 8)) - 1));
  out.insert(out.end(), {0xff, 0xd9});
  return out;
}

/// A scratch folder for files the readers open by path.
class Files {
 public:
  Files() : dir_(fs::temp_directory_path() / ("ferret_image_" + std::to_string(::getpid()))) {
    fs::create_directories(dir_);
  }
  ~Files() { fs::remove_all(dir_); }
  fs::path write(const std::string& name, const Bytes& bytes) const {
    std::ofstream(dir_ / name, std::ios::binary)
        .write(reinterpret_cast<const char*>(bytes.data()),
               static_cast<std::streamsize>(bytes.size()));
    return dir_ / name;
  }

 private:
  fs::path dir_;
};

template <typename F>
InputError input_error(F&& f) {
  try {
    f();
  } catch (const InputError& e) {
    return e;
  }
  ADD_FAILURE() << "no InputError";
  return InputError("", "", "");
}

constexpr int kW = 8, kH = 6;

TEST(ImageFiles, SixteenBitGreyPngIsADepthFrameOfMillimetres) {
  Png p{kW, kH, 0, 16, {}, {}, {}};
  for (int y = 0; y < kH; ++y) {
    Bytes row;
    for (int x = 0; x < kW; ++x) {
      const int mm = x == 0 && y == 0 ? 0 : 300 + 1000 * x + y;  // 0 = no return
      row.insert(row.end(), {static_cast<std::uint8_t>(mm >> 8), static_cast<std::uint8_t>(mm)});
    }
    p.rows.push_back(row);
  }
  const Files files;
  const DepthImageMm d = read_depth_png(files.write("depth.png", png_bytes(p)));
  ASSERT_EQ(d.width_px, kW);
  ASSERT_EQ(d.height_px, kH);
  EXPECT_EQ(d.at(0, 0), 0);
  EXPECT_EQ(d.at(1, 0), 1300);
  EXPECT_EQ(d.at(7, 5), 7305);  // big-endian in the file, host order here
}

TEST(ImageFiles, EveryPngColourTypeDecodesToItsPixels) {
  // RGB 8-bit.
  Png rgb{kW, kH, 2, 8, {}, {}, {}};
  for (int y = 0; y < kH; ++y) {
    Bytes row;
    for (int x = 0; x < kW; ++x)
      row.insert(row.end(),
                 {static_cast<std::uint8_t>(30 * x), static_cast<std::uint8_t>(40 * y), 200});
    rgb.rows.push_back(row);
  }
  const RgbImage a = decode_rgb_image(png_bytes(rgb), "rgb.png");
  EXPECT_EQ(a.at(3, 2, 0), 90);
  EXPECT_EQ(a.at(3, 2, 1), 80);
  EXPECT_EQ(a.at(3, 2, 2), 200);

  // 4-bit palette with transparency (dropped: the frame is RGB).
  Png pal{kW, kH, 3, 4, {}, {}, {0, 128}};
  for (int i = 0; i < 16; ++i)
    pal.plte.insert(pal.plte.end(), {static_cast<std::uint8_t>(16 * i),
                                     static_cast<std::uint8_t>(255 - 16 * i), 128});
  for (int y = 0; y < kH; ++y) {
    Bytes row;
    for (int k = 0; k < kW / 2; ++k)
      row.push_back(static_cast<std::uint8_t>(((k % 16) << 4) | ((k + y) % 16)));
    pal.rows.push_back(row);
  }
  const RgbImage b = decode_rgb_image(png_bytes(pal), "palette.png");
  // Pixel (5, 3): second pixel of byte k = 2, index (2 + 3) % 16 = 5.
  EXPECT_EQ(b.at(5, 3, 0), 80);
  EXPECT_EQ(b.at(5, 3, 1), 175);
  EXPECT_EQ(b.at(5, 3, 2), 128);
  EXPECT_EQ(b.at(4, 3, 0), 32);  // first pixel of byte 2: index 2

  // 1-bit grey: 0b10101010 is white, black, white ...
  Png bits{kW, kH, 0, 1, std::vector<Bytes>(kH, Bytes{0b10101010}), {}, {}};
  const GrayImage c = decode_gray_image(png_bytes(bits), "bits.png");
  EXPECT_EQ(c.at(0, 0), 255);
  EXPECT_EQ(c.at(1, 0), 0);
  const RgbImage c_rgb = decode_rgb_image(png_bytes(bits), "bits.png");
  EXPECT_EQ(c_rgb.at(2, 4, 1), 255);

  // 16-bit RGBA: alpha dropped, 16 bits to 8 (the high byte).
  Png rgba{kW, kH, 6, 16, {}, {}, {}};
  for (int y = 0; y < kH; ++y) {
    Bytes row;
    for (int x = 0; x < kW; ++x)
      for (const int v : {x * 8000, y * 9000, 100, 65535})
        row.insert(row.end(), {static_cast<std::uint8_t>(v >> 8), static_cast<std::uint8_t>(v)});
    rgba.rows.push_back(row);
  }
  const RgbImage d = decode_rgb_image(png_bytes(rgba), "rgba.png");
  EXPECT_NEAR(d.at(7, 0, 0), (7 * 8000) >> 8, 1);
  EXPECT_NEAR(d.at(0, 5, 1), (5 * 9000) >> 8, 1);
  EXPECT_NEAR(d.at(0, 5, 2), 0, 1);

  // Grey + alpha 8-bit, as RGB: r = g = b = grey.
  Png ga{kW, kH, 4, 8, {}, {}, {}};
  for (int y = 0; y < kH; ++y) {
    Bytes row;
    for (int x = 0; x < kW; ++x) row.insert(row.end(), {static_cast<std::uint8_t>(30 * x), 7});
    ga.rows.push_back(row);
  }
  const RgbImage e = decode_rgb_image(png_bytes(ga), "ga.png");
  EXPECT_EQ(e.at(6, 1, 0), 180);
  EXPECT_EQ(e.at(6, 1, 2), 180);
}

TEST(ImageFiles, InterlacedPngDecodesLikeTheSameImageNotInterlaced) {
  // 11 x 9: passes of every size, some rows of a pass shorter than others.
  Png p{11, 9, 2, 8, {}, {}, {}};
  Rng rng(5);
  for (int y = 0; y < 9; ++y) {
    Bytes row;
    for (int i = 0; i < 33; ++i) row.push_back(static_cast<std::uint8_t>(rng.uniform_int(0, 255)));
    p.rows.push_back(row);
  }
  const RgbImage plain = decode_rgb_image(png_bytes(p), "plain.png");
  const RgbImage adam7 = decode_rgb_image(png_interlaced(p, 3), "adam7.png");
  ASSERT_EQ(adam7.width_px, 11);
  ASSERT_EQ(adam7.height_px, 9);
  EXPECT_EQ(adam7.data, plain.data);
  EXPECT_EQ(plain.at(10, 8, 2), p.rows[8][32]);
}

TEST(ImageFiles, JpegDecodesAsGreyAndRgb) {
  const RgbImage rgb = decode_rgb_image(flat_jpeg(24, 16, 3), "flat.jpg");
  ASSERT_EQ(rgb.width_px, 24);
  ASSERT_EQ(rgb.height_px, 16);
  for (const int c : {0, 1, 2}) EXPECT_NEAR(rgb.at(23, 15, c), 128, 1);
  const GrayImage gray = decode_gray_image(flat_jpeg(16, 8, 1), "flat_gray.jpg");
  ASSERT_EQ(gray.width_px, 16);
  EXPECT_NEAR(gray.at(5, 5), 128, 1);
}

TEST(ImageFiles, EncodedPngsDecodeToTheSameValues) {
  Rng rng(11);
  DepthImageMm depth(37, 11);
  for (auto& v : depth.data) v = static_cast<std::uint16_t>(rng.uniform_int(0, 65535));
  EXPECT_EQ(decode_depth_png(encode_png(depth), "d").data, depth.data);
  RgbImage rgb(13, 7);
  for (auto& v : rgb.data) v = static_cast<std::uint8_t>(rng.uniform_int(0, 255));
  EXPECT_EQ(decode_rgb_image(encode_png(rgb), "c").data, rgb.data);
  GrayImage gray(5, 9);
  for (auto& v : gray.data) v = static_cast<std::uint8_t>(rng.uniform_int(0, 255));
  EXPECT_EQ(decode_gray_image(encode_png(gray), "g").data, gray.data);
}

TEST(ImageFiles, TextFileIsNotAnImageNamingTheFile) {
  const Files files;
  const std::string text = "P5 is not here; this is a note\n";
  const fs::path path = files.write("note.png", Bytes(text.begin(), text.end()));
  for (const auto& e : {input_error([&] { (void)read_rgb_image(path); }),
                        input_error([&] { (void)read_gray_image(path); }),
                        input_error([&] { (void)read_depth_png(path); })}) {
    EXPECT_EQ(e.source(), path.string());
    EXPECT_EQ(e.field(), "file format");
  }
  const fs::path empty = files.write("empty.png", {});
  EXPECT_NE(std::string(input_error([&] { (void)read_rgb_image(empty); }).what()).find("empty"),
            std::string::npos);
  const InputError missing = input_error([&] { (void)read_depth_png("/nonexistent/d.png"); });
  EXPECT_EQ(missing.source(), "/nonexistent/d.png");
}

TEST(ImageFiles, DepthMustBeSixteenBitGreyAndTheMessageSaysWhatItGot) {
  const Files files;
  GrayImage gray(4, 3, 100);
  const fs::path p8 = files.write("gray8.png", encode_png(gray));
  const InputError e8 = input_error([&] { (void)read_depth_png(p8); });
  EXPECT_EQ(e8.source(), p8.string());
  EXPECT_EQ(e8.field(), "PNG format");
  EXPECT_NE(std::string(e8.what()).find("8-bit grey"), std::string::npos) << e8.what();
  // 16-bit but RGB: the channels are wrong even though the depth is right.
  Png rgb16{2, 2, 2, 16, std::vector<Bytes>(2, Bytes(12, 0)), {}, {}};
  const InputError e16 =
      input_error([&] { (void)decode_depth_png(png_bytes(rgb16), "rgb16.png"); });
  EXPECT_NE(std::string(e16.what()).find("16-bit RGB"), std::string::npos) << e16.what();
  // A JPEG is never a depth frame.
  const InputError ej = input_error([&] { (void)decode_depth_png(flat_jpeg(8, 8, 1), "d.jpg"); });
  EXPECT_EQ(ej.field(), "file format");
}

TEST(ImageFiles, SizeBeyondTheLimitIsRefusedFromTheHeaderAlone) {
  // Only the signature and IHDR: had the decoder gone on, the missing image data would
  // be the complaint, not the size.
  for (const auto& [w, h] : {std::pair<std::uint32_t, std::uint32_t>{20000, 1}, {1, 16385}}) {
    Png huge{w, h, 0, 16, {}, {}, {}};
    const Bytes header = png_bytes(huge, true);
    for (const auto& e : {input_error([&] { (void)decode_depth_png(header, "huge.png"); }),
                          input_error([&] { (void)decode_rgb_image(header, "huge.png"); })}) {
      EXPECT_EQ(e.source(), "huge.png");
      EXPECT_EQ(e.field(), "image size") << e.what();
      EXPECT_NE(std::string(e.what()).find(std::to_string(w) + " x " + std::to_string(h)),
                std::string::npos)
          << e.what();
    }
  }
  const InputError j =
      input_error([&] { (void)decode_rgb_image(flat_jpeg(20000, 8, 1), "w.jpg"); });
  EXPECT_EQ(j.field(), "image size");
  EXPECT_NE(std::string(j.what()).find("20000 x 8"), std::string::npos) << j.what();
  // 16384 a side is the limit itself, and allowed (checked on a 16384 x 1 frame).
  Png edge{16384, 1, 0, 8, {Bytes(16384, 9)}, {}, {}};
  EXPECT_EQ(decode_gray_image(png_bytes(edge), "edge.png").width_px, 16384);
  // A zero size is refused too.
  Png zero{0, 4, 0, 8, {}, {}, {}};
  EXPECT_EQ(input_error([&] { (void)decode_gray_image(png_bytes(zero, true), "z.png"); }).field(),
            "image size");
}

TEST(ImageFiles, CutShortFilesAreInputErrors) {
  Png rgb{kW, kH, 2, 8, std::vector<Bytes>(kH, Bytes(3 * kW, 50)), {}, {}};
  const Bytes full = png_bytes(rgb);
  for (const std::size_t keep :
       {std::size_t{12}, std::size_t{33}, std::size_t{60}, full.size() - 13}) {
    const Bytes cut(full.begin(), full.begin() + static_cast<std::ptrdiff_t>(keep));
    EXPECT_EQ(input_error([&] { (void)decode_rgb_image(cut, "cut.png"); }).source(), "cut.png")
        << keep;
  }
  // A flipped bit in IHDR fails its CRC.
  Bytes flipped = full;
  flipped[18] ^= 0x01;
  EXPECT_EQ(input_error([&] { (void)decode_rgb_image(flipped, "crc.png"); }).field(), "PNG data");
  // A JPEG cut inside its headers.
  const Bytes jpeg = flat_jpeg(16, 16, 3);
  const Bytes jcut(jpeg.begin(), jpeg.begin() + 40);
  EXPECT_EQ(input_error([&] { (void)decode_rgb_image(jcut, "cut.jpg"); }).field(), "JPEG data");
}

}  // namespace
}  // namespace ferret
