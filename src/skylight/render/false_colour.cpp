// Log-luminance false-colour maps with a legend bar (after Zotti, Wilkie & Purgathofer 2007).
#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <string>
#include <vector>

#include "skylight/core/error.h"
#include "skylight/core/parameters.h"
#include "skylight/render/false_colour.h"

// stb_easy_font.h is a header of static functions; we use only some of them.
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wunused-function"
#include <stb/stb_easy_font.h>
#pragma GCC diagnostic pop

namespace skylight::render {

const ParameterSchema<FalseColourOptions>& FalseColourOptions::schema() {
  static const ParameterSchema<FalseColourOptions> s = [] {
    using F = FalseColourOptions;
    const F d;
    ParameterSchema<F> s;
    s.custom(
        {.name = "false-colour-range",
         .unit = "log10 cd/m^2",
         .kind = ParameterKind::numbers,
         .min = -20.0,
         .max = 20.0,
         .count = 2,
         .default_value = ParameterValue(std::vector<double>{d.log10_min, d.log10_max}),
         .description = "log10 luminance range LO,HI of the false-colour scale"},
        [](F& f, const ParameterValue& v) {
          const auto& r = std::get<std::vector<double>>(v);
          if (!(r[0] < r[1]))
            throw InvalidArgument(fmt::format("{} {},{}: LO must be below HI",
                                              spelled("false-colour-range"), r[0], r[1]));
          f.log10_min = r[0];
          f.log10_max = r[1];
        },
        [](const F& f) -> std::optional<ParameterValue> {
          return std::vector<double>{f.log10_min, f.log10_max};
        });
    return s;
  }();
  return s;
}
namespace {

using Rgb8 = std::array<std::uint8_t, 3>;

constexpr Rgb8 kInvalid = {40, 40, 40};  // negative, zero, non-finite or masked pixels

// One hue per decade, in sRGB-encoded [0, 1] at full brightness, from dark to bright so that the
// map reads like a luminance scale; cycles after the last entry.
constexpr std::array<std::array<double, 3>, 9> kDecadeHues = {{
    {0.25, 0.12, 0.75},  // dark blue / indigo
    {0.00, 0.40, 1.00},  // blue
    {0.00, 0.85, 0.90},  // cyan
    {0.05, 0.80, 0.15},  // green
    {0.95, 0.95, 0.00},  // yellow
    {1.00, 0.55, 0.00},  // orange
    {0.90, 0.05, 0.05},  // red
    {0.90, 0.00, 0.90},  // magenta
    {1.00, 1.00, 1.00},  // white
}};
// Brightness at the bottom of a decade relative to its top: the ramp within a decade, and the
// jump that makes decade boundaries visible.
constexpr double kDecadeFloor = 0.4;
// At most this many decades (a wider range is a mistake and would make an unreadable legend).
constexpr double kMaxDecades = 100.0;

void check_options(const FalseColourOptions& options) {
  if (!std::isfinite(options.log10_min) || !std::isfinite(options.log10_max) ||
      !(options.log10_min < options.log10_max) ||
      options.log10_max - options.log10_min > kMaxDecades)
    throw InvalidArgument(fmt::format(
        "false colour: log10 range [{}, {}] must be finite, increasing and at most {} decades",
        options.log10_min, options.log10_max, kMaxDecades));
}

// The colour of log10 value v on the scale [lo, hi]. Decades are the absolute ones
// [n, n+1) for integer n, so ticks at 10^n fall on colour boundaries; the first decade that
// meets the range gets the first hue. Out-of-range values clamp; NaN is invalid.
Rgb8 colour_of(double v, double lo, double hi) {
  if (std::isnan(v)) return kInvalid;
  v = std::clamp(v, lo, hi);
  const double first = std::floor(lo);
  // A value exactly on a top boundary (v == hi, hi integer) is the top of the decade below.
  const double decade = std::min(std::floor(v), std::ceil(hi) - 1.0);
  const double t = std::clamp(v - decade, 0.0, 1.0);
  const auto index =
      static_cast<size_t>(std::fmod(decade - first, static_cast<double>(kDecadeHues.size())));
  const auto& hue = kDecadeHues[index];
  const double brightness = kDecadeFloor + (1.0 - kDecadeFloor) * t;
  Rgb8 out{};
  for (int c = 0; c < 3; ++c)
    out[c] =
        static_cast<std::uint8_t>(std::lround(std::clamp(hue[c] * brightness, 0.0, 1.0) * 255.0));
  return out;
}

// ---- legend ------------------------------------------------------------------------------------

constexpr Rgb8 kPanel = {0, 0, 0};
constexpr Rgb8 kInk = {230, 230, 230};
constexpr int kGlyphHeight = 7;  // stb_easy_font digits and capitals span 7 units (descenders 9)

struct Rect {
  int x0, y0, x1, y1;  // half-open pixel rectangle [x0, x1) x [y0, y1)
};

void fill(Image8& image, Rect r, const Rgb8& colour, const Rect& clip) {
  r = {std::max(r.x0, clip.x0), std::max(r.y0, clip.y0), std::min(r.x1, clip.x1),
       std::min(r.y1, clip.y1)};
  for (int y = r.y0; y < r.y1; ++y)
    for (int x = r.x0; x < r.x1; ++x) std::copy(colour.begin(), colour.end(), image.pixel(x, y));
}

// stb_easy_font reads its table with (c - 32): keep to printable ASCII.
std::string printable(const std::string& text) {
  std::string s = text;
  for (char& c : s)
    if (c < ' ' || c > '~') c = '?';
  return s;
}

int text_width(const std::string& text, int scale) {
  std::string s = printable(text);
  return stb_easy_font_width(s.data()) * scale;
}

// Draws text with its top-left corner at (x, y), each font unit a scale x scale block; clipped.
void draw_text(Image8& image, int x, int y, const std::string& text, int scale, const Rect& clip) {
  std::string s = printable(text);
  std::vector<char> vertices(s.size() * 1024 + 64);  // ~270 bytes per character on average
  const int quads = stb_easy_font_print(0.0f, 0.0f, s.data(), nullptr, vertices.data(),
                                        static_cast<int>(vertices.size()));
  for (int q = 0; q < quads; ++q) {
    float qx0 = 1e9f, qy0 = 1e9f, qx1 = -1e9f, qy1 = -1e9f;
    for (int v = 0; v < 4; ++v) {  // vertex: x, y, z floats then 4 colour bytes
      float p[2];
      std::memcpy(p, vertices.data() + (static_cast<size_t>(q) * 4 + static_cast<size_t>(v)) * 16,
                  sizeof p);
      qx0 = std::min(qx0, p[0]);
      qx1 = std::max(qx1, p[0]);
      qy0 = std::min(qy0, p[1]);
      qy1 = std::max(qy1, p[1]);
    }
    fill(image,
         {x + static_cast<int>(qx0) * scale, y + static_cast<int>(qy0) * scale,
          x + static_cast<int>(qx1) * scale, y + static_cast<int>(qy1) * scale},
         kInk, clip);
  }
}

// Draws the legend into the panel [x0, image.width) x [0, image.height): the unit on top, a
// vertical colour bar from log10_max (top) to log10_min (bottom), and a tick and a `1eN` label
// at each decade (every k-th decade where they would overlap). Parts that do not fit are left out.
void draw_legend(Image8& image, int x0, const FalseColourOptions& options) {
  const int width = image.width - x0;
  const int height = image.height;
  const Rect panel = {x0, 0, image.width, height};
  fill(image, panel, kPanel, panel);
  if (width <= 0 || height <= 0) return;

  const double lo = options.log10_min;
  const double hi = options.log10_max;
  const int scale = height >= 300 ? 2 : 1;
  const int pad = 2 * scale + 2;
  const int bar_x0 = x0 + pad;
  const int bar_x1 = bar_x0 + 6 * scale + 6;
  // Ticks are drawn over the right half of the bar: outside it they would read as minus signs.
  const int tick_x0 = (bar_x0 + bar_x1) / 2;
  const int label_x = bar_x1 + 2 * scale + 1;

  // Labels: the larger scale only if the widest label fits.
  const int first_decade = static_cast<int>(std::ceil(lo));
  const int last_decade = static_cast<int>(std::floor(hi));
  auto label = [](int decade) { return fmt::format("1e{}", decade); };
  int label_scale = scale;
  int widest = 0;
  for (int d = first_decade; d <= last_decade; ++d)
    widest = std::max(widest, text_width(label(d), 1));
  if (label_x + widest * label_scale > image.width) label_scale = 1;
  const int label_h = kGlyphHeight * label_scale;

  // The unit on top, at the larger scale only if it fits (clipped if even scale 1 does not).
  int unit_scale = scale;
  if (x0 + pad + text_width(options.unit, unit_scale) > image.width) unit_scale = 1;
  const int unit_h = (kGlyphHeight + 2) * unit_scale;  // room for descenders

  int top = pad + unit_h + pad + label_h / 2;
  int bottom = height - 1 - pad - label_h / 2;
  bool show_unit = true;
  bool show_labels = true;
  if (bottom - top < 2 * label_h) {  // short image: drop the unit first
    show_unit = false;
    top = pad + label_h / 2;
  }
  if (bottom - top < label_h) {  // still too short: the bar alone, as tall as possible
    show_labels = false;
    top = std::min(pad, height / 4);
    bottom = height - 1 - top;
  }
  if (show_unit) draw_text(image, x0 + pad, pad, options.unit, unit_scale, panel);

  // Colour bar: row y shows the value at its centre, hi at `top`, lo at `bottom`.
  const double span = std::max(1, bottom - top);
  auto row_of = [&](double v) {
    return top + static_cast<int>(std::lround((hi - v) / (hi - lo) * span));
  };
  for (int y = top; y <= bottom; ++y) {
    const double v = hi - (y - top) / span * (hi - lo);
    fill(image, {bar_x0, y, bar_x1, y + 1}, colour_of(v, lo, hi), panel);
  }
  if (!show_labels) return;

  // Ticks and labels, every `step` decades so that labels do not overlap.
  const double px_per_decade = span / (hi - lo);
  const int step = std::max(1, static_cast<int>(std::ceil((label_h + 3) / px_per_decade)));
  for (int d = first_decade; d <= last_decade; ++d) {
    if (((d % step) + step) % step != 0) continue;
    const int y = row_of(d);
    fill(image, {tick_x0, y, bar_x1, y + 1}, kInk, panel);
    draw_text(image, label_x, y - label_h / 2, label(d), label_scale, panel);
  }
}

}  // namespace

std::array<std::uint8_t, 3> false_colour_of(double log10_value, const FalseColourOptions& options) {
  check_options(options);
  return colour_of(log10_value, options.log10_min, options.log10_max);
}

Image8 false_colour(const ImageF& luminance, const FalseColourOptions& options,
                    const std::vector<std::uint8_t>* mask) {
  check_options(options);
  if (luminance.channels != 1)
    throw InvalidArgument(
        fmt::format("false colour: expected a one-channel luminance image, got {} channels",
                    luminance.channels));
  if (luminance.width < 0 || luminance.height < 0)
    throw InvalidArgument(
        fmt::format("false colour: bad image size {}x{}", luminance.width, luminance.height));
  const size_t pixels =
      static_cast<size_t>(luminance.width) * static_cast<size_t>(luminance.height);
  if (luminance.data.size() != pixels)
    throw InvalidArgument(fmt::format("false colour: image data has {} values, expected {}",
                                      luminance.data.size(), pixels));
  if (mask != nullptr && mask->size() != pixels)
    throw InvalidArgument(
        fmt::format("false colour: mask has {} entries, expected {}", mask->size(), pixels));

  // Legend panel: 90 px for images at least 300 px tall (text at scale 2), else 60 px.
  const int panel = options.legend ? (luminance.height >= 300 ? 90 : 60) : 0;
  Image8 out(luminance.width + panel, luminance.height);
  for (int y = 0; y < luminance.height; ++y) {
    for (int x = 0; x < luminance.width; ++x) {
      const size_t i =
          static_cast<size_t>(y) * static_cast<size_t>(luminance.width) + static_cast<size_t>(x);
      const float l = luminance.data[i];
      const bool valid = std::isfinite(l) && l > 0.0f && (mask == nullptr || (*mask)[i] == 0);
      const Rgb8 c =
          valid ? colour_of(std::log10(double{l}), options.log10_min, options.log10_max) : kInvalid;
      std::copy(c.begin(), c.end(), out.pixel(x, y));
    }
  }
  if (options.legend) draw_legend(out, luminance.width, options);
  return out;
}

}  // namespace skylight::render
