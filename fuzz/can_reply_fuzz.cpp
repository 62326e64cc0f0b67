// A CAN frame from a drive on the bus, through every host-side decoder avar has: CANopen (NMT,
// heartbeat, EMCY, SDO), CiA 402 PDOs, ODrive CANSimple replies, MIT-protocol replies. Decoders
// must refuse what does not fit and decode only finite values from the rest.
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdlib>

#include "avar/firmware_iface/canopen_codec.hpp"
#include "avar/firmware_iface/cia402_codec.hpp"
#include "avar/firmware_iface/mit_can_codec.hpp"
#include "avar/firmware_iface/odrive_can_codec.hpp"
#include "can_frame_input.hpp"

namespace fi = avar::firmware_iface;

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  avar::fuzz::ByteReader in(data, size);
  while (!in.empty()) {
    const fi::CanFrame frame = avar::fuzz::read_can_frame(in);
    std::uint8_t node = 0;
    fi::canopen::NmtCommand command{};
    (void)fi::canopen::decode_nmt(frame, &command, &node);
    fi::canopen::NmtState state{};
    (void)fi::canopen::decode_heartbeat(frame, &node, &state);
    (void)fi::canopen::is_sync(frame);
    fi::canopen::Emcy emcy;
    if (fi::canopen::decode_emcy(frame, &node, &emcy)) (void)fi::cia402::emcy_device_faults(emcy.error_code);
    bool from_server = false;
    fi::canopen::Sdo sdo;
    (void)fi::canopen::decode_sdo(frame, &node, &from_server, &sdo);
    std::uint16_t word = 0;
    std::int32_t value = 0;
    (void)fi::cia402::decode_status_position(frame, frame.id, &word, &value);
    (void)fi::cia402::decode_control_target(frame, frame.id, &word, &value);

    fi::odrive::Heartbeat heartbeat;
    (void)fi::odrive::decode_heartbeat(frame, fi::odrive::HeartbeatLayout::v0_5, &heartbeat);
    (void)fi::odrive::decode_heartbeat(frame, fi::odrive::HeartbeatLayout::v0_6, &heartbeat);
    fi::odrive::EncoderEstimates estimates;
    (void)fi::odrive::decode_encoder_estimates(frame, &estimates);
    std::uint64_t motor_error = 0;
    (void)fi::odrive::decode_motor_error(frame, &motor_error);

    fi::mit::MitReply reply;
    fi::mit::MitReplyFormat format;
    format.id_mask = 0x0F;
    if (fi::mit::decode_reply(frame.payload(), fi::mit::kMiniCheetahRanges, format, &reply) &&
        !(std::isfinite(reply.position) && std::isfinite(reply.velocity) && std::isfinite(reply.torque)))
      std::abort();
  }
  return 0;
}
