// E1.31 (sACN) datagrams from the network, through both the data and the universe discovery
// decoders: an accepted data packet holds at most 512 slots inside the datagram, a universe in
// 1..63999 and a priority up to 200; a discovery packet copies no more universes than asked for
// (their order is the sender's: the decoder does not check E1.31's ascending rule). The first input byte sizes the caller's
// universe list (0..255).
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <span>
#include <vector>

#include "avar/firmware_iface/sacn_codec.hpp"
#include "fuzz_bytes.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  namespace sacn = avar::firmware_iface::sacn;
  avar::fuzz::ByteReader in(data, size);
  std::vector<std::uint16_t> universes(in.u8());
  const auto datagram = in.rest();
  const auto inside = [&](auto view) {
    const auto* first = reinterpret_cast<const std::uint8_t*>(view.data());
    return view.empty() || (first >= datagram.data() && first + view.size() <= datagram.data() + datagram.size());
  };
  if (const auto packet = sacn::decode_data(datagram)) {
    if (packet->slots.size() > sacn::kMaxSlots || !inside(packet->slots) || !inside(packet->source_name)) std::abort();
    if (packet->header.universe < 1 || packet->header.universe > 63999 || packet->header.priority > 200) std::abort();
    if (datagram.size() < sacn::data_packet_size(packet->slots.size())) std::abort();
  }
  if (const auto packet = sacn::decode_discovery(datagram, universes)) {
    if (packet->universe_count > universes.size() || packet->page > packet->last_page || !inside(packet->source_name))
      std::abort();
  }
  return 0;
}
