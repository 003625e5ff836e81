#include "skylight/report/svg_plot.h"

#include <gtest/gtest.h>

#include <cmath>
#include <regex>
#include <string>

#include "skylight/core/error.h"
#include "skylight/io/image.h"
#include "support/xml_check.h"

namespace skylight::report::svg {
namespace {

using skylight::testing_support::check_xml;

TEST(SvgXmlCheck, AcceptsWellFormedAndRejectsBroken) {
  EXPECT_TRUE(check_xml("<?xml version=\"1.0\"?>\n<a x=\"1\"><b/>t &amp; u</a>").ok);
  EXPECT_FALSE(check_xml("<a><b></a></b>").ok);
  EXPECT_FALSE(check_xml("<a x=1/>").ok);
  EXPECT_FALSE(check_xml("<a>1 < 2</a>").ok);
  EXPECT_FALSE(check_xml("<a>R&D</a>").ok);
  EXPECT_FALSE(check_xml("<a x=\"1\" x=\"2\"/>").ok);
  EXPECT_FALSE(check_xml("<a/><b/>").ok);
  EXPECT_FALSE(check_xml("<a>").ok);
}

TEST(SvgEscape, EscapesMarkupCharacters) {
  EXPECT_EQ(escape(R"(a<b>&"c'd)"), "a&lt;b&gt;&amp;&quot;c&#39;d");
  EXPECT_EQ(escape("theta_s [deg]"), "theta_s [deg]");
  EXPECT_EQ(hex_colour({255, 0, 16}), "#ff0010");
}

TEST(SvgTicks, LinearStepsAreOneTwoFive) {
  const auto t = auto_ticks({0.0, 90.0, false, "", {}}, 6);
  ASSERT_FALSE(t.empty());
  EXPECT_DOUBLE_EQ(t.front(), 0.0);
  EXPECT_DOUBLE_EQ(t.back(), 80.0);
  EXPECT_DOUBLE_EQ(t[1] - t[0], 20.0);  // 90 / 6 = 15 -> the next 1-2-2.5-5 step is 20
  const auto u = auto_ticks({-0.3, 0.7, false, "", {}}, 5);
  for (double v : u) {
    EXPECT_GE(v, -0.3);
    EXPECT_LE(v, 0.7);
  }
  EXPECT_EQ(u.size(), 5u);  // -0.2, 0, 0.2, 0.4, 0.6
}

TEST(SvgTicks, LogAxesUseDecades) {
  const auto t = auto_ticks({100.0, 1e6, true, "", {}}, 6);
  ASSERT_EQ(t.size(), 5u);
  for (std::size_t i = 0; i < t.size(); ++i)
    EXPECT_NEAR(t[i], std::pow(10.0, 2.0 + static_cast<double>(i)), 1e-9 * t[i]);
  // Less than three decades: 1, 2, 5 per decade.
  const auto u = auto_ticks({0.1, 10.0, true, "", {}}, 6);
  const std::vector<double> want = {0.1, 0.2, 0.5, 1, 2, 5, 10};
  ASSERT_EQ(u.size(), want.size());
  for (std::size_t i = 0; i < u.size(); ++i) EXPECT_NEAR(u[i], want[i], 1e-12);
  EXPECT_THROW(auto_ticks({0.0, 10.0, true, "", {}}), InvalidArgument);
}

TEST(SvgTicks, Labels) {
  EXPECT_EQ(tick_label(0.0), "0");
  EXPECT_EQ(tick_label(20.0), "20");
  EXPECT_EQ(tick_label(2.5), "2.5");
  EXPECT_EQ(tick_label(0.125), "0.125");
  EXPECT_EQ(tick_label(125000.0), "125000");
  EXPECT_EQ(tick_label(1e6), "1e6");
  EXPECT_EQ(tick_label(2e-5), "2e-5");
  // One notation per axis: a decade axis reaching 1e6 writes every tick as an exponent.
  EXPECT_EQ(tick_labels({100, 1000, 1e4, 1e5, 1e6}),
            (std::vector<std::string>{"1e2", "1e3", "1e4", "1e5", "1e6"}));
  EXPECT_EQ(tick_labels({0, 2.5e6, 5e6}), (std::vector<std::string>{"0", "2.5e6", "5e6"}));
  EXPECT_EQ(tick_labels({0.5, 1, 2, 5}), (std::vector<std::string>{"0.5", "1", "2", "5"}));
}

TEST(SvgPlot, DocumentIsWellFormedAndListsItsImages) {
  Plot p;
  p.id = "t";
  p.title = "A & B <test>";
  p.x = {0, 90, false, "theta_s [deg]", {}};
  p.y = {1, 1e4, true, "L [cd/m2]", {}};
  p.series.push_back(line_series("sky", {0, 45, 90}, {10, 100, 1000}, "#000000"));
  p.series.push_back(marker_series("pts", {10, 20}, {5, 50}, "#ff0000"));
  // A point a log axis cannot show is a gap, not a NaN in the output.
  p.series.push_back(line_series("gap", {0, 30, 60}, {10, 0, 20}, "#00ff00", 1.0, "4 2"));
  p.regions.push_back({0, 10, 1, 10, "#4caf50"});
  p.swatches.push_back({"valid", "#4caf50"});
  p.background_image = "map.png";
  p.has_colour_bar = true;
  p.colour_bar = {0.0, 4.0, "%", "%"};
  p.legend_outside = true;
  const Canvas c = draw(p);
  const std::string doc = c.document();
  const auto check = check_xml(doc);
  EXPECT_TRUE(check.ok) << check.error;
  EXPECT_EQ(doc.find("nan"), std::string::npos);
  EXPECT_EQ(doc.find("inf"), std::string::npos);
  ASSERT_EQ(c.images().size(), 1u);
  EXPECT_EQ(c.images()[0], "map.png");
  // href and xlink:href of the one image (plus the url(#...) references are not hrefs).
  ASSERT_EQ(check.hrefs.size(), 2u);
  EXPECT_EQ(check.hrefs[0], "map.png");
  EXPECT_NE(doc.find("A &amp; B &lt;test&gt;"), std::string::npos);
  // The inline form has no XML declaration.
  EXPECT_EQ(c.svg().rfind("<svg", 0), 0u);
  Plot bad;
  bad.x = {1, 1, false, "", {}};  // empty range
  EXPECT_THROW(draw(bad), InvalidArgument);
}

TEST(SvgColourBar, GradientStopsAreTheFalseColourScale) {
  Canvas c(200, 300, "cb");
  draw_colour_bar(c, 10, 10, 14, 200, {2.0, 5.0, "cd/m2", ""});
  const std::string doc = c.document();
  EXPECT_TRUE(check_xml(doc).ok);
  // Two stops per decade; the top stop is the brightest colour of the top decade.
  const std::regex stop(R"re(<stop offset="([0-9.]+)" stop-color="(#[0-9a-f]{6})"/>)re");
  std::vector<std::pair<double, std::string>> stops;
  for (auto it = std::sregex_iterator(doc.begin(), doc.end(), stop); it != std::sregex_iterator();
       ++it)
    stops.emplace_back(std::stod((*it)[1]), (*it)[2]);
  ASSERT_EQ(stops.size(), 6u);
  const render::FalseColourOptions fo{2.0, 5.0, "cd/m2", false};
  EXPECT_EQ(stops.front().second, hex_colour(render::false_colour_of(5.0 - 1e-9, fo)));
  EXPECT_EQ(stops.back().second, hex_colour(render::false_colour_of(2.0 + 1e-9, fo)));
  EXPECT_DOUBLE_EQ(stops.front().first, 0.0);
  EXPECT_DOUBLE_EQ(stops.back().first, 1.0);
  // Decade boundaries at 1/3 and 2/3 of the bar, each with a jump in colour.
  EXPECT_NEAR(stops[1].first, 1.0 / 3.0, 1e-6);
  EXPECT_NEAR(stops[2].first, 1.0 / 3.0, 1e-6);
  EXPECT_NE(stops[1].second, stops[2].second);
}

TEST(SvgMosaic, LabelsAndImage) {
  Mosaic m;
  m.id = "m";
  m.title = "CIE";
  m.image = "tiles.png";
  m.rows = 2;
  m.columns = 3;
  m.tile_px = 10;
  m.gap_px = 2;
  m.row_header = "type";
  m.column_header = "theta_s";
  m.row_labels = {"1", "2"};
  m.column_labels = {"0", "45", "85"};
  m.colour_bar = {0, 4, "%", "%"};
  const Canvas c = draw(m);
  const auto check = check_xml(c.document());
  EXPECT_TRUE(check.ok) << check.error;
  EXPECT_EQ(c.images(), std::vector<std::string>{"tiles.png"});
  // Two 10 px rows: the colour bar still gets kMinColourBarPx, and the canvas holds it.
  EXPECT_GE(c.height(), kMinColourBarPx);
  // The bar is the rectangle filled with the gradient.
  const std::string doc = c.document();
  const std::size_t fill = doc.find("fill=\"url(#");
  ASSERT_NE(fill, std::string::npos);
  const std::size_t rect = doc.rfind("<rect", fill);
  const std::size_t h = doc.find("height=\"", rect);
  ASSERT_LT(h, fill);
  EXPECT_GE(std::stod(doc.substr(h + 8)), kMinColourBarPx);
  m.row_labels.pop_back();
  EXPECT_THROW(draw(m), InvalidArgument);
}

}  // namespace
}  // namespace skylight::report::svg
