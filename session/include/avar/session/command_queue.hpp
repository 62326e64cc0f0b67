#pragma once
// Commands to a show session, and the bounded lock-free queue they travel in: any number of
// threads push, the session's loop pops at the start of a tick. The queue is Dmitry Vyukov's
// bounded multi-producer array queue (a sequence number per cell): no lock, no allocation after
// construction; a full queue refuses the push, it never blocks.

#include <array>
#include <atomic>
#include <cstddef>
#include <cstdint>
#include <memory>

namespace avar::session {

enum class CommandKind : std::uint8_t {
  play,     ///< show time runs (after a pause, or at the start when the session starts paused)
  pause,    ///< show time stops where it is; the figure holds that frame
  seek,     ///< show time jumps to `value` seconds and keeps running (or stays paused)
  scrub,    ///< show time jumps to `value` seconds and pauses there (dragging the playhead)
  loop,     ///< `value` != 0: the show starts over at its end; 0: it ends there
  hold,     ///< channel `channel` goes to `value` (channel units) over the show, within its limits
  release,  ///< channel `channel` follows the show again
  stop,     ///< ease to rest and end the run
  aim,      ///< the show's target `channel` (its index among the show's targets) is held at `point`
  unaim,    ///< target `channel` follows the show again
};
const char* to_string(CommandKind kind) noexcept;

struct Command {
  CommandKind kind = CommandKind::play;
  std::uint32_t channel = 0;      ///< hold, release: the rig's channel index; aim, unaim: the show's target index
  double value = 0;               ///< seek, scrub: seconds; hold: channel units; loop: on (!= 0) / off
  std::array<double, 3> point{};  ///< aim: metres in the rig's base frame
};

/// What became of a command: applied, or refused and why (kept in the tick record that took it).
enum class CommandOutcome : std::uint8_t {
  applied,
  not_running,     ///< show time commands before the show runs or after it ended
  external_clock,  ///< show time follows a timecode source or a control surface: not the session's
  bad_channel,     ///< no such channel
  bad_value,       ///< not finite
  bad_target,      ///< the show has no such target (or the rig no kinematics)
};
const char* to_string(CommandOutcome outcome) noexcept;

class CommandQueue {
 public:
  /// Room for `capacity` commands, rounded up to a power of two (at least 2). Allocates.
  explicit CommandQueue(std::size_t capacity);

  /// Any thread; lock-free, never blocks. False when the queue is full (the command is dropped).
  bool push(const Command& command) noexcept;
  /// The consumer thread only (one at a time); lock-free. False when empty.
  bool pop(Command& command) noexcept;
  std::size_t capacity() const noexcept { return mask_ + 1; }

 private:
  struct Cell {
    std::atomic<std::size_t> sequence;
    Command command;
  };
  std::unique_ptr<Cell[]> cells_;
  std::size_t mask_;
  alignas(64) std::atomic<std::size_t> tail_{0};  ///< next push
  alignas(64) std::atomic<std::size_t> head_{0};  ///< next pop
};

}  // namespace avar::session
