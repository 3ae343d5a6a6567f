// SPDX-License-Identifier: MIT
#pragma once
// Open a Channel from a bus URL (hil/can/bus_url.hpp): SocketCAN, socketcand client or a named
// in-process VirtualBus. This is what every `--bus` option of hilbridge goes through.

#include <expected>
#include <map>
#include <memory>
#include <string>
#include <string_view>
#include <system_error>

#include <asio/any_io_executor.hpp>

#include "hil/can/bus_url.hpp"
#include "hil/can/channel.hpp"
#include "hil/can/virtual_bus.hpp"
#include "hil/core/clock.hpp"

namespace hil::can {

/// Named in-process buses for `virtual:NAME` URLs. Not a singleton: the owner (a run, a test, a
/// CLI command) creates one and passes it to make_channel. Thread: the buses' thread.
class VirtualBusRegistry {
 public:
  explicit VirtualBusRegistry(const Clock& clock, VirtualBusOptions options = {}) : clock_(clock), options_(options) {}
  /// The bus called `name`, created on first use.
  VirtualBus& get(const std::string& name);
  [[nodiscard]] VirtualBus* find(const std::string& name) noexcept;

 private:
  const Clock& clock_;
  VirtualBusOptions options_;
  std::map<std::string, std::unique_ptr<VirtualBus>, std::less<>> buses_;
};

struct BusError {
  std::error_code code;
  std::string message;  ///< what failed, where, what to do
};

struct ChannelRequest {
  asio::any_io_executor executor;
  const Clock& clock;
  VirtualBusRegistry* virtual_buses = nullptr;  ///< needed for virtual:NAME
  std::string participant = "hilbridge";        ///< participant name on a virtual bus
};

/// Parse `url` and open it. Blocks up to a few seconds for the socketcand handshake.
[[nodiscard]] std::expected<std::unique_ptr<Channel>, BusError> make_channel(std::string_view url,
                                                                             const ChannelRequest& request);
[[nodiscard]] std::expected<std::unique_ptr<Channel>, BusError> make_channel(const BusUrl& url,
                                                                             const ChannelRequest& request);

}  // namespace hil::can
