#pragma once
// The object dictionary of a simulated CANopen device: entries (index:sub) with their size,
// signedness, access, PDO mappability and value range, and the checks an expedited SDO server
// makes before it reads or writes one, each failure answered with the abort code CiA 301 gives
// it (../shared/protocols/canopen-cia402.md, section 3). Meaning (what a write does) is the
// device's: it validates further and applies. Not thread-safe (one device owns it).

#include <cstdint>
#include <vector>

namespace avar::sim {

enum class ObjectAccess : std::uint8_t { read_only, write_only, read_write };
/// Which PDOs an object may be mapped into.
enum class PdoMappable : std::uint8_t { no, rpdo, tpdo, both };

struct ObjectEntry {
  std::uint16_t index = 0;
  std::uint8_t sub = 0;
  std::uint8_t size = 4;  ///< bytes: 1, 2 or 4
  bool is_signed = false;
  ObjectAccess access = ObjectAccess::read_write;
  PdoMappable mappable = PdoMappable::no;
  bool ranged = false;   ///< SDO writes limited to min..max (otherwise the type's whole range)
  std::int64_t min = 0;  ///< in the entry's signedness
  std::int64_t max = 0;
  std::uint32_t raw = 0;  ///< the value, little-endian bytes of `size` in the low bits

  std::int64_t value() const noexcept;  ///< raw as a number of the entry's type
};

class CanopenObjectDictionary {
 public:
  /// Adds an entry; an entry that is not `ranged` gets its type's whole range. Throws
  /// std::invalid_argument for an index:sub already there. Adding moves entries: pointers from
  /// find() are valid until the next add().
  void add(ObjectEntry entry);
  /// By binary search (the entries are kept in index:sub order): a drive looks up its objects
  /// on every step of its simulated time.
  ObjectEntry* find(std::uint16_t index, std::uint8_t sub) noexcept;
  const ObjectEntry* find(std::uint16_t index, std::uint8_t sub) const noexcept;

  /// The raw value of an entry that exists (0 otherwise); no access check (the device's own use).
  std::uint32_t get(std::uint16_t index, std::uint8_t sub) const noexcept;
  std::int64_t value(std::uint16_t index, std::uint8_t sub) const noexcept;
  /// Sets an entry that exists, cut to its size; no checks.
  void set(std::uint16_t index, std::uint8_t sub, std::uint32_t raw) noexcept;

  /// Checks an SDO upload: 0 and *entry set, or the abort code (object does not exist,
  /// sub-index does not exist, read of a write-only object).
  std::uint32_t check_read(std::uint16_t index, std::uint8_t sub, const ObjectEntry** entry) const noexcept;
  /// Checks an SDO download of `data` with `size` bytes (0 = size not indicated): 0 and *entry
  /// and *raw (the value cut to the entry's size) set, or the abort code: object / sub-index does
  /// not exist, write to a read-only object, length too high / too low (size indicated), length
  /// mismatch (size not indicated, and bytes beyond the entry's size are not zero), value too
  /// high / too low (outside min..max).
  std::uint32_t check_write(std::uint16_t index, std::uint8_t sub, std::uint32_t data, std::uint8_t size, ObjectEntry** entry,
                            std::uint32_t* raw) noexcept;

  /// Whether an entry may be mapped into an RPDO (rpdo true) or TPDO with `bits` bits: it
  /// exists, is mappable that way and `bits` is its size.
  bool can_map(std::uint16_t index, std::uint8_t sub, std::uint8_t bits, bool rpdo) const noexcept;

 private:
  /// The first entry at or after index:sub.
  std::vector<ObjectEntry>::const_iterator first_at(std::uint16_t index, std::uint8_t sub) const noexcept;
  bool has_index(std::uint16_t index) const noexcept;

  std::vector<ObjectEntry> entries_;  ///< sorted by index, then sub
};

}  // namespace avar::sim
