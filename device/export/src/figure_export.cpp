#include "avar/device/figure_export.hpp"

#include <cmath>
#include <stdexcept>

#include "avar/core/format.hpp"
#include "avar/core/input_error.hpp"
#include "avar/device/figure.hpp"
#include "avar/firmware_iface/pca9685_codec.hpp"
#include "little_endian.hpp"

namespace avar::device {
namespace {

std::int32_t pulse_ns(double us) { return static_cast<std::int32_t>(std::lround(us * 1000.0)); }

std::size_t board_for(FigureSpec& figure, const rig::LinkSpec& link) {
  for (std::size_t b = 0; b < figure.boards.size(); ++b)
    if (figure.boards[b].link == link.name) return b;
  const auto& o = link.options_as<rig::Pca9685Options>();
  FigureBoardSpec board;
  board.link = link.name;
  board.address = o.address;
  board.frequency_hz = o.frequency_hz;
  board.clock_hz = static_cast<std::uint32_t>(o.clock_hz);
  board.prescale = firmware_iface::pca9685::prescale_for(board.clock_hz, static_cast<std::uint32_t>(o.frequency_hz));
  board.totem_pole = o.totem_pole;
  if (figure.boards.size() == kMaxBoards)
    throw InputError(link.where, "link '" + link.name + "' is a " + std::to_string(kMaxBoards + 1) +
                                     "th PCA9685 board; a device figure drives at most " + std::to_string(kMaxBoards));
  figure.boards.push_back(board);
  return figure.boards.size() - 1;
}

/// A streaming board's PCA9685 for output n: boards at 0x40, 0x41, ... with 16 outputs each,
/// hobby-servo pulses at 50 Hz from the internal 25 MHz oscillator.
std::size_t streaming_board_for(FigureSpec& figure, const rig::LinkSpec& link, int output) {
  const auto index = static_cast<std::size_t>(output / 16);
  while (figure.boards.size() <= index) {
    if (figure.boards.size() == kMaxBoards)
      throw InputError(link.where, "link '" + link.name + "' has outputs beyond " + std::to_string(16 * kMaxBoards) +
                                       "; a streaming board drives at most " + std::to_string(kMaxBoards) + " PCA9685 boards");
    FigureBoardSpec board;
    board.link = link.name;
    board.address = 0x40 + static_cast<int>(figure.boards.size());
    board.prescale = firmware_iface::pca9685::prescale_for(board.clock_hz, static_cast<std::uint32_t>(board.frequency_hz));
    figure.boards.push_back(board);
  }
  return index;
}

/// The figure of a standalone board (pca9685 links) or of a streaming one (an avar-device link).
FigureSpec figure_of(const rig::Rig& rig, bool streaming) {
  FigureSpec figure;
  figure.rig = rig.name;
  const char* protocol = streaming ? "avar-device" : "pca9685";
  const rig::LinkSpec* pin_link = nullptr;  // the pwm link: the device's own pins
  if (streaming) {
    const rig::LinkSpec* link = nullptr;
    for (const rig::LinkSpec& l : rig.links)
      if (l.protocol == protocol) link = &l;
    if (!link)
      throw InputError(SourceLocation{rig.file, 1, 1},
                       "rig '" + rig.name + "' has no avar-device link; a streaming board is the device of one");
    figure.rate = static_cast<std::uint32_t>(link->options_as<rig::AvarDeviceOptions>().device_rate_hz);
  } else {
    if (!(rig.rate_hz >= 1 && rig.rate_hz <= 1000 && rig.rate_hz == std::floor(rig.rate_hz)))
      throw InputError(SourceLocation{rig.file, 1, 1},
                       "rig '" + rig.name + "' ticks at " + format_number(rig.rate_hz) +
                           " Hz; a device figure needs a whole number of ticks per second, 1 to 1000");
    figure.rate = static_cast<std::uint32_t>(rig.rate_hz);
  }
  std::vector<int> actuator_of(rig.channels.size(), -1);
  for (std::size_t a = 0; a < rig.actuators.size(); ++a) {
    const rig::ActuatorSpec& act = rig.actuators[a];
    const rig::LinkSpec& link = rig.link(act.link);
    const rig::ChannelSpec& ch = rig.channel(act.channel);
    const bool on_pin = !streaming && link.protocol == "pwm";
    if (link.protocol != protocol && !on_pin)
      throw InputError(act.where, "channel '" + ch.name + "' is on link '" + link.name + "' (" + link.protocol + "); " +
                                      (streaming ? "a streaming board drives the channels of its avar-device link"
                                                 : "a device figure drives hobby servos on PCA9685 boards or on its own "
                                                   "pins: give the channel a pca9685 or a pwm link"));
    if (on_pin && pin_link && pin_link != &link)
      throw InputError(act.where, "channel '" + ch.name + "' is on pwm link '" + link.name + "', but link '" + pin_link->name +
                                      "' has the device's pins already; a device has one set of pins: put every pin servo "
                                      "on one pwm link");
    if (on_pin) pin_link = &link;
    if (ch.digital())
      throw InputError(ch.where, "channel '" + ch.name + "' is digital; a device figure drives servo pulses (analog channels)");
    if (actuator_of[act.channel.value] >= 0)
      throw InputError(act.where,
                       "channel '" + ch.name + "' has a second actuator; a device figure drives one output per channel");
    actuator_of[act.channel.value] = static_cast<int>(a);
  }
  for (std::size_t c = 0; c < rig.channels.size(); ++c) {
    if (actuator_of[c] < 0) continue;
    const rig::ChannelSpec& ch = rig.channels[c];
    const rig::ActuatorSpec& act = rig.actuators[static_cast<std::size_t>(actuator_of[c])];
    FigureChannelSpec spec;
    spec.name = ch.name;
    spec.range = {ch.min, ch.max};
    spec.rest = ch.rest;
    try {
      spec.limits = (streaming ? streaming_limits : device_limits)(spec.range, ch.rest, ch.max_velocity, ch.max_acceleration,
                                                                   ch.soft_margin, figure.rate);
    } catch (const std::invalid_argument& e) {
      throw InputError(ch.where, "channel '" + ch.name + "': " + e.what());
    }
    const rig::LinkSpec& link = rig.link(act.link);
    spec.on_pin = &link == pin_link;
    if (spec.on_pin) {
      figure.pin_rate = static_cast<std::uint32_t>(link.options_as<rig::PwmOptions>().frequency_hz);
    } else {
      spec.board = streaming ? streaming_board_for(figure, link, act.device_channel) : board_for(figure, link);
    }
    spec.output = streaming ? act.device_channel % 16 : act.device_channel;
    spec.at_low_ns = pulse_ns(act.calibration.to_device(ch.min));
    spec.at_high_ns = pulse_ns(act.calibration.to_device(ch.max));
    const std::int32_t lowest = spec.on_pin ? kMinPinPulseNs : kMinPulseNs, highest = spec.on_pin ? kMaxPinPulseNs : kMaxPulseNs;
    for (const std::int32_t ns : {spec.at_low_ns, spec.at_high_ns})
      if (ns < lowest || ns > highest)
        throw InputError(act.where, "channel '" + ch.name + "' asks a pulse of " + format_number(ns / 1000.0) + " us; " +
                                        (spec.on_pin ? "a pin servo's pulses lie within 544 to 2400 us (what the boards' "
                                                       "Servo libraries put out)"
                                                     : "a device figure's pulses lie within 100 to 5000 us"));
    figure.channels.push_back(spec);
  }
  if (figure.channels.empty())
    throw InputError(SourceLocation{rig.file, 1, 1},
                     "rig '" + rig.name + "' has no actuator; a device figure needs at least one");
  if (figure.channels.size() > kMaxChannels)
    throw InputError(SourceLocation{rig.file, 1, 1}, "rig '" + rig.name + "' drives " + std::to_string(figure.channels.size()) +
                                                         " channels; a device figure drives at most " +
                                                         std::to_string(kMaxChannels));
  return figure;
}

}  // namespace

FigureSpec figure_from_rig(const rig::Rig& rig) { return figure_of(rig, false); }

FigureSpec stream_figure_from_rig(const rig::Rig& rig) { return figure_of(rig, true); }

std::vector<std::uint8_t> encode_figure_record(const FigureSpec& figure) {
  std::vector<std::uint8_t> out = {'a',
                                   'v',
                                   'f',
                                   '1',
                                   kFigureVersion,
                                   static_cast<std::uint8_t>(figure.channels.size()),
                                   static_cast<std::uint8_t>(figure.boards.size()),
                                   0};
  put_fixed(out, figure.rate, 2);
  put_fixed(out, figure.pin_rate, 2);
  for (const FigureBoardSpec& b : figure.boards) {
    out.push_back(static_cast<std::uint8_t>(b.address));
    out.push_back(b.prescale);
    out.push_back(b.totem_pole ? 1 : 0);
    out.push_back(0);
    put_fixed(out, b.clock_hz, 4);
  }
  for (const FigureChannelSpec& c : figure.channels) {
    std::uint8_t limits[kLimitsSize];
    write_limits(c.limits, limits);
    out.insert(out.end(), limits, limits + kLimitsSize);
    out.push_back(c.on_pin ? kPinOutput : static_cast<std::uint8_t>(c.board));
    out.push_back(static_cast<std::uint8_t>(c.output));
    put_fixed(out, 0, 2);
    put_fixed(out, static_cast<std::uint32_t>(c.at_low_ns), 4);
    put_fixed(out, static_cast<std::uint32_t>(c.at_high_ns), 4);
  }
  return out;
}

std::vector<ImageChannel> image_channels(const FigureSpec& figure) {
  std::vector<ImageChannel> channels;
  for (const FigureChannelSpec& c : figure.channels) channels.push_back({c.name, c.range});
  return channels;
}

}  // namespace avar::device
