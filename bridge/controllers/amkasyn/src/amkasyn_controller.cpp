// SPDX-License-Identifier: MIT
// The AMKASYN SF runtime on the controller runtime: image mapping, commanding, axes. See
// amkasyn_controller.hpp; the factory (options, files) is in amkasyn_setup.cpp.
#include "hil/controllers/amkasyn/amkasyn_controller.hpp"

#include <fmt/format.h>

#include <cmath>
#include <cstdlib>

#include "hil/controllers/amkasyn/awl.hpp"
#include "hil/controllers/io_address_s5.hpp"

namespace hil::controllers::amkasyn {
namespace {

constexpr std::uint32_t image_bytes = 256;
constexpr std::uint32_t data_bytes = AmkasynController::plc_flags_base + image_bytes + 1;  // + the zero pulses

}  // namespace

AmkasynController::AmkasynController(std::shared_ptr<const profiles::Profile> profile, AmkasynSetup setup,
                                     std::vector<ControllerAxis> axes)
    : Controller(profile, setup.sfs.empty() ? profiles::ParameterSet{} : setup.sfs.front().parameters,
                 IoLayout{{image_bytes, image_bytes, image_bytes, data_bytes}},
                 std::chrono::microseconds(500) * setup.id2_half_ms),
      setup_(std::move(setup)),
      runtime_(setup_.id2_half_ms, setup_.tables) {
  for (auto& a : axes) add_axis(std::move(a));
  sf_status_ = catalogue("sf_status");
  dfkt_catalogue_ = catalogue("dfkt_status");
  flag_owned_[232] = flag_owned_[233] = true;
  for (int k = 0; k < 4; ++k)
    if (setup_.az[static_cast<std::size_t>(k)]) (void)io().name_bit(fmt::format("az{}_zero", k + 1), zero_pulse_bit(k));
  for (const auto& [number, listing] : setup_.fbs) {
    (void)runtime_.load_fb(number, listing);  // the factory parsed it
    // The flag bytes an APSF function block writes are the SF's, like an SF's M sink: the PLC's
    // flag image does not overwrite them (its MD24 must survive from one SF cycle to the next).
    const auto program = parse_awl(listing);
    if (!program) continue;
    using Op = AwlInstruction::Op;
    for (const auto& ins : program->code) {
      const bool writes = ins.op == Op::transfer || ins.op == Op::assign || ins.op == Op::set || ins.op == Op::reset;
      if (!writes || ins.area != AwlArea::m) continue;
      for (int k = 0; k < std::max(1, ins.width / 8); ++k)
        flag_owned_[static_cast<std::size_t>(ins.address + k) & 0xFF] = true;
    }
  }
  for (const auto& sf : setup_.sfs) {
    // FB 207 at power-up; the factory checked that each init DB is accepted.
    (void)runtime_.init(sf.db.init, image_);
    const auto init = InitDb::parse(sf.db.init);
    if (!init) continue;
    const int n = init->number;
    (void)io().name_bit(fmt::format("sf{}_start", n), command_bit(n, 0));
    (void)io().name_bit(fmt::format("sf{}_reset", n), command_bit(n, 1));
    (void)io().name_bit(fmt::format("sf{}_value_new", n), command_bit(n, 2));
    (void)io().name_bit(fmt::format("sf{}_read_value", n), command_bit(n, 3));
    (void)io().name_bit(fmt::format("sf{}_active", n), command_bit(n, 4));
    (void)io().name_bit(fmt::format("sf{}_error", n), command_bit(n, 5));
    if (init->outputs_to_m && init->out_mask != 0) flag_owned_[init->out_byte] = true;
    const auto& s = init->sink;
    if (s.address == 128 || s.address == 129)
      for (int k = 0; k < (s.address == 128 ? 2 : 4); ++k) flag_owned_[(s.offset + k) & 0xFF] = true;
    if (s.address == 64 && std::find(aa_used_.begin(), aa_used_.end(), s.offset) == aa_used_.end())
      aa_used_.push_back(s.offset);
  }
  std::sort(aa_used_.begin(), aa_used_.end());
}

std::expected<BitAddress, std::string> AmkasynController::resolve_bit(std::string_view text) const {
  if (auto named = io().find_bit(text)) return *named;
  auto a = parse_s5_address(text);
  if (!a) {
    return std::unexpected(
        fmt::format("'{}' is neither a signal of the amkasyn-sf controller nor a PS address "
                    "E n.b / A n.b / M n.b ({})",
                    text, a.error()));
  }
  if (a->operand == S5Operand::marker_bit && !flag_owned_[a->index & 0xFF])
    return BitAddress{IoArea::data, plc_flags_base + a->index, a->bit};  // the PLC's flag write
  auto bit = to_bit_address(*a);
  if (!bit) return std::unexpected(fmt::format("'{}': {}", text, bit.error()));
  return *bit;
}

std::vector<std::string> AmkasynController::trace_signals() const {
  std::vector<std::string> names;
  for (int k : aa_used_) names.push_back(fmt::format("AA{}_mV", k + 1));
  return names;
}

double AmkasynController::trace_value(std::size_t i) const noexcept {
  if (i >= aa_used_.size()) return 0.0;
  return static_cast<double>(image_.analog_out[static_cast<std::size_t>(aa_used_[i])]);
}

void AmkasynController::command(int sf, int code, TimePoint now) noexcept {
  const SfFile* file = nullptr;
  for (const auto& f : setup_.sfs)
    if (f.db.init.dl(0) == sf) file = &f;
  if (file == nullptr) return;
  DataBlock db = code == 5 && file->value_new ? *file->value_new : file->db.command;
  db.set_dr(1, static_cast<std::uint8_t>(code));
  SfStatus s;
  try {
    s = runtime_.command(db, image_);
  } catch (...) {  // allocation of the error text: report the command as refused
    s = SfStatus{true, SfError::start_invalid, "out of memory"};
  }
  io().set(command_bit(sf, 5), s.error);
  if (s.error && sf_status_ != nullptr)
    raise(*sf_status_, static_cast<int>(s.code), now, axis_of(*file), fmt::format("{} ({})", s.text, file->file));
}

int AmkasynController::axis_of(const SfFile& file) const noexcept {
  // An SF's error concerns the drive it writes, else the one it reads, else the whole PS.
  const auto init = InitDb::parse(file.db.init);
  if (!init) return -1;
  for (const Holder h : {init->sink, init->source})
    if (h.address >= 1 && h.address <= 8 && setup_.aw[h.address - 1u])
      return static_cast<int>(setup_.aw[h.address - 1u]->axis);
  return -1;
}

void AmkasynController::report_dfkt_status(TimePoint now) noexcept {
  if (dfkt_catalogue_ == nullptr) return;
  for (const auto& f : setup_.sfs) {
    if (f.db.init.dr(0) != static_cast<int>(SfType::dfkt)) continue;
    const int db = f.db.init.dl(9);  // Tab7: the output table
    const auto it = db != 0 ? setup_.tables.find(db) : setup_.tables.end();
    if (it == setup_.tables.end()) continue;
    const int n = f.db.init.dl(0) & 15;
    const auto status = static_cast<std::uint16_t>(it->second.uw(1) & 0x3F);
    auto& last = dfkt_status_[static_cast<std::size_t>(n)];
    if (status == last) continue;
    const int on_axis = axis_of(f);
    for (int bit = 0; bit < 6; ++bit) {
      const int mask = 1 << bit;
      if ((status & mask) != 0 && (last & mask) == 0)
        raise(*dfkt_catalogue_, mask, now, on_axis, fmt::format("SF{} DFKT, Tab7 = DB{} DW1 bit {}", n, db, bit));
      else if ((status & mask) == 0 && (last & mask) != 0)
        (void)clear_error(*dfkt_catalogue_, mask, on_axis);
    }
    last = status;
  }
}

void AmkasynController::read_image(Duration since_first_cycle) noexcept {
  const auto in = io().bytes(IoArea::input);
  std::copy(in.begin(), in.end(), image_.e.begin());
  const auto data = io().bytes(IoArea::data);
  for (std::size_t n = 0; n < image_bytes; ++n)
    if (!flag_owned_[n]) image_.m[n] = data[plc_flags_base + n];
  for (std::size_t k = 0; k < 8; ++k) {
    const auto& ch = setup_.aw[k];
    if (!ch) continue;
    const auto& st = axis(ch->axis).status();
    auto& d = image_.aw[k];
    d.position_feedback = static_cast<std::int32_t>(static_cast<std::uint32_t>(st.position_inc));
    // The analog input A1 (Config-AW message16), the word the scenario holds at this cycle.
    d.message16 = static_cast<std::int16_t>(analog_word_at(setup_.aw_message16[k], since_first_cycle));
    const double to_rpm4 = 600000.0 / static_cast<double>(setup_.resolution);  // inc/s -> 0.0001 rpm
    switch (ch->message32) {
      case 36:
        d.message32 = static_cast<std::int32_t>(std::llround(st.command_velocity * to_rpm4));
        break;
      case 40:
        d.message32 = static_cast<std::int32_t>(std::llround(st.velocity * to_rpm4));
        break;
      case 32824:
        d.message32 = static_cast<std::int32_t>(std::llround(st.following_error));
        break;
      default:
        d.message32 = d.position_feedback;
        break;
    }
  }
  for (std::size_t k = 0; k < 4; ++k) {
    const auto& ch = setup_.az[k];
    if (!ch) continue;
    const auto count = static_cast<std::uint32_t>(axis(ch->axis).status().position_inc);
    image_.az[k] = static_cast<std::int32_t>(ch->high_word ? count << 16 : count);
    // The zero-pulse input (a printing mark sensor, the encoder's reference mark): a rising edge
    // latches the 32-bit counter of this cycle.
    if (io().rising(zero_pulse_bit(static_cast<int>(k)))) image_.az_zero[k].pulse(static_cast<std::int32_t>(count));
  }
}

void AmkasynController::write_image() noexcept {
  for (std::uint32_t n = 0; n < image_bytes; ++n) {
    io().set(ByteAddress{IoArea::output, n}, image_.a[n]);
    io().set(ByteAddress{IoArea::marker, n}, image_.m[n]);
  }
  for (const auto& f : setup_.sfs) {
    const int n = f.db.init.dl(0);
    io().set(command_bit(n, 4), runtime_.state(n) == SfState::active);
  }
}

void AmkasynController::drive_axes(double dt_s) noexcept {
  for (std::size_t k = 0; k < 8; ++k) {
    const auto& ch = setup_.aw[k];
    if (!ch) continue;
    motion::Axis& ax = axis(ch->axis);
    AxisDrive& d = drives_[k];
    const DriveChannels& c = image_.aw[k];
    const std::int32_t channel = ch->mode == AwMode::swq1_position ? c.swq1 : c.swq2;
    if (!d.ready) continue;
    std::int64_t delta = 0;
    double velocity = 0.0;
    switch (ch->mode) {
      case AwMode::swq1_position: {
        // The drive's synchronous ratio ID 32893 / ID 32892 on each 16-bit difference, exact (the
        // remainder is carried: no drift).
        const std::int64_t num =
            static_cast<std::int16_t>(static_cast<std::uint16_t>(channel - d.last_channel)) * ch->ratio_mul +
            d.speed_rest;
        delta = num / ch->ratio_div;
        d.speed_rest = num % ch->ratio_div;
        velocity = static_cast<double>(delta) / dt_s;
        break;
      }
      case AwMode::swq2_position:
        delta =
            static_cast<std::int32_t>(static_cast<std::uint32_t>(channel) - static_cast<std::uint32_t>(d.last_channel));
        velocity = static_cast<double>(delta) / dt_s;
        break;
      case AwMode::swq2_speed: {
        // inc per cycle = n[0.0001 rpm] * res / (60 * 10^4) * dt; exact with the rest carried.
        const std::int64_t den = 600000LL * 2000LL;  // dt = id2 x 0.5 ms = id2 / 2000 s
        const std::int64_t num =
            static_cast<std::int64_t>(channel) * setup_.resolution * setup_.id2_half_ms + d.speed_rest;
        delta = num / den;
        d.speed_rest = num % den;
        velocity = static_cast<double>(channel) * static_cast<double>(setup_.resolution) / 600000.0;
        break;
      }
    }
    d.last_channel = channel;
    d.target_inc += delta;
    if (delta != 0 || velocity != 0.0) {
      d.resting = 0;
      d.following = !ax.follow(d.target_inc, velocity, 0.0);
    } else if (d.following) {
      // The set-point rests: one cycle at velocity 0, then end the coupled state (the axis
      // settles in position like after any move, and the run can end).
      if (++d.resting >= 2) {
        (void)ax.stop();
        d.following = false;
      } else {
        (void)ax.follow(d.target_inc, 0.0, 0.0);
      }
    }
  }
}

void AmkasynController::on_cycle(const CycleTime& cycle) noexcept {
  // Power-up: the PS enables its drives (controller enable), then the SFs are commanded.
  const bool ready = power_up_axes();
  if (!first_cycle_) first_cycle_ = cycle.now;
  read_image(cycle.now - *first_cycle_);
  if (!started_ && ready) {
    // The drives are enabled: from here on their set-points follow the SF channels, from the
    // values the channels have now (before the START of `start: auto`, so its set-point counts).
    for (std::size_t k = 0; k < 8; ++k) {
      if (!setup_.aw[k]) continue;
      const DriveChannels& c = image_.aw[k];
      drives_[k].ready = true;
      drives_[k].target_inc = axis(setup_.aw[k]->axis).status().command_inc;
      drives_[k].last_channel = setup_.aw[k]->mode == AwMode::swq1_position ? c.swq1 : c.swq2;
    }
    started_ = true;
    if (setup_.auto_start)
      for (const auto& f : setup_.sfs) command(f.db.init.dl(0), f.db.command.dr(1), cycle.now);
  }
  // The PLC's FB 208 calls: the file's commanding DB with the code of the bit's edge.
  for (const auto& f : setup_.sfs) {
    const int n = f.db.init.dl(0);
    if (io().rising(command_bit(n, 1))) command(n, 0, cycle.now);
    if (io().rising(command_bit(n, 0))) command(n, 1, cycle.now);
    if (io().rising(command_bit(n, 2))) command(n, 5, cycle.now);
    if (io().rising(command_bit(n, 3))) command(n, 6, cycle.now);
  }
  runtime_.cycle(image_);
  report_dfkt_status(cycle.now);
  if (ready) drive_axes(to_seconds(cycle_period()));
  write_image();
}

}  // namespace hil::controllers::amkasyn
