#include "avar/sim/canopen_object_dictionary.hpp"

#include <algorithm>
#include <stdexcept>
#include <string>
#include <utility>

#include "avar/firmware_iface/canopen_codec.hpp"

namespace avar::sim {
namespace canopen = firmware_iface::canopen;
namespace {

std::uint32_t od_cut(std::uint32_t raw, std::uint8_t size) noexcept { return size >= 4 ? raw : raw & ((1u << (8 * size)) - 1); }

}  // namespace

std::int64_t ObjectEntry::value() const noexcept { return canopen::sdo_value(raw, size, is_signed); }

void CanopenObjectDictionary::add(ObjectEntry entry) {
  if (!entry.ranged) {
    const int bits = 8 * entry.size;
    entry.min = entry.is_signed ? -(std::int64_t{1} << (bits - 1)) : 0;
    entry.max = entry.is_signed ? (std::int64_t{1} << (bits - 1)) - 1 : (std::int64_t{1} << bits) - 1;
  }
  entry.raw = od_cut(entry.raw, entry.size);
  const auto at = first_at(entry.index, entry.sub);
  if (at != entries_.end() && at->index == entry.index && at->sub == entry.sub)
    throw std::invalid_argument("object " + std::to_string(entry.index) + ":" + std::to_string(entry.sub) +
                                " is already in the dictionary");
  entries_.insert(at, entry);
}

std::vector<ObjectEntry>::const_iterator CanopenObjectDictionary::first_at(std::uint16_t index, std::uint8_t sub) const noexcept {
  return std::lower_bound(entries_.begin(), entries_.end(), std::pair{index, sub}, [](const ObjectEntry& e, const auto& key) {
    return std::pair{e.index, e.sub} < key;
  });
}

bool CanopenObjectDictionary::has_index(std::uint16_t index) const noexcept {
  const auto at = first_at(index, 0);
  return at != entries_.end() && at->index == index;
}

const ObjectEntry* CanopenObjectDictionary::find(std::uint16_t index, std::uint8_t sub) const noexcept {
  const auto at = first_at(index, sub);
  return at != entries_.end() && at->index == index && at->sub == sub ? &*at : nullptr;
}

ObjectEntry* CanopenObjectDictionary::find(std::uint16_t index, std::uint8_t sub) noexcept {
  return const_cast<ObjectEntry*>(std::as_const(*this).find(index, sub));
}

std::uint32_t CanopenObjectDictionary::get(std::uint16_t index, std::uint8_t sub) const noexcept {
  const ObjectEntry* e = find(index, sub);
  return e ? e->raw : 0;
}

std::int64_t CanopenObjectDictionary::value(std::uint16_t index, std::uint8_t sub) const noexcept {
  const ObjectEntry* e = find(index, sub);
  return e ? e->value() : 0;
}

void CanopenObjectDictionary::set(std::uint16_t index, std::uint8_t sub, std::uint32_t raw) noexcept {
  if (ObjectEntry* e = find(index, sub)) e->raw = od_cut(raw, e->size);
}

std::uint32_t CanopenObjectDictionary::check_read(std::uint16_t index, std::uint8_t sub,
                                                  const ObjectEntry** entry) const noexcept {
  const ObjectEntry* e = find(index, sub);
  if (!e) return has_index(index) ? canopen::kSdoAbortNoSubIndex : canopen::kSdoAbortNoObject;
  if (e->access == ObjectAccess::write_only) return canopen::kSdoAbortReadWriteOnly;
  *entry = e;
  return 0;
}

std::uint32_t CanopenObjectDictionary::check_write(std::uint16_t index, std::uint8_t sub, std::uint32_t data, std::uint8_t size,
                                                   ObjectEntry** entry, std::uint32_t* raw) noexcept {
  ObjectEntry* e = find(index, sub);
  if (!e) return has_index(index) ? canopen::kSdoAbortNoSubIndex : canopen::kSdoAbortNoObject;
  if (e->access == ObjectAccess::read_only) return canopen::kSdoAbortWriteReadOnly;
  if (size > e->size) return canopen::kSdoAbortLengthTooHigh;
  if (size != 0 && size < e->size) return canopen::kSdoAbortLengthTooLow;
  if (size == 0 && od_cut(data, e->size) != data) return canopen::kSdoAbortLengthMismatch;
  const std::uint32_t r = od_cut(data, e->size);
  const std::int64_t v = canopen::sdo_value(r, e->size, e->is_signed);
  if (v > e->max) return canopen::kSdoAbortValueTooHigh;
  if (v < e->min) return canopen::kSdoAbortValueTooLow;
  *entry = e;
  *raw = r;
  return 0;
}

bool CanopenObjectDictionary::can_map(std::uint16_t index, std::uint8_t sub, std::uint8_t bits, bool rpdo) const noexcept {
  const ObjectEntry* e = find(index, sub);
  if (!e || bits != 8 * e->size) return false;
  if (e->mappable == PdoMappable::both) return true;
  return e->mappable == (rpdo ? PdoMappable::rpdo : PdoMappable::tpdo);
}

}  // namespace avar::sim
