// Tests of grids/src/png_image.cpp: gridloc's own PNG decoder against OpenCV's, the reference
// (cv::imdecode with IMREAD_UNCHANGED, what load_ros_map used before issue 18), pixel for
// pixel, on PNGs of every colour type, bit depth and row filter, interlaced or not. The PNGs
// are written here with zlib (any header, filter and chunk) or by cv::imencode.
#include "png_image.hpp"

#include <gtest/gtest.h>
#include <zlib.h>

#include <algorithm>
#include <array>
#include <cstdint>
#include <cstdlib>
#include <opencv2/core.hpp>
#include <opencv2/imgcodecs.hpp>
#include <optional>
#include <random>
#include <string>
#include <tuple>
#include <utility>
#include <vector>

#include "png_bytes.hpp"
#include "test_support.hpp"

namespace gridloc {
namespace {

using test::expect_error;

/// A PNG to write: its header, its samples and the chunks that colour them.
struct PngSpec {
  int width = 1, height = 1, depth = 8, colour_type = 0;
  bool interlaced = false;
  std::vector<int> samples;                 ///< rows from the top, samples_per_pixel each
  std::string palette;                      ///< PLTE data (no chunk when empty)
  std::optional<std::string> transparency;  ///< tRNS data (no chunk when absent)
  int filter = -1;  ///< the row filter of every row, or -1: (row + pass) % 5 by turns
};

int samples_per_pixel(int colour_type) {
  return colour_type == 2 ? 3 : colour_type == 4 ? 2 : colour_type == 6 ? 4 : 1;
}

/// Adam7's passes (first column, first row, column step, row step), or the whole image.
std::vector<std::array<int, 4>> passes(bool interlaced) {
  if (!interlaced) return {{0, 0, 1, 1}};
  return {{0, 0, 8, 8}, {4, 0, 8, 8}, {0, 4, 4, 8}, {2, 0, 4, 4},
          {0, 2, 2, 4}, {1, 0, 2, 2}, {0, 1, 1, 2}};
}

/// Row `y` of the pass starting at column x0 with step dx, its samples packed at the depth
/// (the leftmost in the high bits), padded to whole bytes.
std::vector<std::uint8_t> pack_row(const PngSpec& spec, int y, int x0, int dx) {
  const int spp = samples_per_pixel(spec.colour_type);
  std::vector<std::uint8_t> bytes;
  int bits = 0;
  for (int x = x0; x < spec.width; x += dx) {
    for (int k = 0; k < spp; ++k) {
      const int v = spec.samples[(static_cast<std::size_t>(y) * spec.width + x) * spp + k];
      if (bits % 8 == 0) bytes.push_back(0);
      bytes.back() |= static_cast<std::uint8_t>(v << (8 - spec.depth - bits % 8));
      bits += spec.depth;
    }
  }
  return bytes;
}

int paeth_predictor(int a, int b, int c) {
  const int p = a + b - c, pa = std::abs(p - a), pb = std::abs(p - b), pc = std::abs(p - c);
  return (pa <= pb && pa <= pc) ? a : pb <= pc ? b : c;
}

/// The filtered bytes of `row` (filter type `type`) below the unfiltered row `above`.
std::string filter_row(int type, const std::vector<std::uint8_t>& row,
                       const std::vector<std::uint8_t>& above, std::size_t pixel_bytes) {
  std::string out(1, static_cast<char>(type));
  for (std::size_t i = 0; i < row.size(); ++i) {
    const int a = i >= pixel_bytes ? row[i - pixel_bytes] : 0, b = above[i],
              c = i >= pixel_bytes ? above[i - pixel_bytes] : 0;
    const int predicted = type == 1   ? a
                          : type == 2 ? b
                          : type == 3 ? (a + b) / 2
                          : type == 4 ? paeth_predictor(a, b, c)
                                      : 0;
    out += static_cast<char>(row[i] - predicted);
  }
  return out;
}

/// The filtered image data, pass by pass.
std::string filtered_data(const PngSpec& spec) {
  const std::size_t pixel_bytes = std::max(1, spec.depth * samples_per_pixel(spec.colour_type) / 8);
  std::string data;
  int pass_index = 0;
  for (const auto& [x0, y0, dx, dy] : passes(spec.interlaced)) {
    ++pass_index;
    if (x0 >= spec.width || y0 >= spec.height) continue;  // an empty pass has no rows
    std::vector<std::uint8_t> above;
    for (int y = y0, r = 0; y < spec.height; y += dy, ++r) {
      const std::vector<std::uint8_t> row = pack_row(spec, y, x0, dx);
      if (above.empty()) above.assign(row.size(), 0);
      const int type = spec.filter >= 0 ? spec.filter : (r + pass_index) % 5;
      data += filter_row(type, row, above, pixel_bytes);
      above = row;
    }
  }
  return data;
}

/// The PNG file of `spec` holding the filtered image data `raw`, compressed and split over
/// two IDAT chunks.
std::string png_file(const PngSpec& spec, const std::string& raw) {
  uLongf size = compressBound(static_cast<uLong>(raw.size()));
  std::string z(size, '\0');
  EXPECT_EQ(compress2(reinterpret_cast<Bytef*>(z.data()), &size,
                      reinterpret_cast<const Bytef*>(raw.data()), raw.size(), 9),
            Z_OK);
  z.resize(size);
  std::string ihdr = test::be32(spec.width) + test::be32(spec.height);
  for (int field : {spec.depth, spec.colour_type, 0, 0, spec.interlaced ? 1 : 0})
    ihdr += static_cast<char>(field);
  std::string png = "\x89PNG\r\n\x1a\n" + test::png_chunk("IHDR", ihdr);
  if (!spec.palette.empty()) png += test::png_chunk("PLTE", spec.palette);
  if (spec.transparency) png += test::png_chunk("tRNS", *spec.transparency);
  png += test::png_chunk("IDAT", z.substr(0, z.size() / 2));
  png += test::png_chunk("IDAT", z.substr(z.size() / 2));
  return png + test::png_chunk("IEND", "");
}

std::string encode_png(const PngSpec& spec) {
  return png_file(spec, filtered_data(spec));
}

/// `count` random bytes (palette and tRNS contents).
std::string random_bytes(std::size_t count, std::mt19937& rng) {
  std::string bytes;
  for (std::size_t k = 0; k < count; ++k) bytes += static_cast<char>(rng() % 256);
  return bytes;
}

/// A spec of random samples (below 2^depth) of the given size and format.
PngSpec random_spec(int width, int height, int depth, int colour_type, bool interlaced,
                    std::mt19937& rng) {
  PngSpec spec{width, height, depth, colour_type, interlaced, {}, "", std::nullopt, -1};
  const std::size_t count =
      static_cast<std::size_t>(width) * height * samples_per_pixel(colour_type);
  for (std::size_t k = 0; k < count; ++k) spec.samples.push_back(rng() % (1u << depth));
  if (colour_type == 3) spec.palette = random_bytes(3u << depth, rng);
  return spec;
}

std::string describe(const PngSpec& s) {
  return "PNG " + std::to_string(s.width) + " x " + std::to_string(s.height) + ", colour type " +
         std::to_string(s.colour_type) + ", depth " + std::to_string(s.depth) +
         (s.interlaced ? ", interlaced" : "") + ", filter " + std::to_string(s.filter) +
         (s.transparency ? ", tRNS" : "");
}

/// gridloc's decoding of `png`.
Image decode(const std::string& png, const std::string& name) {
  return decode_png(png, read_png_header(png, name), name);
}

/// Sample k of pixel (r, c) of OpenCV's decoding, in gridloc's R, G, B, alpha order.
int opencv_sample(const cv::Mat& img, int r, int c, int k) {
  const int channel = img.channels() >= 3 && k < 3 ? 2 - k : k;  // OpenCV keeps B, G, R
  return img.ptr<std::uint8_t>(r)[c * img.channels() + channel];
}

/// Expects gridloc's decoding of `png` to equal cv::imdecode(IMREAD_UNCHANGED)'s.
void expect_same_as_opencv(const std::string& png, const std::string& what) {
  const Image mine = decode(png, "m.png");
  const cv::Mat theirs =
      cv::imdecode(std::vector<std::uint8_t>(png.begin(), png.end()), cv::IMREAD_UNCHANGED);
  ASSERT_FALSE(theirs.empty()) << what;
  ASSERT_EQ(theirs.depth(), CV_8U) << what;
  ASSERT_EQ(mine.width, theirs.cols) << what;
  ASSERT_EQ(mine.height, theirs.rows) << what;
  ASSERT_EQ(mine.channels, theirs.channels()) << what;
  ASSERT_EQ(mine.pixels.size(), theirs.total() * theirs.channels()) << what;
  for (int r = 0; r < mine.height; ++r) {
    for (int c = 0; c < mine.width; ++c) {
      for (int k = 0; k < mine.channels; ++k) {
        ASSERT_EQ(mine.row(r)[c * mine.channels + k], opencv_sample(theirs, r, c, k))
            << what << ": pixel (row " << r << ", column " << c << "), channel " << k;
      }
    }
  }
}

TEST(PngImage, GreyAtEveryBitDepthMatchesOpenCv) {
  std::mt19937 rng(1);
  for (int depth : {1, 2, 4, 8}) {
    for (bool interlaced : {false, true}) {
      for (const auto& [w, h] : {std::pair{1, 1}, {13, 7}, {33, 17}, {2, 9}}) {
        const PngSpec spec = random_spec(w, h, depth, 0, interlaced, rng);
        expect_same_as_opencv(encode_png(spec), describe(spec));
      }
    }
  }
}

TEST(PngImage, PaletteAtEveryBitDepthMatchesOpenCv) {
  std::mt19937 rng(2);
  for (int depth : {1, 2, 4, 8}) {
    for (bool interlaced : {false, true}) {
      PngSpec spec = random_spec(21, 11, depth, 3, interlaced, rng);
      expect_same_as_opencv(encode_png(spec), describe(spec));
      // tRNS for the first half of the palette: the rest stays opaque.
      spec.transparency = random_bytes((1u << depth) / 2 + 1, rng);
      expect_same_as_opencv(encode_png(spec), describe(spec));
    }
  }
}

TEST(PngImage, ColourAndAlphaImagesMatchOpenCv) {
  std::mt19937 rng(3);
  for (int colour_type : {2, 4, 6}) {
    for (bool interlaced : {false, true}) {
      for (const auto& [w, h] : {std::pair{1, 1}, {19, 10}, {64, 3}}) {
        const PngSpec spec = random_spec(w, h, 8, colour_type, interlaced, rng);
        expect_same_as_opencv(encode_png(spec), describe(spec));
      }
    }
  }
}

TEST(PngImage, EveryRowFilterMatchesOpenCv) {
  std::mt19937 rng(4);
  // The formats give 1, 2, 3 and 4 bytes per pixel and a packed depth (1 byte, the least).
  for (const auto& [depth, colour_type] : {std::pair{8, 0}, {8, 4}, {8, 2}, {8, 6}, {2, 0}}) {
    for (int filter = 0; filter <= 4; ++filter) {
      for (bool interlaced : {false, true}) {
        PngSpec spec = random_spec(17, 12, depth, colour_type, interlaced, rng);
        spec.filter = filter;
        expect_same_as_opencv(encode_png(spec), describe(spec));
      }
    }
  }
}

TEST(PngImage, TransparencyMatchesOpenCv) {
  std::mt19937 rng(5);
  PngSpec rgb = random_spec(15, 9, 8, 2, false, rng);
  for (std::size_t pixel = 0; pixel < 135; pixel += 7) {  // every 7th pixel the key colour
    for (int k = 0; k < 3; ++k) rgb.samples[pixel * 3 + k] = 10 + k;
  }
  rgb.transparency = std::string("\0\x0a\0\x0b\0\x0c", 6);
  expect_same_as_opencv(encode_png(rgb), describe(rgb) + ", key colour");
  const Image keyed = decode(encode_png(rgb), "k.png");
  ASSERT_EQ(keyed.channels, 4);
  EXPECT_EQ(keyed.pixels[3], 0);  // pixel 0 has the key colour: transparent
  EXPECT_EQ(keyed.pixels[7], 255);
  // A key sample above 255 in an 8-bit image (libpng compares its low byte).
  rgb.transparency = std::string("\x01\x0a\0\x0b\x02\x0c", 6);
  expect_same_as_opencv(encode_png(rgb), describe(rgb) + ", key above 255");

  for (int depth : {4, 8}) {  // a grey image's tRNS is ignored: one channel
    PngSpec grey = random_spec(10, 5, depth, 0, false, rng);
    grey.transparency = std::string("\0\x03", 2);
    expect_same_as_opencv(encode_png(grey), describe(grey));
    EXPECT_EQ(decode(encode_png(grey), "g.png").channels, 1);
  }
  PngSpec palette = random_spec(10, 5, 4, 3, true, rng);
  palette.transparency = "";  // an empty palette tRNS: no alpha channel
  expect_same_as_opencv(encode_png(palette), describe(palette) + ", empty tRNS");
  EXPECT_EQ(decode(encode_png(palette), "p.png").channels, 3);
}

TEST(PngImage, PaletteIndicesPastThePaletteMatchOpenCv) {
  std::mt19937 rng(6);
  PngSpec spec = random_spec(16, 16, 8, 3, false, rng);
  spec.palette = random_bytes(3 * 10, rng);  // 10 entries for indices up to 255
  expect_same_as_opencv(encode_png(spec), describe(spec) + ", 10 palette entries");
  spec.transparency = random_bytes(5, rng);
  expect_same_as_opencv(encode_png(spec), describe(spec) + ", 10 palette entries");
}

/// Random pixels of `channels` channels, and a smooth gradient (which libpng's encoder
/// filters with Sub, Up, Average or Paeth rather than None).
std::vector<cv::Mat> opencv_images(int channels, std::mt19937& rng) {
  cv::Mat noise(23, 37, CV_8UC(channels)), gradient(40, 50, CV_8UC(channels));
  for (std::size_t k = 0; k < noise.total() * channels; ++k) noise.data[k] = rng() % 256;
  for (int r = 0; r < gradient.rows; ++r) {
    for (int c = 0; c < gradient.cols * channels; ++c)
      gradient.ptr<std::uint8_t>(r)[c] = static_cast<std::uint8_t>(3 * r + c + (c % channels) * 40);
  }
  return {noise, gradient};
}

TEST(PngImage, OpenCvEncodedImagesDecodeToTheirPixels) {
  std::mt19937 rng(7);
  for (int channels : {1, 3, 4}) {
    for (const cv::Mat& source : opencv_images(channels, rng)) {
      for (int level : {0, 3, 9}) {
        std::vector<std::uint8_t> encoded;
        ASSERT_TRUE(cv::imencode(".png", source, encoded, {cv::IMWRITE_PNG_COMPRESSION, level}));
        const std::string png(encoded.begin(), encoded.end());
        const std::string what =
            std::to_string(channels) + " channels, level " + std::to_string(level);
        expect_same_as_opencv(png, what);
        const Image mine = decode(png, "m.png");
        ASSERT_EQ(mine.channels, channels) << what;
        for (int r = 0; r < source.rows; ++r) {
          for (int c = 0; c < source.cols; ++c) {
            for (int k = 0; k < channels; ++k) {
              ASSERT_EQ(mine.row(r)[c * channels + k], opencv_sample(source, r, c, k)) << what;
            }
          }
        }
      }
    }
  }
}

TEST(PngImage, EightBitSamplesDecodeAsWritten) {
  // Without OpenCV: 8-bit grey, grey + alpha (expanded to grey, grey, grey, alpha), RGB and
  // RGBA give back the samples written, whatever the filters and the interlacing.
  std::mt19937 rng(8);
  for (int colour_type : {0, 2, 4, 6}) {
    for (bool interlaced : {false, true}) {
      const PngSpec spec = random_spec(29, 13, 8, colour_type, interlaced, rng);
      const Image mine = decode(encode_png(spec), "m.png");
      std::vector<std::uint8_t> want;
      for (std::size_t k = 0; k < spec.samples.size(); ++k) {
        const auto v = static_cast<std::uint8_t>(spec.samples[k]);
        if (colour_type == 4 && k % 2 == 0) want.insert(want.end(), {v, v});
        want.push_back(v);
      }
      EXPECT_EQ(mine.pixels, want) << describe(spec);
    }
  }
}

TEST(PngImage, LowBitDepthsScaleToTheFullRange) {
  // Grey 1, 2 and 4 bits: 0 is black and the largest sample white, as libpng expands them.
  for (const auto& [depth, samples, want] :
       {std::tuple{1, std::vector<int>{0, 1}, std::vector<std::uint8_t>{0, 255}},
        {2, {0, 1, 2, 3}, {0, 85, 170, 255}},
        {4, {0, 1, 7, 15}, {0, 17, 119, 255}}}) {
    const PngSpec spec{
        static_cast<int>(samples.size()), 1, depth, 0, false, samples, "", std::nullopt, 0};
    EXPECT_EQ(decode(encode_png(spec), "m.png").pixels, want) << describe(spec);
  }
}

TEST(PngImage, InterlacedDataOfTheWrongLengthIsRefused) {
  std::mt19937 rng(9);
  const PngSpec spec = random_spec(11, 6, 8, 2, true, rng);
  const std::string raw = filtered_data(spec);
  testing::internal::CaptureStderr();
  expect_error([&] { decode(png_file(spec, raw.substr(0, raw.size() - 1)), "short.png"); },
               {"short.png", "truncated"});
  expect_error([&] { decode(png_file(spec, raw + '\0'), "long.png"); },
               {"long.png", "more image data"});
  EXPECT_EQ(testing::internal::GetCapturedStderr(), "");
}

}  // namespace
}  // namespace gridloc
