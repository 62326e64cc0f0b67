#pragma once
// One drive protocol's share of a CAN link (ODrive CAN Simple, CANopen CiA 402, MIT-style): the
// actuators of that protocol on one bus. A CanLink runs one or more of these over one
// FrameTransport; each tick it asks every drive set for its frames (encode_tick), sends them all,
// offers every received frame to each set until all have their replies (take,
// replies_complete) or the reply deadline passed, then lets each judge the tick (settle).
//
// Units: every actuator's calibration maps channel units to the drive's own position unit
// (ODrive turns, CiA 402 counts, MIT radians), saturated to the calibrated window.
// Silence is judged in ticks (a heartbeat budget of N ticks), never on a clock: a simulated
// drive's time and the host's clock may run at different speeds, ticks never do.
//
// Threads: release_channel() and saturated() from any thread; everything else on the link's I/O
// thread. Real-time: encode_tick, take, replies_complete, settle, encode_release and the
// telemetry calls allocate nothing and throw nothing. start() and read_positions() block.

#include <cstddef>
#include <cstdint>
#include <span>
#include <string>

#include "avar/core/status.hpp"
#include "avar/firmware_iface/actuator_link.hpp"
#include "avar/firmware_iface/actuator_table.hpp"
#include "avar/firmware_iface/can_frame.hpp"
#include "avar/firmware_iface/can_outbox.hpp"
#include "avar/firmware_iface/frame_transport.hpp"

namespace avar::firmware_iface {

/// A drive whose replies failed to come this many ticks in a row is still asked, but no longer
/// waited for until it answers again: a drive off the bus must not stall every tick by the reply
/// timeout until its silence budget runs out.
inline constexpr std::uint32_t kStopWaitingAfter = 2;

class CanDrives {
 public:
  /// `actuators`: the drives' configs, each element with `channel` and `calibration`.
  template <class Actuators>
  explicit CanDrives(const Actuators& actuators) : table_(actuators) {}
  virtual ~CanDrives() = default;
  CanDrives(const CanDrives&) = delete;
  CanDrives& operator=(const CanDrives&) = delete;

  /// For messages: "ODrive", "CiA 402 drive", "MIT motor".
  virtual const char* device_name() const noexcept = 0;

  /// Brings every drive up (clears latched errors, configures, enables closed-loop control),
  /// talking to them on `bus` and waiting for their answers on its clock; frames that are not
  /// these drives' own are dropped. Not real-time.
  virtual Status start(FrameTransport& bus) = 0;
  /// After a failed start(): which drive, what it answered ("CiA 402 node 5: SDO abort 0x06090030
  /// (value range exceeded) writing 0x6060:00").
  virtual std::string start_problem() const = 0;

  /// Asks each drive where it is; writes frame[channel] (channel units) and sets known[channel]
  /// for every drive that answered. Not real-time.
  virtual Status read_positions(FrameTransport& bus, std::span<double> frame, std::span<bool> known) = 0;

  /// The most frames encode_tick() or encode_release() adds (sizes the link's outbox).
  virtual std::size_t max_tick_frames() const noexcept = 0;

  /// Appends this tick's frames: a command per driven actuator (its channel's value in `frame`,
  /// indexed by rig channel, through table().to_device), a release for each newly released one,
  /// and whatever asks for feedback (RTR requests, SYNC). Forgets last tick's replies.
  virtual void encode_tick(std::span<const double> frame, CanOutbox& out) noexcept = 0;

  /// Offers one received frame; true when it was one of these drives' (and was used).
  virtual bool take(const CanFrame& frame) noexcept = 0;

  /// Every reply this tick waits for has come (the link stops waiting when all sets say so);
  /// drives that missed kStopWaitingAfter ticks in a row are not waited for.
  virtual bool replies_complete() const noexcept = 0;

  /// Ends the tick: feedback that did not come is forgotten (table().forget_feedback), heartbeat
  /// and reply silences are counted, and a drive silent past its budget, in its fault state or
  /// out of closed-loop control gets the fault bits (kDeviceLost, kDeviceFaultState...) on its
  /// channel's telemetry. Returns ok, or timeout when this tick's replies were incomplete.
  virtual Status settle() noexcept = 0;

  /// Appends the frames that stop driving every actuator (the drives go limp or idle).
  virtual void encode_release(CanOutbox& out) noexcept = 0;

  /// What is wrong with the drive of `channel` (its fault, or its silence), for the message
  /// after a channel fault; empty when nothing is known. Not real-time.
  virtual std::string channel_problem(std::size_t channel) const = 0;

  /// Replies that carried an error (counted into LinkCounters::device_errors). Any thread.
  virtual std::uint64_t device_errors() const noexcept = 0;

  /// From the next encode_tick, stops driving this channel's actuators. Any thread.
  void release_channel(std::size_t channel) noexcept { table_.release_channel(channel); }
  std::uint64_t saturated() const noexcept { return table_.saturated(); }
  void read_telemetry(std::span<ChannelTelemetry> out) const noexcept { table_.read_telemetry(out); }
  const ActuatorTable& table() const noexcept { return table_; }

 protected:
  ActuatorTable& table() noexcept { return table_; }

 private:
  ActuatorTable table_;
};

}  // namespace avar::firmware_iface
