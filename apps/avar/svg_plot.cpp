#include "avar/svg_plot.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <limits>
#include <ostream>
#include <stdexcept>

namespace avar::app {
namespace {

constexpr double kWidth = 1000;
constexpr double kLeft = 80;
constexpr double kRight = 20;
constexpr double kTop = 50;
constexpr double kPanelHeight = 120;
constexpr double kPanelGap = 34;
constexpr double kBottom = 40;
constexpr std::size_t kMaxBuckets = 1000;  // min and max per bucket: at most 2000 points a line
const char* const kCommandColour = "#1f77b4";
const char* const kMeasuredColour = "#e6550d";

std::string escape(const std::string& text) {
  std::string out;
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

std::string num(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.2f", v);
  return buf;
}

std::string label(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%g", std::abs(v) < 1e-12 ? 0.0 : v);
  return buf;
}

/// Tick spacing of 1, 2 or 5 times a power of ten giving about `target` intervals.
double nice_step(double span, int target) {
  if (!(span > 0)) return 1;
  const double raw = span / target;
  const double p = std::pow(10.0, std::floor(std::log10(raw)));
  for (double m : {1.0, 2.0, 5.0})
    if (raw <= m * p) return m * p;
  return 10 * p;
}

struct Axis {
  double lo, hi, pix_lo, pix_hi;
  double map(double v) const { return pix_lo + (v - lo) / (hi - lo) * (pix_hi - pix_lo); }
};

/// Polyline path of a series, decimated to min/max per bucket, broken at NaN.
std::string path_of(const std::vector<double>& t, const std::vector<double>& v, const Axis& x, const Axis& y) {
  std::string d;
  bool pen_down = false;
  const std::size_t n = std::min(t.size(), v.size());
  const std::size_t per_bucket = std::max<std::size_t>(1, (n + kMaxBuckets - 1) / kMaxBuckets);
  for (std::size_t start = 0; start < n; start += per_bucket) {
    const std::size_t end = std::min(n, start + per_bucket);
    std::size_t lo = end, hi = end;
    bool gap = false;
    for (std::size_t i = start; i < end; ++i) {
      if (std::isnan(v[i])) {
        gap = true;
        continue;
      }
      if (lo == end || v[i] < v[lo]) lo = i;
      if (hi == end || v[i] > v[hi]) hi = i;
    }
    if (lo == end) {
      pen_down = false;
      continue;
    }
    for (std::size_t i : {std::min(lo, hi), std::max(lo, hi)}) {
      d += (pen_down ? " L" : " M") + num(x.map(t[i])) + "," + num(y.map(v[i]));
      pen_down = true;
      if (lo == hi) break;
    }
    if (gap) pen_down = false;
  }
  return d;
}

}  // namespace

void write_svg_plot(std::ostream& out, const PlotData& data) {
  const std::size_t panels = data.channels.size();
  const double height = kTop + static_cast<double>(std::max<std::size_t>(panels, 1)) * (kPanelHeight + kPanelGap) + kBottom;
  out << "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n"
      << "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"" << kWidth << "\" height=\"" << num(height) << "\" viewBox=\"0 0 "
      << kWidth << ' ' << num(height) << "\" font-family=\"sans-serif\" font-size=\"11\">\n"
      << "<rect width=\"100%\" height=\"100%\" fill=\"white\"/>\n"
      << "<text x=\"" << kLeft << "\" y=\"22\" font-size=\"15\" font-weight=\"bold\">" << escape(data.title) << "</text>\n"
      << "<line x1=\"" << kWidth - 300 << "\" y1=\"18\" x2=\"" << kWidth - 276 << "\" y2=\"18\" stroke=\"" << kCommandColour
      << "\" stroke-width=\"2\"/><text x=\"" << kWidth - 270 << "\" y=\"22\">commanded</text>\n"
      << "<line x1=\"" << kWidth - 170 << "\" y1=\"18\" x2=\"" << kWidth - 146 << "\" y2=\"18\" stroke=\"" << kMeasuredColour
      << "\" stroke-width=\"2\"/><text x=\"" << kWidth - 140 << "\" y=\"22\">simulated</text>\n";
  if (data.seconds.empty() || panels == 0) {
    out << "<text x=\"" << kLeft << "\" y=\"" << kTop + 40 << "\">no samples</text>\n</svg>\n";
    return;
  }
  const double t0 = data.seconds.front();
  const double t1 = std::max(data.seconds.back(), t0 + 1e-9);
  const double t_step = nice_step(t1 - t0, 10);

  for (std::size_t p = 0; p < panels; ++p) {
    const PlotChannel& ch = data.channels[p];
    const double top = kTop + static_cast<double>(p) * (kPanelHeight + kPanelGap) + 14;
    const double bottom = top + kPanelHeight;
    double lo = std::min(ch.min, ch.max), hi = std::max(ch.min, ch.max);
    for (const auto* series : {&ch.commanded, &ch.measured})
      for (double v : *series)
        if (std::isfinite(v)) lo = std::min(lo, v), hi = std::max(hi, v);
    if (!(hi > lo)) hi = lo + 1;
    const double pad = 0.05 * (hi - lo);
    const Axis x{t0, t1, kLeft, kWidth - kRight};
    const Axis y{lo - pad, hi + pad, bottom, top};

    out << "<g>\n<text x=\"" << kLeft << "\" y=\"" << num(top - 4) << "\" font-weight=\"bold\">" << escape(ch.name)
        << (ch.unit.empty() ? "" : " (" + escape(ch.unit) + ")") << "</text>\n"
        << "<rect x=\"" << kLeft << "\" y=\"" << num(top) << "\" width=\"" << kWidth - kLeft - kRight << "\" height=\""
        << kPanelHeight << "\" fill=\"none\" stroke=\"#999\"/>\n";
    const double y_step = nice_step(y.hi - y.lo, 4);
    for (double v = std::ceil(y.lo / y_step) * y_step; v <= y.hi; v += y_step)
      out << "<line x1=\"" << kLeft - 4 << "\" y1=\"" << num(y.map(v)) << "\" x2=\"" << kWidth - kRight << "\" y2=\""
          << num(y.map(v)) << "\" stroke=\"#eee\"/><text x=\"" << kLeft - 6 << "\" y=\"" << num(y.map(v) + 4)
          << "\" text-anchor=\"end\">" << label(v) << "</text>\n";
    for (double t = std::ceil(t0 / t_step) * t_step; t <= t1 + 1e-9; t += t_step)
      out << "<line x1=\"" << num(x.map(t)) << "\" y1=\"" << num(bottom) << "\" x2=\"" << num(x.map(t)) << "\" y2=\""
          << num(bottom + 4) << "\" stroke=\"#999\"/><text x=\"" << num(x.map(t)) << "\" y=\"" << num(bottom + 15)
          << "\" text-anchor=\"middle\">" << label(t) << "</text>\n";
    for (double limit : {ch.min, ch.max})
      out << "<line x1=\"" << kLeft << "\" y1=\"" << num(y.map(limit)) << "\" x2=\"" << kWidth - kRight << "\" y2=\""
          << num(y.map(limit)) << "\" stroke=\"#c00\" stroke-dasharray=\"5,4\"/>\n";
    for (std::size_t m = 0; m < data.markers.size(); ++m) {
      const auto& [time, name] = data.markers[m];
      if (time < t0 || time > t1) continue;
      out << "<line x1=\"" << num(x.map(time)) << "\" y1=\"" << num(top) << "\" x2=\"" << num(x.map(time)) << "\" y2=\""
          << num(bottom) << "\" stroke=\"#888\" stroke-dasharray=\"2,3\"/>\n";
      // Labels step down the first panel so that close phase changes stay readable.
      if (p == 0)
        out << "<text x=\"" << num(x.map(time) + 3) << "\" y=\"" << num(top + 11 + 11 * static_cast<double>(m % 3))
            << "\" fill=\"#555\">" << escape(name) << "</text>\n";
    }
    out << "<path d=\"" << path_of(data.seconds, ch.commanded, x, y) << "\" fill=\"none\" stroke=\"" << kCommandColour
        << "\" stroke-width=\"1.5\"/>\n";
    if (!ch.measured.empty())
      out << "<path d=\"" << path_of(data.seconds, ch.measured, x, y) << "\" fill=\"none\" stroke=\"" << kMeasuredColour
          << "\" stroke-width=\"1.2\"/>\n";
    out << "</g>\n";
  }
  out << "<text x=\"" << (kLeft + kWidth - kRight) / 2 << "\" y=\"" << num(height - 8) << "\" text-anchor=\"middle\">time (s)</text>\n";
  out << "</svg>\n";
}

void write_svg_plot_file(const std::string& path, const PlotData& data) {
  std::ofstream file(path);
  if (!file) throw std::runtime_error("cannot write plot file " + path);
  write_svg_plot(file, data);
  if (!file) throw std::runtime_error("cannot write plot file " + path);
}

}  // namespace avar::app
