// SPDX-License-Identifier: MIT
#include "hil/serial/clm14/item_devices.hpp"

#include <fmt/format.h>

namespace hil::serial::clm14 {

namespace {
ItemError to_item_error(const ClientError& e) {
  return ItemError{e.code, e.message};
}
std::string squeeze(std::string s) {
  while (!s.empty() && s.back() == ' ') s.pop_back();
  for (char& c : s)
    if (c == ',') c = '.';
  return s;
}
}  // namespace

std::expected<void, ItemError> ProgramDevice::write_item(const Item& item) {
  auto r = client_.write_program_line(std::stoi(item.key), item.text);
  if (!r) return std::unexpected(to_item_error(r.error()));
  return {};
}

std::expected<std::string, ItemError> ProgramDevice::read_item(const std::string& key) {
  auto r = client_.read_program_line(std::stoi(key));
  if (!r) return std::unexpected(to_item_error(r.error()));
  return *r;
}

std::string ProgramDevice::normalise(const std::string&, const std::string& text) const {
  return squeeze(text);
}

std::vector<std::string> ProgramDevice::all_keys() {
  std::vector<std::string> k;
  k.reserve(3000);
  for (int i = 0; i < 3000; ++i) k.push_back(fmt::format("{:04d}", i));
  return k;
}

std::expected<void, ItemError> ParameterDevice::write_item(const Item& item) {
  auto r = client_.write_parameter(item.key, item.text);
  if (!r) return std::unexpected(to_item_error(r.error()));
  return {};
}

std::expected<std::string, ItemError> ParameterDevice::read_item(const std::string& key) {
  auto r = client_.read_parameter(key);
  if (!r) return std::unexpected(to_item_error(r.error()));
  return *r;
}

std::string ParameterDevice::normalise(const std::string&, const std::string& text) const {
  return squeeze(text);
}

std::vector<Item> to_items(const DeviceFile& f) {
  std::vector<Item> out;
  out.reserve(f.items.size());
  for (const auto& i : f.items) out.push_back(Item{i.key, i.text});
  return out;
}

DeviceFile program_from_items(const std::vector<Item>& items) {
  DeviceFile f{FileKind::program, {}};
  std::size_t last = 0;
  bool any = false;
  for (std::size_t i = 0; i < items.size(); ++i) {
    if (squeeze(items[i].text) != "NOP") {
      last = i;
      any = true;
    }
  }
  if (!any) return f;
  for (std::size_t i = 0; i <= last; ++i) f.items.push_back(FileItem{items[i].key, squeeze(items[i].text), 0});
  return f;
}

}  // namespace hil::serial::clm14
