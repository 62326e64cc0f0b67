#include "avar/firmware_iface/slcan_transport.hpp"

#include <algorithm>
#include <cstring>
#include <stdexcept>
#include <string_view>

#include "avar/core/input_error.hpp"

namespace avar::firmware_iface {
namespace {

using slcan::LineKind;

std::span<const std::uint8_t> bytes_of(std::string_view text) noexcept {
  return {reinterpret_cast<const std::uint8_t*>(text.data()), text.size()};
}

std::string milliseconds_text(std::chrono::milliseconds t) { return std::to_string(t.count()) + " ms"; }

}  // namespace

SlcanTransport::SlcanTransport(std::unique_ptr<ByteTransport> port, int bitrate, SlcanTransportConfig config)
    : SlcanTransport(port ? *port : throw std::invalid_argument("SlcanTransport needs a byte transport"), bitrate, config) {
  owned_ = std::move(port);
}

SlcanTransport::SlcanTransport(ByteTransport& port, int bitrate, SlcanTransportConfig config)
    : port_(&port), bitrate_(bitrate), config_(config) {
  name_ = "SLCAN on " + port_->name();
  if (slcan::bitrate_code(bitrate) < 0)
    throw InputError({port_->name(), 0, 0}, "SLCAN adapter: bitrate " + std::to_string(bitrate) +
                                                " bit/s has no Sn code (S0..S8: 10000, 20000, 50000, 100000, "
                                                "125000, 250000, 500000, 800000, 1000000)");
  std::string problem;
  if (!open_sequence(&problem)) throw InputError({port_->name(), 0, 0}, "SLCAN adapter: " + problem);
}

SlcanTransport::~SlcanTransport() {
  if (open_) (void)port_->write(bytes_of("C\r"));
}

bool SlcanTransport::open_sequence(std::string* problem) {
  open_ = false;
  bus_off_ = false;
  clear_input();
  port_->discard_input();

  const std::string timeout_text = milliseconds_text(config_.reply_timeout);
  // Each step: the command, what it is for messages, whether a BEL is acceptable.
  const auto step = [&](std::string_view text, const std::string& what, LineKind expect, bool bell_ok, std::string* answer) {
    slcan::Line line;
    bool bell = false;
    const Status s = command(text, expect, false, &line, &bell);
    if (s == Status::timeout) {
      *problem = "no answer to " + what + " within " + timeout_text +
                 " (is it an SLCAN adapter such as a CANable or USBtin, and the right port?)";
      return false;
    }
    if (s != Status::ok) {
      *problem = "the port failed while sending " + what + " (" + std::string(to_string(s)) + ")";
      return false;
    }
    if (bell && !bell_ok) {
      *problem = "the adapter refused " + what + " (it answered BEL)";
      return false;
    }
    if (answer) *answer = bell ? std::string() : last_answer_;
    return true;
  };

  std::array<std::uint8_t, 4> bitrate_command{};
  const std::size_t n = slcan::encode_bitrate_command(bitrate_command, bitrate_);
  const std::string_view s_text(reinterpret_cast<const char*>(bitrate_command.data()), n - 1);
  const std::string s_what = std::string(s_text) + " (set the bitrate to " + std::to_string(bitrate_) + " bit/s)";
  const char* open_text = config_.listen_only ? "L" : "O";
  const std::string open_what = config_.listen_only ? "L (open listen-only)" : "O (open)";

  if (!step("C", "C (close)", LineKind::empty, true, nullptr) || !step(s_text, s_what, LineKind::empty, false, nullptr) ||
      !step("V", "V (version)", LineKind::version, true, &version_) ||
      !step("N", "N (serial number)", LineKind::serial, true, &serial_) ||
      !step(open_text, open_what, LineKind::empty, false, nullptr))
    return false;
  open_ = true;
  return true;
}

Status SlcanTransport::command(std::string_view text, LineKind expect, bool keep_frames, slcan::Line* answer,
                               bool* bell) noexcept {
  *bell = false;
  if (text.size() + 1 > tx_.size()) return Status::out_of_range;
  std::memcpy(tx_.data(), text.data(), text.size());
  tx_[text.size()] = slcan::kCr;
  if (const Status s = port_->write(std::span(tx_.data(), text.size() + 1)); s != Status::ok) return s;
  counters_.add(&FrameCounters::bytes_sent, text.size() + 1);

  const std::chrono::nanoseconds deadline = port_->now() + config_.reply_timeout;
  RawLine raw;
  for (;;) {
    if (const Status s = next_line(deadline, &raw); s != Status::ok) return s;
    if (raw.bell) {
      *bell = true;
      return Status::ok;
    }
    const slcan::Line line = slcan::parse_line(raw.text);
    if (line.kind == expect || (line.kind == LineKind::empty && expect != LineKind::status)) {
      *answer = line;
      if (expect == LineKind::version || expect == LineKind::serial) {
        try {
          last_answer_.assign(reinterpret_cast<const char*>(raw.text.data()), raw.text.size());
        } catch (...) {
          last_answer_.clear();
        }
      }
      return Status::ok;
    }
    if (line.kind == LineKind::frame || line.kind == LineKind::error_frame) {
      if (keep_frames) {
        CanFrame f = line.frame;
        accept(&f);
        hold(f);
      }
    } else if (line.kind == LineKind::malformed) {
      counters_.add(&FrameCounters::malformed);
    }
  }
}

Status SlcanTransport::next_line(std::chrono::nanoseconds deadline, RawLine* line) noexcept {
  for (;;) {
    switch (take_line(deadline, line)) {
      case Take::none: return Status::timeout;
      case Take::io_error: return Status::io_error;
      case Take::line: break;
    }
    if (!line->noise) return Status::ok;
    counters_.add(&FrameCounters::malformed);
  }
}

SlcanTransport::Take SlcanTransport::take_line(std::chrono::nanoseconds deadline, RawLine* line) noexcept {
  bool read_once = false;
  for (;;) {
    // A terminator (CR, or a BEL, which stands alone) among the bytes read?
    for (std::size_t i = rx_begin_ + scanned_; i < rx_end_; ++i) {
      const std::uint8_t c = rx_[i];
      if (c != slcan::kCr && c != slcan::kBel) continue;
      if (c == slcan::kBel && i > rx_begin_ && !discarding_) {
        // Text before a BEL is a line of its own (noise); the BEL comes next call.
        *line = {std::span<const std::uint8_t>(rx_.data() + rx_begin_, i - rx_begin_), false, false};
        rx_begin_ = i;
        scanned_ = 0;
        return Take::line;
      }
      if (discarding_) {
        // The rest of an over-long line: one malformed line, reported as unreadable text.
        discarding_ = false;
        *line = {{}, false, true};
        rx_begin_ = (c == slcan::kBel) ? i : i + 1;
        scanned_ = 0;
        return Take::line;
      }
      *line = {std::span<const std::uint8_t>(rx_.data() + rx_begin_, i - rx_begin_), c == slcan::kBel, false};
      rx_begin_ = i + 1;
      scanned_ = 0;
      return Take::line;
    }
    scanned_ = rx_end_ - rx_begin_;
    if (scanned_ >= slcan::kMaxLineLength) {
      // No adapter line is this long: noise. Drop it and everything up to the next terminator.
      discarding_ = true;
      rx_begin_ = rx_end_ = scanned_ = 0;
    }
    if (rx_begin_ == rx_end_) {
      rx_begin_ = rx_end_ = 0;
    } else if (rx_begin_ > 0) {
      std::memmove(rx_.data(), rx_.data() + rx_begin_, rx_end_ - rx_begin_);
      rx_end_ -= rx_begin_;
      rx_begin_ = 0;
    }

    const std::chrono::nanoseconds now = port_->now();
    if (read_once && now >= deadline) return Take::none;
    read_once = true;
    const auto left = std::chrono::ceil<std::chrono::milliseconds>(std::max(deadline - now, std::chrono::nanoseconds(0)));
    std::size_t got = 0;
    const Status s = port_->read_some(std::span(rx_.data() + rx_end_, rx_.size() - rx_end_), left, &got);
    if (s == Status::timeout) return Take::none;
    if (s != Status::ok) return Take::io_error;
    rx_end_ += got;
    counters_.add(&FrameCounters::bytes_received, got);
  }
}

void SlcanTransport::accept(CanFrame* frame) noexcept {
  frame->timestamp = port_->now();
  count_received(counters_, *frame);
  if (frame->error && (frame->id & kCanErrorBusOff)) bus_off_ = true;
}

void SlcanTransport::hold(const CanFrame& frame) noexcept {
  if (held_count_ == kHeldFrames) {  // full: the oldest is lost, as in an overrun
    held_first_ = (held_first_ + 1) % kHeldFrames;
    --held_count_;
  }
  held_[(held_first_ + held_count_) % kHeldFrames] = frame;
  ++held_count_;
}

Status SlcanTransport::send(std::span<const CanFrame> frames) noexcept {
  if (!open_ || bus_off_) return Status::io_error;
  for (const CanFrame& f : frames)
    if (f.error || !can_frame_valid(f)) return Status::out_of_range;
  std::size_t used = 0;
  const auto flush = [&]() noexcept {
    if (used == 0) return Status::ok;
    const Status s = port_->write(std::span(tx_.data(), used));
    if (s == Status::ok) counters_.add(&FrameCounters::bytes_sent, used);
    used = 0;
    return s;
  };
  for (const CanFrame& f : frames) {
    if (tx_.size() - used < slcan::kMaxLineLength)
      if (const Status s = flush(); s != Status::ok) return s;
    used += slcan::encode_frame(std::span(tx_).subspan(used), f);
    counters_.add(&FrameCounters::frames_sent);
  }
  return flush();
}

Status SlcanTransport::receive(CanFrame* frame, std::chrono::nanoseconds deadline) noexcept {
  if (held_count_ > 0) {
    *frame = held_[held_first_];
    held_first_ = (held_first_ + 1) % kHeldFrames;
    --held_count_;
    return Status::ok;
  }
  if (!open_) return Status::io_error;
  RawLine raw;
  for (;;) {
    if (const Status s = next_line(deadline, &raw); s != Status::ok) return s;
    if (raw.bell) {
      refused_.fetch_add(1, std::memory_order_relaxed);
      continue;
    }
    const slcan::Line line = slcan::parse_line(raw.text);
    switch (line.kind) {
      case LineKind::frame:
      case LineKind::error_frame:
        *frame = line.frame;
        accept(frame);
        return Status::ok;
      case LineKind::malformed: counters_.add(&FrameCounters::malformed); break;
      default: break;  // acks, bare CRs, stray replies
    }
  }
}

Status SlcanTransport::read_status(std::uint8_t* flags, std::uint32_t* classes) noexcept {
  if (!open_) return Status::io_error;
  slcan::Line line;
  bool bell = false;
  const Status s = command("F", LineKind::status, true, &line, &bell);
  if (s != Status::ok) return s;
  if (bell) return Status::bad_data;
  *flags = line.flags;
  *classes = slcan::error_classes_of_status(line.flags);
  return Status::ok;
}

void SlcanTransport::clear_input() noexcept {
  rx_begin_ = rx_end_ = scanned_ = 0;
  discarding_ = false;
  held_first_ = held_count_ = 0;
}

void SlcanTransport::discard_input() noexcept {
  port_->discard_input();
  clear_input();
}

Status SlcanTransport::reopen() noexcept {
  open_ = false;
  if (port_->reopen() != Status::ok) return Status::io_error;
  try {
    problem_.clear();
    return open_sequence(&problem_) ? Status::ok : Status::io_error;
  } catch (...) {
    return Status::io_error;
  }
}

}  // namespace avar::firmware_iface
