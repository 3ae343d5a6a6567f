// SPDX-License-Identifier: MIT
// Interop: Debian's python3-can `socketcand` interface (an independent implementation of the
// client side) exchanges frames with our hub; bytes are checked on both sides.
#include <gtest/gtest.h>

#include "hub_fixture.hpp"
#include "subprocess.hpp"

namespace can = hil::can;
using can::test::Hub;
using can::test::Inbox;
using can::test::Subprocess;

namespace {

TEST(SocketcandPython, PythonCanExchangesFramesWithOurHub) {
  if (!can::test::python_has("can.interfaces.socketcand"))
    GTEST_SKIP()
        << "/usr/bin/python3 with python3-can's socketcand interface is not installed (apt install python3-can)";
  Hub hub;
  Inbox rx;
  auto local = hub.run([&] {
    auto ch = hub.bus.attach("local");
    ch->set_receive_handler(rx.handler());
    return ch;
  });
  const std::vector<can::Frame> frames = {
      can::make_frame(0x123, {0xDE, 0xAD, 0xBE, 0xEF}),
      can::make_frame(0x080, {}),
      can::make_frame(0x601, {0x40, 0x18, 0x10, 0x01, 0x00, 0x00, 0x00, 0x00}),
      can::make_extended_frame(0x18FF0010, std::vector<std::uint8_t>{0x01, 0x02, 0x03}),
  };
  Subprocess py({"/usr/bin/python3", std::string(HIL_TEST_SOURCE_DIR) + "/socketcand_peer.py", "127.0.0.1",
                 std::to_string(hub.port()), "can0", std::to_string(frames.size())});
  ASSERT_TRUE(py.started());
  ASSERT_TRUE(py.wait_for_line("READY", std::chrono::seconds(60))) << py.output();
  // One frame at a time: python-can 4.1 loses a frame when several arrive split across reads.
  for (std::size_t i = 0; i < frames.size(); ++i) {
    hub.run([&] { EXPECT_FALSE(local->send(frames[i])); });
    auto got = rx.wait_for(i + 1);
    // >=: after the last echo the peer sends 7FF#PY at once; both may arrive before we look.
    ASSERT_GE(got.size(), i + 1) << "no echo for frame " << i << "\n" << py.output();
    can::Frame expected = frames[i];
    expected.id += 1;
    std::reverse(expected.data.begin(), expected.data.begin() + expected.dlc);
    EXPECT_EQ(got[i], expected) << "frame " << i;
  }
  auto got = rx.wait_for(frames.size() + 1);
  ASSERT_EQ(got.size(), frames.size() + 1) << py.output();
  EXPECT_EQ(got.back(), can::make_frame(0x7FF, {'P', 'Y'}));
  EXPECT_EQ(py.wait(), 0) << py.output();
  EXPECT_NE(py.output().find("RX 123#DEADBEEF"), std::string::npos) << py.output();
  EXPECT_NE(py.output().find("RX 18FF0010#010203"), std::string::npos) << py.output();
  EXPECT_NE(py.output().find("RX 80#\n"), std::string::npos) << py.output();
  hub.run([&] { local.reset(); });
}

}  // namespace
