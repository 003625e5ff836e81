// Image files: EXR (OpenEXR), Radiance HDR (own RGBE writer, stb_image reader), PFM (own code),
// PNG (stb_image_write) with text chunks.
#include <unistd.h>

#include <OpenEXR/ImfChannelList.h>
#include <OpenEXR/ImfFrameBuffer.h>
#include <OpenEXR/ImfHeader.h>
#include <OpenEXR/ImfIO.h>
#include <OpenEXR/ImfInputFile.h>
#include <OpenEXR/ImfOutputFile.h>
#include <OpenEXR/ImfStringAttribute.h>
#include <fmt/format.h>
#include <stb/stb_image.h>
#include <stb/stb_image_write.h>

#include <algorithm>
#include <atomic>
#include <bit>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <limits>
#include <memory>
#include <new>
#include <optional>
#include <set>
#include <system_error>

#include "skylight/core/error.h"
#include "skylight/core/numbers.h"
#include "skylight/io/file.h"
#include "skylight/io/image.h"

namespace skylight::io {
namespace {

namespace fs = std::filesystem;

// Runs `body`, turning library exceptions (Iex::BaseExc and other std::exceptions) into one-line
// IoErrors naming `path`, running out of memory included. Our own errors pass through unchanged.
template <class F>
auto converting_errors(const fs::path& path, bool reading, F&& body) {
  try {
    return body();
  } catch (const IoError&) {
    throw;
  } catch (const InvalidArgument&) {
    throw;
  } catch (const std::bad_alloc&) {
    if (reading) throw_read_error(path, "out of memory");
    throw_write_error(path, "out of memory");
  } catch (const std::exception& e) {
    if (reading) throw_read_error(path, e.what());
    throw_write_error(path, e.what());
  }
}

// OpenEXR output through an AtomicFile (so that write errors are never lost, even those raised
// while ~OutputFile writes the line-offset table).
class AtomicExrStream : public Imf::OStream {
 public:
  // OpenEXR's own messages then name the target, not the temporary.
  explicit AtomicExrStream(AtomicFile& file) : Imf::OStream(file.target().c_str()), file_(file) {}
  void write(const char c[], int n) override { file_.write(c, static_cast<size_t>(n)); }
  std::uint64_t tellp() override { return file_.tell(); }
  void seekp(std::uint64_t pos) override { file_.seek(pos); }

