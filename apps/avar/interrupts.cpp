#include "avar/interrupts.hpp"

#include <csignal>

namespace avar::app {
namespace {

std::atomic<int> g_interrupts{0};
std::atomic<bool> g_estop{false};
static_assert(std::atomic<bool>::is_always_lock_free);
static_assert(std::atomic<int>::is_always_lock_free);

extern "C" void on_interrupt(int) { g_interrupts.fetch_add(1, std::memory_order_relaxed); }
extern "C" void on_estop(int) { g_estop.store(true, std::memory_order_relaxed); }

struct sigaction g_previous_int {};
struct sigaction g_previous_term {};
struct sigaction g_previous_quit {};

}  // namespace

InterruptCounter::InterruptCounter() {
  g_interrupts.store(0);
  g_estop.store(false);
  struct sigaction action {};
  action.sa_handler = on_interrupt;
  sigemptyset(&action.sa_mask);
  sigaction(SIGINT, &action, &g_previous_int);
  sigaction(SIGTERM, &action, &g_previous_term);
  struct sigaction estop {};
  estop.sa_handler = on_estop;
  sigemptyset(&estop.sa_mask);
  sigaction(SIGQUIT, &estop, &g_previous_quit);
}

InterruptCounter::~InterruptCounter() {
  sigaction(SIGINT, &g_previous_int, nullptr);
  sigaction(SIGTERM, &g_previous_term, nullptr);
  sigaction(SIGQUIT, &g_previous_quit, nullptr);
}

const std::atomic<int>& InterruptCounter::count() const noexcept { return g_interrupts; }
const std::atomic<bool>& InterruptCounter::estop() const noexcept { return g_estop; }

StopSignals::StopSignals() {
  sigemptyset(&stop_);
  sigaddset(&stop_, SIGINT);
  sigaddset(&stop_, SIGTERM);
  pthread_sigmask(SIG_BLOCK, &stop_, &previous_);
}

StopSignals::~StopSignals() { pthread_sigmask(SIG_SETMASK, &previous_, nullptr); }

bool StopSignals::wait(long timeout_ms) const {
  const timespec timeout{timeout_ms / 1000, (timeout_ms % 1000) * 1'000'000};
  return sigtimedwait(&stop_, nullptr, &timeout) >= 0;
}

}  // namespace avar::app
