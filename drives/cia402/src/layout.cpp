// SPDX-License-Identifier: MIT
#include "hil/cia402/layout.hpp"

namespace hil::cia402 {
namespace {

using canopen::ParameterValue;
using canopen::PdoConfig;
using canopen::PdoMappingEntry;

std::vector<std::uint8_t> le(std::uint64_t v, std::size_t n) {
  std::vector<std::uint8_t> b(n);
  for (std::size_t i = 0; i < n; ++i) b[i] = static_cast<std::uint8_t>(v >> (8 * i));
  return b;
}

void remap(std::vector<ParameterValue>& out, std::uint16_t comm, std::uint16_t map, std::uint32_t cob,
           const std::vector<PdoMappingEntry>& entries, std::uint8_t tt) {
  out.push_back({comm, 1, le(cob | canopen::pdo_cob_invalid, 4)});  // 1. disable
  if (entries.empty()) return;
  out.push_back({map, 0, le(0, 1)});                // 2. sub 0 = 0
  for (std::size_t i = 0; i < entries.size(); ++i)  // 3. entries
    out.push_back({map, static_cast<std::uint8_t>(i + 1), le(canopen::make_mapping_entry(entries[i]), 4)});
  out.push_back({map, 0, le(entries.size(), 1)});  // 4. count
  out.push_back({comm, 2, le(tt, 1)});
  out.push_back({comm, 1, le(cob, 4)});  // 5. enable
}

}  // namespace

canopen::NodeConfig make_axis_node_config(const canopen::DeviceDescription& eds, const AxisOptions& o) {
  canopen::NodeConfig c;
  const auto id = o.node;
  c.id = id;
  if (o.check_identity) {
    c.device_type = static_cast<std::uint32_t>(eds.od.get_int(0x1000, 0));
    if (eds.info.vendor_number != 0) c.vendor_id = eds.info.vendor_number;
    if (eds.info.product_number != 0) c.product_code = eds.info.product_number;
    if (eds.info.revision_number != 0) c.revision = eds.info.revision_number;
  }
  c.configuration = eds.parameter_values;
  const auto hb_ms = std::chrono::duration_cast<std::chrono::milliseconds>(o.heartbeat_producer).count();
  c.configuration.push_back({0x1017, 0, le(static_cast<std::uint64_t>(hb_ms), 2)});
  if (o.master_node != 0) {
    const auto ms = std::chrono::duration_cast<std::chrono::milliseconds>(o.master_heartbeat_timeout).count();
    c.configuration.push_back(
        {0x1016, 1, le((std::uint64_t{o.master_node} << 16) | (static_cast<std::uint64_t>(ms) & 0xFFFF), 4)});
  }
  const std::vector<PdoMappingEntry> rpdo1{{0x6040, 0, 16}, {0x6060, 0, 8}};
  const std::vector<PdoMappingEntry> rpdo2{{0x607A, 0, 32}, {0x60FF, 0, 32}};
  const std::vector<PdoMappingEntry> tpdo1{{0x6041, 0, 16}, {0x6061, 0, 8}, {0x603F, 0, 16}};
  const std::vector<PdoMappingEntry> tpdo2{{0x6064, 0, 32}, {0x606C, 0, 32}};
  remap(c.configuration, 0x1400, 0x1600, 0x200u + id, rpdo1, 1);
  remap(c.configuration, 0x1401, 0x1601, 0x300u + id, rpdo2, 1);
  const std::vector<PdoMappingEntry> rpdo3 = o.profile_objects
                                                 ? std::vector<PdoMappingEntry>{{0x6081, 0, 32}, {0x6083, 0, 32}}
                                                 : std::vector<PdoMappingEntry>{};
  const std::vector<PdoMappingEntry> rpdo4 =
      o.profile_objects ? std::vector<PdoMappingEntry>{{0x6084, 0, 32}} : std::vector<PdoMappingEntry>{};
  remap(c.configuration, 0x1402, 0x1602, 0x400u + id, rpdo3, 1);
  remap(c.configuration, 0x1403, 0x1603, 0x500u + id, rpdo4, 1);
  remap(c.configuration, 0x1800, 0x1A00, 0x180u + id, tpdo1, 1);
  remap(c.configuration, 0x1801, 0x1A01, 0x280u + id, tpdo2, 1);
  remap(c.configuration, 0x1802, 0x1A02, 0x380u + id, {}, 1);
  remap(c.configuration, 0x1803, 0x1A03, 0x480u + id, {}, 1);
  c.heartbeat_consumer = o.heartbeat_consumer;
  c.image = eds.od;
  auto pdo = [](std::uint32_t cob, std::vector<PdoMappingEntry> m, std::uint8_t tt) {
    PdoConfig p;
    p.cob_id = cob;
    p.transmission_type = tt;
    p.mapping = std::move(m);
    return p;
  };
  // The master applies received PDOs at once (0xFF) and sends its own on every SYNC (1).
  c.rx_pdos = {pdo(0x180u + id, tpdo1, 0xFF), pdo(0x280u + id, tpdo2, 0xFF)};
  c.tx_pdos = {pdo(0x200u + id, rpdo1, 1), pdo(0x300u + id, rpdo2, 1)};
  if (o.profile_objects) {
    c.tx_pdos.push_back(pdo(0x400u + id, rpdo3, 1));
    c.tx_pdos.push_back(pdo(0x500u + id, rpdo4, 1));
  }
  return c;
}

}  // namespace hil::cia402