 private:
  AtomicFile& file_;
};

// ---- validation ------------------------------------------------------------------------------

void check_shape(const fs::path& path, int width, int height, int channels, size_t size) {
  if (channels != 1 && channels != 3)
    throw InvalidArgument(fmt::format("cannot write '{}': image has {} channels, expected 1 or 3",
                                      shown_path(path), channels));
  if (width <= 0 || height <= 0)
    throw InvalidArgument(
        fmt::format("cannot write '{}': image is empty ({}x{})", shown_path(path), width, height));
  const size_t expected =
      static_cast<size_t>(width) * static_cast<size_t>(height) * static_cast<size_t>(channels);
  if (size != expected)
    throw InvalidArgument(fmt::format("cannot write '{}': image data has {} values, expected {}",
                                      shown_path(path), size, expected));
}

// Metadata keys must suit every format: 1 to 79 printable ASCII characters (PNG keyword limit),
// no spaces and no '=' (Radiance header lines are NAME=value), each key once.
void check_metadata(const fs::path& path, const Metadata& meta) {
  std::set<std::string> seen;
  for (const auto& [key, value] : meta) {
    const bool ok =
        !key.empty() && key.size() <= 79 &&
        std::all_of(key.begin(), key.end(), [](char c) { return c > ' ' && c <= '~' && c != '='; });
    if (!ok)
      throw InvalidArgument(fmt::format(
          "cannot write '{}': metadata key '{}' must be 1-79 printable ASCII characters without "
          "spaces or '='",
          shown_path(path), key));
    if (!seen.insert(key).second)
      throw InvalidArgument(
          fmt::format("cannot write '{}': metadata key '{}' given twice", shown_path(path), key));
  }
}

// A file's image size against the reader's limit, before its pixels are allocated.
void check_read_size(const fs::path& path, std::int64_t width, std::int64_t height,
                     const ReadImageOptions& options) {
  if (width > 0 && height > 0 && width <= options.max_pixels / height) return;
  if (width <= 0 || height <= 0)
    throw_read_error(path, fmt::format("empty image ({}x{})", width, height));
  throw InvalidArgument(fmt::format("cannot read '{}': {}x{} pixels exceed the limit of {}",
                                    shown_path(path), width, height, options.max_pixels));
}

// No image the project reads may carry NaN or infinity into its computations.
void check_finite(const fs::path& path, const ImageF& image) {
  const auto bad =
      std::find_if(image.data.begin(), image.data.end(), [](float v) { return !std::isfinite(v); });
  if (bad == image.data.end()) return;
  const auto index = static_cast<std::size_t>(bad - image.data.begin());
  const std::size_t pixel = index / static_cast<std::size_t>(image.channels);
  const std::size_t width = static_cast<std::size_t>(image.width);
  throw InvalidArgument(fmt::format(
      "cannot read '{}': pixel ({}, {}) channel {} is {} (images must be finite)", shown_path(path),
      pixel % width, pixel / width, index % static_cast<std::size_t>(image.channels), *bad));
}

// ---- EXR -------------------------------------------------------------------------------------

void write_exr(const fs::path& path, const ImageF& image, const Metadata& meta) {
  static const char* const kRgb[] = {"R", "G", "B"};
  static const char* const kY[] = {"Y"};
  const char* const* names = image.channels == 3 ? kRgb : kY;

  Imf::Header header(image.width, image.height);
  header.compression() = Imf::ZIP_COMPRESSION;
  for (int c = 0; c < image.channels; ++c)
    header.channels().insert(names[c], Imf::Channel(Imf::FLOAT));
  for (const auto& [key, value] : meta) {
    if (header.find(key) != header.end())
      throw InvalidArgument(
          fmt::format("cannot write '{}': metadata key '{}' is a standard EXR attribute",
                      shown_path(path), key));
    header.insert(key, Imf::StringAttribute(value));
  }

  // Imf::Slice wants a mutable base pointer; OutputFile only reads through it.
  char* base = reinterpret_cast<char*>(const_cast<float*>(image.data.data()));
  const size_t x_stride = sizeof(float) * static_cast<size_t>(image.channels);
  const size_t y_stride = x_stride * static_cast<size_t>(image.width);
  Imf::FrameBuffer frame;
  for (int c = 0; c < image.channels; ++c)
    frame.insert(names[c], Imf::Slice(Imf::FLOAT, base + sizeof(float) * static_cast<size_t>(c),
                                      x_stride, y_stride));

  AtomicFile file(path);
  converting_errors(path, false, [&] {
    AtomicExrStream stream(file);
    Imf::OutputFile out(stream, header, Imf::globalThreadCount());
    out.setFrameBuffer(frame);
    out.writePixels(image.height);
  });  // ~OutputFile has written the offset table here
  file.commit();
}

// The size in bytes of the value of each fixed-size attribute type (OpenEXR file layout); OpenEXR
// reads these by their type and ignores the size field, so a size field that disagrees would put
// our walk and OpenEXR's reader at different places in the header.
std::optional<std::int32_t> exr_fixed_attribute_size(std::string_view type) {
  static constexpr std::pair<std::string_view, std::int32_t> kSizes[] = {{"box2i", 16},
                                                                         {"box2f", 16},
                                                                         {"chromaticities", 32},
                                                                         {"compression", 1},
                                                                         {"deepImageState", 1},
                                                                         {"double", 8},
                                                                         {"envmap", 1},
                                                                         {"float", 4},
                                                                         {"int", 4},
                                                                         {"keycode", 28},
                                                                         {"lineOrder", 1},
                                                                         {"m33f", 36},
                                                                         {"m33d", 72},
                                                                         {"m44f", 64},
                                                                         {"m44d", 128},
                                                                         {"rational", 8},
                                                                         {"tiledesc", 9},
                                                                         {"timecode", 8},
                                                                         {"v2i", 8},
                                                                         {"v2f", 8},
                                                                         {"v2d", 16},
                                                                         {"v3i", 12},
                                                                         {"v3f", 12},
                                                                         {"v3d", 24}};
  for (const auto& [name, size] : kSizes)
    if (name == type) return size;
  return std::nullopt;
}

constexpr std::int64_t kMaxSmallTilePixels = 256 * 256;

// Refuses an EXR whose largest tile (tile_pixels) is too large for its data window (width,
// height).
void check_tile_size(const fs::path& path, const std::pair<std::int64_t, std::int64_t>& window,
                     std::int64_t tile_pixels) {
  // OpenEXR allocates a tile's buffer (tile width x height x pixel size) before reading any: a
  // tile may hold no more pixels than the image or a 256 x 256 tile, whichever is larger (found
  // by the fuzz target image_exr: an 8192 x 8192 tile in a 376-byte file asked for 268 MB).
  const std::int64_t cap = std::int64_t{1} << 31;
  const std::int64_t image_pixels = window.first > 0 && window.second > 0
                                        ? std::min(window.first, cap) * std::min(window.second, cap)
                                        : 0;
  if (tile_pixels > std::max(image_pixels, kMaxSmallTilePixels))
    throw_read_error(
        path, "not a valid OpenEXR file: " +
                  fmt::format("tiles of {} pixels for an image of {}", tile_pixels, image_pixels));
}

// The first part's data window, read from the header bytes without OpenEXR: Imf::InputFile sizes
// its line buffers from the data window, and Imf::Header allocates each attribute of an unknown
// type at the size the file states before reading it (2 GB for a 100-byte file), so both are
// checked before OpenEXR sees the file. Header layout (OpenEXR file layout): magic 76 2f 31 01, a
// 4-byte version field, then per part a list of attributes `name\0 type\0 size:int32 value[size]`
// ended by an empty name; multi-part files (version flag 0x1000) end the list of headers with an
// empty header. OpenEXR reads fixed-size types and channel lists by their content, not by the
// size field, so those must agree with it (else the walk and OpenEXR part ways and a later size
// goes unchecked: found by the fuzz target image_exr). Returns the data window's width and height;
// throws read errors naming the path.
std::pair<std::int64_t, std::int64_t> exr_data_window(const fs::path& path) {
  FilePtr f = open_for_read(path);
  std::error_code ec;
  const auto file_size = static_cast<std::int64_t>(fs::file_size(path, ec));
  if (ec) throw_read_error(path, ec.message());
  auto corrupt = [&](const std::string& why) {
    throw_read_error(path, "not a valid OpenEXR file: " + why);
  };
  auto read_u32 = [&]() {
    unsigned char b[4];
    if (std::fread(b, 1, 4, f.get()) != 4) corrupt("truncated header");
    return std::uint32_t{b[0]} | std::uint32_t{b[1]} << 8 | std::uint32_t{b[2]} << 16 |
           std::uint32_t{b[3]} << 24;
  };
  // A NUL-terminated attribute name or type (at most 255 characters with long names).
  auto read_name = [&]() {
    std::string name;
    for (int c = std::fgetc(f.get()); c != 0; c = std::fgetc(f.get())) {
      if (c == EOF) corrupt("truncated header");
      if (name.size() == 255) corrupt("attribute name longer than 255 characters");
      name += static_cast<char>(c);
    }
    return name;
  };
  if (read_u32() != 20000630u) corrupt("missing magic number");  // 76 2f 31 01
  const bool multi_part = (read_u32() & 0x1000u) != 0;
  std::optional<std::pair<std::int64_t, std::int64_t>> window;
  std::int64_t tile_pixels = 0;  // the largest tile of any part
  for (int part = 0;; ++part) {
    bool empty_header = true;
    for (std::string name = read_name(); !name.empty(); name = read_name()) {
      empty_header = false;
      const std::string type = read_name();
      const auto size = static_cast<std::int32_t>(read_u32());
      const std::int64_t pos = std::ftell(f.get());
      if (size < 0 || pos < 0 || size > file_size - pos)
        corrupt(fmt::format("attribute '{}' of {} bytes beyond the end of the file", excerpt(name),
                            size));
      if (const auto fixed = exr_fixed_attribute_size(type); fixed && size != *fixed)
        corrupt(fmt::format("attribute '{}' of type {} has {} bytes, not {}", excerpt(name), type,
                            size, *fixed));
      if (type == "chlist") {
        // Channels `name\0 pixel_type:int32 p_linear:uint8 reserved[3] x_sampling:int32
        // y_sampling:int32`, ended by an empty name.
        std::int64_t used = 0;
        for (std::string channel = read_name(); !channel.empty(); channel = read_name()) {
          used += static_cast<std::int64_t>(channel.size()) + 1 + 16;
          if (used >= size || std::fseek(f.get(), 16, SEEK_CUR) != 0) break;
        }
        if (used + 1 != size)
          corrupt(fmt::format("channel list '{}' does not fill its {} bytes", excerpt(name), size));
      } else if (part == 0 && name == "dataWindow" && type == "box2i") {
        const auto x0 = static_cast<std::int32_t>(read_u32()),
                   y0 = static_cast<std::int32_t>(read_u32()),
                   x1 = static_cast<std::int32_t>(read_u32()),
                   y1 = static_cast<std::int32_t>(read_u32());
        window = {std::int64_t{x1} - x0 + 1, std::int64_t{y1} - y0 + 1};
      } else if (type == "tiledesc") {  // x size, y size, level mode (OpenEXR file layout)
        // Each side as stored (at most 2^32 - 1), capped at 2^31 so that the product fits.
        const std::int64_t tx = std::min<std::int64_t>(read_u32(), std::int64_t{1} << 31),
                           ty = std::min<std::int64_t>(read_u32(), std::int64_t{1} << 31);
        if (std::fseek(f.get(), 1, SEEK_CUR) != 0) corrupt("truncated header");
        tile_pixels = std::max(tile_pixels, tx * ty);
      } else if (std::fseek(f.get(), size, SEEK_CUR) != 0) {
        corrupt("truncated header");
      }
    }
    if (!multi_part || empty_header) break;
  }
  if (!window) corrupt("no dataWindow attribute");
  check_tile_size(path, *window, tile_pixels);
  return *window;
}

// `scalar`: one channel, the first of Z, Y and R present (depth maps); otherwise R,G,B or Y.
ImageF read_exr(const fs::path& path, const ReadImageOptions& options, bool scalar = false) {
  open_for_read(path);  // a clear system message for missing or unreadable files
  return converting_errors(path, true, [&] {
    const auto [first_width, first_height] = exr_data_window(path);
    check_read_size(path, first_width, first_height, options);
    Imf::InputFile in(path.c_str());
    const Imf::Header& header = in.header();
    const Imath::Box2i window = header.dataWindow();
    const std::int64_t w = std::int64_t{window.max.x} - window.min.x + 1;
    const std::int64_t h = std::int64_t{window.max.y} - window.min.y + 1;
    if (w <= 0 || h <= 0 || w > std::numeric_limits<int>::max() ||
        h > std::numeric_limits<int>::max())
      throw_read_error(path, fmt::format("bad data window {}x{}", w, h));
    check_read_size(path, w, h, options);

    const Imf::ChannelList& channels = header.channels();
    std::vector<const char*> names;
    if (scalar) {
      for (const char* name : {"Z", "Y", "R"})
        if (names.empty() && channels.findChannel(name)) names = {name};
      if (names.empty()) {
        std::string present;
        for (auto it = channels.begin(); it != channels.end(); ++it)
          present += (present.empty() ? "" : ", ") + std::string(it.name());
        throw_read_error(path, fmt::format("no Z, Y or R channel (has: {})", present));
      }
    } else if (channels.findChannel("R") && channels.findChannel("G") &&
               channels.findChannel("B")) {
      names = {"R", "G", "B"};
    } else if (channels.findChannel("Y")) {
      names = {"Y"};
    } else {
      std::string present;
      for (auto it = channels.begin(); it != channels.end(); ++it)
        present += (present.empty() ? "" : ", ") + std::string(it.name());
      throw_read_error(path, fmt::format("no R,G,B or Y channels (has: {})", present));
    }

    ImageF image(static_cast<int>(w), static_cast<int>(h), static_cast<int>(names.size()));
    const size_t x_stride = sizeof(float) * names.size();
    const size_t y_stride = x_stride * static_cast<size_t>(w);
    Imf::FrameBuffer frame;
    for (size_t c = 0; c < names.size(); ++c)  // HALF / UINT channels are converted to FLOAT
      frame.insert(names[c],
                   Imf::Slice::Make(Imf::FLOAT, image.data.data() + c, window, x_stride, y_stride));
    in.setFrameBuffer(frame);
    in.readPixels(window.min.y, window.max.y);
    return image;
  });
}

// ---- PFM -------------------------------------------------------------------------------------

std::uint32_t byte_swap(std::uint32_t v) {
  return (v >> 24) | ((v >> 8) & 0xff00u) | ((v << 8) & 0xff0000u) | (v << 24);
}

// PFM: text header "PF" (RGB) or "Pf" (grey), "width height", scale (negative: little-endian),
// one whitespace byte, then float rows from the BOTTOM row up. We write little-endian, scale -1.
void write_pfm(const fs::path& path, const ImageF& image) {
  AtomicFile file(path);
  file.write(fmt::format("{}\n{} {}\n-1.0\n", image.channels == 3 ? "PF" : "Pf", image.width,
                         image.height));
  const size_t row_values = static_cast<size_t>(image.width) * static_cast<size_t>(image.channels);
  std::vector<std::uint32_t> row(row_values);
  for (int y = image.height - 1; y >= 0; --y) {
    std::memcpy(row.data(), image.pixel(0, y), row_values * sizeof(float));
    if constexpr (std::endian::native == std::endian::big)
      for (auto& v : row) v = byte_swap(v);
    file.write(row.data(), row_values * sizeof(float));
  }
  file.commit();
}

ImageF read_pfm(const fs::path& path, const ReadImageOptions& options) {
  const std::vector<char> bytes = read_file(path);
  size_t pos = 0;
  auto is_space = [](char c) { return c == ' ' || c == '\t' || c == '\r' || c == '\n'; };
  // Next whitespace-separated header token (short: the header is a few numbers).
  auto token = [&]() -> std::string {
    while (pos < bytes.size() && is_space(bytes[pos])) ++pos;
    std::string t;
    while (pos < bytes.size() && !is_space(bytes[pos]) && t.size() < 64) t += bytes[pos++];
    return t;
  };
  auto corrupt = [&](const std::string& why) {
    throw_read_error(path, "not a valid PFM file: " + why);
  };

  const std::string magic = token();
  if (magic != "PF" && magic != "Pf") corrupt("missing PF/Pf signature");
  const int channels = magic == "PF" ? 3 : 1;
  auto dimension = [&](const char* what) {
    const std::string t = token();
    const auto v = parse_integer(t);
    if (!v || *v <= 0 || *v > std::numeric_limits<int>::max())
      corrupt(fmt::format("bad {} '{}'", what, excerpt(t)));
    return static_cast<int>(*v);
  };
  const int width = dimension("width");
  const int height = dimension("height");
  check_read_size(path, width, height, options);
  const std::string scale_text = token();
  const auto scale = parse_number(scale_text);
  if (!scale || *scale == 0.0) corrupt(fmt::format("bad scale '{}'", excerpt(scale_text)));
  if (pos >= bytes.size() || !is_space(bytes[pos])) corrupt("truncated header");
  ++pos;  // exactly one whitespace byte before the raster

  const size_t row_values = static_cast<size_t>(width) * static_cast<size_t>(channels);
  const size_t row_bytes = row_values * sizeof(float);
  if (static_cast<size_t>(height) > (bytes.size() - pos) / row_bytes)
    corrupt(fmt::format("truncated raster ({} bytes for {}x{}x{} floats)", bytes.size() - pos,
                        width, height, channels));

  // The magnitude of the scale is ignored (it is 1 in practice); its sign gives the byte order.
  const bool file_little = *scale < 0.0;
  const bool swap = file_little != (std::endian::native == std::endian::little);
  ImageF image(width, height, channels);
  for (int row = 0; row < height; ++row) {
    float* dst = image.pixel(0, height - 1 - row);  // file row 0 is the bottom
    std::memcpy(dst, bytes.data() + pos + static_cast<size_t>(row) * row_values * sizeof(float),
                row_values * sizeof(float));
    if (swap) {
      for (size_t i = 0; i < row_values; ++i) {
        std::uint32_t v;
        std::memcpy(&v, dst + i, sizeof v);
        v = byte_swap(v);
        std::memcpy(dst + i, &v, sizeof v);
      }
    }
  }
  return image;
}

// ---- Radiance HDR ----------------------------------------------------------------------------

// RGBE (Ward): a shared exponent byte e and three 8-bit mantissas m, value = m * 2^(e - 136).
// Mantissas are rounded to nearest (Radiance truncates), so the error of each channel is at most
// half a mantissa step, i.e. <= max(R, G, B) / 255. Negative and non-finite values become 0.
std::array<std::uint8_t, 4> to_rgbe(const float* rgb) {
  double c[3];
  for (int i = 0; i < 3; ++i) c[i] = std::isfinite(rgb[i]) && rgb[i] > 0.0f ? rgb[i] : 0.0;
  const double top = std::max({c[0], c[1], c[2]});
  if (top == 0.0) return {0, 0, 0, 0};
  int e = 0;
  std::frexp(top, &e);                    // top = f * 2^e, f in [0.5, 1)
  if (e < -127) return {0, 0, 0, 0};      // below the smallest exponent byte: black
  double scale = std::ldexp(1.0, 8 - e);  // mantissa of top in [128, 256)
  if (std::round(top * scale) > 255.0) {  // rounds up to 256: next exponent
    ++e;
    scale *= 0.5;
  }
  if (e > 127) {  // beyond RGBE's range (~1.7e38): saturate
    e = 127;
    scale = std::ldexp(1.0, 8 - e);
  }
  std::array<std::uint8_t, 4> out{};
  for (int i = 0; i < 3; ++i)
    out[i] = static_cast<std::uint8_t>(std::min(255.0, std::round(c[i] * scale)));
  out[3] = static_cast<std::uint8_t>(e + 128);
  return out;
}

// Writes uncompressed ("flat") RGBE scanlines, which every Radiance reader (stb_image included)
// accepts: a normalised pixel never starts with the 2,2 run-length marker. Metadata become
// header lines `KEY=value` (newlines in values replaced by spaces).
void write_hdr(const fs::path& path, const ImageF& image, const Metadata& meta) {
  for (const auto& [key, value] : meta) {
    if (key == "FORMAT")
      throw InvalidArgument(
          fmt::format("cannot write '{}': metadata key 'FORMAT' is reserved in Radiance files",
                      shown_path(path)));
  }
  std::string header = "#?RADIANCE\n";
  for (const auto& [key, value] : meta) {
    std::string v = value;
    std::replace_if(
        v.begin(), v.end(), [](char c) { return c == '\n' || c == '\r'; }, ' ');
    header += key + "=" + v + "\n";
  }
  header += fmt::format("FORMAT=32-bit_rle_rgbe\n\n-Y {} +X {}\n", image.height, image.width);

  AtomicFile file(path);
  file.write(header);
  std::vector<std::uint8_t> row(static_cast<size_t>(image.width) * 4);
  for (int y = 0; y < image.height; ++y) {
    for (int x = 0; x < image.width; ++x) {
      const float* p = image.pixel(x, y);
      const float rgb[3] = {p[0], image.channels == 3 ? p[1] : p[0],
                            image.channels == 3 ? p[2] : p[0]};
      const auto rgbe = to_rgbe(rgb);
      std::copy(rgbe.begin(), rgbe.end(), row.begin() + static_cast<std::ptrdiff_t>(x) * 4);
    }
    file.write(row.data(), row.size());
  }
  file.commit();
}

// Walks the pixel data of a Radiance file the way stb_image's reader does (header lines up to an
// empty one, then the resolution line; run-length scanlines when 8 <= width < 32768 and the
// scanline starts with 2, 2, else flat RGBE for the rest of the image) and returns why stb must
// not decode it, or nullptr: stb (Debian's 2022 version) loops forever on a zero-length run or
// dump, which a truncated file also produces (it reads 0 past the end), and reads missing pixels
// of a flat file as black.
const char* hdr_pixel_data_problem(std::string_view bytes, int width, int height) {
  // Header lines after the magic one, up to one that is empty or starts with NUL (stb compares C
  // strings); each line runs to its '\n'. Without one, stb refuses the file before any pixel.
  std::size_t pos = bytes.find('\n');
  for (bool last = false; !last;) {
    if (pos == std::string_view::npos || pos + 1 >= bytes.size()) return nullptr;
    last = bytes[pos + 1] == '\n' || bytes[pos + 1] == '\0';
    pos = bytes.find('\n', pos + 1);
  }
  // Then the resolution line.
  if (pos == std::string_view::npos) return nullptr;
  const std::size_t resolution_end = bytes.find('\n', pos + 1);
  if (resolution_end == std::string_view::npos) return "truncated before the pixel data";
  pos = resolution_end + 1;
  const std::size_t w = static_cast<std::size_t>(width), h = static_cast<std::size_t>(height);
  auto flat_needs = [&](std::size_t pixels) {
    return bytes.size() - pos >= pixels * 4 ? nullptr : "truncated pixel data";
  };
  if (width < 8 || width >= 32768) return flat_needs(w * h);
  for (std::size_t j = 0; j < h; ++j) {
    if (bytes.size() - pos < 4) return "truncated pixel data";
    const auto c1 = static_cast<unsigned char>(bytes[pos]),
               c2 = static_cast<unsigned char>(bytes[pos + 1]),
               hi = static_cast<unsigned char>(bytes[pos + 2]),
               lo = static_cast<unsigned char>(bytes[pos + 3]);
    pos += 4;
    // Not run-length encoded: stb decodes the whole image as flat pixels from here, these 4 bytes
    // being the first one.
    if (c1 != 2 || c2 != 2 || (hi & 0x80u) != 0) return flat_needs(w * h - 1);
    if ((std::size_t{hi} << 8 | lo) != w) return nullptr;  // stb refuses the scanline length
    for (int channel = 0; channel < 4; ++channel) {
      for (std::size_t i = 0; i < w;) {
        if (pos >= bytes.size()) return "truncated run-length data";
        std::size_t count = static_cast<unsigned char>(bytes[pos++]);
        const bool run = count > 128;
        if (run) count -= 128;
        if (count == 0) return "zero-length run in the run-length data";
        if (count > w - i) return nullptr;  // stb refuses an overlong run
        const std::size_t payload = run ? 1 : count;
        if (bytes.size() - pos < payload) return "truncated run-length data";
        pos += payload;
        i += count;
      }
    }
  }
  return nullptr;
}

ImageF read_hdr(const fs::path& path, const ReadImageOptions& options) {
  const std::vector<char> file = read_file(path);
  const auto* data = reinterpret_cast<const stbi_uc*>(file.data());
  const int size = file.size() > static_cast<std::size_t>(std::numeric_limits<int>::max())
                       ? std::numeric_limits<int>::max()
                       : static_cast<int>(file.size());
  // stbi_loadf would also accept an 8-bit image and apply a gamma to it: insist on Radiance.
  if (!stbi_is_hdr_from_memory(data, size)) throw_read_error(path, "not a Radiance HDR file");
  int w = 0, h = 0, n = 0;
  // The size from the header first: stb allocates the whole image before reading a pixel.
  if (!stbi_info_from_memory(data, size, &w, &h, &n)) throw_read_error(path, stbi_failure_reason());
  check_read_size(path, w, h, options);
  if (const char* problem = hdr_pixel_data_problem(
          std::string_view(file.data(), static_cast<std::size_t>(size)), w, h))
    throw_read_error(path, std::string("not a valid Radiance HDR file: ") + problem);
  stbi_set_flip_vertically_on_load_thread(0);  // row 0 at the top, whatever others set globally
  float* pixels = stbi_loadf_from_memory(data, size, &w, &h, &n, 3);  // .hdr: linear, no gamma
  if (pixels == nullptr) throw_read_error(path, stbi_failure_reason());
  ImageF image(w, h, 3);
  std::copy(pixels, pixels + image.data.size(), image.data.begin());
  stbi_image_free(pixels);
  return image;
}

// ---- PNG -------------------------------------------------------------------------------------

std::uint32_t crc32(const std::uint8_t* bytes, size_t n, std::uint32_t crc = 0) {
  static const auto table = [] {
    std::array<std::uint32_t, 256> t{};
    for (std::uint32_t i = 0; i < 256; ++i) {
      std::uint32_t c = i;
      for (int k = 0; k < 8; ++k) c = (c & 1u) ? 0xedb88320u ^ (c >> 1) : c >> 1;
      t[i] = c;
    }
    return t;
  }();
  crc = ~crc;
  for (size_t i = 0; i < n; ++i) crc = table[(crc ^ bytes[i]) & 0xffu] ^ (crc >> 8);
  return ~crc;
}

void put_u32_be(std::vector<std::uint8_t>& out, std::uint32_t v) {
  for (int shift = 24; shift >= 0; shift -= 8) out.push_back(static_cast<std::uint8_t>(v >> shift));
}

// A tEXt chunk (Latin-1 text) when the value is plain ASCII, else an uncompressed iTXt (UTF-8).
std::vector<std::uint8_t> text_chunk(const std::string& key, const std::string& value) {
  const bool ascii = std::all_of(value.begin(), value.end(),
                                 [](char c) { return c == '\n' || (c >= ' ' && c <= '~'); });
  const std::string type = ascii ? "tEXt" : "iTXt";
  std::vector<std::uint8_t> body(type.begin(), type.end());
  body.insert(body.end(), key.begin(), key.end());
  body.push_back(0);
  if (!ascii) body.insert(body.end(), {0, 0, 0, 0});  // not compressed, method, no language/key
  body.insert(body.end(), value.begin(), value.end());
  std::vector<std::uint8_t> chunk;
  put_u32_be(chunk, static_cast<std::uint32_t>(body.size() - 4));
  chunk.insert(chunk.end(), body.begin(), body.end());
  put_u32_be(chunk, crc32(body.data(), body.size()));
  return chunk;
}

void append_bytes(void* context, void* data, int size) {
  auto* out = static_cast<std::vector<std::uint8_t>*>(context);
  const auto* bytes = static_cast<const std::uint8_t*>(data);
  out->insert(out->end(), bytes, bytes + size);
}

}  // namespace

ImageFormat format_from_path(const std::filesystem::path& path) {
  std::string ext = shown_path(path.extension());
  std::transform(ext.begin(), ext.end(), ext.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  if (ext == ".exr") return ImageFormat::exr;
  if (ext == ".hdr") return ImageFormat::hdr;
  if (ext == ".pfm") return ImageFormat::pfm;
  if (ext == ".png") return ImageFormat::png;
  throw InvalidArgument(fmt::format(
      "unsupported image file '{}': extension '{}' is not one of .exr, .hdr, .pfm, .png",
      shown_path(path), shown_path(path.extension())));
}

void write_image(const std::filesystem::path& path, const ImageF& image, const Metadata& meta) {
  const ImageFormat format = format_from_path(path);
  check_shape(path, image.width, image.height, image.channels, image.data.size());
  check_metadata(path, meta);
  switch (format) {
    case ImageFormat::exr:
      write_exr(path, image, meta);
      return;
    case ImageFormat::hdr:
      write_hdr(path, image, meta);
      return;
    case ImageFormat::pfm:  // PFM has no room for metadata
      write_pfm(path, image);
      return;
    case ImageFormat::png:
      throw InvalidArgument(
          fmt::format("cannot write '{}': PNG holds 8-bit data; tone-map the float image first "
                      "(render::write_image_or_preview)",
                      shown_path(path)));
  }
}

void write_png(const std::filesystem::path& path, const Image8& image, const Metadata& meta) {
  check_shape(path, image.width, image.height, 3, image.data.size());
  check_metadata(path, meta);
  std::vector<std::uint8_t> png;
  if (!stbi_write_png_to_func(append_bytes, &png, image.width, image.height, 3, image.data.data(),
                              image.width * 3))
    throw_write_error(path, "PNG encoding failed");
  // Text chunks go right after IHDR (8-byte signature + 25-byte IHDR chunk).
  constexpr size_t kAfterIhdr = 33;
  if (png.size() < kAfterIhdr || std::memcmp(png.data() + 12, "IHDR", 4) != 0)
    throw_write_error(path, "unexpected PNG encoder output");
  std::vector<std::uint8_t> chunks;
  for (const auto& [key, value] : meta) {
    const auto chunk = text_chunk(key, value);
    chunks.insert(chunks.end(), chunk.begin(), chunk.end());
  }
  png.insert(png.begin() + kAfterIhdr, chunks.begin(), chunks.end());

  AtomicFile file(path);
  file.write(png.data(), png.size());
  file.commit();
}

namespace {

// The PNG's chunks as stb may read them, up to IEND (what follows is not part of the image).
//  * A chunk that claims more bytes than the file has left is refused here: stb grows its IDAT
//    buffer to the claimed length before reading, so a few corrupt bytes would cost gigabytes
//    (found by the image_png fuzz target, docs/TESTING.md).
//  * Empty IDAT chunks are dropped: stb copies each IDAT's data into a buffer that is still null
//    before the first non-empty one, and memcpy(nullptr, src, 0) is undefined behaviour (found by
//    the same target). An empty IDAT carries no image data, so dropping it changes nothing.
//  * Bytes after the last whole chunk, with no IEND before them, are refused: the file was cut.
// Everything else is copied as it is (stb reports what is corrupt).
std::vector<char> checked_png_chunks(const std::filesystem::path& path,
                                     const std::vector<char>& png) {
  constexpr std::size_t kSignature = 8, kChunkOverhead = 12;  // length, type, CRC
  std::vector<char> out;
  out.reserve(png.size());
  std::size_t pos = std::min(kSignature, png.size());
  out.insert(out.end(), png.begin(), png.begin() + static_cast<std::ptrdiff_t>(pos));
  while (pos + kChunkOverhead <= png.size()) {
    const auto* p = reinterpret_cast<const unsigned char*>(png.data() + pos);
    const std::uint32_t length = (std::uint32_t{p[0]} << 24) | (std::uint32_t{p[1]} << 16) |
                                 (std::uint32_t{p[2]} << 8) | std::uint32_t{p[3]};
    if (length > png.size() - pos - kChunkOverhead)
      throw_read_error(path, fmt::format("truncated or corrupt PNG: the chunk at byte {} claims "
                                         "{} bytes, {} are left",
                                         pos, length, png.size() - pos - kChunkOverhead));
    const std::size_t end = pos + kChunkOverhead + length;
    if (length != 0 || std::memcmp(p + 4, "IDAT", 4) != 0)
      out.insert(out.end(), png.begin() + static_cast<std::ptrdiff_t>(pos),
                 png.begin() + static_cast<std::ptrdiff_t>(end));
    pos = end;
    if (std::memcmp(p + 4, "IEND", 4) == 0) return out;
  }
  // No IEND: what is left is less than a whole chunk (or nothing). stb would read the header of a
  // partial chunk, an empty IDAT's among them (found by the image_png fuzz target), so a file cut
  // short is refused here by name.
  if (pos < png.size())
    throw_read_error(path,
                     fmt::format("truncated PNG: the {} bytes at byte {} are not a whole chunk",
                                 png.size() - pos, pos));
  return out;
}

// A PNG file's bytes for stb, with the header's size (w x h, n channels) checked.
struct PngFile {
  std::vector<char> bytes;
  int w = 0, h = 0, n = 0;
  const stbi_uc* data() const { return reinterpret_cast<const stbi_uc*>(bytes.data()); }
  int size() const { return static_cast<int>(bytes.size()); }
};

PngFile open_png(const std::filesystem::path& path, const ReadImageOptions& options) {
  PngFile png;
  const std::vector<char> bytes = read_file(path);
  // Only PNG: stb would try its other decoders (PNM, TGA, ...) on anything else, and those have
  // their own undefined behaviour on corrupt input (found by the image_png fuzz target).
  constexpr std::string_view kPngSignature{"\x89PNG\r\n\x1a\n", 8};
  if (bytes.size() < kPngSignature.size() ||
      std::string_view(bytes.data(), kPngSignature.size()) != kPngSignature)
    throw_read_error(path, "not a PNG file (no PNG signature)");
  png.bytes = checked_png_chunks(path, bytes);
  if (png.bytes.size() > static_cast<std::size_t>(std::numeric_limits<int>::max()))
    throw_read_error(path, "larger than 2 GB");
  stbi_set_flip_vertically_on_load_thread(0);  // row 0 at the top, whatever others set globally
  // The header's size first: stb allocates the whole decoded image (up to 2^30 bytes) before
  // inflating the data, so a few bytes would otherwise cost up to a gigabyte.
  if (stbi_info_from_memory(png.data(), png.size(), &png.w, &png.h, &png.n) == 0)
    throw_read_error(path, stbi_failure_reason());
  check_read_size(path, png.w, png.h, options);
  return png;
}

}  // namespace

Image8 read_png(const std::filesystem::path& path, const ReadImageOptions& options) {
  PngFile png = open_png(path, options);
  // 8-bit samples as stored (no gamma applied); grey and grey+alpha expand to RGB.
  stbi_uc* pixels = stbi_load_from_memory(png.data(), png.size(), &png.w, &png.h, &png.n, 3);
  if (pixels == nullptr) throw_read_error(path, stbi_failure_reason());
  Image8 image(png.w, png.h);
  std::copy(pixels, pixels + image.data.size(), image.data.begin());
  stbi_image_free(pixels);
  return image;
}

ImageF read_image(const std::filesystem::path& path, const ReadImageOptions& options) {
  // Running out of memory on a file whose header passed the checks names the file too.
  return converting_errors(path, true, [&] {
    ImageF image;
    switch (format_from_path(path)) {
      case ImageFormat::exr:
        image = read_exr(path, options);
        break;
      case ImageFormat::pfm:
        image = read_pfm(path, options);
        break;
      case ImageFormat::hdr:
        image = read_hdr(path, options);
        break;
      case ImageFormat::png:
        throw InvalidArgument(
            fmt::format("cannot read '{}': PNG files are 8-bit previews; read .exr, .hdr or .pfm",
                        shown_path(path)));
    }
    if (!options.allow_non_finite) check_finite(path, image);
    return image;
  });
}

ImageF read_scalar_image(const std::filesystem::path& path, const ReadImageOptions& options) {
  // Running out of memory on a file whose header passed the checks names the file too.
  return converting_errors(path, true, [&] {
    ImageF image;
    switch (format_from_path(path)) {
      case ImageFormat::exr:
        image = read_exr(path, options, true);
        break;
      case ImageFormat::pfm: {
        const ImageF all = read_pfm(path, options);
        image = ImageF(all.width, all.height, 1);
        for (std::size_t i = 0; i < image.data.size(); ++i)
          image.data[i] = all.data[i * static_cast<std::size_t>(all.channels)];
        break;
      }
      case ImageFormat::png: {
        PngFile png = open_png(path, options);
        if (!stbi_is_16_bit_from_memory(png.data(), png.size()))
          throw InvalidArgument(
              fmt::format("cannot read '{}': an 8-bit PNG is too coarse for depth; write 16-bit",
                          shown_path(path)));
        std::uint16_t* pixels =
            stbi_load_16_from_memory(png.data(), png.size(), &png.w, &png.h, &png.n, 1);
        if (pixels == nullptr) throw_read_error(path, stbi_failure_reason());
        image = ImageF(png.w, png.h, 1);
        for (std::size_t i = 0; i < image.data.size(); ++i)
          image.data[i] = static_cast<float>(pixels[i]) / 65535.0f;
        stbi_image_free(pixels);
        break;
      }
      case ImageFormat::hdr:
        throw InvalidArgument(fmt::format(
            "cannot read '{}' as one channel: use .exr (Z, Y or R), .pfm or a 16-bit .png",
            shown_path(path)));
    }
    if (!options.allow_non_finite) check_finite(path, image);
    return image;
  });
}

Metadata read_exr_metadata(const std::filesystem::path& path) {
  open_for_read(path);
  return converting_errors(path, true, [&] {
    exr_data_window(path);  // the header's sizes checked before OpenEXR allocates them
    Imf::InputFile in(path.c_str());
    Metadata meta;
    for (auto it = in.header().begin(); it != in.header().end(); ++it) {
      if (const auto* s = dynamic_cast<const Imf::StringAttribute*>(&it.attribute()))
        meta.emplace_back(it.name(), s->value());
    }
    return meta;
  });
}
}  // namespace skylight::io
