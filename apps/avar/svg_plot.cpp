#include "avar/svg_plot.hpp"
#include "avar/core/format.hpp"

#include <algorithm>
#include <array>
#include <charconv>
#include <cmath>
#include <fstream>
#include <limits>
#include <ostream>
#include <stdexcept>
#include <string_view>

namespace avar::app {
namespace {

// Page layout, in SVG user units (pixels).
constexpr double kWidth = 1000;
constexpr double kLeft = 80;  // room for the rotated unit and the y tick labels
constexpr double kRight = 24;
constexpr double kTitleBaseline = 26;
constexpr double kLegendBaseline = 48;
constexpr double kMarkerBandTop = 60;
constexpr double kMarkerRowHeight = 13;
constexpr int kMaxMarkerRows = 4;
constexpr double kPanelHeight = 120;
constexpr double kPanelHeader = 22;  // channel name above each panel
constexpr double kPanelGap = 10;
constexpr double kTimeAxisHeight = 46;  // tick labels and "time (s)" under the last panel
constexpr double kFontSize = 11;
constexpr double kGlyphWidth = 0.62;  // average advance of a sans-serif glyph, in font sizes

constexpr std::size_t kMaxBuckets = kMaxPlotPointsPerLine / 2;  // two points (low, high) a bucket

constexpr std::string_view kCommandedColour = "#1f77b4";
constexpr std::string_view kMeasuredColour = "#ff7f0e";
constexpr std::string_view kLimitColour = "#c62828";
constexpr std::string_view kMarkerColour = "#666666";
constexpr std::string_view kGridColour = "#e6e6e6";
constexpr std::string_view kFrameColour = "#999999";
constexpr std::string_view kReplacement = "\xEF\xBF\xBD";  // U+FFFD

/// `text` as valid UTF-8 holding only characters XML 1.0 allows: invalid sequences and control
/// characters become U+FFFD, tabs and line breaks become spaces.
std::string sanitize(std::string_view text) {
  std::string out;
  out.reserve(text.size());
  std::size_t i = 0;
  const auto byte = [&](std::size_t k) { return static_cast<unsigned char>(text[k]); };
  while (i < text.size()) {
    const unsigned char b = byte(i);
    if (b < 0x80) {
      if (b == '\t' || b == '\n' || b == '\r') out += ' ';
      else if (b < 0x20) out += kReplacement;
      else out += static_cast<char>(b);
      ++i;
      continue;
    }
    // Length and the allowed range of the second byte (which excludes overlong forms,
    // surrogates and code points above U+10FFFF).
    std::size_t length = 0;
    unsigned char second_lo = 0x80, second_hi = 0xBF;
    if (b >= 0xC2 && b <= 0xDF) length = 2;
    else if (b >= 0xE0 && b <= 0xEF) {
      length = 3;
      if (b == 0xE0) second_lo = 0xA0;
      if (b == 0xED) second_hi = 0x9F;
    } else if (b >= 0xF0 && b <= 0xF4) {
      length = 4;
      if (b == 0xF0) second_lo = 0x90;
      if (b == 0xF4) second_hi = 0x8F;
    }
    bool valid = length > 0 && i + length <= text.size();
    for (std::size_t k = 1; valid && k < length; ++k) {
      const unsigned char c = byte(i + k);
      valid = k == 1 ? (c >= second_lo && c <= second_hi) : (c >= 0x80 && c <= 0xBF);
    }
    if (!valid) {
      out += kReplacement;
      ++i;
      continue;
    }
    // U+FFFE and U+FFFF are well-formed UTF-8 but not XML characters.
    const bool noncharacter = length == 3 && b == 0xEF && byte(i + 1) == 0xBF && byte(i + 2) >= 0xBE;
    if (noncharacter) out += kReplacement;
    else out.append(text.substr(i, length));
    i += length;
  }
  return out;
}

std::string escape(std::string_view text) {
  std::string out;
  out.reserve(text.size());
  for (char c : text) {
    switch (c) {
      case '<': out += "&lt;"; break;
      case '>': out += "&gt;"; break;
      case '&': out += "&amp;"; break;
      case '"': out += "&quot;"; break;
      case '\'': out += "&apos;"; break;
      default: out += c;
    }
  }
  return out;
}

/// Text ready for an SVG text node or attribute.
std::string xml_text(std::string_view text) { return escape(sanitize(text)); }

/// Estimated rendered width of sanitized UTF-8 text: code points times an average glyph width.
double text_width(std::string_view text, double font_size) {
  const auto code_points = std::count_if(text.begin(), text.end(), [](char c) {
    return (static_cast<unsigned char>(c) & 0xC0) != 0x80;
  });
  return static_cast<double>(code_points) * kGlyphWidth * font_size;
}

/// A coordinate to two decimals without trailing zeros. Coordinates are finite and on the page by
/// construction; the clamp only keeps the text short and valid whatever happens.
std::string coord(double v) {
  if (!std::isfinite(v)) v = 0;
  std::string s = format_fixed(std::clamp(v, -1e6, 1e6), 2);
  s.erase(s.find_last_not_of('0') + 1);
  if (s.back() == '.') s.pop_back();
  return s;
}

/// Tick spacing of 1, 2 or 5 times a power of ten giving at most about `target` intervals;
/// 0 when the span has no usable scale.
double nice_step(double span, double target) {
  const double raw = span / target;
  if (!(raw > 0) || !std::isfinite(raw)) return 0;
  const double p = std::pow(10.0, std::floor(std::log10(raw)));
  for (double m : {1.0, 2.0, 5.0})
    if (raw <= m * p * (1 + 1e-9)) return m * p;
  return 10 * p;
}

/// Multiples of `step` within [lo, hi]; none when the step is unusable.
std::vector<double> ticks(double lo, double hi, double step) {
  std::vector<double> out;
  if (!(step > 0) || !std::isfinite(step)) return out;
  const double first = std::ceil(lo / step - 1e-9);
  const double last = std::floor(hi / step + 1e-9);
  if (!std::isfinite(first) || !std::isfinite(last) || last - first > 100) return out;
  for (double k = first; k <= last; k += 1) out.push_back(k == 0 ? 0.0 : k * step);
  return out;
}

/// A tick value with as many decimals as its step needs (0.5 -> "0.5", 2 -> "2").
std::string tick_label(double v, double step) {
  const int decimals = std::max(0, static_cast<int>(-std::floor(std::log10(step) + 1e-9)));
  if (decimals <= 9 && std::abs(v) < 1e9) return format_fixed(v, decimals);
  std::array<char, 64> buf{};
  const auto result = std::to_chars(buf.data(), buf.data() + buf.size(), v, std::chars_format::general, 6);
  return std::string(buf.data(), result.ptr);
}

/// Linear map from values [lo, hi] to pixels [px_lo, px_hi]; halved terms keep it finite even
/// for a span wider than the largest double.
struct Scale {
  double lo, hi, px_lo, px_hi;
  double map(double v) const { return px_lo + (0.5 * v - 0.5 * lo) / (0.5 * hi - 0.5 * lo) * (px_hi - px_lo); }
};

/// One series on the page: the path data of its lines, and the lone points between two breaks
/// (drawn as dots, since a one-point line shows nothing).
struct SeriesShape {
  std::string path;
  std::vector<std::pair<double, double>> dots;
};

/// A series decimated to the lowest and highest sample of each pixel column, broken wherever a
/// sample (or its time) is not finite. At most kMaxPlotPointsPerLine points, dots included.
SeriesShape series_shape(const std::vector<double>& t, const std::vector<double>& v, const Scale& x, const Scale& y) {
  const std::size_t n = std::min(t.size(), v.size());
  const auto usable = [&](std::size_t i) { return std::isfinite(t[i]) && std::isfinite(v[i]); };
  // unusable_before[i]: unusable samples in [0, i), to tell whether a break lies between two points.
  std::vector<std::size_t> unusable_before(n + 1, 0);
  for (std::size_t i = 0; i < n; ++i) unusable_before[i + 1] = unusable_before[i] + (usable(i) ? 0 : 1);

  SeriesShape shape;
  // The first point of a line waits until a second one joins it; alone, it becomes a dot.
  std::size_t points_in_line = 0;
  std::pair<double, double> first{};
  std::size_t last = 0;
  const auto end_line = [&] {
    if (points_in_line == 1) shape.dots.push_back(first);
    points_in_line = 0;
  };
  const auto emit = [&](std::size_t i) {
    const std::pair<double, double> p{x.map(t[i]), y.map(v[i])};
    if (points_in_line > 0 && unusable_before[i] != unusable_before[last + 1]) end_line();
    if (points_in_line == 0) {
      first = p;
    } else {
      if (points_in_line == 1) shape.path += 'M' + coord(first.first) + ',' + coord(first.second);
      shape.path += 'L' + coord(p.first) + ',' + coord(p.second);
    }
    ++points_in_line;
    last = i;
  };

  // A bucket closes when the pixel column changes, but never before it holds `min_bucket`
  // samples: every closed bucket then has at least n / kMaxBuckets samples, so there are at most
  // kMaxBuckets buckets (even when times go backwards), each giving at most two points.
  const std::size_t min_bucket = std::max<std::size_t>(1, (n + kMaxBuckets - 1) / kMaxBuckets);
  std::size_t count = 0;
  double column = 0;
  bool has_point = false;
  std::size_t lo = 0, hi = 0;
  const auto flush = [&] {
    if (has_point) {
      emit(std::min(lo, hi));
      if (lo != hi) emit(std::max(lo, hi));
    }
    count = 0;
    has_point = false;
  };
  for (std::size_t i = 0; i < n; ++i) {
    const double c = std::isfinite(t[i]) ? std::floor(x.map(t[i]) - x.px_lo) : column;
    if (count > 0 && c != column && count >= min_bucket) flush();
    if (count == 0) column = c;
    ++count;
    if (!usable(i)) continue;
    if (!has_point || v[i] < v[lo]) lo = i;
    if (!has_point || v[i] > v[hi]) hi = i;
    has_point = true;
  }
  flush();
  end_line();
  return shape;
}

void series(std::string& svg, const SeriesShape& shape, std::string_view cls, std::string_view colour,
            std::string_view width) {
  svg += "<path class=\"" + std::string(cls) + "\" d=\"" + shape.path + "\" stroke=\"" + std::string(colour) +
         "\" stroke-width=\"" + std::string(width) + "\" fill=\"none\" stroke-linejoin=\"round\"/>\n";
  for (const auto& [cx, cy] : shape.dots)
    svg += "<circle class=\"" + std::string(cls) + "-dot\" cx=\"" + coord(cx) + "\" cy=\"" + coord(cy) +
           "\" r=\"2.2\" fill=\"" + std::string(colour) + "\"/>\n";
}

struct MarkerLabel {
  double x;  // of the marker line
  std::string text;  // sanitized, not yet escaped
  bool anchor_end;   // text to the left of the line (near the right edge)
  int row;
};

/// Phase-marker labels in rows above the first panel: each label goes to the first row where it
/// does not overlap the previous one, so close phase changes stay readable.
std::vector<MarkerLabel> place_marker_labels(const PlotData& data, const Scale& x) {
  std::vector<std::size_t> order;
  for (std::size_t m = 0; m < data.markers.size(); ++m) {
    const double t = data.markers[m].first;
    if (std::isfinite(t) && t >= x.lo && t <= x.hi) order.push_back(m);
  }
  std::stable_sort(order.begin(), order.end(),
                   [&](std::size_t a, std::size_t b) { return data.markers[a].first < data.markers[b].first; });
  std::array<double, kMaxMarkerRows> row_end;
  row_end.fill(-std::numeric_limits<double>::infinity());
  std::vector<MarkerLabel> out;
  for (std::size_t m : order) {
    MarkerLabel label{x.map(data.markers[m].first), sanitize(data.markers[m].second), false, 0};
    const double w = text_width(label.text, kFontSize);
    double left = label.x + 3, right = left + w;
    if (right > kWidth - 2) {
      label.anchor_end = true;
      right = label.x - 3;
      left = right - w;
    }
    int row = -1;
    for (int r = 0; r < kMaxMarkerRows && row < 0; ++r)
      if (row_end[static_cast<std::size_t>(r)] + 6 <= left) row = r;
    if (row < 0)
      row = static_cast<int>(std::min_element(row_end.begin(), row_end.end()) - row_end.begin());
    row_end[static_cast<std::size_t>(row)] = right;
    label.row = row;
    out.push_back(std::move(label));
  }
  return out;
}

void line(std::string& svg, double x1, double y1, double x2, double y2, std::string_view stroke, std::string_view extra = {}) {
  svg += "<line x1=\"" + coord(x1) + "\" y1=\"" + coord(y1) + "\" x2=\"" + coord(x2) + "\" y2=\"" + coord(y2) +
         "\" stroke=\"" + std::string(stroke) + '"';
  if (!extra.empty()) svg += ' ' + std::string(extra);
  svg += "/>\n";
}

void text(std::string& svg, double x, double y, std::string_view escaped, std::string_view extra = {}) {
  svg += "<text x=\"" + coord(x) + "\" y=\"" + coord(y) + '"';
  if (!extra.empty()) svg += ' ' + std::string(extra);
  svg += '>' + std::string(escaped) + "</text>\n";
}

void document_start(std::string& svg, double height, const std::string& title) {
  svg += "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n";
  svg += "<svg xmlns=\"http://www.w3.org/2000/svg\" version=\"1.1\" width=\"" + coord(kWidth) + "\" height=\"" +
         coord(height) + "\" viewBox=\"0 0 " + coord(kWidth) + ' ' + coord(height) +
         "\" font-family=\"DejaVu Sans, Helvetica, Arial, sans-serif\" font-size=\"" + coord(kFontSize) + "\">\n";
  const std::string escaped = xml_text(title);
  svg += "<title>" + escaped + "</title>\n";
  svg += "<rect width=\"100%\" height=\"100%\" fill=\"white\"/>\n";
  text(svg, kLeft, kTitleBaseline, escaped, "class=\"title\" font-size=\"16\" font-weight=\"bold\"");
}

/// Legend entries left to right under the title: a line sample and its label.
void legend(std::string& svg, bool measured, bool limits, bool markers) {
  struct Entry {
    std::string_view label, colour, dash;
  };
  std::vector<Entry> entries{{"commanded", kCommandedColour, ""}};
  if (measured) entries.push_back({"simulated", kMeasuredColour, ""});
  if (limits) entries.push_back({"limits", kLimitColour, "6 4"});
  if (markers) entries.push_back({"phase change", kMarkerColour, "2 3"});
  svg += "<g class=\"legend\">\n";
  double x = kLeft;
  for (const Entry& e : entries) {
    std::string extra = "stroke-width=\"2\"";
    if (!e.dash.empty()) extra += " stroke-dasharray=\"" + std::string(e.dash) + '"';
    line(svg, x, kLegendBaseline - 4, x + 24, kLegendBaseline - 4, e.colour, extra);
    text(svg, x + 30, kLegendBaseline, e.label);
    x += 30 + text_width(e.label, kFontSize) + 22;
  }
  svg += "</g>\n";
}

void write_message(std::string& svg, const std::string& title, std::string_view message) {
  document_start(svg, 120, title);
  text(svg, kLeft, 70, message, "class=\"message\" font-size=\"14\" fill=\"#555555\"");
  svg += "</svg>\n";
}

/// One channel's panel: frame, grid, y ticks and unit, limits, phase markers, the two series.
void panel(std::string& svg, const PlotChannel& ch, const std::vector<double>& seconds, const Scale& x,
           const std::vector<double>& time_ticks, const std::vector<MarkerLabel>& markers, double top) {
  const double bottom = top + kPanelHeight;
  const bool min_drawn = std::isfinite(ch.min), max_drawn = std::isfinite(ch.max);

  // Vertical range: the limits and every finite sample, padded 5 %; a flat range is widened.
  double lo = std::numeric_limits<double>::infinity(), hi = -lo;
  const auto include = [&](double v) {
    if (std::isfinite(v)) lo = std::min(lo, v), hi = std::max(hi, v);
  };
  include(ch.min);
  include(ch.max);
  for (const auto* series : {&ch.commanded, &ch.measured})
    for (std::size_t i = 0; i < std::min(series->size(), seconds.size()); ++i) include((*series)[i]);
  if (!(lo <= hi)) lo = 0, hi = 1;
  if (!(hi > lo)) {
    const double half = std::max(0.5, std::abs(lo) * 0.05);
    lo -= half, hi += half;
  }
  const double pad = 0.05 * (hi - lo);
  if (std::isfinite(lo - pad) && std::isfinite(hi + pad)) lo -= pad, hi += pad;
  const Scale y{lo, hi, bottom, top};

  svg += "<g class=\"panel\">\n";
  text(svg, kLeft, top - 7, xml_text(ch.name), "class=\"channel\" font-size=\"12\" font-weight=\"bold\"");
  svg += "<rect x=\"" + coord(kLeft) + "\" y=\"" + coord(top) + "\" width=\"" + coord(kWidth - kLeft - kRight) +
         "\" height=\"" + coord(kPanelHeight) + "\" fill=\"none\" stroke=\"" + std::string(kFrameColour) + "\"/>\n";
  for (double t : time_ticks) line(svg, x.map(t), top, x.map(t), bottom, kGridColour);
  const double y_step = nice_step(hi - lo, 4);
  for (double v : ticks(lo, hi, y_step)) {
    line(svg, kLeft, y.map(v), kWidth - kRight, y.map(v), kGridColour);
    line(svg, kLeft - 4, y.map(v), kLeft, y.map(v), kFrameColour);
    text(svg, kLeft - 6, y.map(v) + 4, tick_label(v, y_step), "class=\"tick-y\" text-anchor=\"end\"");
  }
  if (!ch.unit.empty()) {
    const double cx = 18, cy = (top + bottom) / 2;
    text(svg, cx, cy, xml_text(ch.unit),
         "class=\"unit\" text-anchor=\"middle\" transform=\"rotate(-90 " + coord(cx) + ' ' + coord(cy) + ")\"");
  }
  for (auto [drawn, limit] : {std::pair{min_drawn, ch.min}, std::pair{max_drawn, ch.max}})
    if (drawn)
      line(svg, kLeft, y.map(limit), kWidth - kRight, y.map(limit), kLimitColour,
           "class=\"limit\" stroke-dasharray=\"6 4\"");
  for (const MarkerLabel& m : markers)
    line(svg, m.x, top, m.x, bottom, kMarkerColour, "class=\"marker\" stroke-dasharray=\"2 3\"");
  series(svg, series_shape(seconds, ch.commanded, x, y), "commanded", kCommandedColour, "1.6");
  if (!ch.measured.empty()) series(svg, series_shape(seconds, ch.measured, x, y), "measured", kMeasuredColour, "1.3");
  svg += "</g>\n";
}

}  // namespace

void write_svg_plot(std::ostream& out, const PlotData& data) {
  std::string svg;
  double t0 = std::numeric_limits<double>::infinity(), t1 = -t0;
  for (double t : data.seconds)
    if (std::isfinite(t)) t0 = std::min(t0, t), t1 = std::max(t1, t);
  if (!(t0 <= t1)) {
    write_message(svg, data.title, "no samples");
  } else if (data.channels.empty()) {
    write_message(svg, data.title, "no channels");
  } else {
    if (!(t1 > t0)) t0 -= 0.5, t1 += 0.5;  // a single instant sits in the middle
    const Scale x{t0, t1, kLeft, kWidth - kRight};
    const double t_step = nice_step(t1 - t0, 10);
    const std::vector<double> time_ticks = ticks(t0, t1, t_step);
    const std::vector<MarkerLabel> markers = place_marker_labels(data, x);
    int rows = 0;
    for (const MarkerLabel& m : markers) rows = std::max(rows, m.row + 1);
    const double first_top = kMarkerBandTop + kMarkerRowHeight * rows + kPanelHeader;
    const double panels = static_cast<double>(data.channels.size());
    const double last_bottom = first_top + panels * kPanelHeight + (panels - 1) * (kPanelGap + kPanelHeader);
    const double height = last_bottom + kTimeAxisHeight;

    document_start(svg, height, data.title);
    const bool any_measured = std::any_of(data.channels.begin(), data.channels.end(),
                                          [](const PlotChannel& c) { return !c.measured.empty(); });
    const bool any_limit = std::any_of(data.channels.begin(), data.channels.end(),
                                       [](const PlotChannel& c) { return std::isfinite(c.min) || std::isfinite(c.max); });
    legend(svg, any_measured, any_limit, !markers.empty());

    // Marker labels, each on the top of its line; the line stops above the channel names and
    // goes on in every panel.
    svg += "<g class=\"markers\">\n";
    const double band_bottom = kMarkerBandTop + kMarkerRowHeight * rows + 2;
    for (const MarkerLabel& m : markers) {
      const double baseline = kMarkerBandTop + kMarkerRowHeight * (m.row + 1) - 3;
      line(svg, m.x, baseline - 9, m.x, band_bottom, kMarkerColour, "stroke-dasharray=\"2 3\"");
      text(svg, m.anchor_end ? m.x - 3 : m.x + 3, baseline, escape(m.text),
           m.anchor_end ? "class=\"marker-label\" fill=\"#444444\" text-anchor=\"end\"" : "class=\"marker-label\" fill=\"#444444\"");
    }
    svg += "</g>\n";

    for (std::size_t p = 0; p < data.channels.size(); ++p)
      panel(svg, data.channels[p], data.seconds, x, time_ticks, markers,
            first_top + static_cast<double>(p) * (kPanelHeight + kPanelGap + kPanelHeader));

    // The shared time axis, under the last panel.
    svg += "<g class=\"time-axis\">\n";
    for (double t : time_ticks) {
      line(svg, x.map(t), last_bottom, x.map(t), last_bottom + 4, kFrameColour);
      text(svg, x.map(t), last_bottom + 16, tick_label(t, t_step), "class=\"tick-t\" text-anchor=\"middle\"");
    }
    text(svg, (kLeft + kWidth - kRight) / 2, last_bottom + 36, "time (s)", "text-anchor=\"middle\"");
    svg += "</g>\n</svg>\n";
  }
  out.write(svg.data(), static_cast<std::streamsize>(svg.size()));
}

void write_svg_plot_file(const std::string& path, const PlotData& data) {
  std::ofstream file(path, std::ios::binary | std::ios::trunc);
  if (!file) throw std::runtime_error("cannot write plot file " + path);
  write_svg_plot(file, data);
  file.close();
  if (!file) throw std::runtime_error("cannot write plot file " + path);
}

}  // namespace avar::app
