#pragma once
// The device's player: shows from images, played through the limiter at a fixed control rate.
// Power-up rests every channel (a soft start from the rest pose); start(show) plays a show from
// its beginning, also in the middle of another (the limiter carries the motion over, never a
// jump); stop() eases every channel to rest; a show that ends (and does not loop) eases to rest.
// Caller-owned storage, no heap, freestanding C++14. One control tick per tick() call.

#include <stdint.h>

#include "avar/device/curve_engine.hpp"
#include "avar/device/limiter.hpp"

namespace avar {
namespace device {

/// One channel of the figure: its limits, its limiter state and what it outputs.
struct PlayerChannel {
  /// The channel's limits, stored (kLimitsSize bytes, write_limits; in flash on AVR): read each
  /// tick, so RAM holds only the state.
  const uint8_t* limits;
  LimiterState state;
  uint16_t output;  ///< the last tick's 16-bit command
  Channel curve;    ///< channel c of the playing show
  SegmentCache cache;
};

/// A show the player can start: an image whose channel c drives the player's channel c.
struct PlayerShow {
  const uint8_t* image;
  uint32_t size;
};

enum PlayerMode : uint8_t { kPlayerResting = 0, kPlayerPlaying, kPlayerStopping };

struct Player {
  PlayerChannel* channels;
  uint8_t channel_count;
  const PlayerShow* shows;
  uint8_t show_count;
  uint32_t rate;  ///< control ticks per second
  // What plays.
  PlayerMode mode;
  uint8_t show;
  uint32_t ticks_per_second;  ///< the playing show's
  int32_t duration;           ///< its ticks
  bool loops;
  uint32_t elapsed;  ///< control ticks since the show started
};

enum PlayerStatus : uint8_t { kPlayerOk = 0, kPlayerBadShow, kPlayerBadChannels, kPlayerBadLimits };

/// Sets the player up at rest. Every show must check whole and have the player's channel count;
/// every channel's limits must be usable (low <= rest <= high, speed and acceleration above 0,
/// reach as limiter_prepare sets it).
PlayerStatus player_init(Player& player, PlayerChannel* channels, uint8_t channel_count, const PlayerShow* shows,
                         uint8_t show_count, uint32_t rate);
/// Plays show `index` from its start (a show already playing hands its motion over).
PlayerStatus player_start(Player& player, uint8_t index);
/// Eases every channel to rest.
void player_stop(Player& player);
/// One control tick: each channel's target (the show's value, or rest), through the limiter.
void player_tick(Player& player);

}  // namespace device
}  // namespace avar
