#pragma once
// FrameTransport over an SLCAN (Lawicel ASCII) adapter such as a CANable or USBtin on any
// ByteTransport: a SerialTransport for /dev/ttyACM0, a pseudo-terminal, or a simulated wire
// (../shared/protocols/slcan.md). Deadlines run on the byte transport's clock (its now()); the
// frames' timestamps are the time their line was read, on that clock (the adapter's own
// millisecond timestamps, when it sends them, are read and not used).
//
// Threads: one thread uses the transport; counters() from any thread. Real-time: send, receive,
// now and discard_input allocate nothing and throw nothing.

#include <array>
#include <chrono>
#include <cstdint>
#include <memory>
#include <span>
#include <string>

#include "avar/firmware_iface/atomic_frame_counters.hpp"
#include "avar/firmware_iface/byte_transport.hpp"
#include "avar/firmware_iface/frame_transport.hpp"
#include "avar/firmware_iface/slcan_codec.hpp"

namespace avar::firmware_iface {

struct SlcanTransportConfig {
  /// How long the adapter may take to answer each command of the open sequence and `F`.
  std::chrono::milliseconds reply_timeout{500};
  /// Open with `L` (listen only: receives, never transmits or acknowledges) instead of `O`.
  bool listen_only = false;
};

class SlcanTransport final : public FrameTransport {
 public:
  /// Takes the port and opens the adapter: `C` (closes whatever was open; a BEL is fine), `Sn`
  /// for `bitrate` (bit/s, one of the nine SLCAN rates), `V` and `N` (kept for messages; a BEL
  /// is fine), then `O` (or `L`). Throws InputError naming the port and the step when the
  /// bitrate has no `Sn` code or the adapter does not answer as expected. Not real-time.
  SlcanTransport(std::unique_ptr<ByteTransport> port, int bitrate, SlcanTransportConfig config = {});
  /// The same over a borrowed port, which must outlive this transport.
  SlcanTransport(ByteTransport& port, int bitrate, SlcanTransportConfig config = {});
  /// Sends `C` (the adapter leaves the bus).
  ~SlcanTransport() override;
  SlcanTransport(const SlcanTransport&) = delete;
  SlcanTransport& operator=(const SlcanTransport&) = delete;

  /// Writes every frame's line in one write (several when they outgrow the send buffer).
  /// out_of_range (and nothing written) when a frame is invalid or an error frame; io_error once
  /// the adapter reported bus-off, until reopen().
  Status send(std::span<const CanFrame> frames) noexcept override;
  /// The next frame line, decoded. Skips transmit acks (`z`, `Z`) and bare CR replies; a BEL
  /// (a command the adapter refused) is counted in refused(); anything else that does not
  /// decode, up to the next CR, is counted in FrameCounters::malformed and skipped. The Linux
  /// state and error lines (`s`, `e`) come as error frames.
  Status receive(CanFrame* frame, std::chrono::nanoseconds deadline) noexcept override;
  std::chrono::nanoseconds now() const noexcept override { return port_->now(); }
  void discard_input() noexcept override;
  /// Reopens the byte transport and runs the open sequence again (this also restarts the
  /// adapter's controller after a bus-off).
  Status reopen() noexcept override;
  int bitrate() const noexcept override { return bitrate_; }
  FrameCounters counters() const noexcept override { return counters_.snapshot(); }
  /// "SLCAN on /dev/ttyACM0".
  const std::string& name() const noexcept override { return name_; }

  /// Asks the adapter for its status flags (`F`): *flags gets the Lawicel byte, *classes its
  /// CanErrorClass bits (slcan::error_classes_of_status). Frames that arrive meanwhile are kept
  /// for receive(). ok, timeout (no answer within the reply timeout), bad_data (a BEL: the
  /// adapter has no `F`), io_error. Not real-time (it waits for the adapter).
  Status read_status(std::uint8_t* flags, std::uint32_t* classes) noexcept;

  /// What the adapter answered to `V` and `N` ("V1013", "NA123"); empty when it refused.
  const std::string& version() const noexcept { return version_; }
  const std::string& serial_number() const noexcept { return serial_; }
  /// BEL replies met while receiving: transmit commands the adapter refused.
  std::uint64_t refused() const noexcept { return refused_.load(std::memory_order_relaxed); }
  /// After a failed reopen(): the step that failed and what the adapter answered.
  const std::string& open_problem() const noexcept { return problem_; }
  ByteTransport& port() noexcept { return *port_; }

  /// Frames received while read_status() waited, kept for receive().
  static constexpr std::size_t kHeldFrames = 64;

 private:
  /// One line taken from the input: its text (without CR) or a BEL.
  struct RawLine {
    std::span<const std::uint8_t> text;
    bool bell = false;
    bool noise = false;  ///< the end of a line too long to be anything an adapter sends
  };
  enum class Take { line, none, io_error };

  /// Runs the open sequence; on failure returns false with *problem naming the step.
  bool open_sequence(std::string* problem);
  /// Sends a command and waits for its answer: a bare CR, a BEL or a line of kind `expect`.
  /// Frame lines in between are dropped when `hold` is false, else kept for receive().
  Status command(std::string_view text, slcan::LineKind expect, bool keep_frames, slcan::Line* answer, bool* bell) noexcept;
  /// Takes the next line from the input, reading until `deadline`.
  Take take_line(std::chrono::nanoseconds deadline, RawLine* line) noexcept;
  /// The next line that is not noise (noise is counted as malformed): ok, timeout or io_error.
  Status next_line(std::chrono::nanoseconds deadline, RawLine* line) noexcept;
  /// A received frame or error frame: counted, stamped, bus-off latched.
  void accept(CanFrame* frame) noexcept;
  void hold(const CanFrame& frame) noexcept;
  void clear_input() noexcept;

  std::unique_ptr<ByteTransport> owned_;  ///< the port, when this transport owns it
  ByteTransport* port_;
  int bitrate_;
  SlcanTransportConfig config_;
  std::string name_;
  std::string version_;
  std::string serial_;
  std::string last_answer_;  ///< the text of the last V or N answer
  std::string problem_;
  bool open_ = false;
  bool bus_off_ = false;

  std::array<std::uint8_t, 4096> tx_{};
  std::array<std::uint8_t, 4096> rx_{};
  std::size_t rx_begin_ = 0;  ///< first byte not yet taken
  std::size_t rx_end_ = 0;    ///< one past the last byte read
  std::size_t scanned_ = 0;   ///< bytes from rx_begin_ already searched for a terminator
  bool discarding_ = false;   ///< dropping an over-long line up to its CR
  std::array<CanFrame, kHeldFrames> held_{};
  std::size_t held_first_ = 0;
  std::size_t held_count_ = 0;

  AtomicFrameCounters counters_;
  std::atomic<std::uint64_t> refused_{0};
};

}  // namespace avar::firmware_iface
