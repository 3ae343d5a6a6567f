// SPDX-License-Identifier: MIT
// The SF scheduler and the FB 207 / FB 208 commanding state machine. See sf_runtime.hpp.
#include "hil/controllers/amkasyn/sf_runtime.hpp"

#include <fmt/format.h>

namespace hil::controllers::amkasyn {

SfState SfRuntime::state(int sf) const noexcept {
  if (sf < 0 || sf >= max_sf) return SfState::unassigned;
  const Slot& s = slots_[static_cast<std::size_t>(sf)];
  if (!s.init) return SfState::unassigned;
  return s.active ? SfState::active : SfState::reset;
}

SfStatus SfRuntime::finish(ProcessImage& image, SfStatus s) {
  // MB 232 bit 0 = error bit, MB 233 = error number (valid right after this command).
  image.m[232] = static_cast<std::uint8_t>(s.error ? 1 : 0);
  image.m[233] = static_cast<std::uint8_t>(static_cast<int>(s.code));
  status_ = s;
  return s;
}

SfStatus SfRuntime::init(const DataBlock& init_db, ProcessImage& image) {
  auto parsed = InitDb::parse(init_db);
  if (!parsed) return finish(image, {true, parsed.error().code, parsed.error().text});
  Slot& slot = slots_[parsed->number];
  if (slot.active)
    return finish(image, {true, SfError::start_while_active,
                          fmt::format("FB 207 for SF{} while it is active: RESET it first", parsed->number)});
  slot.init = *parsed;
  slot.sf = make_fast_function(parsed->type);
  for (std::size_t k = 0; k < 8; ++k) {
    const auto it = parsed->tables[k] ? dbs_->find(parsed->tables[k]) : dbs_->end();
    slot.tables[k] = it == dbs_->end() ? nullptr : &it->second;
  }
  return finish(image, {});
}

void SfRuntime::refresh_tables(Slot& slot) noexcept {
  for (std::size_t k = 0; k < 8; ++k) {  // a table DB may have been created after FB 207
    const auto it = slot.init->tables[k] ? dbs_->find(slot.init->tables[k]) : dbs_->end();
    slot.tables[k] = it == dbs_->end() ? nullptr : &it->second;
  }
}

SfStatus SfRuntime::command(DataBlock& cmd, ProcessImage& image) {
  SfStatus s = command(static_cast<const DataBlock&>(cmd), image);
  if (read_value_) cmd.set_dd(32, *read_value_);
  return s;
}

SfIo SfRuntime::make_io(Slot& slot, ProcessImage& image, const ProcessImage& snapshot) noexcept {
  const InitDb& in = *slot.init;
  SfIo io(image);
  io.source = read_source(snapshot, links_, in.source);
  io.sink_now = in.sink.address == 255 ? links_[in.number] : read_sink(image, in.sink);
  const int ib = in.in_bit();
  if (ib < 8) {
    const auto& area = in.inputs_from_m ? snapshot.m : snapshot.e;
    io.in = static_cast<std::uint8_t>(area[in.in_byte] >> ib);
  }
  const int ob = in.out_bit();
  io.out_owned = static_cast<std::uint8_t>(ob < 8 ? 0xFFu >> ob : 0u);
  if (ob < 8) {
    const auto& area = in.outputs_to_m ? image.m : image.a;
    io.out = static_cast<std::uint8_t>(area[in.out_byte] >> ob);
  }
  io.cycle_half_ms = id2_ * in.cycle_factor;
  io.tables = &slot.tables;
  io.dbs = dbs_;
  io.fbs = &fbs_;
  io.options = &options_;
  return io;
}

void SfRuntime::apply(Slot& slot, SfIo& io, ProcessImage& image) noexcept {
  const InitDb& in = *slot.init;
  if (io.sink) {
    links_[in.number] = *io.sink;
    write_sink(image, in.sink, *io.sink);
  }
  const int ob = in.out_bit();
  if (ob < 8) {
    auto& area = in.outputs_to_m ? image.m : image.a;
    const auto mask = static_cast<std::uint8_t>(io.out_owned << ob);
    area[in.out_byte] = static_cast<std::uint8_t>((area[in.out_byte] & ~mask) | ((io.out << ob) & mask));
  }
}

SfStatus SfRuntime::command(const DataBlock& cmd, ProcessImage& image) {
  const int n = cmd.dr(0);
  const int code = cmd.dr(1);
  read_value_.reset();
  if (n >= max_sf)
    return finish(image, {true, SfError::start_invalid, fmt::format("FB 208: DR0 SF number = {}: must be 0..15", n)});
  Slot& slot = slots_[static_cast<std::size_t>(n)];
  if (!slot.init)
    return finish(image, {true, SfError::start_invalid,
                          fmt::format("FB 208 for SF{}: the slot is not initialised (FB 207 first)", n)});
  SfIo io = make_io(slot, image, image);
  const bool xfipw = slot.init->type == SfType::xfipw;
  switch (code) {
    case 0:  // RESET: allowed at any time
      if (slot.active && slot.sf) {
        slot.sf->reset(io);
        apply(slot, io, image);
      }
      slot.active = false;
      return finish(image, {});
    case 1: {  // START
      if (slot.active)
        return finish(image, {true, xfipw ? SfError::xfipw_not_reset : SfError::start_while_active,
                              fmt::format("START for SF{} while it is active: RESET it first", n)});
      if (!slot.sf)
        return finish(image, {true, SfError::start_invalid,
                              fmt::format("START for SF{}: SF type {} ({}) is not implemented by hilbridge", n,
                                          static_cast<int>(slot.init->type), to_string(slot.init->type))});
      refresh_tables(slot);
      if (auto f = slot.sf->start(cmd, *slot.init, io))
        return finish(image, {true, f->code, fmt::format("SF{} {}", n, f->text)});
      apply(slot, io, image);
      slot.active = true;
      return finish(image, {});
    }
    case 5:  // VALUE NEW
      if (!slot.active)
        return finish(image, {true, xfipw ? SfError::xfipw_not_started : SfError::value_new_not_active,
                              fmt::format("VALUE NEW for SF{} outside SF-ACTIVE", n)});
      if (auto f = slot.sf->value_new(cmd, io))
        return finish(image, {true, f->code, fmt::format("SF{} {}", n, f->text)});
      return finish(image, {});
    case 6: {  // READ VALUE: XFIPW, only in RESET
      if (!xfipw)
        return finish(
            image, {true, SfError::start_invalid,
                    fmt::format("READ VALUE for SF{}: only XFIPW has it (SF type {})", n, to_string(slot.init->type))});
      if (slot.active)
        return finish(image, {true, SfError::xfipw_not_reset,
                              fmt::format("READ VALUE for SF{} while it is active: RESET it first", n)});
      refresh_tables(slot);
      auto v = slot.sf->read_value(cmd, *slot.init, io);
      if (!v) return finish(image, {true, v.error().code, fmt::format("SF{} {}", n, v.error().text)});
      read_value_ = *v;
      return finish(image, {});
    }
    default:
      return finish(
          image, {true, SfError::start_invalid,
                  fmt::format("FB 208 for SF{}: DR1 code = {}: must be 0 RESET, 1 START, 5 VALUE NEW or 6 READ VALUE",
                              n, code)});
  }
}

void SfRuntime::cycle(ProcessImage& image) noexcept {
  snapshot_ = image;  // process data copied once: every SF sees the same inputs
  for (auto& d : image.aw) d.swq1_written = d.swq2_written = false;
  for (std::size_t n = 0; n < slots_.size(); ++n) {
    Slot& slot = slots_[n];
    if (!slot.active || !slot.sf) continue;
    if (tick_ % slot.init->cycle_factor != 0) continue;
    SfIo io = make_io(slot, image, snapshot_);
    slot.sf->step(io);
    if (io.fault) {  // a running time error: the SF stops, the error stays until commanded again
      slot.active = false;
      (void)finish(image, {true, io.fault->code, fmt::format("SF{} {}", n, io.fault->text)});
      continue;
    }
    apply(slot, io, image);
  }
  ++tick_;
}

std::expected<void, std::string> SfRuntime::load_fb(int number, std::string_view listing) {
  if (number < 0 || number > 63) return std::unexpected(fmt::format("FB {}: the number must be 0..63", number));
  auto p = parse_awl(listing);
  if (!p) return std::unexpected(fmt::format("FB {}: {}", number, p.error()));
  fbs_[number] = std::move(*p);
  return {};
}

bool SfRuntime::owns_output_byte(int byte, bool flag_area) const noexcept {
  for (const auto& s : slots_)
    if (s.init && s.init->out_mask != 0 && s.init->out_byte == byte && s.init->outputs_to_m == flag_area) return true;
  return false;
}

}  // namespace hil::controllers::amkasyn

#include "hil/controllers/amkasyn/sf_types.hpp"

namespace hil::controllers::amkasyn {

std::unique_ptr<FastFunction> make_fast_function(SfType type) {
  switch (type) {
    case SfType::copy:
      return make_copy();
    case SfType::fipw:
      return make_fipw();
    case SfType::fipz:
      return make_fipz();
    case SfType::stdfkt:
      return make_stdfkt();
    case SfType::dfkt:
      return make_dfkt();
    case SfType::fgen:
      return make_fgen();
    case SfType::regl:
      return make_regl();
    case SfType::imes:
      return make_imes();
    case SfType::binea:
      return make_binea();
    case SfType::xfipw:
      return make_xfipw();
    case SfType::epos:
      return make_epos();
    case SfType::apsf:
      return make_apsf();
    case SfType::cam:
      return make_cam();
    default:
      return nullptr;  // not an SF type (InitDb::parse refuses it)
  }
}

}  // namespace hil::controllers::amkasyn
