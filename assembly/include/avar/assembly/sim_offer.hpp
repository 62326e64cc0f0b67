#pragma once
// A simulated device that `avar sim NAME` serves to other programs, as its registry entry offers
// it: what the device is, where it is served, its options, an example, and how to make it from
// the options' values. The command line walks the registry and adds one subcommand per offer, so
// a new protocol's simulator needs no code in the front end. Load-time only: making the device;
// serving it (a pseudo-terminal host, a loop over a loopback node) is the caller's.

#include <functional>
#include <map>
#include <memory>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

#include "avar/sim/byte_device.hpp"
#include "avar/sim/sim_dmx_node.hpp"

namespace avar::assembly {

/// Where a stand-alone simulated device is served.
enum class SimTransport {
  pty,           ///< a pseudo-terminal, like a USB serial adapter (its path is printed)
  udp_loopback,  ///< a UDP socket on 127.0.0.1 (its HOST:PORT is printed)
  in_process,    ///< only inside the avar process that drives it (`avar play --sim`)
};

const char* to_string(SimTransport t) noexcept;

/// One option of a stand-alone simulated device: `--ids 3,7`.
struct SimOption {
  const char* name;           ///< without dashes: "ids"
  const char* default_value;  ///< as text; "" for a flag (off unless given)
  const char* help;
  bool flag = false;  ///< takes no value: on when given
};

/// A bad option value; the message names the option ("--ids: 3 is given twice; ...").
class SimOptionError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

/// The options' values as given (or their defaults), by name. The readers throw SimOptionError.
class SimValues {
 public:
  void set(const std::string& name, std::string value) { values_[name] = std::move(value); }
  const std::string& text(const std::string& name) const;
  long long integer(const std::string& name) const;
  /// Comma-separated whole numbers.
  std::vector<long long> integers(const std::string& name) const;
  /// A flag: "" or "false" off, anything else on.
  bool flag(const std::string& name) const;

 private:
  std::map<std::string, std::string> values_;
};

/// A stand-alone simulated device, ready to serve.
struct ServedDevice {
  std::unique_ptr<sim::ByteDevice> device;        ///< served on a pseudo-terminal
  std::unique_ptr<sim::SimDmxNode> network_node;  ///< or listening on loopback UDP
  std::string description;                        ///< "simulated Maestro (12 channels, device number 12)"
  /// The status line; called with the device locked (pty) or between receptions (node).
  std::function<std::string()> state;
};

struct SimOffer {
  const char* name;         ///< the subcommand: `avar sim maestro`
  const char* alias;        ///< another name it answers to, or nullptr (`slcan` for `can`)
  const char* summary;      ///< one line for `avar sim --help`
  const char* description;  ///< what the device is and how it behaves, for `avar sim NAME --help`
  SimTransport transport;
  const char* example;  ///< command lines using it with `avar play ... --port`
  std::vector<SimOption> options;
  /// The device from the options' values (throws SimOptionError); nullptr for in_process, where
  /// `description` says how to reach the simulated device instead.
  ServedDevice (*make)(const SimValues& values) = nullptr;
};

/// Every offer: one per protocol of the registry, then one per CAN drive protocol, in their order.
std::vector<const SimOffer*> sim_offers();

/// The help text after `avar sim NAME`'s options: description, transport, example.
std::string sim_offer_help(const SimOffer& offer);

}  // namespace avar::assembly
