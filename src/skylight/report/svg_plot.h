// A small direct-SVG plotting layer for the validation report (report/report.h): axes with ticks
// and labels (linear or log10), line and marker series, categorical and colour-bar legends, and
// raster maps embedded as <image href="file.png"> (the PNG is written next to the SVG).
//
// Why direct SVG: no extra dependency (PLplot or gnuplot would add a package and a process), the
// output is vector graphics whose text stays searchable and selectable in the HTML report, and it
// is deterministic (the same numbers give the same bytes), so the report can be tested as text.
#pragma once

#include <array>
#include <cstdint>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "skylight/render/false_colour.h"

namespace skylight::report::svg {

// XML-escapes text for element content and attribute values (&, <, >, ", ').
std::string escape(std::string_view text);
// "#rrggbb" for an 8-bit colour.
std::string hex_colour(const std::array<std::uint8_t, 3>& rgb);

// An SVG document under construction: elements are appended as text in user units (px).
class Canvas {
 public:
  // id_prefix makes the ids of clip paths and gradients unique within an HTML page.
  Canvas(double width, double height, std::string id_prefix = "fig")
      : width_(width), height_(height), id_prefix_(std::move(id_prefix)) {}
  double width() const { return width_; }
  double height() const { return height_; }

  void rect(double x, double y, double w, double h, std::string_view fill,
            std::string_view stroke = "none", double stroke_width = 1.0);
  void line(double x0, double y0, double x1, double y1, std::string_view stroke,
            double stroke_width = 1.0, std::string_view dash = "");
  // A polyline through the points; `clip_id` (optional) names a clipPath.
  void polyline(const std::vector<std::array<double, 2>>& points, std::string_view stroke,
                double stroke_width, std::string_view dash = "", std::string_view clip_id = "");
  void circle(double cx, double cy, double r, std::string_view fill,
              std::string_view stroke = "none", std::string_view clip_id = "");
  // anchor: "start", "middle" or "end"; rotate: degrees about (x, y).
  void text(double x, double y, std::string_view content, double size = 12.0,
            std::string_view anchor = "start", double rotate = 0.0, std::string_view weight = "");
  // A raster image file referenced by a relative path (href and xlink:href, for old viewers).
  // pixelated: nearest-neighbour scaling (categorical maps).
  void image(double x, double y, double w, double h, std::string_view href, bool pixelated = false);
  // A clipPath rectangle with the given id, for series drawn inside a plot area.
  void clip_rect(std::string_view id, double x, double y, double w, double h);
  void raw(std::string_view element) { body_ += element; }
  // A fresh id "<prefix>-<name>-<n>" for a definition (clip path, gradient).
  std::string new_id(std::string_view name);

  // The <svg> element with xmlns (valid inline in HTML and as a file).
  std::string svg() const;
  // A standalone file: XML declaration + svg().
  std::string document() const;
  // Relative paths of every raster image referenced, in order.
  const std::vector<std::string>& images() const { return images_; }

 private:
  double width_, height_;
  std::string id_prefix_;
  int next_id_ = 0;
  std::string body_;
  std::vector<std::string> images_;
};

struct Axis {
  double min = 0.0, max = 1.0;  // data range shown (log: both > 0)
  bool log = false;             // log10 scale
  std::string label;
  // Tick positions in data units; empty = automatic (1-2-5 steps, or decades for log).
  std::vector<double> ticks;
};

// Automatic ticks: linear 1-2-5 steps (about `target` of them), or for log axes the decades
// (with 2 and 5 in between when the range spans fewer than three decades).
std::vector<double> auto_ticks(const Axis& axis, int target = 6);
// Tick label: shortest of fixed or exponent notation that shows the value to 3 digits.
std::string tick_label(double value);
// The labels of one axis's ticks in one notation: tick_label() when every non-zero tick is shown
// in fixed notation, else exponents for all ("1e2", "1e3", "1e4", "2.5e6"; 0 stays "0").
std::vector<std::string> tick_labels(const std::vector<double>& ticks);

enum class Marker { none, circle };

struct Series {
  std::string name;  // legend entry; empty = not in the legend
  std::vector<double> x, y;
  std::string colour = "#1f77b4";
  double width = 1.5;
  std::string dash;  // stroke-dasharray, e.g. "6 3"; empty = solid
  bool line = true;
  Marker marker = Marker::none;
  double marker_radius = 2.5;
  std::string marker_stroke = "none";  // outline of the markers (e.g. for white markers)
};

// A line series (dash: stroke-dasharray, empty = solid) and a marker-only series.
Series line_series(std::string name, std::vector<double> x, std::vector<double> y,
                   std::string colour, double width = 1.5, std::string dash = "");
Series marker_series(std::string name, std::vector<double> x, std::vector<double> y,
                     std::string colour, double radius = 2.5);

// A categorical legend entry drawn as a filled square.
struct Swatch {
  std::string name;
  std::string colour;
};

// The shortest colour bar drawn [px]: a bar beside a plot or mosaic is at least this tall.
inline constexpr double kMinColourBarPx = 200.0;

// A vertical colour bar on the false-colour scale of render/image.h.
struct ColourBar {
  double log10_min = 0.0, log10_max = 6.0;
  std::string unit;       // shown above the bar
  std::string tick_unit;  // appended to each decade label ("%" or "")
};

// A filled rectangle in data coordinates [x0, x1] x [y0, y1] (e.g. a cell of a categorical map).
struct Region {
  double x0 = 0, x1 = 0, y0 = 0, y1 = 0;
  std::string colour;
};

// A 2-D plot: axes, an optional raster image filling the plot area (the data range of both axes),
// regions, series on top (clipped to the area), a legend of series and swatches, an optional colour
// bar.
struct Plot {
  std::string id;  // unique within an HTML page (prefixes the clipPath id)
  std::string title;
  Axis x, y;
  std::vector<Region> regions;  // drawn under the series, clipped to the plot area
  std::vector<Series> series;
  std::vector<Swatch> swatches;
  std::string background_image;  // relative PNG path; empty = none
  bool pixelated = false;        // nearest-neighbour scaling of the image
  bool has_colour_bar = false;
  ColourBar colour_bar;
  double width = 640, height = 400;
  bool legend_outside = false;  // legend right of the plot area instead of inside its top right
};

Canvas draw(const Plot& plot);

// Draws a colour bar with its top-left corner at (x, y).
void draw_colour_bar(Canvas& c, double x, double y, double w, double h, const ColourBar& bar);

// A mosaic of equally sized tiles (one PNG holding the whole grid) with column and row labels, as
// Zotti et al. 2007 Figs. 4-7: tile (row r, column k) occupies pixels [k (tile + gap), ...) of the
// PNG. The SVG scales the PNG by `scale`.
struct Mosaic {
  std::string id, title;
  std::string image;  // relative PNG path
  int rows = 0, columns = 0;
  int tile_px = 0, gap_px = 0;  // in PNG pixels
  double scale = 1.0;
  std::string row_header, column_header;  // e.g. "T", "θs [deg]"
  std::vector<std::string> row_labels, column_labels;
  ColourBar colour_bar;
};
Canvas draw(const Mosaic& mosaic);

}  // namespace skylight::report::svg
