// avar export --verify of a streaming board (avar export --stream): the exported figure record
// played by the streaming figure, on the host and under the target's emulator, from one scripted
// stream of avar-device frames. The script is built by the run itself with the protocol's codec
// from a seeded generator, so both builds take the same bytes at the same ticks: knots every
// AVAR_KNOT_US, AVAR_LEAD_US ahead, random values and slopes; avar's clock drifting against the
// board's and arriving late; damaged bytes; hello and query; a silence past the watchdog; channel
// releases and a release of all; a stop; avar's clock starting over; the board's microsecond
// counter wrapping. Every control tick's I2C bytes, every channel's output and every answer's
// bytes are hashed, one line per second: "stream SECOND HASH SAMPLES", then "samples N ticks T".
// Freestanding C++14.
#include "avar/device/stream_figure.hpp"
#include "avar_stream.h"
#include "platform.hpp"
#include "verify_io.hpp"

namespace {

using namespace avar::device;
namespace wire = avar::firmware_iface::avar_device;

StreamFigureStorage<AVAR_CHANNEL_COUNT, AVAR_BOARD_COUNT, AVAR_KNOTS> storage;
StreamFigure& figure = storage.figure;
Hash hash = {2166136261u};

const uint32_t kTickUs = 1000000UL / AVAR_RATE_HZ;
const uint32_t kSeconds = 26;  // the script's length

constexpr FigureIo io = hashing_io(hash);

uint32_t seed = 20261207u;
uint32_t next_random() {  // xorshift32
  seed ^= seed << 13;
  seed ^= seed >> 17;
  seed ^= seed << 5;
  return seed;
}

uint8_t frame[wire::kOverhead + 5 + 4 * AVAR_CHANNEL_COUNT];
uint8_t reply[stream_reply_room(AVAR_CHANNEL_COUNT)];
wire::Knot knots[AVAR_CHANNEL_COUNT];
uint32_t frames_sent = 0;

/// The frame's bytes into the board at `now`, one in 37 with a byte damaged; answers hashed.
void deliver(uint32_t size, uint32_t now) {
  if (++frames_sent % 37 == 0) frame[next_random() % size] ^= static_cast<uint8_t>(1u << (next_random() % 8));
  for (uint32_t i = 0; i < size; ++i) {
    const uint16_t n = stream_receive(figure.player, frame[i], now, reply);
    for (uint16_t k = 0; k < n; ++k) hash.add(reply[k], 1);
  }
}

/// avar's knot frame for `at`: each channel a random step from its last value, a random slope.
void send_knots(uint32_t at, uint32_t now) {
  for (uint8_t c = 0; c < AVAR_CHANNEL_COUNT; ++c) {
    const int32_t step = static_cast<int32_t>(next_random() % 16384u) - 8192;
    int32_t value = static_cast<int32_t>(knots[c].value) + step;
    value = value < 0 ? 0 : value > 65535 ? 65535 : value;
    knots[c].value = static_cast<uint16_t>(value);
    knots[c].slope = wire::slope_field(static_cast<int32_t>(next_random() % 400001u) - 200000);
  }
  deliver(static_cast<uint32_t>(wire::encode_knots(at, knots, AVAR_CHANNEL_COUNT, frame)), now);
}

int run() {
  if (storage.open(avar_stream::kFigure, sizeof avar_stream::kFigure, AVAR_WATCHDOG_US) != kFigureOk ||
      stream_figure_begin(figure, io) != kFigureOk) {
    platform_line("figure refused");
    return 1;
  }
  for (uint8_t c = 0; c < AVAR_CHANNEL_COUNT; ++c) knots[c].value = 32768;
  const uint32_t knot_ticks = AVAR_KNOT_US / kTickUs > 0 ? AVAR_KNOT_US / kTickUs : 1;
  const uint32_t start = 0xffffffffu - 3000000u;  // the board's micros() wraps 3 s in
  uint32_t host_base = 123456789u;                // avar's clock at the script's start
  uint32_t samples = 0, in_second = 0;
  const uint32_t ticks = kSeconds * AVAR_RATE_HZ;
  for (uint32_t t = 0; t < ticks; ++t) {
    const uint32_t now = start + t * kTickUs;
    const uint32_t second = t / AVAR_RATE_HZ, tick_in_second = t % AVAR_RATE_HZ;
    const bool whole_second = tick_in_second == 0;
    if (whole_second && second == 16) host_base -= 7000000u;  // avar starts over: its clock jumps back
    // avar's clock runs 1/4096 fast against the board's and its messages arrive up to 3 ms late.
    const uint32_t elapsed = now - start, host = host_base + elapsed + elapsed / 4096u - next_random() % 3000u;
    // The script: streaming, but silent in second 6 (past the watchdog), stopped in 12..13 and 23..;
    // hello at 0, 11 and 19; a query at 9; channels released at 10, all at 18.
    const bool silent = second == 6 || second == 12 || second == 18 || second >= 23;
    if (whole_second && (second == 0 || second == 11 || second == 19))
      deliver(static_cast<uint32_t>(wire::encode_hello(frame)), now);
    if (whole_second && second == 9) deliver(static_cast<uint32_t>(wire::encode_query(frame)), now);
    if (whole_second && second == 10) {
      const uint8_t mask[(AVAR_CHANNEL_COUNT + 7) / 8] = {1};  // the first channel
      deliver(static_cast<uint32_t>(wire::encode_release_channels(mask, sizeof mask, frame)), now);
    }
    if (whole_second && (second == 12 || second == 23)) deliver(static_cast<uint32_t>(wire::encode_stop(frame)), now);
    if (whole_second && second == 18) deliver(static_cast<uint32_t>(wire::encode_release(frame)), now);
    if (!silent && t % knot_ticks == 0) {
      deliver(static_cast<uint32_t>(wire::encode_time(host, frame)), now);
      send_knots(host + AVAR_LEAD_US, now);
    }
    stream_figure_tick(figure, now, io);
    for (uint8_t c = 0; c < AVAR_CHANNEL_COUNT; ++c) hash.add(storage.channels[c].output, 2);
    hash.add(figure.player.state, 1);
    samples += AVAR_CHANNEL_COUNT;
    if (++in_second == AVAR_RATE_HZ) {
      line(platform_line, "stream ", second, hash.value, in_second * AVAR_CHANNEL_COUNT);
      in_second = 0;
    }
  }
  samples_line(platform_line, samples, ticks);
  return figure.io_fault ? 1 : 0;
}

}  // namespace

int main() { platform_exit(run()); }
