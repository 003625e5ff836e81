#include <sys/resource.h>
#include <unistd.h>

#include <csignal>

#include <Imath/half.h>
#include <OpenEXR/ImfChannelList.h>
#include <OpenEXR/ImfFrameBuffer.h>
#include <OpenEXR/ImfHeader.h>
#include <OpenEXR/ImfOutputFile.h>
#include <fmt/format.h>
#include <gtest/gtest.h>
#include <stb/stb_image.h>

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstring>
#include <fstream>
#include <initializer_list>
#include <limits>
#include <string>
#include <utility>
#include <vector>

#include "skylight/core/error.h"
#include "skylight/io/image.h"
#include "support/scratch_dir.h"

namespace skylight::io {
namespace {

namespace fs = std::filesystem;
using testing_support::ScratchDir;
using testing_support::slurp;

// A fresh directory per test, removed afterwards.
void spit(const fs::path& path, const std::string& bytes) {
  std::ofstream out(path, std::ios::binary);
  out << bytes;
}

// Exact comparison of float bit patterns (distinguishes -0 from 0, keeps NaN payloads).
void expect_bit_identical(const ImageF& a, const ImageF& b) {
  ASSERT_EQ(a.width, b.width);
  ASSERT_EQ(a.height, b.height);
  ASSERT_EQ(a.channels, b.channels);
  ASSERT_EQ(a.data.size(), b.data.size());
  for (size_t i = 0; i < a.data.size(); ++i)
    EXPECT_EQ(std::bit_cast<std::uint32_t>(a.data[i]), std::bit_cast<std::uint32_t>(b.data[i]))
        << "value " << i << ": " << a.data[i] << " vs " << b.data[i];
}

// Values that trip up lossy or careless codecs: negatives, huge and tiny magnitudes, -0, inf, NaN.
ImageF distinctive_rgb() {
  const float values[] = {0.0f,     -0.0f,
                          1.0f,     -2.5f,
                          1e6f,     1e-6f,
                          3.25f,    -1e-6f,
                          65504.0f, 1.0e30f,
                          7.0e-39f, 0.1f,
                          42.0f,    0.5f,
                          -1e6f,    std::numeric_limits<float>::infinity(),
                          123.456f, std::numeric_limits<float>::quiet_NaN()};
  ImageF image(3, 2, 3);
  for (size_t i = 0; i < image.data.size(); ++i) image.data[i] = values[i % std::size(values)];
  return image;
}

ImageF ramp_grey(int w, int h) {
  ImageF image(w, h, 1);
  for (size_t i = 0; i < image.data.size(); ++i)
    image.data[i] = 0.001f * static_cast<float>(i * i) - 0.5f;
  return image;
}

// Writes `image` in the format of the extension; .png gets 8-bit data derived from the floats
// (PNG holds 8-bit data only; incompressible floats stay incompressible) so that every format's
// writer goes through the same checks.
void write_any(const fs::path& path, const ImageF& image, const Metadata& meta = {}) {
  if (format_from_path(path) != ImageFormat::png) return write_image(path, image, meta);
  Image8 img(image.width, image.height);
  for (std::size_t i = 0; i < img.data.size(); ++i) {
    const float v = image.data[(i / 3) * static_cast<std::size_t>(image.channels) +
                               (image.channels == 3 ? i % 3 : 0)];
    img.data[i] = static_cast<std::uint8_t>(static_cast<unsigned>(std::abs(v) * 977.0f) & 0xffu);
  }
  write_png(path, img, meta);
}

bool has(const Metadata& meta, const std::string& key, const std::string& value) {
  return std::find(meta.begin(), meta.end(), std::pair(key, value)) != meta.end();
}

// ---- EXR ---------------------------------------------------------------------------------------

TEST(ImageIo, ExrRgbRoundTripIsBitIdenticalWithMetadata) {
  ScratchDir dir;
  const ImageF image = distinctive_rgb();
  const Metadata meta = {{"skylight:model", "Perez 1993"}, {"comment", "sky \xc2\xb0 line"}};
  write_image(dir / "sky.exr", image, meta);
  expect_bit_identical(read_image(dir / "sky.exr", {.allow_non_finite = true}), image);
  const Metadata back = read_exr_metadata(dir / "sky.exr");
  EXPECT_TRUE(has(back, "skylight:model", "Perez 1993"));
  EXPECT_TRUE(has(back, "comment", "sky \xc2\xb0 line"));
}

TEST(ImageIo, ExrLuminanceRoundTripIsBitIdentical) {
  ScratchDir dir;
  const ImageF image = ramp_grey(5, 4);
  write_image(dir / "y.EXR", image);  // extension case does not matter
  const ImageF back = read_image(dir / "y.EXR");
  EXPECT_EQ(back.channels, 1);
  expect_bit_identical(back, image);
  EXPECT_TRUE(read_exr_metadata(dir / "y.EXR").empty());
}

// An EXR as another program writes it, through OpenEXR itself: one channel of pixel type `type`
// per (name, values), each holding the data window's pixels in row order.
void write_foreign_exr(const fs::path& path, const Imath::Box2i& window, Imf::PixelType type,
                       std::initializer_list<std::pair<const char*, const void*>> channels) {
  Imf::Header header(window, window);
  Imf::FrameBuffer frame;
  for (const auto& [name, values] : channels) {
    header.channels().insert(name, Imf::Channel(type));
    frame.insert(name, Imf::Slice::Make(type, values, window));
  }
  Imf::OutputFile out(path.c_str(), header);
  out.setFrameBuffer(frame);
  out.writePixels(window.max.y - window.min.y + 1);
}

TEST(ImageIo, ExrHalfChannelsAndOffsetDataWindowAreRead) {
  ScratchDir dir;
  const fs::path path = dir / "half.exr";
  // A file from elsewhere: HALF luminance, data window starting at (5, 7).
  const Imath::Box2i window({5, 7}, {7, 8});  // 3 x 2 pixels
  const std::vector<half> values = {half(0.5f),  half(2.0f), half(1024.0f),
                                    half(-3.0f), half(0.0f), half(0.25f)};
  write_foreign_exr(path, window, Imf::HALF, {{"Y", values.data()}});
  const ImageF image = read_image(path);
  ASSERT_EQ(image.width, 3);
  ASSERT_EQ(image.height, 2);
  ASSERT_EQ(image.channels, 1);
  for (size_t i = 0; i < values.size(); ++i) EXPECT_EQ(image.data[i], float(values[i])) << i;
}

// ---- one-channel images (depth maps) ------------------------------------------------------------

// A grey 16-bit PNG with stored (uncompressed) deflate blocks, written by hand: stb cannot write
// 16-bit PNGs.
std::string png16(int w, int h, const std::vector<std::uint16_t>& values) {
  const auto crc = [](const std::string& bytes) {
    std::uint32_t c = 0xffffffffu;
    for (unsigned char b : bytes) {
      c ^= b;
      for (int k = 0; k < 8; ++k) c = (c >> 1) ^ (0xedb88320u & (0u - (c & 1u)));
    }
    return c ^ 0xffffffffu;
  };
  const auto be32 = [](std::uint32_t v) {
    return std::string{static_cast<char>(v >> 24), static_cast<char>(v >> 16),
                       static_cast<char>(v >> 8), static_cast<char>(v)};
  };
  const auto chunk = [&](const std::string& type, const std::string& data) {
    return be32(static_cast<std::uint32_t>(data.size())) + type + data + be32(crc(type + data));
  };
  std::string raw;
  for (int y = 0; y < h; ++y) {
    raw += '\0';  // filter type none
    for (int x = 0; x < w; ++x) {
      const std::uint16_t v = values[static_cast<std::size_t>(y * w + x)];
      raw += static_cast<char>(v >> 8);
      raw += static_cast<char>(v & 0xff);
    }
  }
  std::uint32_t a = 1, b = 0;
  for (unsigned char ch : raw) {
    a = (a + ch) % 65521;
    b = (b + a) % 65521;
  }
  const auto len = static_cast<std::uint16_t>(raw.size());  // one stored block (< 64 KiB)
  std::string z = "\x78\x01";
  z += '\x01';
  z += static_cast<char>(len & 0xff);
  z += static_cast<char>(len >> 8);
  z += static_cast<char>(~len & 0xff);
  z += static_cast<char>((~len >> 8) & 0xff);
  z += raw + be32((b << 16) | a);
  const std::string ihdr = be32(static_cast<std::uint32_t>(w)) +
                           be32(static_cast<std::uint32_t>(h)) +
                           std::string("\x10\x00\x00\x00\x00", 5);
  return std::string("\x89PNG\r\n\x1a\n", 8) + chunk("IHDR", ihdr) + chunk("IDAT", z) +
         chunk("IEND", "");
}

TEST(ImageIo, ScalarImagesFromExrZPfmAndSixteenBitPng) {
  ScratchDir dir;
  // EXR: Z is preferred over Y and R.
  const fs::path exr = dir / "depth.exr";
  const std::vector<float> r(6, 1.0f), y(6, 2.0f), z = {10.0f, 20.0f, 30.0f, 40.0f, 50.0f, 60.0f};
  write_foreign_exr(exr, Imath::Box2i({0, 0}, {2, 1}), Imf::FLOAT,
                    {{"R", r.data()}, {"Y", y.data()}, {"Z", z.data()}});
  const ImageF from_exr = read_scalar_image(exr);
  ASSERT_EQ(from_exr.channels, 1);
  EXPECT_EQ(from_exr.data, z);
  // An RGB EXR gives its R channel; an RGB PFM its first channel.
  ImageF rgb(2, 1, 3);
  rgb.data = {1.0f, 2.0f, 3.0f, 4.0f, 5.0f, 6.0f};
  write_image(dir / "rgb.exr", rgb);
  write_image(dir / "rgb.pfm", rgb);
  EXPECT_EQ(read_scalar_image(dir / "rgb.exr").data, (std::vector<float>{1.0f, 4.0f}));
  EXPECT_EQ(read_scalar_image(dir / "rgb.pfm").data, (std::vector<float>{1.0f, 4.0f}));
  // 16-bit PNG: v / 65535, row 0 on top.
  spit(dir / "d.png", png16(3, 2, {0, 65535, 32768, 1, 2, 3}));
  const ImageF from_png = read_scalar_image(dir / "d.png");
  ASSERT_EQ(from_png.width, 3);
  ASSERT_EQ(from_png.height, 2);
  EXPECT_EQ(from_png.data[0], 0.0f);
  EXPECT_EQ(from_png.data[1], 1.0f);
  EXPECT_EQ(from_png.data[2], 32768.0f / 65535.0f);
  EXPECT_EQ(from_png.data[5], 3.0f / 65535.0f);
  // 8-bit PNG and HDR are refused with the path named.
  write_png(dir / "eight.png", Image8(2, 2));
  EXPECT_THROW(read_scalar_image(dir / "eight.png"), InvalidArgument);
  write_image(dir / "x.hdr", rgb);
  EXPECT_THROW(read_scalar_image(dir / "x.hdr"), InvalidArgument);
}

// ---- PFM ---------------------------------------------------------------------------------------

TEST(ImageIo, PfmRoundTripIsBitIdenticalAndKeepsRowOrder) {
  ScratchDir dir;
  const ImageF image = distinctive_rgb();
  write_image(dir / "a.pfm", image, {{"ignored", "PFM has no metadata"}});
  expect_bit_identical(read_image(dir / "a.pfm", {.allow_non_finite = true}), image);

  // On disk: little-endian header, then the BOTTOM row first.
  const std::string bytes = slurp(dir / "a.pfm");
  const std::string header = "PF\n3 2\n-1.0\n";
  ASSERT_EQ(bytes.substr(0, header.size()), header);
  ASSERT_EQ(bytes.size(), header.size() + image.data.size() * 4);
  float first = 0.0f;
  std::memcpy(&first, bytes.data() + header.size(), 4);
  EXPECT_EQ(std::bit_cast<std::uint32_t>(first),
            std::bit_cast<std::uint32_t>(image.pixel(0, 1)[0]));

  const ImageF grey = ramp_grey(4, 3);
  write_image(dir / "g.pfm", grey);
  EXPECT_EQ(slurp(dir / "g.pfm").substr(0, 3), "Pf\n");
  expect_bit_identical(read_image(dir / "g.pfm"), grey);
}

TEST(ImageIo, PfmReadsBigEndianFiles) {
  ScratchDir dir;
  // Pf, 2 x 2, positive scale = big-endian; file rows bottom-up: (3, 4) then (1, 2).
  std::string bytes = "Pf\n2 2\n1.0\n";
  for (float v : {3.0f, 4.0f, 1.0f, 2.0f}) {
    const auto bits = std::bit_cast<std::uint32_t>(v);
    for (int shift = 24; shift >= 0; shift -= 8) bytes += static_cast<char>((bits >> shift) & 0xff);
  }
  spit(dir / "be.pfm", bytes);
  const ImageF image = read_image(dir / "be.pfm");
  ASSERT_EQ(image.channels, 1);
  EXPECT_EQ(image.data, (std::vector<float>{1.0f, 2.0f, 3.0f, 4.0f}));
}

// ---- Radiance HDR ------------------------------------------------------------------------------

// RGBE keeps an 8-bit mantissa per channel under the pixel's shared exponent; with rounding the
// error of any channel is at most half a step, <= max(R, G, B) / 255.
constexpr double kRgbeRelativeTolerance = 1.0 / 255.0;

TEST(ImageIo, HdrRoundTripWithinRgbePrecision) {
  ScratchDir dir;
  ImageF image(16, 3, 3);  // >= 8 wide: exercises the reader's run-length detection
  for (int y = 0; y < image.height; ++y)
    for (int x = 0; x < image.width; ++x) {
      float* p = image.pixel(x, y);
      const float base = std::pow(10.0f, static_cast<float>(x) - 6.0f);  // 1e-6 ... 1e9
      p[0] = base * (1.0f + 0.37f * static_cast<float>(y));
      p[1] = base * 0.123f;
      p[2] = (x % 3 == 0) ? -base : base * 0.9f;  // negatives must come back as 0
    }
  const Metadata meta = {{"SKYLIGHT_MODEL", "CIE 15"}, {"note", "two\nlines"}};
  write_image(dir / "sky.hdr", image, meta);

  const std::string bytes = slurp(dir / "sky.hdr");
  EXPECT_EQ(bytes.rfind("#?RADIANCE\n", 0), 0u);
  EXPECT_NE(bytes.find("\nSKYLIGHT_MODEL=CIE 15\n"), std::string::npos);
  EXPECT_NE(bytes.find("\nnote=two lines\n"), std::string::npos);

  const ImageF back = read_image(dir / "sky.hdr");
  ASSERT_EQ(back.width, image.width);
  ASSERT_EQ(back.height, image.height);
  ASSERT_EQ(back.channels, 3);
  for (int y = 0; y < image.height; ++y)
    for (int x = 0; x < image.width; ++x) {
      const float* p = image.pixel(x, y);
      const float* q = back.pixel(x, y);
      const double top = std::max({p[0], p[1], p[2], 0.0f});
      for (int c = 0; c < 3; ++c) {
        const double expected = std::max(p[c], 0.0f);
        EXPECT_NEAR(q[c], expected, top * kRgbeRelativeTolerance) << x << "," << y << " c" << c;
        if (p[c] < 0.0f) {
          EXPECT_EQ(q[c], 0.0f);
        }
      }
    }
}

TEST(ImageIo, HdrWritesGreyAsRgbAndZeroesNonFinite) {
  ScratchDir dir;
  ImageF grey(4, 1, 1);
  grey.data = {0.0f, 5.0f, std::numeric_limits<float>::infinity(),
               std::numeric_limits<float>::quiet_NaN()};
  write_image(dir / "g.hdr", grey);
  const ImageF back = read_image(dir / "g.hdr");
  ASSERT_EQ(back.channels, 3);
  for (int c = 0; c < 3; ++c) {
    EXPECT_EQ(back.pixel(0, 0)[c], 0.0f);
    EXPECT_EQ(back.pixel(1, 0)[c], 5.0f);  // 5 = 160/256 * 2^3: exact in RGBE
    EXPECT_EQ(back.pixel(2, 0)[c], 0.0f);
    EXPECT_EQ(back.pixel(3, 0)[c], 0.0f);
  }
}

// ---- PNG ---------------------------------------------------------------------------------------

// An RGB image of bytes (i * step) mod 256 in memory order.
Image8 byte_pattern(int w, int h, std::size_t step) {
  Image8 img(w, h);
  for (std::size_t i = 0; i < img.data.size(); ++i)
    img.data[i] = static_cast<std::uint8_t>(i * step % 256);
  return img;
}

TEST(ImageIo, PngIsWrittenWithTextChunks) {
  ScratchDir dir;
  Image8 img(6, 5);
  img.pixel(1, 0)[0] = 200;
  write_png(dir / "p.png", img, {{"Software", "skylight"}, {"Title", "Sky \xc3\xa9"}});
  const std::string bytes = slurp(dir / "p.png");
  EXPECT_NE(bytes.find(std::string("tEXtSoftware\0skylight", 21)), std::string::npos);
  EXPECT_NE(bytes.find(std::string("iTXtTitle\0\0\0\0\0Sky \xc3\xa9", 20)), std::string::npos);
  int w = 0, h = 0, n = 0;  // stb_image checks the chunk CRCs
  unsigned char* pixels = stbi_load((dir / "p.png").c_str(), &w, &h, &n, 3);
  ASSERT_NE(pixels, nullptr) << stbi_failure_reason();
  EXPECT_EQ(w, 6);
  EXPECT_EQ(h, 5);
  EXPECT_EQ(pixels[0], 0);
  EXPECT_EQ(pixels[3], 200);
  stbi_image_free(pixels);
}

TEST(ImageIo, PngRoundTripIsExactAndMissingPngIsAnIoError) {
  ScratchDir dir;
  const Image8 img = byte_pattern(7, 3, 37);
  write_png(dir / "m.png", img);
  const Image8 back = read_png(dir / "m.png");
  EXPECT_EQ(back.width, 7);
  EXPECT_EQ(back.height, 3);
  EXPECT_EQ(back.data, img.data);
  EXPECT_THROW(read_png(dir / "missing.png"), IoError);
}

// A PNG header declaring more pixels than the limit is refused before stb allocates the decoded
// image (stb itself refuses only images over 2^30 bytes, so a 45-byte file declaring 10000 x 10000
// RGB would otherwise cost 300 MB before the missing data is noticed); stb does not check chunk
// CRCs, so zero CRCs are enough here.
TEST(ImageIo, PngOverThePixelLimitIsRefusedFromItsHeader) {
  ScratchDir dir;
  const auto be32 = [](std::uint32_t v) {
    return std::string{static_cast<char>(v >> 24), static_cast<char>(v >> 16),
                       static_cast<char>(v >> 8), static_cast<char>(v)};
  };
  std::string png = "\x89PNG\r\n\x1a\n";
  png += be32(13) + "IHDR" + be32(10000) + be32(10000);
  png += std::string{'\x08', '\x02', '\0', '\0', '\0'} + be32(0);  // 8-bit RGB, CRC
  spit(dir / "huge.png", png);
  try {
    read_png(dir / "huge.png", {.max_pixels = std::int64_t{1} << 20});
    ADD_FAILURE() << "a 10000 x 10000 PNG header was accepted";
  } catch (const InvalidArgument& e) {
    EXPECT_NE(std::string(e.what()).find("10000x10000 pixels exceed the limit of 1048576"),
              std::string::npos)
        << e.what();
  }
  Image8 six(3, 2);
  write_png(dir / "six.png", six);
  EXPECT_THROW(read_png(dir / "six.png", {.max_pixels = 5}), InvalidArgument);
  EXPECT_EQ(read_png(dir / "six.png", {.max_pixels = 6}).data.size(), 18u);
}

// An empty IDAT chunk (legal PNG, no data) before the first data chunk made stb call
// memcpy(nullptr, src, 0), undefined behaviour that the sanitizer pass stops on (found by the
// image_png fuzz target): read_png drops empty IDATs, and the pixels are those of the plain file.
TEST(ImageIo, PngWithAnEmptyIdatChunkReadsTheSamePixels) {
  ScratchDir dir;
  const Image8 img = byte_pattern(3, 2, 41);
  write_png(dir / "plain.png", img);
  std::string bytes = slurp(dir / "plain.png");
  const std::size_t idat = bytes.find("IDAT");
  ASSERT_NE(idat, std::string::npos);
  bytes.insert(idat - 4, std::string("\0\0\0\0IDAT\0\0\0\0", 12));
  spit(dir / "empty_idat.png", bytes);
  EXPECT_EQ(read_png(dir / "empty_idat.png").data, img.data);
  // Anything without the PNG signature is refused before stb's other decoders see it (its PNM
  // header parser overflows an int on long digit strings: found by the same target).
  spit(dir / "pnm.png", "P6666666666666666666666666666\n");
  EXPECT_THROW(read_png(dir / "pnm.png"), IoError);
}

// A small PNG as write_png writes it, and the offset of its IEND chunk (its length field).
struct PlainPng {
  Image8 image = byte_pattern(3, 2, 41);
  std::string bytes;
  std::size_t iend = 0;
};
PlainPng plain_png(const ScratchDir& dir) {
  PlainPng png;
  write_png(dir / "plain.png", png.image);
  png.bytes = slurp(dir / "plain.png");
  const std::size_t type = png.bytes.find("IEND");
  EXPECT_NE(type, std::string::npos);
  png.iend = type - 4;
  return png;
}

// read_png refuses `bytes` with an IoError whose message contains `fragment`.
void expect_png_refused(const ScratchDir& dir, const std::string& bytes,
                        const std::string& fragment) {
  spit(dir / "bad.png", bytes);
  try {
    (void)read_png(dir / "bad.png");
    ADD_FAILURE() << "read a PNG that should be refused with '" << fragment << "'";
  } catch (const IoError& e) {
    EXPECT_NE(std::string(e.what()).find(fragment), std::string::npos) << e.what();
  }
}

// A chunk that claims more bytes than the file has is refused before stb grows its buffer to the
// claimed length (a few bytes once asked for 2 GiB: the image_png fuzz target, corpus file
// oom_idat_length_*); bytes after IEND are not read.
TEST(ImageIo, PngChunkLongerThanTheFileIsRefused) {
  ScratchDir dir;
  const PlainPng png = plain_png(dir);
  expect_png_refused(dir,
                     png.bytes.substr(0, png.iend) + std::string("\x7f\xff\xff\xf0IDAT", 8) +
                         "xB`\x82 and some more",
                     "truncated or corrupt PNG: the chunk at byte");
  spit(dir / "trailing.png", png.bytes + std::string("\xff\xff\xff\xffjunk", 8));
  EXPECT_EQ(read_png(dir / "trailing.png").data, png.image.data);
}

// A file cut inside a chunk, before IEND, is refused by name: stb would read the partial chunk's
// header (an empty IDAT's in the image_png fuzz target's find, corpus file cut_empty_idat_*).
TEST(ImageIo, PngCutInsideAChunkIsRefused) {
  ScratchDir dir;
  const PlainPng png = plain_png(dir);
  for (const std::size_t cut : {png.iend + 1, png.iend + 8, png.iend + 11}) {
    SCOPED_TRACE(cut);
    expect_png_refused(dir, png.bytes.substr(0, cut), "truncated PNG: the");
  }
  spit(dir / "cut_empty_idat.png",
       png.bytes.substr(0, png.iend) + std::string("\0\0\0\0IDAT\x82", 9));
  EXPECT_THROW((void)read_png(dir / "cut_empty_idat.png"), IoError);
}

TEST(ImageIo, FloatImageToPngIsRefused) {
  ScratchDir dir;
  EXPECT_THROW(write_image(dir / "p.png", ramp_grey(2, 2)), InvalidArgument);
  EXPECT_TRUE(dir.entries().empty());
}

// ---- atomicity and errors ----------------------------------------------------------------------

TEST(ImageIo, WriteIntoMissingDirectoryThrowsAndCreatesNothing) {
  ScratchDir dir;
  for (const char* name : {"x.exr", "x.hdr", "x.pfm", "x.png"}) {
    const fs::path path = dir / "missing" / name;
    try {
      write_any(path, distinctive_rgb());
      FAIL() << "no exception for " << path;
    } catch (const IoError& e) {
      EXPECT_NE(std::string(e.what()).find(path.string()), std::string::npos) << e.what();
      EXPECT_NE(std::string(e.what()).find("No such file or directory"), std::string::npos);
    }
  }
  EXPECT_TRUE(dir.entries().empty());
}

TEST(ImageIo, SuccessfulWritesLeaveNoTemporaryFiles) {
  ScratchDir dir;
  for (const char* name : {"a.exr", "a.hdr", "a.pfm", "a.png"}) {
    write_any(dir / name, distinctive_rgb(), {{"k", "v"}});
    write_any(dir / name, ramp_grey(3, 3), {{"k", "v"}});  // overwriting works too
  }
  EXPECT_EQ(dir.entries(), (std::vector<std::string>{"a.exr", "a.hdr", "a.pfm", "a.png"}));
  EXPECT_EQ(read_image(dir / "a.pfm").channels, 1);
}

TEST(ImageIo, FailedWriteLeavesExistingTargetUntouched) {
  ScratchDir dir;
  write_image(dir / "a.exr", ramp_grey(2, 2));
  const std::string before = slurp(dir / "a.exr");
  // "channels" collides with a standard EXR attribute.
  EXPECT_THROW(write_image(dir / "a.exr", distinctive_rgb(), {{"channels", "x"}}), InvalidArgument);
  EXPECT_THROW(write_image(dir / "a.exr", distinctive_rgb(), {{"bad key", "x"}}), InvalidArgument);
  EXPECT_EQ(slurp(dir / "a.exr"), before);
  EXPECT_EQ(dir.entries(), (std::vector<std::string>{"a.exr"}));
}

// Lowers the process's file-size limit for its lifetime, so that writes fail part-way (EFBIG).
class FileSizeLimit {
 public:
  explicit FileSizeLimit(rlim_t bytes) {
    previous_signal_ = std::signal(SIGXFSZ, SIG_IGN);  // get EFBIG instead of being killed
    ::getrlimit(RLIMIT_FSIZE, &previous_);
    rlimit lower = previous_;
    lower.rlim_cur = bytes;
    ::setrlimit(RLIMIT_FSIZE, &lower);
  }
  ~FileSizeLimit() {
    ::setrlimit(RLIMIT_FSIZE, &previous_);
    std::signal(SIGXFSZ, previous_signal_);
  }

