#include "avar/firmware_iface/canopen_sdo_client.hpp"

#include <cstdio>

#include "avar/firmware_iface/can_conversation.hpp"
#include "avar/firmware_iface/canopen_codec.hpp"

namespace avar::firmware_iface::canopen {
namespace {

SdoOutcome sdo_transfer(FrameTransport& bus, std::uint8_t node, const CanFrame& request, SdoKind expected,
                        std::chrono::nanoseconds timeout) {
  Sdo asked;
  std::uint8_t n = 0;
  bool from_server = false;
  decode_sdo(request, &n, &from_server, &asked);
  Sdo answer;
  const Status s = ask_frame(bus, request, timeout, [&](const CanFrame& f) {
    Sdo sdo;
    std::uint8_t from = 0;
    bool server = false;
    if (!decode_sdo(f, &from, &server, &sdo) || !server || from != node) return false;
    if (sdo.index != asked.index || sdo.sub != asked.sub) return false;
    if (sdo.kind != expected && sdo.kind != SdoKind::abort) return false;
    answer = sdo;
    return true;
  });
  SdoOutcome outcome;
  if (s == Status::timeout) {
    const CanFrame abort = encode_sdo_abort(node, false, asked.index, asked.sub, kSdoAbortTimeout);
    static_cast<void>(bus.send(std::span<const CanFrame>(&abort, 1)));
    outcome.status = Status::timeout;
    outcome.abort_code = kSdoAbortTimeout;
    return outcome;
  }
  if (s != Status::ok) {
    outcome.status = s;
    return outcome;
  }
  if (answer.kind == SdoKind::abort) {
    outcome.status = Status::out_of_range;
    outcome.abort_code = answer.data;
    return outcome;
  }
  outcome.value = answer.size ? static_cast<std::uint32_t>(sdo_value(answer.data, answer.size, false)) : answer.data;
  outcome.size = answer.size;
  return outcome;
}

}  // namespace

SdoOutcome sdo_download(FrameTransport& bus, std::uint8_t node, std::uint16_t index, std::uint8_t sub, std::uint32_t value,
                        std::uint8_t size, std::chrono::nanoseconds timeout) {
  return sdo_transfer(bus, node, encode_sdo_download(node, index, sub, value, size), SdoKind::download_response, timeout);
}

SdoOutcome sdo_upload(FrameTransport& bus, std::uint8_t node, std::uint16_t index, std::uint8_t sub,
                      std::chrono::nanoseconds timeout) {
  return sdo_transfer(bus, node, encode_sdo_upload(node, index, sub), SdoKind::upload_response, timeout);
}

std::string describe_sdo_failure(const SdoOutcome& outcome, bool writing, std::uint16_t index, std::uint8_t sub) {
  char object[32];
  std::snprintf(object, sizeof object, "%s 0x%04X:%02X", writing ? "writing" : "reading", index, sub);
  if (outcome.status == Status::out_of_range) {
    char code[16];
    std::snprintf(code, sizeof code, "0x%08X", outcome.abort_code);
    return std::string("SDO abort ") + code + " (" + sdo_abort_name(outcome.abort_code) + ") " + object;
  }
  return std::string("no SDO answer ") + object + " (" + std::string(to_string(outcome.status)) + ")";
}

}  // namespace avar::firmware_iface::canopen
