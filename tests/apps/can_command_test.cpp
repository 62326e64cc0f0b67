// CAN from the command line: `avar sim slcan --pty` as any SLCAN client sees it (the real SLCAN
// transport opens it and a drive answers), and the CAN example figures played by `avar play`.
#include <gtest/gtest.h>

#include "../support/child_process.hpp"
#include "../support/cli_run.hpp"
#include "avar/firmware_iface/can_conversation.hpp"
#include "avar/firmware_iface/odrive_can_codec.hpp"
#include "avar/firmware_iface/serial_transport.hpp"
#include "avar/firmware_iface/slcan_transport.hpp"

namespace avar::app {
namespace {

TEST(CanCommand, SimSlcanServesAnAdapterWithOdrivesThatAnswer) {
  testing::ChildProcess sim({AVAR_BINARY, "sim", "slcan", "--pty", "--drive", "odrive", "--ids", "1,2"});
  ASSERT_TRUE(sim.started());
  std::string path = sim.read_out_until("\n");
  ASSERT_FALSE(path.empty());
  path.pop_back();
  {
    firmware_iface::SlcanTransport bus(std::make_unique<firmware_iface::SerialTransport>(path, 115200), 1'000'000);
    // Node 2's encoder estimate on request (RTR), at its power-up position 0.
    firmware_iface::CanFrame answer;
    namespace od = firmware_iface::odrive;
    ASSERT_EQ(
        firmware_iface::ask_frame(
            bus, od::encode_get_encoder_estimates(2), std::chrono::seconds(2),
            [](const firmware_iface::CanFrame& f) { return f.id == od::can_id(2, od::kGetEncoderEstimates) && !f.rtr; }, &answer),
        Status::ok);
    od::EncoderEstimates e;
    ASSERT_TRUE(od::decode_encoder_estimates(answer, &e));
    EXPECT_FLOAT_EQ(e.position, 0);
    // Node 1's cyclic heartbeat arrives on its own (every 100 ms).
    ASSERT_EQ(
        firmware_iface::await_frame(bus, std::chrono::seconds(2),
                                    [](const firmware_iface::CanFrame& f) { return f.id == od::can_id(1, od::kHeartbeat); }),
        Status::ok);
  }
  sim.signal(SIGINT);
  EXPECT_EQ(sim.wait(), 0) << sim.err();
  EXPECT_NE(sim.err().find("simulated SLCAN adapter with ODrives at nodes 1,2 on a 1000000 bit/s bus"), std::string::npos)
      << sim.err();
}

TEST(CanCommand, SimSlcanRefusesNodesTheDriveCannotHave) {
  testing::ChildProcess sim({AVAR_BINARY, "sim", "slcan", "--pty", "--drive", "cia402", "--ids", "0"});
  EXPECT_EQ(sim.wait(), 2);
  EXPECT_NE(sim.err().find("--ids: 0 is not a CiA 402 drive node; expected 1 to 127"), std::string::npos) << sim.err();
  testing::ChildProcess twice({AVAR_BINARY, "sim", "slcan", "--pty", "--ids", "4,4"});
  EXPECT_EQ(twice.wait(), 2);
  EXPECT_NE(twice.err().find("--ids: 4 is given twice"), std::string::npos) << twice.err();
}

TEST(CanCommand, PlaysBothCanExamplesOnTheSimulator) {
  for (const auto& [show, rig] :
       {std::pair{"odrive-arm.yaml", "odrive-arm.yaml"}, std::pair{"turntable-tour.yaml", "cia402-turntable.yaml"}}) {
    const testing::CliResult r =
        testing::run_avar({"play", std::string(AVAR_SOURCE_DIR "/examples/shows/") + show, "--rig",
                           std::string(AVAR_SOURCE_DIR "/examples/rigs/") + rig, "--fast", "--no-progress"});
    EXPECT_EQ(r.code, 0) << r.err;
    EXPECT_NE(r.out.find("simulated CAN bus"), std::string::npos) << r.out;
    EXPECT_NE(r.out.find("0 timeouts"), std::string::npos) << r.out;
  }
}

}  // namespace
}  // namespace avar::app
