#include "avar/session/command_queue.hpp"

#include <bit>

namespace avar::session {

const char* to_string(CommandKind kind) noexcept {
  switch (kind) {
    case CommandKind::play: return "play";
    case CommandKind::pause: return "pause";
    case CommandKind::seek: return "seek";
    case CommandKind::scrub: return "scrub";
    case CommandKind::loop: return "loop";
    case CommandKind::hold: return "hold";
    case CommandKind::release: return "release";
    case CommandKind::stop: return "stop";
    case CommandKind::aim: return "aim";
    case CommandKind::unaim: return "unaim";
  }
  return "?";
}

const char* to_string(CommandOutcome outcome) noexcept {
  switch (outcome) {
    case CommandOutcome::applied: return "applied";
    case CommandOutcome::not_running: return "not running";
    case CommandOutcome::external_clock: return "show time follows an external clock";
    case CommandOutcome::bad_channel: return "no such channel";
    case CommandOutcome::bad_value: return "value not finite";
    case CommandOutcome::bad_target: return "no such target";
  }
  return "?";
}

CommandQueue::CommandQueue(std::size_t capacity) {
  const std::size_t size = std::bit_ceil(capacity < 2 ? std::size_t{2} : capacity);
  cells_ = std::make_unique<Cell[]>(size);
  for (std::size_t i = 0; i < size; ++i) cells_[i].sequence.store(i, std::memory_order_relaxed);
  mask_ = size - 1;
}

bool CommandQueue::push(const Command& command) noexcept {
  std::size_t pos = tail_.load(std::memory_order_relaxed);
  for (;;) {
    Cell& cell = cells_[pos & mask_];
    const std::size_t seq = cell.sequence.load(std::memory_order_acquire);
    const auto diff = static_cast<std::ptrdiff_t>(seq) - static_cast<std::ptrdiff_t>(pos);
    if (diff == 0) {
      if (tail_.compare_exchange_weak(pos, pos + 1, std::memory_order_relaxed)) {
        cell.command = command;
        cell.sequence.store(pos + 1, std::memory_order_release);
        return true;
      }
    } else if (diff < 0) {
      return false;  // full: the cell still holds a command not yet popped
    } else {
      pos = tail_.load(std::memory_order_relaxed);
    }
  }
}

bool CommandQueue::pop(Command& command) noexcept {
  const std::size_t pos = head_.load(std::memory_order_relaxed);
  Cell& cell = cells_[pos & mask_];
  const std::size_t seq = cell.sequence.load(std::memory_order_acquire);
  if (static_cast<std::ptrdiff_t>(seq) - static_cast<std::ptrdiff_t>(pos + 1) < 0) return false;  // empty
  command = cell.command;
  head_.store(pos + 1, std::memory_order_relaxed);
  cell.sequence.store(pos + mask_ + 1, std::memory_order_release);
  return true;
}

}  // namespace avar::session
