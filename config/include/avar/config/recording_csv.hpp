#pragma once
// The CSV of recorded samples `avar fit` reads (as `avar sample` writes it): a header
// `seconds,<channel>,...`, then one row of numbers per sample time. Load time only: allocates and
// throws InputError naming file, line and column.

#include <iosfwd>
#include <string>
#include <vector>

namespace avar::config {

/// The samples of a CSV: one time column, one value column per channel.
struct Recording {
  std::vector<std::string> channels;
  std::vector<double> times;
  std::vector<std::vector<double>> values;  ///< [channel][row]
  std::vector<int> lines;                   ///< file line of each row
};

/// Reads and validates the whole CSV: InputError for an unreadable or empty file, a header that
/// does not start with `seconds` or has no channel, empty or repeated channel names, rows with
/// another cell count than the header, cells that are not finite numbers, times below 0 or not
/// strictly increasing, no rows, samples spanning no time.
Recording read_recording(const std::string& path);

/// The same from a stream; `path` names it in errors.
Recording read_recording(std::istream& file, const std::string& path);

}  // namespace avar::config
