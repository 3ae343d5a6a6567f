// SPDX-License-Identifier: MIT
// SF APSF (type 10, manual §3.11): runs a user AWL function block (the subset of awl.hpp) every SF
// cycle. SF-PAE at the start of the FB: ED 212 = the SF source (16-bit sources zero-extended: the
// FB sign-extends differences with WWD, as the manual's example does), EB 216 = the SF's input
// byte, EB 217 = the commanding code for one SF cycle after a command (1 START, 0 RESET), else
// 255; AD 212 = the sink's current value, AB 216 = the SF's output byte. SF-PAA at the end:
// AD 212 -> the sink, bits mask..mask+n-1 of AB 216 -> the output byte (n = DW6).
// These six bytes are the SF's own (an overlay): the PLC's E/A bytes 212..217 are not touched;
// every other E/A/M byte, and the DB opened by DW5 (or "A DB n"), are the PS's.
// RESET runs the FB once more with EB 217 = 0 (so it can stop its axis) and applies its outputs.
// A forbidden command refuses START (SF error 6, all of them listed); more than `budget`
// statements in one cycle or a failed DB access is a running time error: the SF stops (RESET
// state) with error 6 in MB 232/233.
#include <fmt/format.h>

#include "hil/controllers/amkasyn/sf_types.hpp"

namespace hil::controllers::amkasyn {
namespace {

constexpr int apsf_budget = 10000;  ///< statements per SF cycle (the original: ~5 us each)

class Overlay final : public AwlMemory {
 public:
  Overlay(ProcessImage& im, DbStore* dbs, std::array<std::uint8_t, 6>& e, std::array<std::uint8_t, 5>& a) noexcept
      : im_(im), dbs_(dbs), e_(e), a_(a) {}
  std::uint8_t byte(AwlArea area, int n) const noexcept override {
    n &= 0xFF;
    if (area == AwlArea::e)
      return n >= 212 && n <= 217 ? e_[static_cast<std::size_t>(n - 212)] : im_.e[static_cast<std::size_t>(n)];
    if (area == AwlArea::a)
      return n >= 212 && n <= 216 ? a_[static_cast<std::size_t>(n - 212)] : im_.a[static_cast<std::size_t>(n)];
    return im_.m[static_cast<std::size_t>(n)];
  }
  void set_byte(AwlArea area, int n, std::uint8_t v) noexcept override {
    n &= 0xFF;
    if (area == AwlArea::e) {
      (n >= 212 && n <= 217 ? e_[static_cast<std::size_t>(n - 212)] : im_.e[static_cast<std::size_t>(n)]) = v;
    } else if (area == AwlArea::a) {
      (n >= 212 && n <= 216 ? a_[static_cast<std::size_t>(n - 212)] : im_.a[static_cast<std::size_t>(n)]) = v;
    } else {
      im_.m[static_cast<std::size_t>(n)] = v;
    }
  }
  bool db_word(int db, int n, std::uint16_t& v) const noexcept override {
    const DataBlock* d = find(db);
    if (!d || n < 0 || static_cast<std::size_t>(n) >= d->size()) return false;
    v = d->uw(static_cast<std::size_t>(n));
    return true;
  }
  bool set_db_word(int db, int n, std::uint16_t v) noexcept override {
    DataBlock* d = find(db);
    if (!d || n < 0 || static_cast<std::size_t>(n) >= d->size()) return false;
    d->set_dw(static_cast<std::size_t>(n), v);  // within the block: no growth, no allocation
    return true;
  }