 private:
  rlimit previous_{};
  void (*previous_signal_)(int) = nullptr;
};

TEST(ImageIo, WriteFailingPartWayLeavesNoTargetAndNoTemporary) {
  ScratchDir dir;
  ImageF noise(64, 64, 3);  // ~48 kB of incompressible values, in every format
  std::uint32_t state = 12345;
  for (float& v : noise.data) {
    state = state * 1664525u + 1013904223u;
    v = static_cast<float>(state >> 8) / 65536.0f;
  }
  for (const char* name : {"n.exr", "n.hdr", "n.pfm", "n.png"}) {
    FileSizeLimit limit(2000);  // bytes
    try {
      write_any(dir / name, noise);
      ADD_FAILURE() << "no exception for " << name;
    } catch (const IoError& e) {
      EXPECT_NE(std::string(e.what()).find((dir / name).string()), std::string::npos) << e.what();
    }
  }
  EXPECT_TRUE(dir.entries().empty());
}

// The IoError for reading `path` must name it.
void expect_read_error(const fs::path& path) {
  try {
    read_image(path);
    ADD_FAILURE() << "no exception for " << path;
  } catch (const IoError& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find(path.string()), std::string::npos) << what;
    EXPECT_EQ(what.find('\n'), std::string::npos) << what;
  }
}

TEST(ImageIo, ReadingMissingOrCorruptFilesThrowsIoErrorNamingThePath) {
  ScratchDir dir;
  for (const char* name : {"none.exr", "none.hdr", "none.pfm"}) expect_read_error(dir / name);
  spit(dir / "garbage.exr", "this is not an OpenEXR file at all, just some bytes\x01\x02\x03");
  expect_read_error(dir / "garbage.exr");
  EXPECT_THROW(read_exr_metadata(dir / "garbage.exr"), IoError);
  spit(dir / "garbage.hdr", "#?NOTRADIANCE\n\n");
  expect_read_error(dir / "garbage.hdr");
  spit(dir / "short.pfm", "PF\n4 4\n-1.0\n0123");  // raster truncated
  expect_read_error(dir / "short.pfm");
  spit(dir / "bad.pfm", "P6\n4 4\n255\n");
  expect_read_error(dir / "bad.pfm");

  // A truncated but otherwise valid EXR.
  write_image(dir / "cut.exr", distinctive_rgb());
  const std::string whole = slurp(dir / "cut.exr");
  spit(dir / "cut.exr", whole.substr(0, whole.size() / 2));
  expect_read_error(dir / "cut.exr");
}

// Found by the fuzz targets image_pfm and image_exr (docs/TESTING.md): NaN and infinite pixels
// were read into the image; by default they are refused, naming the first.
TEST(ImageIo, NonFinitePixelsAreRefusedUnlessAllowed) {
  ScratchDir dir;
  for (const char* name : {"nan.pfm", "nan.exr"}) {
    ImageF image(3, 2, 3);
    image.pixel(2, 1)[1] = std::numeric_limits<float>::quiet_NaN();
    write_image(dir / name, image);
    try {
      read_image(dir / name);
      ADD_FAILURE() << name << " accepted";
    } catch (const InvalidArgument& e) {
      EXPECT_NE(std::string(e.what()).find("pixel (2, 1) channel 1 is nan"), std::string::npos)
          << e.what();
    }
    EXPECT_TRUE(std::isnan(read_image(dir / name, {.allow_non_finite = true}).pixel(2, 1)[1]));
  }
}

// Found by the fuzz targets image_hdr and image_exr (docs/TESTING.md): a header alone made the
// reader allocate the whole declared image (up to 2 GB from a 60-byte .hdr, more for EXR), and an
// HDR header of height 0 gave an empty image. The size is checked before any pixel memory.
TEST(ImageIo, HeadersAskingForTooManyPixelsAreRefusedBeforeReading) {
  ScratchDir dir;
  auto expect_refused = [](const fs::path& path, const ReadImageOptions& options) {
    try {
      read_image(path, options);
      ADD_FAILURE() << path << " accepted";
    } catch (const InvalidArgument& e) {
      EXPECT_NE(std::string(e.what()).find("pixels exceed the limit of"), std::string::npos)
          << e.what();
    }
  };
  spit(dir / "huge.hdr", "#?RADIANCE\nFORMAT=32-bit_rle_rgbe\n\n-Y 16000000 +X 16000000\n");
  expect_refused(dir / "huge.hdr", {});
  spit(dir / "huge.pfm", "PF\n2000000000 2000000000\n-1.0\n");
  expect_refused(dir / "huge.pfm", {});
  // A valid 3 x 2 image against a limit of 5 pixels: the EXR header's data window is enough.
  write_image(dir / "six.exr", ImageF(3, 2, 1));
  write_image(dir / "six.hdr", ImageF(3, 2, 3));
  write_image(dir / "six.pfm", ImageF(3, 2, 3));
  for (const char* name : {"six.exr", "six.hdr", "six.pfm"}) {
    expect_refused(dir / name, {.max_pixels = 5});
    EXPECT_EQ(read_image(dir / name, {.max_pixels = 6}).data.size() % 6, 0u) << name;
  }
  spit(dir / "empty.hdr", "#?RADIANCE\nFORMAT=32-bit_rle_rgbe\n\n-Y 0 +X 8\n");
  expect_read_error(dir / "empty.hdr");
}

// Found by the fuzz target image_hdr (docs/TESTING.md): stb_image loops forever on a zero-length
// run-length dump or run (count 0 or 128), which a truncated run-length file also gives (stb reads
// 0 past the end); a truncated flat file was read with black pixels. All are read errors now.
TEST(ImageIo, HdrZeroLengthRunsAndTruncatedPixelDataAreReadErrors) {
  ScratchDir dir;
  const std::string header = "#?RADIANCE\nFORMAT=32-bit_rle_rgbe\n\n-Y 1 +X 8\n";
  const std::string marker("\x02\x02\x00\x08", 4);
  // R: a run of 8, G: a dump of 8, B and E: runs of 8 -- a valid scanline, then its corruptions.
  const std::string dump8 = std::string("\x08", 1) + "\x01\x02\x03\x04\x05\x06\x07\x08";
  const std::string valid = header + marker + "\x88\x64" + dump8 + "\x88\x32\x88\x82";
  spit(dir / "valid.hdr", valid);
  const ImageF image = read_image(dir / "valid.hdr");
  ASSERT_EQ(image.width, 8);
  EXPECT_EQ(image.pixel(0, 0)[0], 100.0f * 4.0f / 256.0f);  // m 2^(e - 136), e = 130
  // stb ends the header at a line that starts with NUL as at an empty one.
  const std::string nul_header =
      "#?RADIANCE\nFORMAT=32-bit_rle_rgbe\n" + std::string(1, '\0') + "`0\n-Y 1 +X 8\n";
  spit(dir / "nul.hdr", nul_header + marker + "\x88\x64" + dump8 + "\x88\x32\x88\x82");
  EXPECT_EQ(read_image(dir / "nul.hdr").data, image.data);
  for (const std::string& bad :
       {header + marker + std::string("\x00", 1) + dump8,          // a dump of 0
        nul_header + marker + "\x88\x64" + dump8 + "\x88",         // ends in the third channel
        header + marker + "\x80\x01" + dump8,                      // a run of 0
        header + marker + "\x88\x64" + dump8,                      // ends after two channels
        header + "\x80\x40\x20\x81" + std::string(20, '\x40')}) {  // flat, 6 of 8 pixels
    spit(dir / "bad.hdr", bad);
    expect_read_error(dir / "bad.hdr");
  }
}

// Found by the fuzz target image_exr (docs/TESTING.md): OpenEXR's message quoted a channel name
// with control characters into ours.
TEST(ImageIo, ExrErrorsQuotingFileBytesStayPrintable) {
  ScratchDir dir;
  write_image(dir / "y.exr", ImageF(1, 1, 1));
  std::string bytes = slurp(dir / "y.exr");
  const std::size_t list = bytes.find(std::string("chlist\0", 7));
  ASSERT_NE(list, std::string::npos);
  const std::size_t name = list + 7 + 4;  // after the type and the attribute size
  ASSERT_EQ(bytes.substr(name, 2), std::string("Y\0", 2));
  bytes[name] = '\x01';      // channel name "\x01"
  bytes[name + 2] = '\x09';  // pixel type 9: invalid
  spit(dir / "bad.exr", bytes);
  try {
    read_image(dir / "bad.exr");
    ADD_FAILURE() << "accepted";
  } catch (const IoError& e) {
    const std::string message = e.what();
    EXPECT_NE(message.find("\\x01"), std::string::npos) << message;
    EXPECT_TRUE(std::none_of(message.begin(), message.end(), [](char c) {
      return static_cast<unsigned char>(c) < 0x20;
    })) << message;
  }
}

// Found by the fuzz target image_exr (docs/TESTING.md): a float attribute whose size field says 0
// ended our walk of the header early (its value began with a NUL, read as the empty name that ends
// the header), while OpenEXR reads a float's 4 bytes whatever the field says and went on to an
// attribute of an unknown type declaring 1.6 GB, which it allocated before finding the end of the
// 700-byte file. Fixed-size types and channel lists must now fill exactly their size field, and
// read_exr_metadata walks the header too.
TEST(ImageIo, ExrAttributeSizesThatDisagreeWithTheirTypeAreRefusedBeforeOpenExr) {
  ScratchDir dir;
  write_image(dir / "y.exr", ImageF(1, 1, 1));
  const std::string bytes = slurp(dir / "y.exr");
  const std::string window("dataWindow\0box2i\0", 17);
  const std::size_t after_window = bytes.find(window) + window.size() + 4 + 16;
  ASSERT_LT(after_window, bytes.size());
  auto le32 = [](std::uint32_t v) {
    std::string s(4, '\0');
    for (int i = 0; i < 4; ++i) s[i] = static_cast<char>((v >> (8 * i)) & 0xffu);
    return s;
  };
  const std::string planted = std::string("skew\0float\0", 11) + le32(0) +
                              std::string("\0\0\x80\x3f", 4) + std::string("big\0blob\0", 9) +
                              le32(1600000000u) + "xyz";
  spit(dir / "planted.exr", bytes.substr(0, after_window) + planted + bytes.substr(after_window));
  for (const bool metadata : {false, true}) {
    try {
      if (metadata)
        read_exr_metadata(dir / "planted.exr");
      else
        read_image(dir / "planted.exr");
      ADD_FAILURE() << "accepted";
    } catch (const IoError& e) {
      EXPECT_NE(std::string(e.what()).find("attribute 'skew' of type float has 0 bytes, not 4"),
                std::string::npos)
          << e.what();
    }
  }
  // A channel list whose size field is one byte more than its channels.
  std::string list = bytes;
  const std::size_t size_at = list.find(std::string("chlist\0", 7)) + 7;
  list.replace(size_at, 4, le32(static_cast<std::uint8_t>(list[size_at]) + 1u));
  spit(dir / "list.exr", list);
  try {
    read_image(dir / "list.exr");
    ADD_FAILURE() << "accepted";
  } catch (const IoError& e) {
    EXPECT_NE(std::string(e.what()).find("channel list 'channels' does not fill its"),
              std::string::npos)
        << e.what();
  }
}

// Found by the fuzz target image_exr: OpenEXR allocates one tile's buffer before reading the
// pixels, so a 3 x 3 image declaring 8192 x 8192 tiles asked for 268 MB. A tile may hold no more
// pixels than the image or a 256 x 256 tile.
TEST(ImageIo, ExrTilesLargerThanTheImageAndASmallTileAreRefused) {
  ScratchDir dir;
  const std::string tiled =
      testing_support::source_file("tests/fuzz/corpus/image_exr/y_half_tiled_3x3.exr");
  const std::size_t at = tiled.find(std::string("tiledesc\0", 9));
  ASSERT_NE(at, std::string::npos);
  spit(dir / "tiled.exr", tiled);
  EXPECT_EQ(read_image(dir / "tiled.exr").data.size(), 9u);
  std::string big = tiled;
  for (std::size_t k : {at + 9 + 4, at + 9 + 8}) {  // after the size field: x size, y size
    big[k] = 0;
    big[k + 1] = 0x20;  // 8192
    big[k + 2] = big[k + 3] = 0;
  }
  spit(dir / "big.exr", big);
  try {
    read_image(dir / "big.exr");
    ADD_FAILURE() << "accepted";
  } catch (const IoError& e) {
    EXPECT_NE(std::string(e.what()).find("tiles of 67108864 pixels for an image of 9"),
              std::string::npos)
        << e.what();
  }
}

TEST(ImageIo, FormatFromPath) {
  EXPECT_EQ(format_from_path("a/b.exr"), ImageFormat::exr);
  EXPECT_EQ(format_from_path("b.HDR"), ImageFormat::hdr);
  EXPECT_EQ(format_from_path("b.Pfm"), ImageFormat::pfm);
  EXPECT_EQ(format_from_path("b.png"), ImageFormat::png);
  EXPECT_THROW(format_from_path("photo.jpg"), InvalidArgument);
  EXPECT_THROW(format_from_path("noextension"), InvalidArgument);
  try {
    format_from_path("dir/photo.jpg");
  } catch (const InvalidArgument& e) {
    EXPECT_NE(std::string(e.what()).find("dir/photo.jpg"), std::string::npos);
  }
}

TEST(ImageIo, WriteRejectsEmptyOrInconsistentImages) {
  ScratchDir dir;
  EXPECT_THROW(write_image(dir / "e.exr", ImageF()), InvalidArgument);
  ImageF two(2, 2, 2);
  EXPECT_THROW(write_image(dir / "e.exr", two), InvalidArgument);
  ImageF short_data(2, 2, 3);
  short_data.data.pop_back();
  EXPECT_THROW(write_image(dir / "e.pfm", short_data), InvalidArgument);
  EXPECT_TRUE(dir.entries().empty());
}

}  // namespace
}  // namespace skylight::io
