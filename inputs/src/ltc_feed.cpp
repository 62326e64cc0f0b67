#include "avar/inputs/ltc_feed.hpp"

#include <cmath>

namespace avar::inputs {

void LtcFeed::feed(std::span<const float> samples, std::int64_t block_end_ns) noexcept {
  if (samples.empty()) return;
  const std::int64_t block_end = fed_ + static_cast<std::int64_t>(samples.size());  // one past its last sample
  const double ns_per_sample = 1e9 / decoder_.sample_rate();
  const std::uint64_t bad_before = decoder_.bad_frames();
  decoder_.feed(samples, [&](const TimecodeFix& fix, std::int64_t last) {
    // The frame's last sample arrived (block_end - last - 1) samples before the block's end.
    const auto early = static_cast<std::int64_t>(std::llround(static_cast<double>(block_end - (last + 1)) * ns_per_sample));
    mailbox_.publish(fix, block_end_ns - early);
    counters_.add(&TimecodeCounters::fixes);
  });
  for (std::uint64_t i = bad_before; i < decoder_.bad_frames(); ++i) counters_.add(&TimecodeCounters::bad);
  fed_ = block_end;
}

}  // namespace avar::inputs