 private:
  DataBlock* find(int db) const noexcept {
    if (!dbs_ || db <= 0) return nullptr;
    const auto it = dbs_->find(db);
    return it == dbs_->end() ? nullptr : &it->second;
  }
  ProcessImage& im_;
  DbStore* dbs_;
  std::array<std::uint8_t, 6>& e_;
  std::array<std::uint8_t, 5>& a_;
};

class Apsf final : public FastFunction {
 public:
  std::optional<SfFault> start(const DataBlock& cmd, const InitDb& init, SfIo& io) override {
    if (cmd.dl(0) != 0) return start_error("APSF", "DL0 fct", cmd.dl(0), "must be 0");
    if (cmd.dl(1) != 0) return start_error("APSF", "DL1 BA", cmd.dl(1), "must be 0");
    if (cmd.dw(3) < 0 || cmd.dw(3) > 131) return start_error("APSF", "DW3 SF cycle time", cmd.dw(3), "0 (not used)");
    const int fb = cmd.dw(4), db = cmd.dw(5), n = cmd.dw(6);
    if (fb < 0 || fb > 63) return start_error("APSF", "DW4 FB number", fb, "0..63");
    if (db < 0 || db > 63) return start_error("APSF", "DW5 DB number", db, "0 (none) or 1..63");
    if (n < 0 || n > 8) return start_error("APSF", "DW6 number of output bits", n, "0..8");
    if (n > 0 && init.out_mask == 0)
      return start_error("APSF", "DW6 number of output bits", n, "needs an output bit mask (FB 207 DR5)");
    if (n > 8 - init.out_bit() && n > 0)
      return start_error("APSF", "DW6 number of output bits", n,
                         "the bits from the mask's bit on must fit in the byte");
    const auto it = io.fbs ? io.fbs->find(fb) : FbStore::const_iterator{};
    if (!io.fbs || it == io.fbs->end())
      return start_error("APSF", "DW4 FB number", fb, "the FB is not loaded (SfRuntime::load_fb)");
    if (!it->second.forbidden.empty()) {
      std::string list;
      for (const auto& f : it->second.forbidden) list += (list.empty() ? "" : "; ") + f;
      return SfFault{
          SfError::apsf_runtime,
          fmt::format("APSF: FB{} uses forbidden commands (timers, block calls, E DB, STP, STS): {}", fb, list)};
    }
    if (db != 0 && (!io.dbs || !io.dbs->contains(db)))
      return start_error("APSF", "DW5 DB number", db, "the DB does not exist");
    program_ = it->second;  // a copy: the FB of a started SF does not change
    db_ = db;
    bits_ = n;
    init_ = init;
    code_ = 1;  // EB 217 shows START in the first cycle
    return std::nullopt;
  }

  void step(SfIo& io) noexcept override {
    run(io, code_);
    code_ = 255;
  }

  void reset(SfIo& io) noexcept override { run(io, 0); }

 private:
  void run(SfIo& io, int code) noexcept {
    std::array<std::uint8_t, 6> e{};
    std::array<std::uint8_t, 5> a{};
    const auto put = [](auto& area, std::size_t at, std::uint32_t v) {
      for (std::size_t k = 0; k < 4; ++k) area[at + k] = static_cast<std::uint8_t>(v >> (8 * (3 - k)));
    };
    const std::uint32_t src =
        io.source.wide ? static_cast<std::uint32_t>(io.source.value) : static_cast<std::uint16_t>(io.source.value);
    put(e, 0, src);                                                                             // ED 212
    e[4] = init_.in_mask ? (init_.inputs_from_m ? io.image.m : io.image.e)[init_.in_byte] : 0;  // EB 216
    e[5] = static_cast<std::uint8_t>(code);                                                     // EB 217
    put(a, 0, static_cast<std::uint32_t>(io.sink_now));                                         // AD 212
    const int ob = init_.out_bit();
    a[4] = ob < 8 ? (init_.outputs_to_m ? io.image.m : io.image.a)[init_.out_byte] : 0;  // AB 216
    Overlay mem(io.image, io.dbs, e, a);
    const AwlRun r = run_awl(program_, mem, db_, apsf_budget);
    if (!r.ok) {
      io.fault = SfFault{SfError::apsf_runtime, "APSF running time error: " + r.error};
      return;
    }
    io.sink =
        static_cast<std::int32_t>((static_cast<std::uint32_t>(a[0]) << 24) | (static_cast<std::uint32_t>(a[1]) << 16) |
                                  (static_cast<std::uint32_t>(a[2]) << 8) | a[3]);
    if (ob < 8) {
      io.out = static_cast<std::uint8_t>(a[4] >> ob);
      io.out_owned = static_cast<std::uint8_t>((1u << bits_) - 1u);
    }
  }

  AwlProgram program_;
  InitDb init_{};
  int db_ = 0, bits_ = 0, code_ = 255;
};

}  // namespace

std::unique_ptr<FastFunction> make_apsf() {
  return std::make_unique<Apsf>();
}

}  // namespace hil::controllers::amkasyn
