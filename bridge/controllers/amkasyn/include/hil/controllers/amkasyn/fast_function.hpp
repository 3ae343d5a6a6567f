// SPDX-License-Identifier: MIT
#pragma once
// One fast function (SF) type: START checks and initialises from the commanding DB (FB 208) and
// its tables, step() runs one SF cycle. Pure: everything the SF sees and writes goes through SfIo;
// step() never throws or allocates.

#include <array>
#include <cstdint>
#include <expected>
#include <map>
#include <optional>

#include "hil/controllers/amkasyn/awl.hpp"
#include "hil/controllers/amkasyn/data_block.hpp"
#include "hil/controllers/amkasyn/init_db.hpp"
#include "hil/controllers/amkasyn/process_image.hpp"
#include "hil/controllers/amkasyn/sf_error.hpp"

namespace hil::controllers::amkasyn {

/// The PS data blocks by number (tables live here; FB 207 names them).
using DbStore = std::map<int, DataBlock>;
/// Tab0..Tab7 of one SF (nullptr = not assigned).
using SfTables = std::array<DataBlock*, 8>;

/// Choices where the manual is ambiguous (docs/amkasyn.md "Decisions"); set on the runtime.
struct SfOptions {
  /// FGEN sequence mode: false (default) = a sequence ramps up from rest and ramps down to end at
  /// rest exactly after DD4 increments; true = the literal reading of "all velocity changes use the
  /// ramps, except beginning and end of a sequence": full velocity from the first cycle, a stop
  /// without a ramp at DD4.
  bool fgen_sequence_without_ramps = false;
};

/// One SF cycle's view. `source` comes from the cycle's snapshot (an SF link, address 255, from
/// the producer's sink of this cycle); writes go to `sink` / `out` and are applied after step().
struct SfIo {
  explicit SfIo(ProcessImage& im) noexcept : image(im) {}
  ProcessImage& image;               ///< live image (flag words of overrides, offsets, ...)
  HolderValue source{};              ///< the SF source this cycle
  std::int32_t sink_now = 0;         ///< the sink's current value
  std::optional<std::int32_t> sink;  ///< set to write the sink
  std::uint8_t in = 0;               ///< E1 at bit 0, E2 at bit 1, ...
  std::uint8_t out = 0;              ///< A1 at bit 0, ...; only the bits the SF owns are written
  std::uint8_t out_owned = 0;        ///< which of `out`'s bits the SF drives (default: all it has)
  int cycle_half_ms = 2;             ///< SF cycle in 0.5 ms units (ID 2 x cycle factor)
  const SfTables* tables = nullptr;
  DbStore* dbs = nullptr;        ///< all PS data blocks (APSF's opened DB)
  const FbStore* fbs = nullptr;  ///< the loaded FBs (APSF)
  std::optional<SfFault> fault;  ///< set by step(): a running time error, the SF stops
  const SfOptions* options = nullptr;
  [[nodiscard]] bool e(int k) const noexcept { return ((in >> (k - 1)) & 1) != 0; }  ///< E1..E8
  void a(int k, bool v) noexcept {
    const auto m = static_cast<std::uint8_t>(1u << (k - 1));
    out = v ? static_cast<std::uint8_t>(out | m) : static_cast<std::uint8_t>(out & ~m);
  }
};

class FastFunction {
 public:
  virtual ~FastFunction() = default;
  /// START: check every parameter (errors name the field, the value and the rule) and
  /// initialise. On error the SF stays in RESET.
  virtual std::optional<SfFault> start(const DataBlock& cmd, const InitDb& init, SfIo& io) = 0;
  /// VALUE NEW (only in SF-ACTIVE): take over the parameters the SF allows.
  virtual std::optional<SfFault> value_new(const DataBlock& cmd, SfIo& io);
  /// READ VALUE (code 6, only XFIPW, in RESET): the value for DD32 of the commanding DB,
  /// computed with the same DB assignment as START.
  virtual std::expected<std::int32_t, SfFault> read_value(const DataBlock& cmd, const InitDb& init, SfIo& io);
  /// One SF cycle.
  virtual void step(SfIo& io) noexcept = 0;
  /// RESET: back to the basic state (e.g. DFKT stops the axis).
  virtual void reset(SfIo& io) noexcept;
};

/// "field = value: rule" START error.
[[nodiscard]] SfFault start_error(const char* sf, const char* field, long long value, const char* rule);

}  // namespace hil::controllers::amkasyn
