#include "avar/interrupts.hpp"

#include <csignal>

namespace avar::app {
namespace {

std::atomic<int> g_interrupts{0};
static_assert(std::atomic<int>::is_always_lock_free);

extern "C" void on_interrupt(int) { g_interrupts.fetch_add(1, std::memory_order_relaxed); }

struct sigaction g_previous_int {};
struct sigaction g_previous_term {};

}  // namespace

InterruptCounter::InterruptCounter() {
  g_interrupts.store(0);
  struct sigaction action {};
  action.sa_handler = on_interrupt;
  sigemptyset(&action.sa_mask);
  sigaction(SIGINT, &action, &g_previous_int);
  sigaction(SIGTERM, &action, &g_previous_term);
}

InterruptCounter::~InterruptCounter() {
  sigaction(SIGINT, &g_previous_int, nullptr);
  sigaction(SIGTERM, &g_previous_term, nullptr);
}

const std::atomic<int>& InterruptCounter::count() const noexcept { return g_interrupts; }

}  // namespace avar::app
