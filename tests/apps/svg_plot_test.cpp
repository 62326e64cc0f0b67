// The `--plot` SVG writer: document structure, escaping, round ticks, decimation that keeps
// spikes, broken lines at missing samples, edge cases, byte-for-byte determinism, file errors.
#include "avar/svg_plot.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <iomanip>
#include <limits>
#include <random>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "../support/temp_file.hpp"

namespace avar::app {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
constexpr double kInf = std::numeric_limits<double>::infinity();

std::string render(const PlotData& data) {
  std::ostringstream out;
  write_svg_plot(out, data);
  return out.str();
}

std::size_t count(const std::string& haystack, const std::string& needle) {
  std::size_t n = 0;
  for (std::size_t at = haystack.find(needle); at != std::string::npos; at = haystack.find(needle, at + needle.size())) ++n;
  return n;
}

/// Well-formedness as far as this writer can get it wrong: one root, every element closed in
/// order, attribute values quoted, and no raw '<' or stray '&' outside markup.
::testing::AssertionResult well_formed(const std::string& svg) {
  std::vector<std::string> open;
  std::size_t roots = 0;
  std::size_t i = 0;
  if (svg.rfind("<?xml ", 0) != 0) return ::testing::AssertionFailure() << "no XML declaration";
  i = svg.find("?>") + 2;
  while (i < svg.size()) {
    const std::size_t lt = svg.find('<', i);
    const std::string chars = svg.substr(i, lt == std::string::npos ? std::string::npos : lt - i);
    for (std::size_t amp = chars.find('&'); amp != std::string::npos; amp = chars.find('&', amp + 1)) {
      const std::string rest = chars.substr(amp);
      if (rest.rfind("&lt;", 0) && rest.rfind("&gt;", 0) && rest.rfind("&amp;", 0) && rest.rfind("&quot;", 0) &&
          rest.rfind("&apos;", 0))
        return ::testing::AssertionFailure() << "stray & in text at " << i + amp;
    }
    if (chars.find('>') != std::string::npos) return ::testing::AssertionFailure() << "raw > in text at " << i;
    if (lt == std::string::npos) break;
    const std::size_t gt = svg.find('>', lt);
    if (gt == std::string::npos) return ::testing::AssertionFailure() << "unterminated tag at " << lt;
    const std::string tag = svg.substr(lt + 1, gt - lt - 1);
    if (tag.find('<') != std::string::npos) return ::testing::AssertionFailure() << "< inside tag at " << lt;
    if (count(tag, "\"") % 2 != 0) return ::testing::AssertionFailure() << "unbalanced quotes in <" << tag << ">";
    if (tag.front() == '/') {
      if (open.empty() || open.back() != tag.substr(1))
        return ::testing::AssertionFailure() << "</" << tag.substr(1) << "> closes " << (open.empty() ? "nothing" : open.back());
      open.pop_back();
    } else {
      if (open.empty() && ++roots > 1) return ::testing::AssertionFailure() << "second root element at " << lt;
      if (tag.back() != '/') open.push_back(tag.substr(0, tag.find_first_of(" \n")));
    }
    i = gt + 1;
  }
  if (!open.empty()) return ::testing::AssertionFailure() << "<" << open.back() << "> never closed";
  if (roots != 1 || svg.find("<svg ") == std::string::npos) return ::testing::AssertionFailure() << "no single <svg> root";
  return ::testing::AssertionSuccess();
}

/// No non-finite number anywhere (the tests' names and units avoid these letter sequences).
bool finite_numbers_only(const std::string& svg) {
  std::string lower = svg;
  std::transform(lower.begin(), lower.end(), lower.begin(), [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return lower.find("nan") == std::string::npos && lower.find("inf") == std::string::npos;
}

/// The value of attribute `name` in the element holding `at`.
double attribute(const std::string& svg, std::size_t at, const std::string& name) {
  const std::size_t tag = svg.rfind('<', at);
  const std::size_t a = svg.find(" " + name + "=\"", tag);
  return std::stod(svg.substr(a + name.size() + 3));
}

struct Point {
  double x, y;
};
/// The lines (subpaths) of every <path class="cls"> in document order.
std::vector<std::vector<std::vector<Point>>> paths(const std::string& svg, const std::string& cls) {
  std::vector<std::vector<std::vector<Point>>> out;
  const std::string start = "<path class=\"" + cls + "\" d=\"";
  for (std::size_t at = svg.find(start); at != std::string::npos; at = svg.find(start, at + 1)) {
    const std::size_t begin = at + start.size();
    const std::string d = svg.substr(begin, svg.find('"', begin) - begin);
    std::vector<std::vector<Point>> lines;
    std::size_t i = 0;
    while (i < d.size()) {
      const char op = d[i];
      EXPECT_TRUE(op == 'M' || op == 'L') << d.substr(i, 20);
      if (op != 'M' && op != 'L') break;
      std::size_t used = 0;
      const double x = std::stod(d.substr(i + 1), &used);
      i += 1 + used;
      EXPECT_EQ(d[i], ',');
      const double y = std::stod(d.substr(i + 1), &used);
      i += 1 + used;
      if (op == 'M' || lines.empty()) lines.emplace_back();
      lines.back().push_back({x, y});
    }
    for (const auto& l : lines) EXPECT_GE(l.size(), 2u) << "a lone point is a dot, not a line";
    out.push_back(std::move(lines));
  }
  return out;
}

/// Centres of the dots of series `cls` (its lone points between breaks).
std::vector<Point> dots(const std::string& svg, const std::string& cls) {
  std::vector<Point> out;
  const std::string start = "<circle class=\"" + cls + "-dot\"";
  for (std::size_t at = svg.find(start); at != std::string::npos; at = svg.find(start, at + 1))
    out.push_back({attribute(svg, at + 1, "cx"), attribute(svg, at + 1, "cy")});
  return out;
}

std::size_t point_count(const std::vector<std::vector<Point>>& lines) {
  std::size_t n = 0;
  for (const auto& l : lines) n += l.size();
  return n;
}

/// Texts of the elements carrying class="cls", in document order.
std::vector<std::string> texts(const std::string& svg, const std::string& cls) {
  std::vector<std::string> out;
  const std::string marker = "class=\"" + cls + "\"";
  for (std::size_t at = svg.find(marker); at != std::string::npos; at = svg.find(marker, at + 1)) {
    const std::size_t begin = svg.find('>', at) + 1;
    out.push_back(svg.substr(begin, svg.find('<', begin) - begin));
  }
  return out;
}

PlotData sine_data(std::size_t samples, std::size_t channels, double rate_hz = 50) {
  PlotData data;
  data.title = "hello-head";
  for (std::size_t k = 0; k < samples; ++k) data.seconds.push_back(static_cast<double>(k) / rate_hz);
  for (std::size_t c = 0; c < channels; ++c) {
    PlotChannel ch{"channel" + std::to_string(c), "deg", -30, 30, {}, {}};
    for (double t : data.seconds) {
      ch.commanded.push_back(25 * std::sin(t + static_cast<double>(c)));
      ch.measured.push_back(25 * std::sin(t - 0.05 + static_cast<double>(c)));
    }
    data.channels.push_back(std::move(ch));
  }
  return data;
}

TEST(SvgPlot, OnePanelPerChannelWithNameUnitTicksAndDashedLimits) {
  const std::string svg = render(sine_data(600, 3));
  ASSERT_TRUE(well_formed(svg));
  EXPECT_EQ(svg.rfind("<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n<svg xmlns=\"http://www.w3.org/2000/svg\"", 0), 0u);
  EXPECT_EQ(count(svg, "<g class=\"panel\">"), 3u);
  EXPECT_EQ(texts(svg, "channel"), (std::vector<std::string>{"channel0", "channel1", "channel2"}));
  EXPECT_EQ(texts(svg, "unit"), (std::vector<std::string>{"deg", "deg", "deg"}));
  EXPECT_EQ(texts(svg, "title"), std::vector<std::string>{"hello-head"});
  EXPECT_EQ(count(svg, "class=\"limit\" stroke-dasharray="), 6u);
  EXPECT_EQ(paths(svg, "commanded").size(), 3u);
  EXPECT_EQ(paths(svg, "measured").size(), 3u);
  // Panels stack downwards without overlapping: each channel name is below the previous panel.
  const std::size_t first = svg.find("class=\"channel\""), second = svg.find("class=\"channel\"", first + 1);
  EXPECT_GE(attribute(svg, second, "y") - attribute(svg, first, "y"), 120.0);
  // y ticks in every panel, the time axis once, under the last panel.
  EXPECT_GE(texts(svg, "tick-y").size(), 3u * 3u);
  EXPECT_EQ(count(svg, "<g class=\"time-axis\">"), 1u);
  EXPECT_NE(svg.find(">time (s)</text>"), std::string::npos);
}

TEST(SvgPlot, LegendNamesTheSeriesInDistinctColoursAndOnlyWhatIsDrawn) {
  const std::string svg = render(sine_data(100, 2));
  const std::size_t legend = svg.find("<g class=\"legend\">");
  ASSERT_NE(legend, std::string::npos);
  const std::string block = svg.substr(legend, svg.find("</g>", legend) - legend);
  EXPECT_NE(block.find(">commanded</text>"), std::string::npos);
  EXPECT_NE(block.find(">simulated</text>"), std::string::npos);
  EXPECT_NE(block.find(">limits</text>"), std::string::npos);
  EXPECT_EQ(block.find(">phase change</text>"), std::string::npos);  // no markers given
  // The legend's line colours are the ones the two series are drawn with, and they differ.
  const auto stroke_of = [&](const std::string& cls) {
    const std::size_t at = svg.find("<path class=\"" + cls + "\"");
    const std::size_t s = svg.find("stroke=\"", at) + 8;
    return svg.substr(s, svg.find('"', s) - s);
  };
  const std::string commanded = stroke_of("commanded"), measured = stroke_of("measured");
  EXPECT_NE(commanded, measured);
  EXPECT_NE(block.find("stroke=\"" + commanded + "\""), std::string::npos);
  EXPECT_NE(block.find("stroke=\"" + measured + "\""), std::string::npos);

  PlotData no_feedback = sine_data(100, 2);
  for (auto& ch : no_feedback.channels) ch.measured.clear();
  const std::string without = render(no_feedback);
  EXPECT_EQ(without.find("simulated"), std::string::npos);
  EXPECT_EQ(without.find("class=\"measured\""), std::string::npos);
  EXPECT_EQ(paths(without, "commanded").size(), 2u);
}

TEST(SvgPlot, EscapesNamesUnitsTitleAndMarkers) {
  PlotData data = sine_data(50, 1);
  data.title = "show <\"a\" & 'b'>";
  data.channels[0].name = "jaw<1>&co";
  data.channels[0].unit = "\"%\"";
  data.markers = {{0.2, "<homing>"}};
  const std::string svg = render(data);
  ASSERT_TRUE(well_formed(svg));
  EXPECT_NE(svg.find(">show &lt;&quot;a&quot; &amp; &apos;b&apos;&gt;</text>"), std::string::npos);
  EXPECT_NE(svg.find(">jaw&lt;1&gt;&amp;co</text>"), std::string::npos);
  EXPECT_NE(svg.find(">&quot;%&quot;</text>"), std::string::npos);
  EXPECT_NE(svg.find(">&lt;homing&gt;</text>"), std::string::npos);
  EXPECT_EQ(svg.find("jaw<1>"), std::string::npos);
  EXPECT_EQ(svg.find("<homing>"), std::string::npos);
}

TEST(SvgPlot, KeepsValidUtf8AndReplacesWhatXmlCannotHold) {
  PlotData data = sine_data(50, 3);
  data.channels[0].unit = "\xC2\xB0";                 // degree sign, kept
  data.channels[1].name = "a\x01" "b\tc";             // control character, tab
  data.channels[2].name = "x\xC3(y\xE0\x80\x80z\xFF"; // truncated, overlong, invalid byte
  data.title = "t\xEF\xBF\xBE";                       // U+FFFE, not an XML character
  const std::string svg = render(data);
  ASSERT_TRUE(well_formed(svg));
  EXPECT_EQ(texts(svg, "unit")[0], "\xC2\xB0");
  EXPECT_EQ(texts(svg, "channel")[1], "a\xEF\xBF\xBD" "b c");
  EXPECT_EQ(texts(svg, "channel")[2],
            "x\xEF\xBF\xBD(y\xEF\xBF\xBD\xEF\xBF\xBD\xEF\xBF\xBDz\xEF\xBF\xBD");
  EXPECT_EQ(texts(svg, "title")[0], "t\xEF\xBF\xBD");
  for (char c : svg) EXPECT_FALSE(static_cast<unsigned char>(c) < 0x20 && c != '\n');
}

TEST(SvgPlot, ShortRunsKeepEverySample) {
  const std::string svg = render(sine_data(50, 1));
  const auto commanded = paths(svg, "commanded");
  ASSERT_EQ(commanded.size(), 1u);
  ASSERT_EQ(commanded[0].size(), 1u);  // one unbroken line
  EXPECT_EQ(commanded[0][0].size(), 50u);
  // Left to right across the panel: the first sample on the left edge, the last on the right.
  EXPECT_DOUBLE_EQ(commanded[0][0].front().x, 80);
  EXPECT_DOUBLE_EQ(commanded[0][0].back().x, 976);
  for (std::size_t i = 1; i < 50; ++i) EXPECT_GT(commanded[0][0][i].x, commanded[0][0][i - 1].x);
}

TEST(SvgPlot, DecimatesLongRunsAndKeepsSpikesVisible) {
  constexpr std::size_t kSamples = 1'000'000;
  PlotData data;
  data.seconds.resize(kSamples);
  PlotChannel ch{"jaw", "deg", 0, 30, std::vector<double>(kSamples, 10.0), std::vector<double>(kSamples, 10.0)};
  for (std::size_t k = 0; k < kSamples; ++k) data.seconds[k] = static_cast<double>(k) * 1e-3;
  ch.commanded[123'457] = 28;  // one-sample spikes, up and down
  ch.measured[765'433] = 1;
  data.channels.push_back(std::move(ch));
  const std::string svg = render(data);
  ASSERT_TRUE(well_formed(svg));
  const auto commanded = paths(svg, "commanded"), measured = paths(svg, "measured");
  ASSERT_EQ(commanded.size(), 1u);
  ASSERT_EQ(measured.size(), 1u);
  EXPECT_LE(point_count(commanded[0]), kMaxPlotPointsPerLine);
  EXPECT_LE(point_count(measured[0]), kMaxPlotPointsPerLine);
  EXPECT_GE(point_count(commanded[0]), 800u);  // about a point per pixel column, not fewer
  EXPECT_EQ(commanded[0].size(), 1u);

  const auto ys = [](const std::vector<std::vector<Point>>& lines) {
    std::vector<double> out;
    for (const auto& l : lines)
      for (const Point& p : l) out.push_back(p.y);
    return out;
  };
  const std::vector<double> cy = ys(commanded[0]), my = ys(measured[0]);
  const double flat = cy.front();
  const double top = *std::min_element(cy.begin(), cy.end());
  const double bottom = *std::max_element(my.begin(), my.end());
  // The panel is 120 px for about 31.5 deg: the spikes stand far off the flat line.
  EXPECT_LT(top, flat - 60);
  EXPECT_GT(bottom, flat + 25);
  EXPECT_EQ(std::count(cy.begin(), cy.end(), top), 1);
}

TEST(SvgPlot, DecimationBoundHoldsWhateverTheTimesDo) {
  for (std::uint32_t seed = 1; seed <= 5; ++seed) {
    SCOPED_TRACE(::testing::Message() << "seed " << seed);
    std::mt19937 rng(seed);
    std::uniform_real_distribution<double> time(0, 100), value(-1, 1);
    PlotData data;
    PlotChannel ch{"c", "u", -1, 1, {}, {}};
    for (std::size_t k = 0; k < 50'000; ++k) {
      data.seconds.push_back(time(rng));  // unsorted: buckets cannot rely on columns alone
      ch.commanded.push_back(value(rng));
    }
    data.channels.push_back(std::move(ch));
    const auto commanded = paths(render(data), "commanded");
    ASSERT_EQ(commanded.size(), 1u);
    EXPECT_LE(point_count(commanded[0]), kMaxPlotPointsPerLine);
  }
}

TEST(SvgPlot, MissingSamplesBreakTheLineAndLonePointsShowAsDots) {
  PlotData data;
  data.seconds = {0, 1, 2, 3, 4, 5, 6, 7, 8};
  data.channels.push_back({"jaw", "deg", 0, 10, {1, 2, 3, 4, 5, 6, 7, 8, 9}, {1, 2, kNaN, kNaN, 5, kNaN, 7, kInf, 9}});
  const std::string svg = render(data);
  ASSERT_TRUE(well_formed(svg));
  const auto measured = paths(svg, "measured");
  ASSERT_EQ(measured.size(), 1u);
  ASSERT_EQ(measured[0].size(), 1u);  // samples 0 and 1; samples 4, 6 and 8 stand alone
  EXPECT_EQ(measured[0][0].size(), 2u);
  const std::vector<Point> lone = dots(svg, "measured");
  ASSERT_EQ(lone.size(), 3u);
  const auto commanded = paths(svg, "commanded");
  ASSERT_EQ(commanded[0].size(), 1u);
  ASSERT_EQ(commanded[0][0].size(), 9u);
  EXPECT_TRUE(dots(svg, "commanded").empty());
  for (std::size_t k = 0; k < 3; ++k) {  // the dots sit where the commanded line has the same sample
    EXPECT_DOUBLE_EQ(lone[k].x, commanded[0][0][4 + 2 * k].x);
    EXPECT_DOUBLE_EQ(lone[k].y, commanded[0][0][4 + 2 * k].y);
  }
  EXPECT_TRUE(finite_numbers_only(svg));
}

TEST(SvgPlot, TicksAreRoundOneTwoFiveSteps) {
  PlotData data;
  for (int k = 0; k <= 127; ++k) data.seconds.push_back(k * 0.1);
  data.channels.push_back({"lid", "%", 0, 100, std::vector<double>(128, 50.0), {}});
  std::string svg = render(data);
  EXPECT_EQ(texts(svg, "tick-t"), (std::vector<std::string>{"0", "2", "4", "6", "8", "10", "12"}));
  EXPECT_EQ(texts(svg, "tick-y"), (std::vector<std::string>{"0", "50", "100"}));

  data.seconds.resize(11);
  data.channels[0] = {"jaw", "rad", -0.3, 0.25, std::vector<double>(11, 0.0), {}};
  svg = render(data);
  EXPECT_EQ(texts(svg, "tick-t"),
            (std::vector<std::string>{"0.0", "0.1", "0.2", "0.3", "0.4", "0.5", "0.6", "0.7", "0.8", "0.9", "1.0"}));
  EXPECT_EQ(texts(svg, "tick-y"), (std::vector<std::string>{"-0.2", "0.0", "0.2"}));

  // Ticks are evenly spaced in pixels.
  std::vector<double> xs;
  for (std::size_t at = svg.find("class=\"tick-t\""); at != std::string::npos; at = svg.find("class=\"tick-t\"", at + 1))
    xs.push_back(attribute(svg, at, "x"));
  ASSERT_EQ(xs.size(), 11u);
  for (std::size_t i = 2; i < xs.size(); ++i) EXPECT_NEAR(xs[i] - xs[i - 1], xs[1] - xs[0], 0.02);
}

TEST(SvgPlot, PhaseMarkersAreLinesInEveryPanelWithReadableLabels) {
  PlotData data = sine_data(600, 2);  // 0 to 11.98 s
  data.markers = {{0.0, "homing"}, {0.1, "running"}, {11.9, "stopping"}, {50, "later"}, {kNaN, "never"}};
  const std::string svg = render(data);
  ASSERT_TRUE(well_formed(svg));
  EXPECT_EQ(texts(svg, "marker-label"), (std::vector<std::string>{"homing", "running", "stopping"}));
  EXPECT_EQ(count(svg, "class=\"marker\""), 3u * 2u);
  EXPECT_NE(svg.find(">phase change</text>"), std::string::npos);
  // Close phase changes go to different rows; the label at the right edge ends at its line.
  const std::size_t homing = svg.find(">homing<"), running = svg.find(">running<"), stopping = svg.find(">stopping<");
  EXPECT_NE(attribute(svg, homing, "y"), attribute(svg, running, "y"));
  EXPECT_NE(svg.substr(svg.rfind('<', stopping), stopping - svg.rfind('<', stopping)).find("text-anchor=\"end\""),
            std::string::npos);
  EXPECT_LT(attribute(svg, stopping, "x"), 976.0);
}

TEST(SvgPlot, NoSamplesOrNoChannelsStillMakeAValidDocument) {
  PlotData empty;
  std::string svg = render(empty);
  ASSERT_TRUE(well_formed(svg));
  EXPECT_NE(svg.find(">no samples</text>"), std::string::npos);
  EXPECT_EQ(svg.find("class=\"panel\""), std::string::npos);

  PlotData channels_only;
  channels_only.title = "t";
  channels_only.channels.push_back({"jaw", "deg", 0, 1, {}, {}});
  channels_only.seconds = {kNaN, kInf};
  svg = render(channels_only);
  ASSERT_TRUE(well_formed(svg));
  EXPECT_NE(svg.find(">no samples</text>"), std::string::npos);

  PlotData samples_only;
  samples_only.seconds = {0, 1};
  svg = render(samples_only);
  ASSERT_TRUE(well_formed(svg));
  EXPECT_NE(svg.find(">no channels</text>"), std::string::npos);
}

TEST(SvgPlot, ConstantSignalsEqualLimitsAndOneSampleStayFiniteAndOnThePanel) {
  PlotData data;
  data.seconds = {2.5};
  data.channels.push_back({"jaw", "deg", 5, 5, {5}, {5}});
  data.channels.push_back({"lid", "%", kNaN, kInf, {0}, {}});
  data.channels.push_back({"eye", "deg", 0, 0, {}, {}});
  const std::string svg = render(data);
  ASSERT_TRUE(well_formed(svg));
  EXPECT_TRUE(finite_numbers_only(svg));
  EXPECT_EQ(count(svg, "<g class=\"panel\">"), 3u);
  EXPECT_EQ(count(svg, "class=\"limit\""), 2u + 0u + 2u);  // non-finite limits are not drawn
  EXPECT_FALSE(texts(svg, "tick-y").empty());
  EXPECT_FALSE(texts(svg, "tick-t").empty());
  ASSERT_EQ(paths(svg, "commanded").size(), 3u);
  EXPECT_EQ(point_count(paths(svg, "commanded")[0]), 0u);
  const std::vector<Point> lone = dots(svg, "commanded");  // jaw and lid; eye has no samples
  ASSERT_EQ(lone.size(), 2u);
  EXPECT_EQ(dots(svg, "measured").size(), 1u);
  // The single instant sits mid-panel, inside the panel vertically.
  const std::size_t rect = svg.find("<rect x=");
  const double top = attribute(svg, rect, "y");
  EXPECT_DOUBLE_EQ(lone[0].x, (80.0 + 976.0) / 2);
  EXPECT_GT(lone[0].y, top);
  EXPECT_LT(lone[0].y, top + 120);
}

TEST(SvgPlot, ExtremeValuesKeepCoordinatesFinite) {
  PlotData data;
  data.seconds = {-1e300, 0, 1e300};
  data.channels.push_back({"far", "m", -1e308, 1e308, {-1.7e308, 0, 1.7e308}, {1e-300, -1e-300, 0}});
  const std::string svg = render(data);
  ASSERT_TRUE(well_formed(svg));
  EXPECT_TRUE(finite_numbers_only(svg));
  const auto commanded = paths(svg, "commanded");
  ASSERT_EQ(commanded.size(), 1u);
  ASSERT_EQ(commanded[0].size(), 1u);
  EXPECT_EQ(commanded[0][0].size(), 3u);
  for (const Point& p : commanded[0][0]) {
    EXPECT_GE(p.x, 80);
    EXPECT_LE(p.x, 976);
  }
}

TEST(SvgPlot, SeriesLongerOrShorterThanTheTimesAreCut) {
  PlotData data;
  data.seconds = {0, 1, 2, 3};
  data.channels.push_back({"jaw", "deg", 0, 10, {1, 2, 3, 4, 5, 6}, {1, 2}});
  const std::string svg = render(data);
  EXPECT_EQ(point_count(paths(svg, "commanded")[0]), 4u);
  EXPECT_EQ(point_count(paths(svg, "measured")[0]), 2u);
}

TEST(SvgPlot, SameDataSameBytesWhateverTheStreamFormatting) {
  PlotData data = sine_data(3000, 4);
  data.markers = {{0, "homing"}, {1.2, "show"}, {55, "stopping"}};
  const std::string first = render(data);
  EXPECT_EQ(render(data), first);
  std::ostringstream formatted;
  formatted << std::fixed << std::setprecision(1) << std::showpos << std::uppercase;
  write_svg_plot(formatted, data);
  EXPECT_EQ(formatted.str(), first);
}

TEST(SvgPlot, RandomDataAlwaysGivesAValidBoundedDocument) {
  for (std::uint32_t seed = 100; seed < 140; ++seed) {
    SCOPED_TRACE(::testing::Message() << "seed " << seed);
    std::mt19937 rng(seed);
    const auto uniform = [&](double lo, double hi) { return std::uniform_real_distribution<double>(lo, hi)(rng); };
    const auto below = [&](std::size_t n) { return std::uniform_int_distribution<std::size_t>(0, n - 1)(rng); };
    PlotData data;
    data.title = "random";
    const std::size_t samples = below(6000);
    double t = uniform(-5, 5);
    for (std::size_t k = 0; k < samples; ++k) data.seconds.push_back(t += uniform(0, 0.02));
    const std::size_t channels = below(5);
    const double missing = uniform(0, 0.3);
    for (std::size_t c = 0; c < channels; ++c) {
      const double scale = std::pow(10.0, uniform(-4, 6));
      PlotChannel ch{"c" + std::to_string(c), "u", -scale * uniform(0, 1), scale * uniform(0, 1), {}, {}};
      const std::size_t length = below(samples + 2);
      for (std::size_t k = 0; k < length; ++k) {
        ch.commanded.push_back(uniform(-scale, scale));
        if (c % 2 == 0) ch.measured.push_back(uniform(0, 1) < missing ? kNaN : uniform(-scale, scale));
      }
      data.channels.push_back(std::move(ch));
    }
    for (std::size_t m = below(6); m > 0; --m) data.markers.emplace_back(uniform(-6, 130), "phase" + std::to_string(m));
    const std::string svg = render(data);
    ASSERT_TRUE(well_formed(svg));
    EXPECT_TRUE(finite_numbers_only(svg));
    if (samples == 0 || channels == 0) continue;
    EXPECT_EQ(count(svg, "<g class=\"panel\">"), channels);
    // Per panel and series, line points and dots together stay within the bound.
    for (std::size_t at = svg.find("<g class=\"panel\">"); at != std::string::npos;
         at = svg.find("<g class=\"panel\">", at + 1)) {
      const std::string block = svg.substr(at, svg.find("</g>", at) - at);
      for (const char* cls : {"commanded", "measured"}) {
        const auto lines = paths(block, cls);
        EXPECT_LE(lines.size(), 1u);
        EXPECT_LE((lines.empty() ? 0 : point_count(lines[0])) + dots(block, cls).size(), kMaxPlotPointsPerLine);
      }
    }
  }
}

TEST(SvgPlot, FileWriterWritesTheDocumentAndNamesAnUnwritablePath) {
  const PlotData data = sine_data(200, 2);
  const std::string path = testing::temp_path("plot.svg");
  write_svg_plot_file(path, data);
  std::ifstream in(path, std::ios::binary);
  std::ostringstream contents;
  contents << in.rdbuf();
  EXPECT_EQ(contents.str(), render(data));
  std::remove(path.c_str());

  const std::string bad = testing::temp_path("missing-folder") + "/plot.svg";
  try {
    write_svg_plot_file(bad, data);
    FAIL() << "no error for " << bad;
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find(bad), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace avar::app
