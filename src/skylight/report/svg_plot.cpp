#include "skylight/report/svg_plot.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

#include "skylight/core/error.h"

namespace skylight::report::svg {
namespace {

constexpr std::string_view kFont = "DejaVu Sans, Arial, Helvetica, sans-serif";
constexpr std::string_view kInk = "#222222";
constexpr std::string_view kGrid = "#dddddd";
// Rough width of a character of the sans-serif font relative to its size, to lay out legends.
constexpr double kCharWidth = 0.55;

// Coordinates with 2 decimals: sub-pixel precision without bloating the files.
std::string num(double v) {
  if (!std::isfinite(v)) return "0";
  std::string s = fmt::format("{:.2f}", v);
  while (!s.empty() && s.back() == '0') s.pop_back();
  if (!s.empty() && s.back() == '.') s.pop_back();
  if (s == "-0") s = "0";
  return s;
}

double text_width(std::string_view s, double size) {
  // UTF-8 continuation bytes do not start a character.
  double n = 0;
  for (unsigned char c : s)
    if ((c & 0xC0) != 0x80) n += 1;
  return n * size * kCharWidth;
}

// Data value -> axis coordinate (log10 for log axes); NaN for values a log axis cannot show.
double axis_value(const Axis& a, double v) {
  if (!a.log) return v;
  return v > 0.0 ? std::log10(v) : std::nan("");
}

void check_axis(const Axis& a, std::string_view which) {
  if (!(std::isfinite(a.min) && std::isfinite(a.max) && a.min < a.max) || (a.log && !(a.min > 0.0)))
    throw InvalidArgument(
        fmt::format("plot: {} axis range [{}, {}] must be finite and increasing "
                    "(and positive on a log axis)",
                    which, a.min, a.max));
}

}  // namespace

std::string escape(std::string_view text) {
  std::string out;
  out.reserve(text.size());
  for (char c : text) {
    switch (c) {
      case '&':
        out += "&amp;";
        break;
      case '<':
        out += "&lt;";
        break;
      case '>':
        out += "&gt;";
        break;
      case '"':
        out += "&quot;";
        break;
      case '\'':
        out += "&#39;";
        break;
      default:
        out += c;
    }
  }
  return out;
}

std::string hex_colour(const std::array<std::uint8_t, 3>& rgb) {
  return fmt::format("#{:02x}{:02x}{:02x}", rgb[0], rgb[1], rgb[2]);
}

// ---- Canvas ----------------------------------------------------------------------------------

std::string Canvas::new_id(std::string_view name) {
  return fmt::format("{}-{}-{}", id_prefix_, name, next_id_++);
}

void Canvas::rect(double x, double y, double w, double h, std::string_view fill,
                  std::string_view stroke, double stroke_width) {
  body_ += fmt::format(R"(<rect x="{}" y="{}" width="{}" height="{}" fill="{}")", num(x), num(y),
                       num(w), num(h), fill);
  if (stroke != "none")
    body_ += fmt::format(R"( stroke="{}" stroke-width="{}")", stroke, num(stroke_width));
  body_ += "/>\n";
}

void Canvas::line(double x0, double y0, double x1, double y1, std::string_view stroke,
                  double stroke_width, std::string_view dash) {
  body_ += fmt::format(R"(<line x1="{}" y1="{}" x2="{}" y2="{}" stroke="{}" stroke-width="{}")",
                       num(x0), num(y0), num(x1), num(y1), stroke, num(stroke_width));
  if (!dash.empty()) body_ += fmt::format(R"( stroke-dasharray="{}")", dash);
  body_ += "/>\n";
}

void Canvas::polyline(const std::vector<std::array<double, 2>>& points, std::string_view stroke,
                      double stroke_width, std::string_view dash, std::string_view clip_id) {
  if (points.size() < 2) return;
  std::string pts;
  for (const auto& p : points) {
    if (!pts.empty()) pts += ' ';
    pts += num(p[0]) + "," + num(p[1]);
  }
  body_ += fmt::format(
      R"(<polyline points="{}" fill="none" stroke="{}" stroke-width="{}" stroke-linejoin="round")",
      pts, stroke, num(stroke_width));
  if (!dash.empty()) body_ += fmt::format(R"( stroke-dasharray="{}")", dash);
  if (!clip_id.empty()) body_ += fmt::format(" clip-path=\"url(#{})\"", clip_id);
  body_ += "/>\n";
}

void Canvas::circle(double cx, double cy, double r, std::string_view fill, std::string_view stroke,
                    std::string_view clip_id) {
  body_ +=
      fmt::format(R"(<circle cx="{}" cy="{}" r="{}" fill="{}")", num(cx), num(cy), num(r), fill);
  if (stroke != "none") body_ += fmt::format(R"( stroke="{}" stroke-width="0.6")", stroke);
  if (!clip_id.empty()) body_ += fmt::format(" clip-path=\"url(#{})\"", clip_id);
  body_ += "/>\n";
}

void Canvas::text(double x, double y, std::string_view content, double size,
                  std::string_view anchor, double rotate, std::string_view weight) {
  body_ += fmt::format(R"(<text x="{}" y="{}" font-size="{}" text-anchor="{}")", num(x), num(y),
                       num(size), anchor);
  if (rotate != 0.0)
    body_ += fmt::format(" transform=\"rotate({} {} {})\"", num(rotate), num(x), num(y));
  if (!weight.empty()) body_ += fmt::format(R"( font-weight="{}")", weight);
  body_ += '>';
  body_ += escape(content);
  body_ += "</text>\n";
}

void Canvas::image(double x, double y, double w, double h, std::string_view href, bool pixelated) {
  const std::string h_esc = escape(href);
  body_ += fmt::format(R"(<image x="{}" y="{}" width="{}" height="{}" href="{}" xlink:href="{}" )"
                       R"(preserveAspectRatio="none")",
                       num(x), num(y), num(w), num(h), h_esc, h_esc);
  if (pixelated) body_ += R"( style="image-rendering:pixelated" image-rendering="optimizeSpeed")";
  body_ += "/>\n";
  images_.emplace_back(href);
}

void Canvas::clip_rect(std::string_view id, double x, double y, double w, double h) {
  body_ +=
      fmt::format(R"(<clipPath id="{}"><rect x="{}" y="{}" width="{}" height="{}"/></clipPath>)"
                  "\n",
                  id, num(x), num(y), num(w), num(h));
}

std::string Canvas::svg() const {
  return fmt::format(
      R"(<svg xmlns="http://www.w3.org/2000/svg" xmlns:xlink="http://www.w3.org/1999/xlink" )"
      R"(version="1.1" width="{}" height="{}" viewBox="0 0 {} {}" font-family="{}">)"
      "\n"
      R"(<rect x="0" y="0" width="{}" height="{}" fill="white"/>)"
      "\n{}</svg>\n",
      num(width_), num(height_), num(width_), num(height_), kFont, num(width_), num(height_),
      body_);
}

std::string Canvas::document() const {
  return "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n" + svg();
}

Series line_series(std::string name, std::vector<double> x, std::vector<double> y,
                   std::string colour, double width, std::string dash) {
  Series s;
  s.name = std::move(name);
  s.x = std::move(x);
  s.y = std::move(y);
  s.colour = std::move(colour);
  s.width = width;
  s.dash = std::move(dash);
  return s;
}

Series marker_series(std::string name, std::vector<double> x, std::vector<double> y,
                     std::string colour, double radius) {
  Series s = line_series(std::move(name), std::move(x), std::move(y), std::move(colour));
  s.line = false;
  s.marker = Marker::circle;
  s.marker_radius = radius;
  return s;
}

// ---- ticks -----------------------------------------------------------------------------------

std::vector<double> auto_ticks(const Axis& a, int target) {
  check_axis(a, "tick");
  std::vector<double> ticks;
  if (a.log) {
    const double lo = std::log10(a.min), hi = std::log10(a.max);
    const int d0 = static_cast<int>(std::floor(lo)), d1 = static_cast<int>(std::ceil(hi));
    const double span = hi - lo;
    const int every = std::max(1, static_cast<int>(std::ceil(span / std::max(target, 1))));
    for (int d = d0; d <= d1; ++d) {
      if (span < 3.0) {
        for (double m : {1.0, 2.0, 5.0}) {
          const double v = m * std::pow(10.0, d);
          if (v >= a.min * (1 - 1e-12) && v <= a.max * (1 + 1e-12)) ticks.push_back(v);
        }
      } else if (d % every == 0) {
        const double v = std::pow(10.0, d);
        if (v >= a.min * (1 - 1e-12) && v <= a.max * (1 + 1e-12)) ticks.push_back(v);
      }
    }
    return ticks;
  }
  const double raw = (a.max - a.min) / std::max(target, 1);
  const double mag = std::pow(10.0, std::floor(std::log10(raw)));
  double step = mag;
  for (double m : {1.0, 2.0, 2.5, 5.0, 10.0}) {
    step = m * mag;
    if (step >= raw) break;
  }
  const double first = std::ceil(a.min / step - 1e-9) * step;
  for (double v = first; v <= a.max + 1e-9 * step; v += step)
    ticks.push_back(std::abs(v) < 1e-12 * step ? 0.0 : v);
  return ticks;
}

std::string tick_label(double v) {
  if (v == 0.0) return "0";
  const double a = std::abs(v);
  if (a >= 1e-3 && a < 1e6) {
    std::string s = fmt::format("{:.3f}", v);
    while (s.back() == '0') s.pop_back();
    if (s.back() == '.') s.pop_back();
    return s;
  }
  const int e = static_cast<int>(std::floor(std::log10(a)));
  const double m = v / std::pow(10.0, e);
  if (std::abs(m - std::round(m)) < 1e-9 && std::round(std::abs(m)) == 1.0)
    return fmt::format("{}1e{}", v < 0 ? "-" : "", e);
  return fmt::format("{:.3g}e{}", m, e);
}

std::vector<std::string> tick_labels(const std::vector<double>& ticks) {
  // Fixed notation when every non-zero tick has it in tick_label(), else exponents for all.
  bool fixed = true;
  for (double v : ticks)
    if (v != 0.0 && !(std::abs(v) >= 1e-3 && std::abs(v) < 1e6)) fixed = false;
  std::vector<std::string> labels;
  for (double v : ticks) {
    if (fixed || v == 0.0) {
      labels.push_back(tick_label(v));
      continue;
    }
    const int e = static_cast<int>(std::floor(std::log10(std::abs(v)) + 1e-12));
    const double m = v / std::pow(10.0, e);
    labels.push_back(std::abs(std::abs(m) - 1.0) < 1e-9 ? fmt::format("{}1e{}", v < 0 ? "-" : "", e)
                                                        : fmt::format("{:.3g}e{}", m, e));
  }
  return labels;
}

// ---- colour bar ------------------------------------------------------------------------------

void draw_colour_bar(Canvas& c, double x, double y, double w, double h, const ColourBar& bar) {
  const render::FalseColourOptions fo{bar.log10_min, bar.log10_max, bar.unit, false};
  const double lo = bar.log10_min, hi = bar.log10_max;
  // The scale is linear in the sRGB-encoded value within each decade and jumps at decade
  // boundaries, so a vertical linear gradient with two stops per decade reproduces it exactly.
  const std::string id = c.new_id("bar");
  std::string stops;
  auto stop = [&](double v, double at) {
    stops += fmt::format(R"(<stop offset="{:.6f}" stop-color="{}"/>)", (hi - at) / (hi - lo),
                         hex_colour(render::false_colour_of(v, fo)));
  };
  // From the top (hi) down to lo, offset 0 at the top.
  double top = hi;
  while (top > lo + 1e-12) {
    const double decade = std::floor(top - 1e-9);  // the decade [decade, decade + 1) below top
    const double bottom = std::max(decade, lo);
    stop(top - 1e-9, top);
    stop(bottom + 1e-9, bottom);
    top = bottom;
  }
  c.raw(fmt::format(
      R"(<defs><linearGradient id="{}" x1="0" y1="0" x2="0" y2="1">{}</linearGradient></defs>)"
      "\n",
      id, stops));
  c.rect(x, y, w, h, fmt::format("url(#{})", id), std::string(kInk), 0.8);
  if (!bar.unit.empty()) c.text(x, y - 8, bar.unit, 11);
  for (int d = static_cast<int>(std::ceil(lo - 1e-9)); d <= static_cast<int>(std::floor(hi + 1e-9));
       ++d) {
    const double ty = y + (hi - d) / (hi - lo) * h;
    c.line(x + w, ty, x + w + 4, ty, kInk, 1.0);
    c.text(x + w + 6, ty + 4, fmt::format("1e{}{}", d, bar.tick_unit), 10);
  }
}

// ---- plots -----------------------------------------------------------------------------------

namespace {

// The plot area of a Plot in canvas pixels and the map from axis values into it.
struct PlotArea {
  const Plot& p;
  double left, top, pw, ph;
  double x0, x1, y0, y1;  // the axes' ends, through axis_value
  PlotArea(const Plot& plot, double l, double t, double w, double h)
      : p(plot), left(l), top(t), pw(w), ph(h) {
    x0 = axis_value(p.x, p.x.min);
    x1 = axis_value(p.x, p.x.max);
    y0 = axis_value(p.y, p.y.min);
    y1 = axis_value(p.y, p.y.max);
  }
  double px(double v) const { return left + (axis_value(p.x, v) - x0) / (x1 - x0) * pw; }
  double py(double v) const { return top + ph - (axis_value(p.y, v) - y0) / (y1 - y0) * ph; }
};

// Grid, ticks and axis labels.
void draw_axes(Canvas& c, const PlotArea& a) {
  const Plot& p = a.p;
  // The ticks inside the range, labelled in one notation per axis (tick_labels).
  auto shown = [](const Axis& axis) {
    std::vector<double> v;
    for (double t : axis.ticks.empty() ? auto_ticks(axis) : axis.ticks)
      if (t >= axis.min && t <= axis.max) v.push_back(t);
    return v;
  };
  const auto xt = shown(p.x), yt = shown(p.y);
  const auto xl = tick_labels(xt), yl = tick_labels(yt);
  const bool grid = p.background_image.empty() && p.regions.empty();
  for (std::size_t i = 0; i < xt.size(); ++i) {
    const double X = a.px(xt[i]);
    if (grid) c.line(X, a.top, X, a.top + a.ph, kGrid, 0.8);
    c.line(X, a.top + a.ph, X, a.top + a.ph + 5, kInk, 1.0);
    c.text(X, a.top + a.ph + 18, xl[i], 11, "middle");
  }
  for (std::size_t i = 0; i < yt.size(); ++i) {
    const double Y = a.py(yt[i]);
    if (grid) c.line(a.left, Y, a.left + a.pw, Y, kGrid, 0.8);
    c.line(a.left - 5, Y, a.left, Y, kInk, 1.0);
    c.text(a.left - 8, Y + 4, yl[i], 11, "end");
  }
  c.text(a.left + a.pw / 2, p.height - 8, p.x.label, 12, "middle");
  c.text(16, a.top + a.ph / 2, p.y.label, 12, "middle", -90);
}

// Regions and series, clipped to the plot area; gaps at values the axes cannot show.
void draw_series(Canvas& c, const PlotArea& a) {
  const Plot& p = a.p;
  const std::string clip = c.new_id("clip");
  c.clip_rect(clip, a.left, a.top, a.pw, a.ph);
  for (const auto& r : p.regions) {
    const double xa = a.px(r.x0), xb = a.px(r.x1), ya = a.py(r.y0), yb = a.py(r.y1);
    if (!std::isfinite(xa) || !std::isfinite(xb) || !std::isfinite(ya) || !std::isfinite(yb))
      continue;
    c.rect(std::min(xa, xb), std::min(ya, yb), std::abs(xb - xa), std::abs(yb - ya), r.colour);
  }
  for (const auto& s : p.series) {
    if (s.x.size() != s.y.size())
      throw InvalidArgument(fmt::format("plot '{}': series '{}' has {} x and {} y values", p.id,
                                        s.name, s.x.size(), s.y.size()));
    std::vector<std::array<double, 2>> run;
    auto flush = [&] {
      if (s.line) c.polyline(run, s.colour, s.width, s.dash, clip);
      run.clear();
    };
    for (std::size_t i = 0; i < s.x.size(); ++i) {
      const double X = a.px(s.x[i]), Y = a.py(s.y[i]);
      if (!std::isfinite(X) || !std::isfinite(Y)) {
        flush();
        continue;
      }
      // Keep far-off points finite but outside the area (the clip path hides them).
      run.push_back({std::clamp(X, -1e5, 1e5), std::clamp(Y, -1e5, 1e5)});
      if (s.marker == Marker::circle && X >= a.left - 1 && X <= a.left + a.pw + 1 &&
          Y >= a.top - 1 && Y <= a.top + a.ph + 1)
        c.circle(X, Y, s.marker_radius, s.colour, s.marker_stroke, clip);
    }
    flush();
  }
}

// The named series and the swatches: what the legend lists, and its width.
struct Legend {
  std::vector<const Series*> named;
  double width = 0.0;
  int rows = 0;
  explicit Legend(const Plot& p) {
    for (const auto& s : p.series)
      if (!s.name.empty()) named.push_back(&s);
    for (const auto* s : named) width = std::max(width, 34 + text_width(s->name, 11));
    for (const auto& s : p.swatches) width = std::max(width, 22 + text_width(s.name, 11));
    width += 10;
    rows = static_cast<int>(named.size() + p.swatches.size());
  }
};

void draw_legend(Canvas& c, const PlotArea& a, const Legend& legend) {
  const Plot& p = a.p;
  const double row_h = 16;
  const double lh = legend.rows * row_h + 8;
  // Outside: right of the plot area and of the colour bar.
  const double lx = p.legend_outside ? a.left + a.pw + (p.has_colour_bar ? 84 : 10)
                                     : a.left + a.pw - legend.width - 6;
  const double ly = p.legend_outside ? a.top : a.top + 6;
  c.rect(lx, ly, legend.width, lh, "white", "#999999", 0.8);
  double ry = ly + 4 + row_h / 2;
  for (const auto* s : legend.named) {
    if (s->line) c.line(lx + 6, ry, lx + 28, ry, s->colour, s->width, s->dash);
    if (s->marker == Marker::circle)
      c.circle(lx + 17, ry, s->marker_radius, s->colour, s->marker_stroke);
    c.text(lx + 34, ry + 4, s->name, 11);
    ry += row_h;
  }
  for (const auto& sw : p.swatches) {
    c.rect(lx + 6, ry - 6, 12, 12, sw.colour, "#555555", 0.6);
    c.text(lx + 22, ry + 4, sw.name, 11);
    ry += row_h;
  }
}

}  // namespace

Canvas draw(const Plot& p) {
  check_axis(p.x, "x");
  check_axis(p.y, "y");
  Canvas c(p.width, p.height, p.id.empty() ? std::string("plot") : p.id);
  const Legend legend(p);
  const double left = 68, top = p.title.empty() ? 14 : 32, bottom = 46;
  double right = 16;
  if (p.has_colour_bar) right += 74;
  if (p.legend_outside && legend.rows > 0) right += legend.width + 8;
  const double pw = p.width - left - right, ph = p.height - top - bottom;
  if (!(pw > 10 && ph > 10))
    throw InvalidArgument(fmt::format("plot '{}': {}x{} px is too small", p.id, p.width, p.height));
  const PlotArea area(p, left, top, pw, ph);
  if (!p.title.empty()) c.text(left, 20, p.title, 13, "start", 0, "bold");
  if (!p.background_image.empty()) c.image(left, top, pw, ph, p.background_image, p.pixelated);
  draw_axes(c, area);
  draw_series(c, area);
  c.rect(left, top, pw, ph, "none", std::string(kInk), 1.0);
  if (legend.rows > 0) draw_legend(c, area, legend);
  if (p.has_colour_bar) draw_colour_bar(c, left + pw + 16, top + 14, 14, ph - 14, p.colour_bar);
  return c;
}

Canvas draw(const Mosaic& m) {
  if (m.rows <= 0 || m.columns <= 0 || m.tile_px <= 0 || m.gap_px < 0 || !(m.scale > 0))
    throw InvalidArgument(fmt::format("mosaic '{}': bad layout {}x{} tiles of {} px", m.id, m.rows,
                                      m.columns, m.tile_px));
  if (m.row_labels.size() != static_cast<std::size_t>(m.rows) ||
      m.column_labels.size() != static_cast<std::size_t>(m.columns))
    throw InvalidArgument(fmt::format("mosaic '{}': {} row and {} column labels for {}x{} tiles",
                                      m.id, m.row_labels.size(), m.column_labels.size(), m.rows,
                                      m.columns));
  const double cell = (m.tile_px + m.gap_px) * m.scale;
  const double img_w = (m.columns * (m.tile_px + m.gap_px) - m.gap_px) * m.scale;
  const double img_h = (m.rows * (m.tile_px + m.gap_px) - m.gap_px) * m.scale;
  double label_w = text_width(m.row_header, 12);
  for (const auto& l : m.row_labels) label_w = std::max(label_w, text_width(l, 12));
  const double left = label_w + 16, top = (m.title.empty() ? 12 : 34) + 30;
  const double bar_w = 90;
  // The colour bar is at least kMinColourBarPx tall (readable decades) even beside a short image.
  const double bar_h = std::max(kMinColourBarPx, img_h - 10);
  Canvas c(left + img_w + bar_w + 10, std::max(top + img_h, top + 10 + bar_h + 20) + 12,
           m.id.empty() ? "mosaic" : m.id);
  if (!m.title.empty()) c.text(8, 20, m.title, 13, "start", 0, "bold");
  c.text(left + img_w / 2, top - 24, m.column_header, 12, "middle");
  c.text(left - 8, top - 8, m.row_header, 12, "end", 0, "bold");
  for (int k = 0; k < m.columns; ++k)
    c.text(left + k * cell + m.tile_px * m.scale / 2, top - 8, m.column_labels[k], 11, "middle");
  for (int r = 0; r < m.rows; ++r)
    c.text(left - 8, top + r * cell + m.tile_px * m.scale / 2 + 4, m.row_labels[r], 11, "end");
  c.image(left, top, img_w, img_h, m.image);
  draw_colour_bar(c, left + img_w + 14, top + 10, 14, bar_h, m.colour_bar);
  return c;
}

}  // namespace skylight::report::svg
