#pragma once
// The text both kinds of exported project share (a show-playing figure, a streaming board): C++
// identifiers and byte arrays, figures with thousands separators, and the library's own files.

#include <cstdint>
#include <string>
#include <vector>

#include "avar/device/project_export.hpp"

namespace avar::device {

/// `name` as a C++ identifier: anything but letters and digits an underscore, never a leading digit.
std::string identifier(const std::string& name);
/// 32,256
std::string with_commas(std::size_t n);
/// The bytes as the body of a C array initializer, 16 to a line.
std::string byte_array(const std::vector<std::uint8_t>& bytes);
/// "0x40"
std::string hex_byte(int value);

/// library.properties and library.json for the project, naming `include` as the header a sketch
/// includes; `sentence` and `paragraph` describe the library.
void add_library_files(Project& project, const ExportOptions& options, const std::string& include, const std::string& sentence,
                       const std::string& paragraph);
/// The engine's and the figure's sources as this avar was built with them (config.hpp set to the
/// project's features), those of the project's kind only (a streaming board's player and
/// protocol, or a show player's Arduino glue).
void add_source_files(Project& project);
/// The embedded source at `path` ("host/avar_figure_host.cpp").
std::string embedded_text(const std::string& path);

}  // namespace avar::device
