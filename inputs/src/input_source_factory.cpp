#include "avar/inputs/input_source_factory.hpp"

#include <algorithm>
#include <charconv>
#include <stdexcept>
#include <string>

#include "avar/inputs/hid_input.hpp"
#include "avar/inputs/midi_input.hpp"
#include "avar/inputs/osc_input.hpp"
#include "avar/inputs/prefixed_input_source.hpp"

namespace avar::inputs {

const std::string_view kInputSourceForms =
    "osc://HOST:PORT (osc://:9000 listens on 127.0.0.1 port 9000, osc://0.0.0.0:9000 on every interface), "
    "midi:PORT (part of the port's name or its number: midi:nano, midi:1), hid:VID:PID[:SERIAL] (hex ids: "
    "hid:054c:09cc), each optionally named NAME=URI (pad=hid:054c:09cc names its controls pad.*)";

namespace {

constexpr std::uint16_t kDefaultOscPort = 9000;

[[noreturn]] void bad_uri(std::string_view uri, std::string_view why) {
  throw std::invalid_argument("input '" + std::string(uri) + "': " + std::string(why) + "; expected " +
                              std::string(kInputSourceForms));
}

bool prefix_character(char c) {
  return (c >= 'A' && c <= 'Z') || (c >= 'a' && c <= 'z') || (c >= '0' && c <= '9') || c == '_' || c == '-';
}

std::unique_ptr<InputSource> make_osc(std::string_view uri, std::string_view authority) {
  std::string_view host = authority;
  std::uint16_t port = kDefaultOscPort;
  if (const auto colon = authority.rfind(':'); colon != std::string_view::npos) {
    host = authority.substr(0, colon);
    const std::string_view digits = authority.substr(colon + 1);
    const auto [end, error] = std::from_chars(digits.data(), digits.data() + digits.size(), port);
    if (digits.empty() || error != std::errc{} || end != digits.data() + digits.size())
      bad_uri(uri, "the port must be a number 0..65535");
  }
  if (host.empty()) host = "127.0.0.1";
  try {
    return std::make_unique<OscInput>(std::string(host), port);
  } catch (const std::invalid_argument& e) {
    bad_uri(uri, e.what());
  }
}

std::unique_ptr<InputSource> make_unnamed(std::string_view full, std::string_view uri) {
  if (uri.starts_with("osc://")) {
    std::string_view authority = uri.substr(6);
    if (authority.ends_with('/')) authority.remove_suffix(1);
    if (authority.find('/') != std::string_view::npos) bad_uri(full, "an OSC input takes no path");
    return make_osc(full, authority);
  }
  if (uri.starts_with("midi:")) {
    const std::string_view port = uri.substr(5);
    if (port.empty()) bad_uri(full, "which MIDI port? (`aconnect -i` lists them)");
    return std::make_unique<MidiInput>(std::string(port));
  }
  if (uri.starts_with("hid:")) {
    try {
      return make_hid_input(uri.substr(4));
    } catch (const std::invalid_argument& e) {
      bad_uri(full, e.what());
    }
  }
  bad_uri(full, "unknown kind of input");
}

}  // namespace

std::unique_ptr<InputSource> make_input_source(std::string_view uri) {
  const auto equals = uri.find('=');
  const auto colon = uri.find(':');
  if (equals != std::string_view::npos && (colon == std::string_view::npos || equals < colon)) {
    const std::string_view name = uri.substr(0, equals);
    if (name.empty() || !std::all_of(name.begin(), name.end(), prefix_character))
      bad_uri(uri, "an input's name (before '=') is letters, digits, '_' and '-'");
    return std::make_unique<PrefixedInputSource>(std::string(name), make_unnamed(uri, uri.substr(equals + 1)));
  }
  return make_unnamed(uri, uri);
}

}  // namespace avar::inputs
