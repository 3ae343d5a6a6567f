// SPDX-License-Identifier: MIT
#pragma once
// CLM1.4 program lines and parameters as ItemDevices (for send/read/verify).

#include <string>
#include <vector>

#include "hil/serial/clm14/client.hpp"
#include "hil/serial/clm14/files.hpp"
#include "hil/serial/item_transfer.hpp"

namespace hil::serial::clm14 {

class ProgramDevice final : public ItemDevice {
 public:
  explicit ProgramDevice(Client& c) : client_(c) {}
  std::expected<void, ItemError> write_item(const Item& item) override;
  std::expected<std::string, ItemError> read_item(const std::string& key) override;
  [[nodiscard]] std::string normalise(const std::string& key, const std::string& text) const override;
  /// "0000".."2999"
  [[nodiscard]] static std::vector<std::string> all_keys();

 private:
  Client& client_;
};

class ParameterDevice final : public ItemDevice {
 public:
  explicit ParameterDevice(Client& c) : client_(c) {}
  std::expected<void, ItemError> write_item(const Item& item) override;
  std::expected<std::string, ItemError> read_item(const std::string& key) override;
  [[nodiscard]] std::string normalise(const std::string& key, const std::string& text) const override;

 private:
  Client& client_;
};

/// Items of a parsed file, in file order.
[[nodiscard]] std::vector<Item> to_items(const DeviceFile& f);
/// A program as read from the device: drops the NOP lines after the last instruction.
[[nodiscard]] DeviceFile program_from_items(const std::vector<Item>& items);

}  // namespace hil::serial::clm14
