// The device show image: a whole show encodes and every channel plays; a damaged image is refused
// before anything plays (truncated at every length, corrupted at random bytes), and one that still
// passes the check samples within the engine's bounds (the sanitizer build checks every access).
#include <gtest/gtest.h>

#include <algorithm>
#include <random>
#include <stdexcept>
#include <string>
#include <vector>

#include "avar/config/rig_file.hpp"
#include "avar/config/show_file.hpp"
#include "avar/core/input_error.hpp"
#include "avar/device/image_sampler.hpp"
#include "avar/device/show_export.hpp"

namespace avar::device {
namespace {

std::vector<ImageChannel> hello_channels(const playback::Show& show) {
  const rig::Rig rig = config::load_rig_file(AVAR_SOURCE_DIR "/examples/rigs/hello-head.yaml");
  std::vector<ImageChannel> channels;
  for (const playback::Track& t : show.tracks) {
    const rig::ChannelSpec& c = rig.channels[rig.find_channel(t.channel).value()];
    channels.push_back({t.channel, {c.min, c.max}});
  }
  return channels;
}

TEST(DeviceShowImage, EncodesAShowWhoseHeaderSaysWhatItHolds) {
  const playback::Show show = config::load_show_file(AVAR_SOURCE_DIR "/examples/shows/hello-head.yaml");
  const ShowImage image = encode_show_image(show, hello_channels(show));
  ImageSampler sampler(image.bytes);
  EXPECT_EQ(sampler.channel_count(), show.tracks.size());
  EXPECT_EQ(sampler.ticks_per_second(), image.ticks_per_second);
  EXPECT_EQ(sampler.duration_ticks(), static_cast<std::int32_t>(show.duration * image.ticks_per_second));
  EXPECT_EQ(sampler.loops(), show.loop);
  std::size_t keys = 0;
  for (const playback::Track& t : show.tracks) keys += t.raw.keys.size();
  EXPECT_EQ(image.keys, keys);
  EXPECT_LE(image.key_bytes, 12 * keys) << "at most 12 bytes per key";
  EXPECT_EQ(std::string(image.bytes.begin(), image.bytes.begin() + 4), "avd1");
}

TEST(DeviceShowImage, RefusesATruncatedImageAtEveryLength) {
  const playback::Show show = config::load_show_file(AVAR_SOURCE_DIR "/examples/shows/hello-head.yaml");
  const std::vector<std::uint8_t> bytes = encode_show_image(show, hello_channels(show)).bytes;
  ShowHeader header;
  for (std::size_t n = 0; n < bytes.size(); ++n) {
    const std::vector<std::uint8_t> cut(bytes.begin(), bytes.begin() + static_cast<std::ptrdiff_t>(n));
    EXPECT_NE(check_image(cut.data(), static_cast<std::uint32_t>(n), header), kImageOk) << n << " bytes";
  }
  EXPECT_EQ(check_image(bytes.data(), static_cast<std::uint32_t>(bytes.size()), header), kImageOk);
  EXPECT_THROW(ImageSampler(std::vector<std::uint8_t>(bytes.begin(), bytes.end() - 1)), std::invalid_argument);
}

TEST(DeviceShowImage, ACorruptedImageIsRefusedOrPlaysWithinTheEnginesBounds) {
  const playback::Show show = config::load_show_file(AVAR_SOURCE_DIR "/examples/shows/hello-head.yaml");
  const std::vector<std::uint8_t> bytes = encode_show_image(show, hello_channels(show)).bytes;
  std::mt19937 rng(33);
  int refused = 0;
  for (int trial = 0; trial < 3000; ++trial) {
    std::vector<std::uint8_t> damaged = bytes;
    const int flips = 1 + static_cast<int>(rng() % 4);
    for (int f = 0; f < flips; ++f) damaged[rng() % damaged.size()] = static_cast<std::uint8_t>(rng());
    try {
      ImageSampler sampler(damaged);
      // Ticks from -2 s to 15 s at the image's own rate (a damaged rate: within 32 bits).
      const std::int64_t per_ms = std::min<std::int64_t>(sampler.ticks_per_second() / 1000, 100000);
      for (std::size_t c = 0; c < sampler.channel_count(); ++c)
        for (std::int64_t ms = -2000; ms < 15000; ms += 97) sampler.output(c, static_cast<std::int32_t>(ms * per_ms));
    } catch (const std::invalid_argument&) {
      ++refused;
    }
  }
  EXPECT_GT(refused, 100);
}

TEST(DeviceShowImage, RefusesWhatTheEngineCannotPlayNamingTheKey) {
  const playback::Show show = config::load_show_file(AVAR_SOURCE_DIR "/examples/shows/hello-head.yaml");
  std::vector<ImageChannel> channels = hello_channels(show);
  channels[0].range = {1, 1};
  try {
    encode_show_image(show, channels);
    ADD_FAILURE() << "an empty range was accepted";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("expected min below max"), std::string::npos) << e.what();
  }
  channels = hello_channels(show);
  channels[0].name = "tail";
  EXPECT_THROW(encode_show_image(show, channels), InputError);
  // Keys closer than a tick of the rate asked for.
  playback::RawCurve raw({playback::RawKey{}, playback::RawKey{}}, {"close.yaml", 1, 1});
  raw.keys[1].time = 0.0004;
  raw.keys[1].where = {"close.yaml", 3, 5};
  try {
    encode_channel_record(raw, playback::Curve::build(raw), {0, 1}, 1000);
    ADD_FAILURE() << "keys 0.4 ms apart were accepted at 1 kHz";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("close.yaml:3:5: key 2 (0.0004 s) is less than a tick"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace avar::device
