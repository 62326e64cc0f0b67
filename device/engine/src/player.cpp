#include "avar/device/player.hpp"

#include "avar/device/fixed_math.hpp"

namespace avar {
namespace device {
PlayerStatus player_init(Player& p, PlayerChannel* channels, uint8_t channel_count, const PlayerShow* shows, uint8_t show_count,
                         uint32_t rate) {
  p.channels = channels;
  p.channel_count = channel_count;
  p.shows = shows;
  p.show_count = show_count;
  p.rate = rate;
  p.mode = kPlayerResting;
  p.show = 0;
  p.ticks_per_second = 1;
  p.duration = 0;
  p.loops = false;
  p.elapsed = 0;
  if (rate == 0 || channel_count == 0) return kPlayerBadChannels;
  for (uint8_t s = 0; s < show_count; ++s) {
    ShowHeader h;
    if (check_image(shows[s].image, shows[s].size, h) != kImageOk) return kPlayerBadShow;
    if (h.channel_count != channel_count) return kPlayerBadChannels;
  }
  for (uint8_t c = 0; c < channel_count; ++c) {
    const ChannelLimits limits = read_limits(channels[c].limits);
    if (!limits_usable(limits)) return kPlayerBadLimits;
    channels[c].state = limiter_at_rest(limits);
    channels[c].output = limiter_output(channels[c].state);
    reset_cache(channels[c].cache);
  }
  return kPlayerOk;
}

PlayerStatus player_start(Player& p, uint8_t index) {
  if (index >= p.show_count) return kPlayerBadShow;
  const PlayerShow& show = p.shows[index];
  ShowHeader h;
  if (check_image(show.image, show.size, h) != kImageOk) return kPlayerBadShow;
  for (uint8_t c = 0; c < p.channel_count; ++c) {
    if (!open_channel(show.image, show.size, c, p.channels[c].curve)) return kPlayerBadShow;
    reset_cache(p.channels[c].cache);
  }
  p.show = index;
  p.ticks_per_second = h.ticks_per_second;
  p.duration = h.duration;
  p.loops = (h.flags & kShowLoops) != 0;
  p.elapsed = 0;
  p.mode = kPlayerPlaying;
  return kPlayerOk;
}

void player_stop(Player& p) {
  if (p.mode == kPlayerPlaying) p.mode = kPlayerStopping;
}

void player_tick(Player& p) {
  int32_t tick = 0;
  if (p.mode == kPlayerPlaying) {
    // The show's tick of this control tick, exact: elapsed * ticks_per_second / rate.
    int64_t t = static_cast<int64_t>(static_cast<uint64_t>(p.elapsed) * p.ticks_per_second / p.rate);
    if (p.loops && p.duration > 0) {
      t %= p.duration;
    } else if (t > p.duration) {
      p.mode = kPlayerStopping;  // the show is over: to rest
    }
    tick = static_cast<int32_t>(t);
    ++p.elapsed;
  }
  for (uint8_t c = 0; c < p.channel_count; ++c) {
    PlayerChannel& ch = p.channels[c];
    const ChannelLimits limits = read_limits(ch.limits);
    // The show's value in Q8 output units, to Q16; on stop (or rest) the rest pose.
    const int64_t target = p.mode == kPlayerPlaying ? sample_q8(ch.curve, ch.cache, tick) * 256 : limits.rest;
    limiter_step(limits, ch.state, target);
    ch.output = limiter_output(ch.state);
  }
  if (p.mode == kPlayerStopping) {
    bool resting = true;
    for (uint8_t c = 0; c < p.channel_count; ++c)
      resting =
          resting && p.channels[c].state.position == read_limits(p.channels[c].limits).rest && p.channels[c].state.velocity == 0;
    if (resting) p.mode = kPlayerResting;
  }
}

}  // namespace device
}  // namespace avar
