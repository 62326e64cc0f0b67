#include "avar/firmware_iface/canopen_codec.hpp"

#include "avar/core/byte_order.hpp"

namespace avar::firmware_iface::canopen {
namespace {

// Command specifier field (bits 5-7 of byte 0) and the expedited / size-indicated flags.
constexpr std::uint8_t kSdoCsMask = 0xE0;
constexpr std::uint8_t kSdoClientDownload = 0x20;
constexpr std::uint8_t kSdoClientUpload = 0x40;
constexpr std::uint8_t kSdoServerDownload = 0x60;
constexpr std::uint8_t kSdoServerUpload = 0x40;
constexpr std::uint8_t kSdoAbortCommand = 0x80;
constexpr std::uint8_t kSdoExpedited = 0x02;
constexpr std::uint8_t kSdoSizeIndicated = 0x01;

CanFrame canopen_frame8(std::uint32_t id) noexcept {
  CanFrame f;
  f.id = id;
  f.dlc = 8;
  return f;
}

CanFrame canopen_sdo_frame(std::uint32_t id, std::uint8_t command, std::uint16_t index, std::uint8_t sub,
                           std::uint32_t data) noexcept {
  CanFrame f = canopen_frame8(id);
  f.data[0] = command;
  put_le(&f.data[1], index, 2);
  f.data[3] = sub;
  put_le(&f.data[4], data, 4);
  return f;
}

/// 1..4; anything else means 4.
std::uint8_t sdo_normal_size(std::uint8_t size) noexcept { return size >= 1 && size <= 4 ? size : 4; }

/// Expedited command byte with `size` (1..4) bytes: base | n << 2 | e | s, n = unused bytes.
std::uint8_t sdo_expedited_command(std::uint8_t base, std::uint8_t size) noexcept {
  return static_cast<std::uint8_t>(base | (4 - size) << 2 | kSdoExpedited | kSdoSizeIndicated);
}

std::uint32_t sdo_masked(std::uint32_t value, std::uint8_t size) noexcept {
  return size >= 4 ? value : value & ((1u << (8 * size)) - 1);
}

/// Fills the data fields of a download request or upload response.
void sdo_decode_transfer(const CanFrame& f, Sdo* sdo) noexcept {
  const std::uint8_t c = f.data[0];
  sdo->expedited = c & kSdoExpedited;
  if (sdo->expedited) sdo->size = (c & kSdoSizeIndicated) ? static_cast<std::uint8_t>(4 - ((c >> 2) & 0x03)) : 0;
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

const char* nmt_state_name(NmtState state) noexcept {
  switch (state) {
    case NmtState::boot_up: return "boot-up";
    case NmtState::stopped: return "Stopped";
    case NmtState::operational: return "Operational";
    case NmtState::pre_operational: return "Pre-operational";
  }
  return "unknown NMT state";
}

CanFrame encode_sync() noexcept {
  CanFrame f;
  f.id = kSyncCobId;
  return f;
}

bool is_sync(const CanFrame& f) noexcept { return f.id == kSyncCobId && !f.extended && !f.rtr && !f.error && f.dlc <= 1; }

CanFrame encode_emcy(std::uint8_t node, const Emcy& emcy) noexcept {
  CanFrame f = canopen_frame8(emcy_cob_id(node));
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
    case kSdoAbortTimeout: return "SDO timeout";
    case kSdoAbortInvalidCommand: return "invalid command specifier";
    case kSdoAbortUnsupportedAccess: return "unsupported access";
    case kSdoAbortReadWriteOnly: return "read of write-only object";
    case kSdoAbortWriteReadOnly: return "write to read-only object";
    case kSdoAbortNoObject: return "object does not exist";
    case kSdoAbortCannotMap: return "object cannot be mapped to PDO";
    case kSdoAbortPdoTooLong: return "mapped objects exceed PDO length";
    case kSdoAbortLengthMismatch: return "data type / length mismatch";
    case kSdoAbortLengthTooHigh: return "length too high";
    case kSdoAbortLengthTooLow: return "length too low";
    case kSdoAbortNoSubIndex: return "sub-index does not exist";
    case kSdoAbortValueRange: return "value range exceeded";
    case kSdoAbortValueTooHigh: return "value too high";
    case kSdoAbortValueTooLow: return "value too low";
    case kSdoAbortGeneral: return "general error";
    case kSdoAbortLocalControl: return "local control";
    case kSdoAbortDeviceState: return "not allowed in present device state";
    default: return "unknown abort code";
  }
}

CanFrame encode_sdo_download(std::uint8_t node, std::uint16_t index, std::uint8_t sub, std::uint32_t value,
                             std::uint8_t size) noexcept {
  const std::uint8_t n = sdo_normal_size(size);
  return canopen_sdo_frame(sdo_request_cob_id(node), sdo_expedited_command(kSdoClientDownload, n), index, sub,
                           sdo_masked(value, n));
}

CanFrame encode_sdo_download_response(std::uint8_t node, std::uint16_t index, std::uint8_t sub) noexcept {
  return canopen_sdo_frame(sdo_response_cob_id(node), kSdoServerDownload, index, sub, 0);
}

CanFrame encode_sdo_upload(std::uint8_t node, std::uint16_t index, std::uint8_t sub) noexcept {
  return canopen_sdo_frame(sdo_request_cob_id(node), kSdoClientUpload, index, sub, 0);
}

CanFrame encode_sdo_upload_response(std::uint8_t node, std::uint16_t index, std::uint8_t sub, std::uint32_t value,
                                    std::uint8_t size) noexcept {
  const std::uint8_t n = sdo_normal_size(size);
  return canopen_sdo_frame(sdo_response_cob_id(node), sdo_expedited_command(kSdoServerUpload, n), index, sub,
                           sdo_masked(value, n));
}

CanFrame encode_sdo_abort(std::uint8_t node, bool from_server, std::uint16_t index, std::uint8_t sub,
                          std::uint32_t code) noexcept {
  return canopen_sdo_frame(from_server ? sdo_response_cob_id(node) : sdo_request_cob_id(node), kSdoAbortCommand, index, sub,
                           code);
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
  const std::uint8_t cs = f.data[0] & kSdoCsMask;
  if (cs == kSdoAbortCommand) {
    sdo->kind = SdoKind::abort;
  } else if (*from_server) {
    if (cs == kSdoServerDownload) {
      sdo->kind = SdoKind::download_response;
    } else if (cs == kSdoServerUpload) {
      sdo->kind = SdoKind::upload_response;
      sdo_decode_transfer(f, sdo);
    }
  } else {
    if (cs == kSdoClientDownload) {
      sdo->kind = SdoKind::download_request;
      sdo_decode_transfer(f, sdo);
    } else if (cs == kSdoClientUpload) {
      sdo->kind = SdoKind::upload_request;
    }
  }
  return true;
}

std::int64_t sdo_value(std::uint32_t value, std::uint8_t size, bool is_signed) noexcept {
  size = sdo_normal_size(size);
  const std::uint32_t v = sdo_masked(value, size);
  if (!is_signed) return v;
  const std::uint32_t sign = 1u << (8 * size - 1);
  return static_cast<std::int64_t>(v ^ sign) - static_cast<std::int64_t>(sign);
}

}  // namespace avar::firmware_iface::canopen
