// SPDX-License-Identifier: MIT
#include "hil/controllers/modbus_io_link.hpp"

#include <fmt/format.h>

namespace hil::controllers {

std::expected<ModbusIoPlans, std::string> make_io_plans(const ModbusIoLinkConfig& config) {
  std::vector<modbus::BitRef> in;
  std::vector<modbus::BitRef> out;
  for (const auto& b : config.inputs) in.push_back(b.ref);
  for (const auto& b : config.outputs) out.push_back(b.ref);
  auto reads = modbus::make_bit_plan(in, false);
  if (!reads) return std::unexpected(reads.error());
  auto writes = modbus::make_bit_plan(out, true);
  if (!writes) return std::unexpected(writes.error());
  return ModbusIoPlans{std::move(*reads), std::move(*writes)};
}

ModbusIoLink::ModbusIoLink(ModbusIoLinkConfig config, ModbusIoPlans plans, std::unique_ptr<ModbusIoBus> bus)
    : config_(std::move(config)),
      plans_(std::move(plans)),
      bus_(std::move(bus)),
      inputs_(plans_.reads.bits, 0),
      outputs_(plans_.writes.bits, 0) {}

void ModbusIoLink::raise(modbus::ModbusError error) noexcept {
  healthy_ = false;
  if (faulted_) return;
  faulted_ = true;
  ++fault_count_;
  try {  // only on the transition into an outage
    fault_.code = modbus::make_error_code(error);
    fault_.text = fmt::format(
        "{} ({}): {}; its inputs read 0 until it answers again (check the terminal's power, cable and address)",
        config_.name, bus_->describe(),
        error == modbus::ModbusError::timeout && status_.error == modbus::ModbusError::none
            ? fmt::format("no answered poll for {:.0f} ms (stale_after {:.0f} ms)", to_seconds(status_.age) * 1e3,
                          to_seconds(config_.stale_after) * 1e3)
            : fault_.code.message());
  } catch (...) {
    fault_.text.clear();  // the code alone still says what happened
  }
}

void ModbusIoLink::read(TimePoint now, IoImage& image) noexcept {
  bus_->fetch(now, inputs_, status_);
  if (status_.error != modbus::ModbusError::none) {
    raise(status_.error);
  } else if (status_.age > config_.stale_after) {
    raise(modbus::ModbusError::timeout);
  } else if (status_.polls == 0) {
    healthy_ = false;  // starting: no input yet, not (yet) a fault
  } else {
    healthy_ = true;
    faulted_ = false;
  }
  for (std::size_t i = 0; i < config_.inputs.size(); ++i)
    image.set(config_.inputs[i].bit, healthy_ && inputs_[plans_.reads.slots[i]] != 0);
  if (config_.status_bit) image.set(*config_.status_bit, healthy_);
}

void ModbusIoLink::write(TimePoint now, const IoImage& image) noexcept {
  if (config_.outputs.empty()) return;
  for (std::size_t i = 0; i < config_.outputs.size(); ++i)
    outputs_[plans_.writes.slots[i]] = image.get(config_.outputs[i].bit) ? 1 : 0;
  bus_->put(now, outputs_);
}

}  // namespace hil::controllers
