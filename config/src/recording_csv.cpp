#include "avar/config/recording_csv.hpp"

#include <charconv>
#include <cmath>
#include <fstream>
#include <istream>
#include <set>

#include "avar/core/format.hpp"
#include "avar/core/input_error.hpp"

namespace avar::config {
namespace {

struct Cell {
  std::string text;
  int column = 1;  ///< 1-based character column where the cell starts
};

std::vector<Cell> split_cells(const std::string& line) {
  std::vector<Cell> cells;
  std::size_t start = 0;
  for (;;) {
    const std::size_t comma = line.find(',', start);
    const std::size_t end = comma == std::string::npos ? line.size() : comma;
    std::string text = line.substr(start, end - start);
    const auto first = text.find_first_not_of(" \t");
    const auto last = text.find_last_not_of(" \t");
    text = first == std::string::npos ? "" : text.substr(first, last - first + 1);
    cells.push_back({text, static_cast<int>(start) + 1});
    if (comma == std::string::npos) return cells;
    start = comma + 1;
  }
}

double parse_number(const std::string& path, int line, const Cell& cell, const std::string& column_name) {
  double value = 0;
  const char* begin = cell.text.data();
  const char* end = begin + cell.text.size();
  const auto [ptr, ec] = std::from_chars(begin, end, value);
  const SourceLocation where{path, line, cell.column};
  if (cell.text.empty() || ec != std::errc() || ptr != end)
    throw InputError(where, "found '" + cell.text + "' in column '" + column_name + "'; expected a number");
  if (!std::isfinite(value))
    throw InputError(where, "found " + cell.text + " in column '" + column_name + "'; expected a finite number");
  return value;
}

}  // namespace

Recording read_recording(std::istream& file, const std::string& path) {
  Recording r;
  std::string line;
  int number = 0;
  bool header = false;
  while (std::getline(file, line)) {
    ++number;
    if (!line.empty() && line.back() == '\r') line.pop_back();
    if (line.find_first_not_of(" \t") == std::string::npos) continue;
    const std::vector<Cell> cells = split_cells(line);
    if (!header) {
      header = true;
      if (cells[0].text != "seconds")
        throw InputError({path, number, cells[0].column},
                         "found '" + cells[0].text + "' as the first column; expected the header to start with 'seconds'");
      if (cells.size() < 2)
        throw InputError({path, number, 1}, "found only 'seconds' in the header; expected at least one channel column");
      std::set<std::string> seen;
      for (std::size_t c = 1; c < cells.size(); ++c) {
        if (cells[c].text.empty())
          throw InputError({path, number, cells[c].column}, "found an empty channel name; expected a name");
        if (!seen.insert(cells[c].text).second)
          throw InputError({path, number, cells[c].column},
                           "channel '" + cells[c].text + "' appears twice; expected each channel once");
        r.channels.push_back(cells[c].text);
      }
      r.values.resize(r.channels.size());
      continue;
    }
    if (cells.size() != r.channels.size() + 1)
      throw InputError({path, number, 1}, "found " + std::to_string(cells.size()) + " cells; expected " +
                                              std::to_string(r.channels.size() + 1) + " (seconds and the " +
                                              std::to_string(r.channels.size()) + " channels of the header)");
    const double t = parse_number(path, number, cells[0], "seconds");
    if (t < 0)
      throw InputError({path, number, cells[0].column},
                       "found time " + format_number(t) + " s; expected times of 0 s or more (show keys lie within the show)");
    if (!r.times.empty() && !(t > r.times.back()))
      throw InputError({path, number, cells[0].column}, "time " + format_number(t) + " s is not after the previous row's " +
                                                            format_number(r.times.back()) +
                                                            " s; expected times to strictly increase");
    r.times.push_back(t);
    r.lines.push_back(number);
    for (std::size_t c = 0; c < r.channels.size(); ++c)
      r.values[c].push_back(parse_number(path, number, cells[c + 1], r.channels[c]));
  }
  if (!header) throw InputError({path, 1, 1}, "the file is empty; expected a header 'seconds,<channel>,...' and rows of samples");
  if (r.times.empty())
    throw InputError({path, number, 1}, "found no rows after the header; expected at least one row of samples");
  if (!(r.times.back() > 0))
    throw InputError({path, r.lines.back(), 1},
                     "the samples end at 0 s; expected the last sample after 0 s (the show's duration)");
  return r;
}

Recording read_recording(const std::string& path) {
  std::ifstream file(path);
  if (!file) throw InputError({path, 0, 0}, "cannot open the file; expected a readable CSV file (as `avar sample` writes)");
  return read_recording(file, path);
}

}  // namespace avar::config
