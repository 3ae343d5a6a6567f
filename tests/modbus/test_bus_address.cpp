// SPDX-License-Identifier: MIT
// The `bus:` and `listen:` parsers of a Modbus I/O link, table-driven.
#include <gtest/gtest.h>

#include "hil/modbus/bus_address.hpp"

namespace hil::modbus {
namespace {

TEST(ModbusBusAddress, AcceptedForms) {
  EXPECT_EQ(parse_bus_address("sim")->kind, BusAddress::Kind::sim);
  const auto tcp = parse_bus_address("tcp://192.168.0.30");
  ASSERT_TRUE(tcp);
  EXPECT_EQ(tcp->kind, BusAddress::Kind::tcp);
  EXPECT_EQ(tcp->endpoint, (Endpoint{"192.168.0.30", 502}));
  EXPECT_EQ(tcp->to_string(), "tcp://192.168.0.30:502");
  EXPECT_EQ(parse_bus_address("tcp://[::1]:1502")->endpoint, (Endpoint{"::1", 1502}));
  EXPECT_EQ(parse_bus_address("tcp://[::1]:1502")->to_string(), "tcp://[::1]:1502");
  EXPECT_EQ(parse_bus_address("tcp://plc-7.local:5020")->endpoint, (Endpoint{"plc-7.local", 5020}));
  EXPECT_EQ(parse_endpoint("127.0.0.1:0", true, 502, true).value(), (Endpoint{"127.0.0.1", 0}));
}

TEST(ModbusBusAddress, ErrorsSayWhatAndWhy) {
  const std::pair<const char*, const char*> cases[] = {
      {"simulated", "expected sim (the simulated terminal) or tcp://HOST[:PORT]"},
      {"tcp://", "missing host"},
      {"tcp://host:0", "the port must be a number 1..65535"},
      {"tcp://host:70000", "the port must be a number 1..65535"},
      {"tcp://host:", "the port must be a number 1..65535"},
      {"tcp://::1:502", "write IPv6 hosts in brackets"},
      {"tcp://[::1", "unterminated [IPv6] host"},
      {"tcp://[%0]:5", "the host has characters"},
      {"tcp://a b:5", "the host has characters"},
  };
  for (const auto& [text, why] : cases) {
    SCOPED_TRACE(text);
    const auto r = parse_bus_address(text);
    ASSERT_FALSE(r);
    EXPECT_NE(r.error().find(std::string("bad Modbus bus '") + text + "'"), std::string::npos) << r.error();
    EXPECT_NE(r.error().find(why), std::string::npos) << r.error();
  }
  EXPECT_NE(parse_endpoint("127.0.0.1", true, 502, true).error().find("expected HOST:PORT"), std::string::npos);
  EXPECT_NE(parse_endpoint("127.0.0.1:0", true, 502, false).error().find("1..65535"), std::string::npos);
}

}  // namespace
}  // namespace hil::modbus
