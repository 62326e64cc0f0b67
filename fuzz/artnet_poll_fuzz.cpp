// ArtPoll and ArtPollReply datagrams from the network (both decoders see every datagram, as the
// node and the controller each do): a reply must claim at most 4 ports and keep its name fields
// inside their arrays; whatever decodes re-encodes to a packet that decodes to the same fields.
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <span>

#include "avar/firmware_iface/artnet_poll_codec.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  namespace artnet = avar::firmware_iface::artnet;
  const std::span<const std::uint8_t> datagram(data, size);
  if (const auto poll = artnet::decode_poll(datagram)) {
    std::uint8_t again[artnet::kPollSize] = {};
    if (artnet::encode_poll(again, *poll) != artnet::kPollSize) std::abort();
    const auto back = artnet::decode_poll(again);
    if (!back || back->flags != poll->flags || back->target_top != poll->target_top ||
        back->target_bottom != poll->target_bottom || back->oem != poll->oem)
      std::abort();
  }
  if (const auto reply = artnet::decode_poll_reply(datagram)) {
    if (reply->num_ports > 4 || reply->short_name.view().size() >= artnet::kShortNameSize ||
        reply->long_name.view().size() >= artnet::kLongNameSize || reply->node_report.view().size() >= artnet::kNodeReportSize)
      std::abort();
    for (std::size_t i = 0; i < 4; ++i) {
      if (reply->output_port_address(i) > 32767) std::abort();
    }
    std::uint8_t again[artnet::kPollReplySize] = {};
    if (artnet::encode_poll_reply(again, *reply) != artnet::kPollReplySize) std::abort();
    const auto back = artnet::decode_poll_reply(again);
    if (!back || back->num_ports != reply->num_ports || back->short_name.view() != reply->short_name.view() ||
        back->long_name.view() != reply->long_name.view() || back->ip != reply->ip)
      std::abort();
  }
  return 0;
}
