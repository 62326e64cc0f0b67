#pragma once
// Checks of stand-alone simulator options that several offers share. Throw SimOptionError.

#include <algorithm>
#include <cstdint>
#include <string>
#include <vector>

#include "avar/assembly/sim_offer.hpp"

namespace avar::assembly {

/// The servo IDs of option `ids` (each 0..max_id, none twice).
inline std::vector<std::uint8_t> checked_ids(const SimValues& values, long long max_id, const char* what) {
  std::vector<std::uint8_t> ids;
  for (long long id : values.integers("ids")) {
    if (id < 0 || id > max_id)
      throw SimOptionError("--ids: " + std::to_string(id) + " is not " + what + "; expected 0 to " + std::to_string(max_id));
    if (std::find(ids.begin(), ids.end(), id) != ids.end())
      throw SimOptionError("--ids: " + std::to_string(id) + " is given twice; every servo on a bus needs its own ID");
    ids.push_back(static_cast<std::uint8_t>(id));
  }
  return ids;
}

/// "3,7" for messages.
inline std::string id_list(const std::vector<std::uint8_t>& ids) {
  std::string out;
  for (std::uint8_t id : ids) out += (out.empty() ? "" : ",") + std::to_string(id);
  return out;
}

}  // namespace avar::assembly
