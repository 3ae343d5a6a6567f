// SPDX-License-Identifier: MIT
#include "hil/can/io/make_channel.hpp"

#include "hil/can/io/socketcand_channel.hpp"
#include "hil/can/linux/socketcan_channel.hpp"

namespace hil::can {

VirtualBus& VirtualBusRegistry::get(const std::string& name) {
  auto it = buses_.find(name);
  if (it == buses_.end()) it = buses_.emplace(name, std::make_unique<VirtualBus>(clock_, name, options_)).first;
  return *it->second;
}

VirtualBus* VirtualBusRegistry::find(const std::string& name) noexcept {
  auto it = buses_.find(name);
  return it == buses_.end() ? nullptr : it->second.get();
}

std::expected<std::unique_ptr<Channel>, BusError> make_channel(std::string_view url, const ChannelRequest& request) {
  auto parsed = parse_bus_url(url);
  if (!parsed) return std::unexpected(BusError{std::make_error_code(std::errc::invalid_argument), parsed.error()});
  return make_channel(*parsed, request);
}

std::expected<std::unique_ptr<Channel>, BusError> make_channel(const BusUrl& url, const ChannelRequest& request) {
  std::string diag;
  switch (url.kind) {
    case BusUrl::Kind::virtual_bus: {
      if (request.virtual_buses == nullptr)
        return std::unexpected(
            BusError{std::make_error_code(std::errc::operation_not_supported),
                     "bus '" + url.to_string() + "': in-process virtual buses are not available to this command"});
      return request.virtual_buses->get(url.name).attach(request.participant);
    }
    case BusUrl::Kind::socketcand: {
      auto ch = socketcand::SocketcandChannel::connect(request.executor, request.clock, url.host, url.port, url.name,
                                                       {}, &diag);
      if (!ch) return std::unexpected(BusError{ch.error(), diag});
      return std::unique_ptr<Channel>(std::move(*ch));
    }
    case BusUrl::Kind::socketcan: {
      auto ch = socketcan::SocketCanChannel::open(request.executor, request.clock, url.name, {}, &diag);
      if (!ch) return std::unexpected(BusError{ch.error(), diag});
      return std::unique_ptr<Channel>(std::move(*ch));
    }
  }
  return std::unexpected(BusError{std::make_error_code(std::errc::invalid_argument), "unknown bus kind"});
}

}  // namespace hil::can
