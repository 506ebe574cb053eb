// Round trips of ferret's PNG/JPEG codecs, checked against OpenCV's own decoder.
#include <gtest/gtest.h>

#include <opencv2/core.hpp>
#include <opencv2/imgcodecs.hpp>

#include "ferret/core/crc32.hpp"
#include "ferret/core/error.hpp"
#include "ferret/perception/colour.hpp"
#include "ferret/perception/image.hpp"

namespace ferret {
namespace {

TEST(ImageCodec, DepthPngRoundTripsEveryBit) {
  DepthImageMm depth(7, 3);
  for (std::size_t i = 0; i < depth.data.size(); ++i)
    depth.data[i] = static_cast<std::uint16_t>(i * 9301u + 258u);  // both bytes vary
  depth.at(0, 0) = 0;                                              // no return
  depth.at(6, 2) = 65535;                                          // the far end of the range
  const auto png = encode_png(depth);
  const DepthImageMm back = decode_depth_png(png, "d.png");
  EXPECT_EQ(back.width_px, 7);
  EXPECT_EQ(back.height_px, 3);
  EXPECT_EQ(back.data, depth.data);
  // OpenCV reads the same millimetres (the byte order in the file is PNG's big-endian).
  const cv::Mat cv16 = cv::imdecode(png, cv::IMREAD_UNCHANGED);
  ASSERT_EQ(cv16.type(), CV_16UC1);
  EXPECT_EQ(cv16.at<std::uint16_t>(1, 2), depth.at(2, 1));
}

TEST(ImageCodec, RgbPngKeepsChannelOrder) {
  RgbImage rgb(2, 2);
  rgb.at(0, 0, 0) = 255;  // red top-left
  rgb.at(1, 0, 1) = 255;  // green top-right
  rgb.at(0, 1, 2) = 255;  // blue bottom-left
  const auto png = encode_png(rgb);
  EXPECT_EQ(decode_rgb_image(png, "c.png").data, rgb.data);
  const cv::Mat bgr = cv::imdecode(png, cv::IMREAD_COLOR);
  EXPECT_EQ(bgr.at<cv::Vec3b>(0, 0), cv::Vec3b(0, 0, 255));  // OpenCV's BGR: red
  // Grey from colour: BT.601 weights, as to_gray() and libjpeg (not libpng's BT.709).
  const GrayImage grey = decode_gray_image(png, "c.png");
  const GrayImage same = to_gray(rgb);
  EXPECT_NEAR(grey.at(0, 0), 0.299 * 255, 1);
  EXPECT_NEAR(grey.at(1, 0), 0.587 * 255, 1);
  EXPECT_NEAR(grey.at(0, 1), 0.114 * 255, 1);
  EXPECT_EQ(same.at(0, 0), 76);   // round(0.299 * 255)
  EXPECT_EQ(same.at(1, 0), 150);  // round(0.587 * 255)
  EXPECT_EQ(same.at(0, 1), 29);   // round(0.114 * 255)
  for (std::size_t i = 0; i < grey.data.size(); ++i)
    EXPECT_NEAR(grey.data[i], same.data[i], 1) << i;
}

TEST(ImageCodec, GreyPngAndJpegDecode) {
  cv::Mat grey(16, 24, CV_8UC1);
  for (int y = 0; y < 16; ++y)
    for (int x = 0; x < 24; ++x) grey.at<std::uint8_t>(y, x) = static_cast<std::uint8_t>(x * 10);
  std::vector<std::uint8_t> png, jpg;
  cv::imencode(".png", grey, png);
  cv::imencode(".jpg", grey, jpg, {cv::IMWRITE_JPEG_QUALITY, 98});
  const GrayImage a = decode_gray_image(png, "g.png");
  EXPECT_EQ(a.at(23, 15), 230);
  const RgbImage as_rgb = decode_rgb_image(png, "g.png");
  EXPECT_EQ(as_rgb.at(5, 3, 0), 50);
  EXPECT_EQ(as_rgb.at(5, 3, 2), 50);
  const GrayImage b = decode_gray_image(jpg, "g.jpg");
  ASSERT_EQ(b.width_px, 24);
  ASSERT_EQ(b.height_px, 16);
  for (int x = 0; x < 24; x += 5) EXPECT_NEAR(b.at(x, 8), x * 10, 6) << x;
}

// A PNG with one more chunk after IHDR: `type`, the given length field, `body` and its CRC.
std::vector<std::uint8_t> with_chunk_after_ihdr(const std::vector<std::uint8_t>& png,
                                                const char* type, std::uint32_t length,
                                                const std::string& body) {
  std::string chunk(type, 4);
  chunk += body;
  const std::uint32_t crc = crc32(chunk);
  std::vector<std::uint8_t> out(png.begin(), png.begin() + 33);  // signature 8 + IHDR 25
  for (int s = 24; s >= 0; s -= 8) out.push_back(static_cast<std::uint8_t>(length >> s));
  for (const char c : chunk) out.push_back(static_cast<std::uint8_t>(c));
  for (int s = 24; s >= 0; s -= 8) out.push_back(static_cast<std::uint8_t>(crc >> s));
  for (std::size_t i = 33; i < png.size(); ++i) out.push_back(png[i]);
  return out;
}

TEST(ImageCodec, AMetadataChunkIsReadOnlyUpToEightMegabytes) {
  RgbImage rgb(3, 2);
  rgb.at(2, 1, 1) = 200;
  const auto png = encode_png(rgb);
  // Metadata of an ordinary size is no obstacle.
  const auto texted = with_chunk_after_ihdr(png, "tEXt", 13, std::string("Comment\0hello", 13));
  EXPECT_EQ(decode_rgb_image(texted, "c.png").data, rgb.data);
  // A zTXt chunk whose length field claims 2 GB (the fuzzer's "zTXt" read as a length)
  // is refused before libpng allocates it, naming the chunk.
  const auto huge = with_chunk_after_ihdr(png, "zTXt", 0x7a545874u, "x");
  try {
    (void)decode_rgb_image(huge, "c.png");
    FAIL() << "a 2 GB chunk was accepted";
  } catch (const InputError& e) {
    EXPECT_EQ(e.field(), "PNG data");
    EXPECT_NE(std::string(e.what()).find("'zTXt' claiming 2052348020 bytes"), std::string::npos)
        << e.what();
  }
  // A chunk type of arbitrary bytes is named printably (fmt's "{:?}" aborted on it).
  try {
    (void)decode_rgb_image(with_chunk_after_ihdr(png, "\xff\xdbxy", 1u << 30, ""), "c.png");
    FAIL() << "a 1 GB chunk was accepted";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("'\\xff\\xdbxy'"), std::string::npos) << e.what();
  }
}

TEST(ImageCodec, DepthMustBeSixteenBitGrey) {
  cv::Mat eight(4, 4, CV_8UC1, cv::Scalar(7));
  std::vector<std::uint8_t> png;
  cv::imencode(".png", eight, png);
  try {
    (void)decode_depth_png(png, "d.png");
    FAIL();
  } catch (const InputError& e) {
    EXPECT_EQ(e.source(), "d.png");
    EXPECT_EQ(e.field(), "PNG format");
    EXPECT_NE(std::string(e.what()).find("8-bit grey"), std::string::npos) << e.what();
  }
  // A truncated PNG is one InputError, not a crash or a message on stderr.
  cv::Mat sixteen(40, 40, CV_16UC1, cv::Scalar(1234));
  cv::imencode(".png", sixteen, png);
  png.resize(png.size() / 2);
  EXPECT_THROW((void)decode_depth_png(png, "d.png"), InputError);
}

}  // namespace
}  // namespace ferret
