// The OSC cue sender: messages fired from one thread are sent from its own, each once, in order,
// with their arguments (read back by a liblo server on loopback).

#include "avar/firmware_iface/osc_cue_sender.hpp"

#include <gtest/gtest.h>

#include <cstdint>
#include <cstring>
#include <lo/lo.h>

#include <string>
#include <vector>

#include "../support/osc_sender.hpp"

namespace avar::firmware_iface {
namespace {

TEST(OscCueSender, SendsEachFiredMessageOnceInOrderWithItsArguments) {
  const int port = testing::free_udp_port();
  lo_server server = lo_server_new(std::to_string(port).c_str(), nullptr);
  ASSERT_NE(server, nullptr);
  std::vector<std::string> got;
  lo_server_add_method(
      server, nullptr, nullptr,
      [](const char* path, const char* types, lo_arg** argv, int argc, lo_message, void* user) -> int {
        std::string s = std::string(path) + " " + types;
        // liblo's arguments are 4-byte aligned, not as lo_arg's union (8): read the bytes.
        for (int i = 0; i < argc; ++i) {
          const auto* bytes = reinterpret_cast<const char*>(argv[i]);
          if (types[i] == 'i') {
            std::int32_t v = 0;
            std::memcpy(&v, bytes, sizeof v);
            s += " " + std::to_string(v);
          }
          if (types[i] == 'f') {
            float v = 0;
            std::memcpy(&v, bytes, sizeof v);
            s += " " + std::to_string(v);
          }
          if (types[i] == 's') s += std::string(" ") + bytes;
        }
        static_cast<std::vector<std::string>*>(user)->push_back(s);
        return 0;
      },
      &got);
  {
    OscCueSender sender(
        {{"127.0.0.1", port, "/a", {{'i', 3, ""}, {'s', 0, "go"}}}, {"127.0.0.1", port, "/b", {{'f', 0.25, ""}}}});
    EXPECT_TRUE(sender.fire(1));
    EXPECT_TRUE(sender.fire(0));
    EXPECT_FALSE(sender.fire(2));  // no such message
    sender.flush();
    EXPECT_EQ(sender.sent(), 2U);
    EXPECT_EQ(sender.dropped(), 1U);
  }
  while (got.size() < 2 && lo_server_recv_noblock(server, 2000) > 0) {
  }
  lo_server_free(server);
  ASSERT_EQ(got.size(), 2U);
  EXPECT_EQ(got[0], "/b f 0.250000");
  EXPECT_EQ(got[1], "/a is 3 go");
}

}  // namespace
}  // namespace avar::firmware_iface
