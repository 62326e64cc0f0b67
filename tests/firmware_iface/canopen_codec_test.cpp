// Golden frames from ../shared/protocols/canopen-cia402.md, section 8 (vectors C1..C13), and
// encode/decode round trips over seeded random families.
#include "avar/firmware_iface/canopen_codec.hpp"

#include <gtest/gtest.h>

#include <random>
#include <string>
#include <vector>

namespace avar::firmware_iface::canopen {
namespace {

using Bytes = std::vector<std::uint8_t>;

Bytes canopen_payload(const CanFrame& f) { return Bytes(f.payload().begin(), f.payload().end()); }

void canopen_expect_frame(const CanFrame& f, std::uint32_t id, const Bytes& data) {
  EXPECT_EQ(f.id, id);
  EXPECT_FALSE(f.extended);
  EXPECT_FALSE(f.rtr);
  EXPECT_EQ(canopen_payload(f), data);
}

TEST(CanopenCodec, C1_C2_NmtCommands) {
  canopen_expect_frame(encode_nmt(NmtCommand::start, 0), 0x000, {0x01, 0x00});
  canopen_expect_frame(encode_nmt(NmtCommand::enter_pre_operational, 5), 0x000, {0x80, 0x05});
  NmtCommand command{};
  std::uint8_t node = 0;
  ASSERT_TRUE(decode_nmt(encode_nmt(NmtCommand::reset_communication, 9), &command, &node));
  EXPECT_EQ(command, NmtCommand::reset_communication);
  EXPECT_EQ(node, 9);
  EXPECT_FALSE(decode_nmt(encode_sync(), &command, &node));
}

TEST(CanopenCodec, C3_C4_BootUpAndHeartbeat) {
  canopen_expect_frame(encode_heartbeat(1, NmtState::boot_up), 0x701, {0x00});
  canopen_expect_frame(encode_heartbeat(1, NmtState::operational), 0x701, {0x05});
  std::uint8_t node = 0;
  NmtState state{};
  // Bit 7 is the node-guarding toggle, not part of the state.
  const std::uint8_t toggled[1] = {0x85};
  ASSERT_TRUE(decode_heartbeat(can_data_frame(0x705, toggled), &node, &state));
  EXPECT_EQ(node, 5);
  EXPECT_EQ(state, NmtState::operational);
  const std::uint8_t pre_op[1] = {0x7F};
  ASSERT_TRUE(decode_heartbeat(can_data_frame(0x77F, pre_op), &node, &state));
  EXPECT_EQ(node, 127);
  EXPECT_EQ(state, NmtState::pre_operational);
  EXPECT_FALSE(decode_heartbeat(can_data_frame(0x700, pre_op), &node, &state));  // node 0
  EXPECT_FALSE(decode_heartbeat(can_data_frame(0x601, pre_op), &node, &state));
}

TEST(CanopenCodec, C5_C6_C7_C9_C10_DownloadRequests) {
  canopen_expect_frame(encode_sdo_download(1, 0x6060, 0, 1, 1), 0x601, {0x2F, 0x60, 0x60, 0x00, 0x01, 0x00, 0x00, 0x00});
  canopen_expect_frame(encode_sdo_download(1, 0x6040, 0, 0x0006, 2), 0x601, {0x2B, 0x40, 0x60, 0x00, 0x06, 0x00, 0x00, 0x00});
  canopen_expect_frame(encode_sdo_download(1, 0x6040, 0, 0x000F, 2), 0x601, {0x2B, 0x40, 0x60, 0x00, 0x0F, 0x00, 0x00, 0x00});
  canopen_expect_frame(encode_sdo_download(1, 0x607A, 0, 10000, 4), 0x601, {0x23, 0x7A, 0x60, 0x00, 0x10, 0x27, 0x00, 0x00});
  canopen_expect_frame(encode_sdo_download(1, 0x607A, 0, static_cast<std::uint32_t>(-10000), 4), 0x601,
                       {0x23, 0x7A, 0x60, 0x00, 0xF0, 0xD8, 0xFF, 0xFF});
  // Three bytes: n = 1 unused byte.
  canopen_expect_frame(encode_sdo_download(3, 0x2000, 7, 0xAABBCCDD, 3), 0x603, {0x27, 0x00, 0x20, 0x07, 0xDD, 0xCC, 0xBB, 0x00});
}

TEST(CanopenCodec, C8_DownloadResponse) {
  canopen_expect_frame(encode_sdo_download_response(1, 0x6040, 0), 0x581, {0x60, 0x40, 0x60, 0x00, 0x00, 0x00, 0x00, 0x00});
  std::uint8_t node = 0;
  bool from_server = false;
  Sdo sdo;
  ASSERT_TRUE(decode_sdo(encode_sdo_download_response(1, 0x6040, 0), &node, &from_server, &sdo));
  EXPECT_TRUE(from_server);
  EXPECT_EQ(sdo.kind, SdoKind::download_response);
  EXPECT_EQ(sdo.index, 0x6040);
  EXPECT_EQ(sdo.sub, 0);
}

TEST(CanopenCodec, C11_UploadRequestAndResponse) {
  canopen_expect_frame(encode_sdo_upload(1, 0x6064, 0), 0x601, {0x40, 0x64, 0x60, 0x00, 0x00, 0x00, 0x00, 0x00});
  const CanFrame answer = encode_sdo_upload_response(1, 0x6064, 0, 123456, 4);
  canopen_expect_frame(answer, 0x581, {0x43, 0x64, 0x60, 0x00, 0x40, 0xE2, 0x01, 0x00});
  std::uint8_t node = 0;
  bool from_server = false;
  Sdo sdo;
  ASSERT_TRUE(decode_sdo(answer, &node, &from_server, &sdo));
  EXPECT_EQ(node, 1);
  EXPECT_EQ(sdo.kind, SdoKind::upload_response);
  EXPECT_EQ(sdo.size, 4);
  EXPECT_EQ(sdo.data, 123456u);
  // The other sizes: 0x4F / 0x4B / 0x47.
  EXPECT_EQ(encode_sdo_upload_response(1, 0x6061, 0, 8, 1).data[0], 0x4F);
  EXPECT_EQ(encode_sdo_upload_response(1, 0x6041, 0, 0x237, 2).data[0], 0x4B);
  EXPECT_EQ(encode_sdo_upload_response(1, 0x2000, 0, 0x123456, 3).data[0], 0x47);
  // 0x42: expedited, size not indicated.
  const std::uint8_t unsized[8] = {0x42, 0x64, 0x60, 0x00, 1, 2, 3, 4};
  ASSERT_TRUE(decode_sdo(can_data_frame(0x581, unsized), &node, &from_server, &sdo));
  EXPECT_EQ(sdo.kind, SdoKind::upload_response);
  EXPECT_TRUE(sdo.expedited);
  EXPECT_EQ(sdo.size, 0);
  EXPECT_EQ(sdo.data, 0x04030201u);
}

TEST(CanopenCodec, C12_Abort) {
  const CanFrame abort = encode_sdo_abort(1, true, 0x6099, 0, kSdoAbortNoObject);
  canopen_expect_frame(abort, 0x581, {0x80, 0x99, 0x60, 0x00, 0x00, 0x00, 0x02, 0x06});
  std::uint8_t node = 0;
  bool from_server = false;
  Sdo sdo;
  ASSERT_TRUE(decode_sdo(abort, &node, &from_server, &sdo));
  EXPECT_EQ(sdo.kind, SdoKind::abort);
  EXPECT_EQ(sdo.data, 0x06020000u);
  EXPECT_STREQ(sdo_abort_name(sdo.data), "object does not exist");
  // The client aborts on its own identifier.
  EXPECT_EQ(encode_sdo_abort(1, false, 0x6064, 0, kSdoAbortTimeout).id, 0x601u);
}

TEST(CanopenCodec, C13_Sync) {
  const CanFrame sync = encode_sync();
  canopen_expect_frame(sync, 0x080, {});
  EXPECT_TRUE(is_sync(sync));
  const std::uint8_t counter[1] = {7};
  EXPECT_TRUE(is_sync(can_data_frame(0x080, counter)));
  const std::uint8_t emcy[8] = {};
  EXPECT_FALSE(is_sync(can_data_frame(0x081, emcy)));
}

TEST(CanopenCodec, EveryAbortCodeOfTheNoteHasItsName) {
  const std::pair<std::uint32_t, const char*> names[] = {
      {0x05040000, "SDO timeout"},
      {0x05040001, "invalid command specifier"},
      {0x06010000, "unsupported access"},
      {0x06010001, "read of write-only object"},
      {0x06010002, "write to read-only object"},
      {0x06020000, "object does not exist"},
      {0x06040041, "object cannot be mapped to PDO"},
      {0x06070010, "data type / length mismatch"},
      {0x06070012, "length too high"},
      {0x06070013, "length too low"},
      {0x06090011, "sub-index does not exist"},
      {0x06090030, "value range exceeded"},
      {0x06090031, "value too high"},
      {0x06090032, "value too low"},
      {0x08000000, "general error"},
      {0x08000021, "local control"},
      {0x08000022, "not allowed in present device state"},
  };
  for (const auto& [code, name] : names) EXPECT_STREQ(sdo_abort_name(code), name) << std::hex << code;
  EXPECT_STREQ(sdo_abort_name(0x06040042), "mapped objects exceed PDO length");
  EXPECT_STREQ(sdo_abort_name(0x12345678), "unknown abort code");
}

TEST(CanopenCodec, CobIdsOfThePredefinedConnectionSet) {
  EXPECT_EQ(emcy_cob_id(5), 0x085u);
  EXPECT_EQ(tpdo_cob_id(1, 5), 0x185u);
  EXPECT_EQ(tpdo_cob_id(4, 5), 0x485u);
  EXPECT_EQ(rpdo_cob_id(1, 5), 0x205u);
  EXPECT_EQ(rpdo_cob_id(4, 5), 0x505u);
  EXPECT_EQ(sdo_response_cob_id(5), 0x585u);
  EXPECT_EQ(sdo_request_cob_id(5), 0x605u);
  EXPECT_EQ(heartbeat_cob_id(5), 0x705u);
  EXPECT_EQ(decode_cob_id(0x000).function, CobFunction::nmt);
  EXPECT_EQ(decode_cob_id(0x080).function, CobFunction::sync);
  EXPECT_EQ(decode_cob_id(0x100).function, CobFunction::time);
  EXPECT_EQ(decode_cob_id(0x77F).function, CobFunction::heartbeat);
  EXPECT_EQ(decode_cob_id(0x77F).node, 127);
  EXPECT_EQ(decode_cob_id(0x180).function, CobFunction::unknown);  // node 0
  EXPECT_EQ(decode_cob_id(0x681).function, CobFunction::unknown);
  EXPECT_EQ(decode_cob_id(0x7FF).function, CobFunction::unknown);
  const CobFunction by_base[] = {CobFunction::emcy,  CobFunction::tpdo1,        CobFunction::rpdo1,       CobFunction::tpdo2,
                                 CobFunction::rpdo2, CobFunction::tpdo3,        CobFunction::rpdo3,       CobFunction::tpdo4,
                                 CobFunction::rpdo4, CobFunction::sdo_response, CobFunction::sdo_request, CobFunction::heartbeat};
  const std::uint32_t bases[] = {0x080, 0x180, 0x200, 0x280, 0x300, 0x380, 0x400, 0x480, 0x500, 0x580, 0x600, 0x700};
  for (std::size_t i = 0; i < std::size(bases); ++i)
    for (std::uint8_t node : {std::uint8_t{1}, std::uint8_t{64}, std::uint8_t{127}}) {
      const CobId cob = decode_cob_id(bases[i] + node);
      EXPECT_EQ(cob.function, by_base[i]) << std::hex << bases[i];
      EXPECT_EQ(cob.node, node);
    }
}

TEST(CanopenCodec, EmcyLayout) {
  Emcy emcy;
  emcy.error_code = 0x7121;
  emcy.error_register = 0x81;
  emcy.vendor = {1, 2, 3, 4, 5};
  const CanFrame f = encode_emcy(5, emcy);
  canopen_expect_frame(f, 0x085, {0x21, 0x71, 0x81, 1, 2, 3, 4, 5});
  std::uint8_t node = 0;
  Emcy back;
  ASSERT_TRUE(decode_emcy(f, &node, &back));
  EXPECT_EQ(node, 5);
  EXPECT_EQ(back.error_code, 0x7121);
  EXPECT_EQ(back.error_register, 0x81);
  EXPECT_EQ(back.vendor, emcy.vendor);
  EXPECT_FALSE(decode_emcy(encode_sync(), &node, &back));
}

TEST(CanopenCodec, SegmentedAndBlockFramesAreOther) {
  std::uint8_t node = 0;
  bool from_server = false;
  Sdo sdo;
  // Segmented download initiate (e = 0, s = 1, size 10 in the data bytes).
  const std::uint8_t segmented[8] = {0x21, 0x08, 0x10, 0x00, 10, 0, 0, 0};
  ASSERT_TRUE(decode_sdo(can_data_frame(0x601, segmented), &node, &from_server, &sdo));
  EXPECT_EQ(sdo.kind, SdoKind::download_request);
  EXPECT_FALSE(sdo.expedited);
  const std::uint8_t block[8] = {0xC6, 0x08, 0x10, 0x00, 0, 0, 0, 0};
  ASSERT_TRUE(decode_sdo(can_data_frame(0x601, block), &node, &from_server, &sdo));
  EXPECT_EQ(sdo.kind, SdoKind::other);
  const std::uint8_t short_frame[4] = {0x40, 0x64, 0x60, 0x00};
  EXPECT_FALSE(decode_sdo(can_data_frame(0x601, short_frame), &node, &from_server, &sdo));
}

TEST(CanopenCodec, PdoMappingEntries) {
  EXPECT_EQ(pdo_mapping_entry(0x6040, 0, 16), 0x60400010u);
  EXPECT_EQ(pdo_mapping_entry(0x607A, 0, 32), 0x607A0020u);
  EXPECT_EQ(pdo_mapping_entry(0x607D, 2, 32), 0x607D0220u);
  EXPECT_EQ(decode_pdo_mapping(0x60640020u), (PdoMapping{0x6064, 0, 32}));
}

TEST(CanopenCodec, SdoValueSignExtension) {
  EXPECT_EQ(sdo_value(0xFF, 1, true), -1);
  EXPECT_EQ(sdo_value(0xFF, 1, false), 255);
  EXPECT_EQ(sdo_value(0x12348000, 2, true), -32768);
  EXPECT_EQ(sdo_value(0xFFFFD8F0, 4, true), -10000);
  EXPECT_EQ(sdo_value(0xFFFFFFFF, 4, false), 4294967295);
}

TEST(CanopenCodec, RandomSdoRoundTrips) {
  const unsigned seed = std::random_device{}();
  SCOPED_TRACE("seed " + std::to_string(seed));
  std::mt19937 rng(seed);
  std::uniform_int_distribution<std::uint32_t> word;
  for (int i = 0; i < 2000; ++i) {
    const auto node = static_cast<std::uint8_t>(1 + word(rng) % 127);
    const auto index = static_cast<std::uint16_t>(word(rng));
    const auto sub = static_cast<std::uint8_t>(word(rng));
    const auto size = static_cast<std::uint8_t>(1 + word(rng) % 4);
    const std::uint32_t value = word(rng);
    const std::uint32_t kept = size == 4 ? value : value & ((1u << (8 * size)) - 1);
    std::uint8_t n = 0;
    bool from_server = false;
    Sdo sdo;

    ASSERT_TRUE(decode_sdo(encode_sdo_download(node, index, sub, value, size), &n, &from_server, &sdo));
    EXPECT_EQ(n, node);
    EXPECT_FALSE(from_server);
    EXPECT_EQ(sdo.kind, SdoKind::download_request);
    EXPECT_EQ(sdo.index, index);
    EXPECT_EQ(sdo.sub, sub);
    EXPECT_EQ(sdo.size, size);
    EXPECT_EQ(sdo.data, kept);

    ASSERT_TRUE(decode_sdo(encode_sdo_upload_response(node, index, sub, value, size), &n, &from_server, &sdo));
    EXPECT_TRUE(from_server);
    EXPECT_EQ(sdo.kind, SdoKind::upload_response);
    EXPECT_EQ(sdo.size, size);
    EXPECT_EQ(sdo.data, kept);

    ASSERT_TRUE(decode_sdo(encode_sdo_upload(node, index, sub), &n, &from_server, &sdo));
    EXPECT_EQ(sdo.kind, SdoKind::upload_request);
    EXPECT_EQ(sdo.index, index);

    const bool server = word(rng) & 1;
    ASSERT_TRUE(decode_sdo(encode_sdo_abort(node, server, index, sub, value), &n, &from_server, &sdo));
    EXPECT_EQ(from_server, server);
    EXPECT_EQ(sdo.kind, SdoKind::abort);
    EXPECT_EQ(sdo.data, value);

    const auto command = static_cast<NmtCommand>(std::vector<std::uint8_t>{0x01, 0x02, 0x80, 0x81, 0x82}[word(rng) % 5]);
    NmtCommand c{};
    ASSERT_TRUE(decode_nmt(encode_nmt(command, node), &c, &n));
    EXPECT_EQ(c, command);
    EXPECT_EQ(n, node);

    Emcy emcy;
    emcy.error_code = static_cast<std::uint16_t>(value);
    emcy.error_register = sub;
    Emcy back;
    ASSERT_TRUE(decode_emcy(encode_emcy(node, emcy), &n, &back));
    EXPECT_EQ(back.error_code, emcy.error_code);
    EXPECT_EQ(back.error_register, emcy.error_register);

    const PdoMapping m{index, sub, static_cast<std::uint8_t>(value)};
    EXPECT_EQ(decode_pdo_mapping(pdo_mapping_entry(m)), m);
  }
}

}  // namespace
}  // namespace avar::firmware_iface::canopen
