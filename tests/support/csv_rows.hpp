#pragma once
// Reading CSV output (avar sample, traces) in tests: rows of cells split at commas, no quoting
// (avar never writes quoted cells).

#include <istream>
#include <sstream>
#include <string>
#include <vector>

namespace avar::testing {

inline std::vector<std::string> csv_cells(const std::string& line) {
  std::vector<std::string> cells;
  std::stringstream in(line);
  for (std::string cell; std::getline(in, cell, ',');) cells.push_back(cell);
  return cells;
}

inline std::vector<std::vector<std::string>> csv_rows(std::istream& lines) {
  std::vector<std::vector<std::string>> rows;
  for (std::string line; std::getline(lines, line);) rows.push_back(csv_cells(line));
  return rows;
}

inline std::vector<std::vector<std::string>> csv_rows(const std::string& text) {
  std::stringstream lines(text);
  return csv_rows(lines);
}

}  // namespace avar::testing
