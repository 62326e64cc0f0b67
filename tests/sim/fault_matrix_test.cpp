// The fault matrix: every protocol avar speaks x every fault between driver and device (drop,
// corrupt one byte, truncate, delay past the timeout, duplicate, reorder, disconnect and come
// back, device silent, device answering garbage), each cell a short show played on the stepped
// clock through the real driver and transport against the simulated device, the fault injected
// partway. Every cell asserts: (a) the show keeps running, or a fault is latched within the
// link's watchdog time and the fail-safe is carried out; (b) the device never stood outside its
// channel's limits; (c) the link's counters (the trace's counter columns) record the fault where
// the driver can see it. The matrix (pass / FAIL / n/a with the reason) is printed at the end of
// the run: `avar_sim_tests --gtest_filter='FaultMatrix*'`; the README's "Fault matrix" is its copy.

#include <gtest/gtest.h>

#include <cstdio>
#include <map>
#include <set>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include "avar/assembly/can_drive.hpp"
#include "fault_matrix/cell_run.hpp"

namespace avar::fault_matrix {
namespace {

struct Cell {
  std::size_t protocol;
  FaultKind fault;
};

void PrintTo(const Cell& c, std::ostream* os) { *os << protocol_cases()[c.protocol].name << " x " << fault_name(c.fault); }

/// What each cell run in this process ended with: verdict and evidence.
struct Recorded {
  bool pass = false;
  std::string evidence;
};
std::map<std::pair<std::size_t, std::size_t>, Recorded>& matrix_results() {
  static std::map<std::pair<std::size_t, std::size_t>, Recorded> results;
  return results;
}

std::vector<Cell> applicable_cells() {
  std::vector<Cell> cells;
  for (std::size_t p = 0; p < protocol_cases().size(); ++p)
    for (FaultKind f : kFaults)
      if (protocol_cases()[p].not_applicable[static_cast<std::size_t>(f)] == kApplies) cells.push_back({p, f});
  return cells;
}

bool reads_while_playing(const ProtocolCase& pc) {
  return pc.not_applicable[static_cast<std::size_t>(FaultKind::silent)] == kApplies;
}

std::string evidence_of(const CellRun& r) {
  std::ostringstream s;
  if (r.fault.cause == control::FaultCause::none) s << "ran through";
  else
    s << control::to_string(r.fault.cause) << " +" << static_cast<int>(std::lround((r.fault.time_s - r.onset_s) * 1000)) << " ms";
  const auto delta = [&](const char* name, std::uint64_t a, std::uint64_t b) {
    if (b > a) s << "; " << name << " +" << (b - a);
  };
  delta("timeouts", r.before.timeouts, r.after.timeouts);
  delta("crc", r.before.crc_errors, r.after.crc_errors);
  delta("framing", r.before.framing_errors, r.after.framing_errors);
  delta("retries", r.before.retries, r.after.retries);
  if (r.reconnects_after_replug > 0) s << "; reconnects +" << r.reconnects_after_replug;
  if (r.node_out_of_order > 0) s << "; node out-of-order " << r.node_out_of_order;
  return s.str();
}

/// (c): what the counters must show for this fault, where the driver can see it at all.
void expect_counted(const ProtocolCase& pc, FaultKind f, const CellRun& r) {
  const firmware_iface::LinkCounters& a = r.before;
  const firmware_iface::LinkCounters& b = r.after;
  const std::uint64_t timeouts = b.timeouts - a.timeouts;
  const std::uint64_t bad = (b.crc_errors - a.crc_errors) + (b.framing_errors - a.framing_errors);
  const sim::FaultCounts& i = r.injected;
  if (f == FaultKind::disconnect) {
    EXPECT_TRUE(r.resent_after_replug) << "the link did not come back once the wire did";
    if (pc.carrier == Carrier::network) {
      EXPECT_GT(r.injected.commands_dropped, 0u);
      EXPECT_EQ(r.node_packets_in_window, 0u) << "the node heard the link through a pulled cable";
    }
    if (pc.carrier != Carrier::network) {
      EXPECT_EQ(r.reconnects_after_replug, 1u);
    }
    return;
  }
  if (pc.carrier == Carrier::network) {
    // The link cannot see the network: the node's own account is the evidence.
    if (f == FaultKind::drop) {
      EXPECT_GT(i.commands_dropped, 0u);
    }
    if (f == FaultKind::duplicate) {
      EXPECT_GT(i.replies_duplicated, 0u);
      EXPECT_GT(r.node_out_of_order, 0u) << "the node applied a repeated sequence number (E1.31 6.7.2 discards it)";
    }
    if (f == FaultKind::reorder) {
      EXPECT_GT(i.replies_reordered, 0u);
      EXPECT_GT(r.node_out_of_order, 0u) << "the node applied a datagram that came after its successor";
    }
    return;
  }
  if (!reads_while_playing(pc)) {
    if (f == FaultKind::drop) {
      EXPECT_GT(i.commands_dropped, 0u) << "nothing was dropped";
    }
    if (f == FaultKind::garbage) {
      EXPECT_GT(i.garbage_bytes, 0u);
      EXPECT_EQ(b.replies, a.replies) << "noise was taken for a reply";
    }
    return;
  }
  switch (f) {
    case FaultKind::drop:
      EXPECT_GT(i.commands_dropped, 0u);
      EXPECT_GT(timeouts, 0u) << "lost requests were not counted as timeouts";
      break;
    case FaultKind::corrupt:
      EXPECT_GT(i.replies_corrupted, 0u);
      EXPECT_GT(bad + timeouts, 0u) << "corrupt replies were not counted";
      break;
    case FaultKind::truncate:
      EXPECT_GT(i.replies_truncated, 0u);
      EXPECT_GT(bad + timeouts, 0u) << "short replies were not counted";
      break;
    case FaultKind::delay: EXPECT_GT(timeouts, 0u) << "late replies were not counted as timeouts"; break;
    case FaultKind::duplicate:
      EXPECT_GT(i.replies_duplicated, 0u);
      EXPECT_GT(b.replies, a.replies) << "no replies were taken while replies came twice";
      break;
    case FaultKind::reorder:
      EXPECT_GT(i.replies_reordered, 0u);
      EXPECT_GT(bad + timeouts, 0u) << "replies out of their exchange were not counted";
      break;
    case FaultKind::silent:
      EXPECT_GT(i.replies_silenced, 0u);
      EXPECT_GT(timeouts, 0u) << "the silence was not counted";
      break;
    case FaultKind::garbage:
      EXPECT_GT(i.garbage_bytes, 0u);
      EXPECT_GT(bad + timeouts, 0u) << "noise was not counted";
      break;
    case FaultKind::disconnect: break;
  }
}

class FaultMatrix : public ::testing::TestWithParam<Cell> {};

TEST_P(FaultMatrix, ShowSurvivesOrFailsSafeWithinTheWatchdogAndTheCountersSayWhy) {
  const Cell cell = GetParam();
  const ProtocolCase& pc = protocol_cases()[cell.protocol];
  const std::uint64_t seed = 1 + cell.protocol * kFaultCount + static_cast<std::uint64_t>(cell.fault);
  const CellRun r = run_cell(pc, cell.fault, seed);
  ASSERT_TRUE(r.started) << r.problem;
  ASSERT_GE(r.onset_s, 0) << "the show never reached the fault's onset";
  SCOPED_TRACE(evidence_of(r));

  // (a) The show runs through, or it faults within the watchdog time and fails safe (the loop
  // ends once the fail-safe motions are over).
  EXPECT_EQ(r.end_phase, r.fault.cause == control::FaultCause::none ? control::Phase::disabled : control::Phase::faulted);
  const bool continuous = cell.fault == FaultKind::silent || cell.fault == FaultKind::disconnect;
  const bool must_fault = (cell.fault == FaultKind::silent && reads_while_playing(pc)) ||
                          (cell.fault == FaultKind::disconnect && pc.carrier != Carrier::network);
  if (r.fault.cause == control::FaultCause::none) {
    EXPECT_FALSE(must_fault) << "the show ran through a fault it must have stopped for";
    EXPECT_GE(r.show_time_reached, r.show_end - r.tick_s) << "the show stopped early without a fault";
  } else {
    EXPECT_GE(r.fault.time_s, r.onset_s) << "a fault before the injection";
    const double from = continuous || r.lifted_s < 0 ? r.onset_s : r.lifted_s;
    EXPECT_LE(r.fault.time_s, from + r.watchdog_s + 2 * r.tick_s) << "the fault came later than the watchdog allows";
    if (!r.link_dead) {
      for (std::size_t c = 0; c < r.rest.size(); ++c) {
        EXPECT_NEAR(r.final_command[c], r.rest[c], 1e-6) << "channel " << c << " did not end at its fail-safe rest";
      }
    }
  }
  // (b) No command ever took the device beyond its channel's limits.
  EXPECT_LE(r.worst_excursion, 0.5) << r.worst_where;
  // (c) The counters record the fault.
  expect_counted(pc, cell.fault, r);

  matrix_results()[{cell.protocol, static_cast<std::size_t>(cell.fault)}] = {!HasFailure(), evidence_of(r)};
}

std::string cell_name(const ::testing::TestParamInfo<Cell>& info) {
  return std::string(protocol_cases()[info.param.protocol].name) + "_" + fault_name(info.param.fault);
}

INSTANTIATE_TEST_SUITE_P(Cells, FaultMatrix, ::testing::ValuesIn(applicable_cells()), cell_name);

TEST(FaultMatrixRows, EveryProtocolAndCanDriveOfTheRegistryHasARow) {
  std::set<std::string> rows;
  for (const ProtocolCase& pc : protocol_cases()) {
    const rig::Rig rig = config::load_rig_text(pc.rig_text, std::string(pc.name) + ".yaml");
    rows.insert(rig.links[0].protocol);
    for (const rig::ActuatorSpec& a : rig.actuators)
      if (rig.links[0].protocol == "can") rows.insert(std::string("can/") + assembly::can_drive_of(a).name);
  }
  for (const assembly::Protocol* p : assembly::protocols()) EXPECT_TRUE(rows.count(p->name)) << p->name << " has no row";
  for (const assembly::CanDriveProtocol* d : assembly::can_drive_protocols())
    EXPECT_TRUE(rows.count(std::string("can/") + d->name)) << d->name << " has no row";
}

/// Prints the matrix of the cells this process ran, and what each cell's counters said.
class MatrixPrinter final : public ::testing::Environment {
 public:
  void TearDown() override {
    if (matrix_results().empty()) return;
    std::ostringstream out;
    out << "\nFault matrix (pass: ran through or failed safe within the watchdog, the limits held, the fault was"
           " counted; n/a: see the reasons; .: not run here)\n\n| protocol |";
    for (FaultKind f : kFaults) out << ' ' << fault_name(f) << " |";
    out << "\n|---|";
    for (std::size_t i = 0; i < kFaultCount; ++i) out << "---|";
    out << '\n';
    for (std::size_t p = 0; p < protocol_cases().size(); ++p) {
      out << "| " << protocol_cases()[p].name << " |";
      for (std::size_t f = 0; f < kFaultCount; ++f) {
        const int reason = protocol_cases()[p].not_applicable[f];
        const auto found = matrix_results().find({p, f});
        if (reason != kApplies) out << " n/a (" << reason + 1 << ") |";
        else if (found == matrix_results().end()) out << " . |";
        else out << (found->second.pass ? " pass |" : " FAIL |");
      }
      out << '\n';
    }
    out << '\n';
    for (std::size_t r = 0; r < kNotApplicableReasons.size(); ++r)
      out << "(" << r + 1 << ") " << kNotApplicableReasons[r] << '\n';
    out << "\nWhat each cell latched and counted (from the fault's onset):\n\n";
    for (const auto& [key, rec] : matrix_results())
      out << "- " << protocol_cases()[key.first].name << " / " << fault_name(kFaults[key.second]) << ": " << rec.evidence << '\n';
    std::fputs(out.str().c_str(), stdout);
  }
};

[[maybe_unused]] ::testing::Environment* const fault_matrix_printer = ::testing::AddGlobalTestEnvironment(new MatrixPrinter);

}  // namespace
}  // namespace avar::fault_matrix
