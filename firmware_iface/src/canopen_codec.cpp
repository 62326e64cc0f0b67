#include "avar/firmware_iface/canopen_codec.hpp"

namespace avar::firmware_iface::canopen {
namespace {

// Command specifier field (bits 5-7 of byte 0) and the expedited / size-indicated flags.
constexpr std::uint8_t kCsMask = 0xE0;
constexpr std::uint8_t kClientDownload = 0x20;
constexpr std::uint8_t kClientUpload = 0x40;
constexpr std::uint8_t kServerDownload = 0x60;
constexpr std::uint8_t kServerUpload = 0x40;
constexpr std::uint8_t kAbort = 0x80;
constexpr std::uint8_t kExpedited = 0x02;
constexpr std::uint8_t kSizeIndicated = 0x01;

CanFrame frame8(std::uint32_t id) noexcept {
  CanFrame f;
  f.id = id;
  f.dlc = 8;
  return f;
}

CanFrame sdo_frame(std::uint32_t id, std::uint8_t command, std::uint16_t index, std::uint8_t sub, std::uint32_t data) noexcept {
  CanFrame f = frame8(id);
  f.data[0] = command;
  put_le(&f.data[1], index, 2);
  f.data[3] = sub;
  put_le(&f.data[4], data, 4);
  return f;
}

/// 1..4; anything else means 4.
std::uint8_t normal_size(std::uint8_t size) noexcept { return size >= 1 && size <= 4 ? size : 4; }

/// Expedited command byte with `size` (1..4) bytes: base | n << 2 | e | s, n = unused bytes.
std::uint8_t expedited_command(std::uint8_t base, std::uint8_t size) noexcept {
  return static_cast<std::uint8_t>(base | (4 - size) << 2 | kExpedited | kSizeIndicated);
}

std::uint32_t masked(std::uint32_t value, std::uint8_t size) noexcept {
  return size >= 4 ? value : value & ((1u << (8 * size)) - 1);
}

/// Fills the data fields of a download request or upload response.
void decode_transfer(const CanFrame& f, Sdo* sdo) noexcept {
  const std::uint8_t c = f.data[0];
  sdo->expedited = c & kExpedited;
  if (sdo->expedited) sdo->size = (c & kSizeIndicated) ? static_cast<std::uint8_t>(4 - ((c >> 2) & 0x03)) : 0;
  else sdo->size = 0;
}

}  // namespace

CobId decode_cob_id(std::uint32_t id) noexcept {
  if (id == kNmtCobId) return {CobFunction::nmt, 0};
  if (id == kSyncCobId) return {CobFunction::sync, 0};
  if (id == kTimeCobId) return {CobFunction::time, 0};
  if (id > kCanMaxStandardId) return {};
  const auto node = static_cast<std::uint8_t>(id & 0x7F);
  if (!valid_node(node)) return {};
  static constexpr CobFunction kByCode[16] = {
      CobFunction::unknown,     CobFunction::emcy,    CobFunction::unknown,   CobFunction::tpdo1,
      CobFunction::rpdo1,       CobFunction::tpdo2,   CobFunction::rpdo2,     CobFunction::tpdo3,
      CobFunction::rpdo3,       CobFunction::tpdo4,   CobFunction::rpdo4,     CobFunction::sdo_response,
      CobFunction::sdo_request, CobFunction::unknown, CobFunction::heartbeat, CobFunction::unknown,
  };
  const CobFunction function = kByCode[id >> 7];
  if (function == CobFunction::unknown) return {};
  return {function, node};
}

CanFrame encode_nmt(NmtCommand command, std::uint8_t node) noexcept {
  const std::uint8_t bytes[2] = {static_cast<std::uint8_t>(command), node};
  return can_data_frame(kNmtCobId, bytes);
}

bool decode_nmt(const CanFrame& f, NmtCommand* command, std::uint8_t* node) noexcept {
  if (f.id != kNmtCobId || f.extended || f.rtr || f.error || f.dlc != 2) return false;
  *command = static_cast<NmtCommand>(f.data[0]);
  *node = f.data[1];
  return true;
}

CanFrame encode_heartbeat(std::uint8_t node, NmtState state) noexcept {
  const std::uint8_t bytes[1] = {static_cast<std::uint8_t>(state)};
  return can_data_frame(heartbeat_cob_id(node), bytes);
}

bool decode_heartbeat(const CanFrame& f, std::uint8_t* node, NmtState* state) noexcept {
  if (f.extended || f.rtr || f.error || f.dlc < 1) return false;
  const CobId cob = decode_cob_id(f.id);
  if (cob.function != CobFunction::heartbeat) return false;
  *node = cob.node;
  *state = static_cast<NmtState>(f.data[0] & 0x7F);
  return true;
}

CanFrame encode_sync() noexcept {
  CanFrame f;
  f.id = kSyncCobId;
  return f;
}

bool is_sync(const CanFrame& f) noexcept { return f.id == kSyncCobId && !f.extended && !f.rtr && !f.error && f.dlc <= 1; }

CanFrame encode_emcy(std::uint8_t node, const Emcy& emcy) noexcept {
  CanFrame f = frame8(emcy_cob_id(node));
  put_le(&f.data[0], emcy.error_code, 2);
  f.data[2] = emcy.error_register;
  for (std::size_t i = 0; i < emcy.vendor.size(); ++i) f.data[3 + i] = emcy.vendor[i];
  return f;
}

bool decode_emcy(const CanFrame& f, std::uint8_t* node, Emcy* emcy) noexcept {
  if (f.extended || f.rtr || f.error || f.dlc != 8) return false;
  const CobId cob = decode_cob_id(f.id);
  if (cob.function != CobFunction::emcy) return false;
  *node = cob.node;
  emcy->error_code = static_cast<std::uint16_t>(get_le(&f.data[0], 2));
  emcy->error_register = f.data[2];
  for (std::size_t i = 0; i < emcy->vendor.size(); ++i) emcy->vendor[i] = f.data[3 + i];
  return true;
}

const char* sdo_abort_name(std::uint32_t code) noexcept {
  switch (code) {
    case kSdoAbortTimeout: return "SDO protocol timed out";
    case kSdoAbortInvalidCommand: return "invalid command specifier";
    case kSdoAbortUnsupportedAccess: return "unsupported access to an object";
    case kSdoAbortReadWriteOnly: return "attempt to read a write-only object";
    case kSdoAbortWriteReadOnly: return "attempt to write a read-only object";
    case kSdoAbortNoObject: return "object does not exist";
    case kSdoAbortCannotMap: return "object cannot be mapped to the PDO";
    case kSdoAbortPdoTooLong: return "mapped objects would exceed the PDO length";
    case kSdoAbortLengthMismatch: return "data type does not match, length does not match";
    case kSdoAbortLengthTooHigh: return "data type does not match, length too high";
    case kSdoAbortLengthTooLow: return "data type does not match, length too low";
    case kSdoAbortNoSubIndex: return "sub-index does not exist";
    case kSdoAbortValueRange: return "value range of parameter exceeded";
    case kSdoAbortValueTooHigh: return "value of parameter written too high";
    case kSdoAbortValueTooLow: return "value of parameter written too low";
    case kSdoAbortGeneral: return "general error";
    case kSdoAbortLocalControl: return "cannot transfer: local control";
    case kSdoAbortDeviceState: return "cannot transfer: not allowed in the present device state";
    default: return "unknown abort code";
  }
}

CanFrame encode_sdo_download(std::uint8_t node, std::uint16_t index, std::uint8_t sub, std::uint32_t value,
                             std::uint8_t size) noexcept {
  const std::uint8_t n = normal_size(size);
  return sdo_frame(sdo_request_cob_id(node), expedited_command(kClientDownload, n), index, sub, masked(value, n));
}

CanFrame encode_sdo_download_response(std::uint8_t node, std::uint16_t index, std::uint8_t sub) noexcept {
  return sdo_frame(sdo_response_cob_id(node), kServerDownload, index, sub, 0);
}

CanFrame encode_sdo_upload(std::uint8_t node, std::uint16_t index, std::uint8_t sub) noexcept {
  return sdo_frame(sdo_request_cob_id(node), kClientUpload, index, sub, 0);
}

CanFrame encode_sdo_upload_response(std::uint8_t node, std::uint16_t index, std::uint8_t sub, std::uint32_t value,
                                    std::uint8_t size) noexcept {
  const std::uint8_t n = normal_size(size);
  return sdo_frame(sdo_response_cob_id(node), expedited_command(kServerUpload, n), index, sub, masked(value, n));
}

CanFrame encode_sdo_abort(std::uint8_t node, bool from_server, std::uint16_t index, std::uint8_t sub,
                          std::uint32_t code) noexcept {
  return sdo_frame(from_server ? sdo_response_cob_id(node) : sdo_request_cob_id(node), kAbort, index, sub, code);
}

bool decode_sdo(const CanFrame& f, std::uint8_t* node, bool* from_server, Sdo* sdo) noexcept {
  if (f.extended || f.rtr || f.error || f.dlc != 8) return false;
  const CobId cob = decode_cob_id(f.id);
  if (cob.function != CobFunction::sdo_response && cob.function != CobFunction::sdo_request) return false;
  *node = cob.node;
  *from_server = cob.function == CobFunction::sdo_response;
  *sdo = Sdo{};
  sdo->command = f.data[0];
  sdo->index = static_cast<std::uint16_t>(get_le(&f.data[1], 2));
  sdo->sub = f.data[3];
  sdo->data = get_le(&f.data[4], 4);
  const std::uint8_t cs = f.data[0] & kCsMask;
  if (cs == kAbort) {
    sdo->kind = SdoKind::abort;
  } else if (*from_server) {
    if (cs == kServerDownload) {
      sdo->kind = SdoKind::download_response;
    } else if (cs == kServerUpload) {
      sdo->kind = SdoKind::upload_response;
      decode_transfer(f, sdo);
    }
  } else {
    if (cs == kClientDownload) {
      sdo->kind = SdoKind::download_request;
      decode_transfer(f, sdo);
    } else if (cs == kClientUpload) {
      sdo->kind = SdoKind::upload_request;
    }
  }
  return true;
}

std::int64_t sdo_value(std::uint32_t value, std::uint8_t size, bool is_signed) noexcept {
  size = normal_size(size);
  const std::uint32_t v = masked(value, size);
  if (!is_signed) return v;
  const std::uint32_t sign = 1u << (8 * size - 1);
  return static_cast<std::int64_t>(v ^ sign) - static_cast<std::int64_t>(sign);
}

}  // namespace avar::firmware_iface::canopen
