#pragma once
// The plot of `avar play --plot FILE.svg`: one panel per channel, commanded and measured
// position over time, the channel's limits dashed, phase changes marked. A small hand-written
// SVG writer (no plotting library in the dependency set covers this). Offline code: allocates.

#include <iosfwd>
#include <string>
#include <utility>
#include <vector>

namespace avar::app {

struct PlotChannel {
  std::string name;
  std::string unit;
  double min = 0;  ///< channel limits, drawn dashed
  double max = 1;
  std::vector<double> commanded;
  std::vector<double> measured;  ///< empty when there is no feedback; NaN breaks the line
};

struct PlotData {
  std::string title;
  std::vector<double> seconds;
  std::vector<PlotChannel> channels;
  std::vector<std::pair<double, std::string>> markers;  ///< time and label of each phase change
};

/// Writes a complete, deterministic SVG document.
void write_svg_plot(std::ostream& out, const PlotData& data);
/// Same, to a file; throws std::runtime_error naming the path when it cannot be written.
void write_svg_plot_file(const std::string& path, const PlotData& data);

}  // namespace avar::app
