#include "project_text.hpp"

#include <cctype>
#include <cstdio>
#include <stdexcept>

#include "avar/device/show_image.hpp"
#include "embedded_sources.hpp"

namespace avar::device {
namespace {

std::string json_string(const std::string& text) {
  std::string out = "\"";
  for (const char c : text) {
    if (c == '"' || c == '\\') out += '\\';
    out += c;
  }
  return out + "\"";
}

std::string config_header(std::uint8_t features, bool fast, bool pins) {
  std::string text = "// Written by avar export: this project's shows use only what is switched on here.\n";
  text += std::string("#define AVAR_DEVICE_EASINGS ") + (features & kFeatureEasings ? "1" : "0") + "\n";
  text += std::string("#define AVAR_DEVICE_CYCLES ") + (features & kFeatureCycles ? "1" : "0") + "\n";
  text += std::string("#define AVAR_DEVICE_EXTRAPOLATION ") + (features & kFeatureExtrapolation ? "1" : "0") + "\n";
  text += std::string("#define AVAR_DEVICE_FAST ") + (fast ? "1" : "0") + "\n";
  text += std::string("#define AVAR_DEVICE_PINS ") + (pins ? "1" : "0") + "\n";
  return text;
}

/// Whether the embedded source at `path` belongs in a project of this kind: the streaming
/// player, its protocol and its glue in a streaming board's; the show player's glue in a figure's;
/// no Arduino glue (src/avar_*) in a Linux program's.
bool of_kind(const std::string& path, bool stream, bool host) {
  if (host && path.rfind("src/avar_", 0) == 0) return false;  // the Arduino glue: not in a Linux program
  const bool streaming_only = path.find("/stream_") != std::string::npos || path.find("avar_device_codec") != std::string::npos ||
                              path.rfind("src/avar_stream_figure.", 0) == 0;
  const bool shows_only = path.rfind("src/avar_figure.", 0) == 0 || path.rfind("src/avar_pin_io.", 0) == 0;
  return stream ? !shows_only : !streaming_only;
}

}  // namespace

std::string identifier(const std::string& name) {
  std::string id;
  for (const char ch : name) id += std::isalnum(static_cast<unsigned char>(ch)) ? ch : '_';
  if (id.empty() || std::isdigit(static_cast<unsigned char>(id.front()))) id.insert(0, "_");
  return id;
}

std::string with_commas(std::size_t n) {
  std::string digits = std::to_string(n), out;
  for (std::size_t i = 0; i < digits.size(); ++i) {
    if (i != 0 && (digits.size() - i) % 3 == 0) out += ',';
    out += digits[i];
  }
  return out;
}

std::string byte_array(const std::vector<std::uint8_t>& bytes) {
  std::string text;
  char hex[8];
  for (std::size_t i = 0; i < bytes.size(); ++i) {
    text += i % 16 == 0 ? "\n    " : " ";
    std::snprintf(hex, sizeof hex, "0x%02x,", bytes[i]);
    text += hex;
  }
  return text + "\n";
}

std::string hex_byte(int value) {
  char hex[8];
  std::snprintf(hex, sizeof hex, "0x%02x", value & 0xff);
  return hex;
}

void add_library_files(Project& p, const ExportOptions& o, const std::string& include, const std::string& sentence,
                       const std::string& paragraph) {
  // Servos on pins: the core's Servo library, but an ESP32's is a library of its own.
  const bool esp32_servo = p.target->architecture == "esp32" && p.figure.pin_rate != 0;
  p.files.push_back({"library.properties",
                     "name=" + p.library_name + "\nversion=" + o.version +
                         "\nauthor=avar export\nmaintainer=avar export\nsentence=" + sentence + "\nparagraph=" + paragraph +
                         "\ncategory=Device Control\nurl=" + (o.url.empty() ? "file:///" + p.library_name : o.url) +
                         "\narchitectures=" + std::string(p.target->architecture) + "\nincludes=" + include + "\n" +
                         (esp32_servo ? "depends=ESP32Servo\n" : "")});
  p.files.push_back(
      {"library.json", "{\n  \"name\": " + json_string(p.library_name) + ",\n  \"version\": " + json_string(o.version) +
                           ",\n  \"description\": " + json_string(sentence) +
                           ",\n  \"keywords\": [\"avar\", \"animatronics\", \"servo\", \"pca9685\"],\n"
                           "  \"frameworks\": \"arduino\",\n  \"platforms\": " +
                           json_string(std::string(p.target->platformio)) +
                           (esp32_servo ? ",\n  \"dependencies\": {\"madhephaestus/ESP32Servo\": \"*\"}" : "") + "\n}\n"});
}

std::string embedded_text(const std::string& path) {
  for (const EmbeddedSource& e : embedded_sources())
    if (path == e.path) return e.text;
  throw std::logic_error("no embedded source " + path);
}

void add_source_files(Project& p) {
  for (const EmbeddedSource& e : embedded_sources()) {
    const std::string path = e.path;
    if (path.rfind("src/", 0) != 0 || !of_kind(path, p.stream, p.target->host())) continue;  // not verify/ or host/
    p.files.push_back({path, path == "src/avar/device/config.hpp"
                                 ? config_header(p.features, p.fast, p.figure.pin_rate != 0) + e.text
                                 : e.text});
  }
}

}  // namespace avar::device
