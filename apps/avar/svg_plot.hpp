#pragma once
// The plot of `avar play --plot FILE.svg`: one panel per channel, commanded and simulated
// position over a shared time axis, the channel's limits dashed, phase changes marked. A small
// hand-written SVG writer (no plotting library in the dependency set covers this).
//
// Offline code: allocates, may throw; never call it from the real-time loop. The functions keep
// no state, so different threads may write different plots at the same time.

#include <cstddef>
#include <iosfwd>
#include <string>
#include <utility>
#include <vector>

namespace avar::app {

/// One channel's panel. Positions are in the channel's own unit; sample k belongs to
/// PlotData::seconds[k]. A series shorter than `seconds` ends early, longer is cut.
struct PlotChannel {
  std::string name;
  std::string unit;              ///< labels the y axis; may be empty
  double min = 0;                ///< channel limits, drawn dashed; a non-finite limit is not drawn
  double max = 1;
  std::vector<double> commanded;
  std::vector<double> measured;  ///< empty when there is no feedback; a non-finite sample breaks the line
};

struct PlotData {
  std::string title;
  std::vector<double> seconds;  ///< time of each sample, s, non-decreasing
  std::vector<PlotChannel> channels;
  /// Time (s) and label of each phase change, e.g. {0.0, "homing"}; times outside the samples'
  /// span are not drawn.
  std::vector<std::pair<double, std::string>> markers;
};

/// At most this many points in the line of one series: long runs are decimated to the lowest and
/// highest sample of each horizontal pixel, so short spikes stay visible.
inline constexpr std::size_t kMaxPlotPointsPerLine = 2000;

/// Writes a complete SVG document (UTF-8, valid XML): the same data gives the same bytes,
/// whatever the stream's formatting flags or locale. Text is escaped; control characters and
/// invalid UTF-8 in names become U+FFFD. With no finite sample time or no channel the document
/// says so ("no samples", "no channels") instead of drawing panels.
void write_svg_plot(std::ostream& out, const PlotData& data);

/// write_svg_plot to the file at `path` (created or truncated); throws std::runtime_error naming
/// the path when it cannot be opened or written.
void write_svg_plot_file(const std::string& path, const PlotData& data);

}  // namespace avar::app
