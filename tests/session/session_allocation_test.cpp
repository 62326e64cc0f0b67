// The session's part of a tick allocates nothing: taking commands from the queue, the
// controller's tick under the session's clock and hold layer, and writing the tick's record
// and handing it out.
#include <gtest/gtest.h>

#include <atomic>

#include "../support/allocation_counter.hpp"
#include "avar/config/rig_file.hpp"
#include "avar/config/show_file.hpp"
#include "avar/session/show_session.hpp"

namespace avar::session {
namespace {

std::atomic<int> no_interrupts_alloc{0};

/// Counts allocations on the loop thread (the stepped session's: this test's; the simulated
/// devices serve on threads of their own) from the end of one tick's publishing (the session's
/// observer, last) to the next tick's loop observer (first after the tick): the commands taken,
/// the tick, the plant's step. And from the loop observer to the session observer: the record
/// written and handed out. Pushes commands between ticks (allocation-free too).
class Counter final : public control::TickObserver, public SessionObserver {
 public:
  explicit Counter(ShowSession& s) : session_(s) {}
  void after_tick(std::uint64_t tick, double, double, double, control::Controller&) override {
    const long now = testing::thread_allocations;
    if (tick > kWarm && armed_) in_tick_ += now - mark_;
    mark_ = now;
  }
  void on_tick(const TickRecord& r) override {
    const long now = testing::thread_allocations;
    if (r.tick > kWarm) in_record_ += now - mark_;
    // Commands for the next ticks, every kind, for 800 ticks; then a stop ends the run.
    if (r.tick == 900) session_.stop();
    if (r.tick < 800) switch (r.tick % 50) {
        case 10: session_.hold(0, 25); break;
        case 20: session_.seek(static_cast<double>(r.tick % 7)); break;
        case 25: session_.pause(); break;
        case 30: session_.play(); break;
        case 35: session_.scrub(3); break;
        case 40: session_.release(0); break;
        case 45: session_.loop(r.tick % 100 == 45); break;
        default: break;
      }
    mark_ = testing::thread_allocations;
    armed_ = true;
    ++records_;
  }
  static constexpr std::uint64_t kWarm = 20;
  long in_tick_ = 0, in_record_ = 0;
  std::uint64_t records_ = 0;

 private:
  ShowSession& session_;
  long mark_ = 0;
  bool armed_ = false;
};

TEST(SessionAllocation, NoAllocationInTheTickNorInItsRecord) {
  const rig::Rig rig = config::load_rig_file(std::string(AVAR_SOURCE_DIR) + "/examples/rigs/hello-head.yaml");
  const playback::Show show = config::load_show_file(std::string(AVAR_SOURCE_DIR) + "/examples/shows/hello-head.yaml");
  SessionConfig config;
  config.stepped = true;
  config.links.simulate_all = true;
  ShowSession session(rig, show, config);
  Counter counter(session);
  session.add_observer(counter);
  session.set_loop_observer(&counter);
  ASSERT_FALSE(session.start_links());
  session.begin();
  const control::RunResult run = session.run(no_interrupts_alloc);
  ASSERT_GT(run.ticks, 500u);
  EXPECT_EQ(counter.records_, run.ticks);
  EXPECT_EQ(counter.in_tick_, 0) << "allocations in " << run.ticks << " ticks";
  EXPECT_EQ(counter.in_record_, 0) << "allocations writing " << run.ticks << " records";
}

}  // namespace
}  // namespace avar::session
