// SPDX-License-Identifier: MIT
#include "hil/controllers/elg/pc_data_image.hpp"

#include <cmath>

namespace hil::controllers::elg {
namespace {

/// The value as an exact count of 1e-5 units; nullopt with more than five decimals.
std::optional<std::int64_t> e5(const PcValue& v) {
  if (v.decimals > 5) return std::nullopt;
  std::int64_t x = static_cast<std::int64_t>(v.digits);
  for (int i = v.decimals; i < 5; ++i) x *= 10;
  return v.negative ? -x : x;
}

/// A whole number within [lo, hi]; nullopt otherwise.
std::optional<std::int64_t> whole(const PcValue& v, std::int64_t lo, std::int64_t hi) {
  const auto x = e5(v);
  if (!x || *x % Decimal5::scale != 0) return std::nullopt;
  const std::int64_t n = *x / Decimal5::scale;
  if (n < lo || n > hi) return std::nullopt;
  return n;
}

PcValue milli(double units) {
  const auto m = std::llround(units * 1000.0);
  return PcValue{m < 0, 3, static_cast<std::uint64_t>(m < 0 ? -m : m)};
}

}  // namespace

PcDataImage::PcDataImage(Gearbox& gearbox, std::map<int, std::string>& md, std::map<int, std::string>& sd,
                         DatumCheck check, ElgAxisDeclaration axes)
    : gearbox_(gearbox), md_(md), sd_(sd), check_(std::move(check)), declaration_(axes) {}

void PcDataImage::update(const AxisFeedback& axes) {
  axes_ = axes;
  if (input_pending_ && !gearbox_.status().coupled) push_input();
}

PcReply PcDataImage::request(const PcRequest& request) {
  PcReply reply = handle_pc_request(request, *this);
  if (reply.alarm) gearbox_.raise_message(*reply.alarm);  // message only; the transfer is acknowledged
  return reply;
}

std::optional<std::string> PcDataImage::datum(DatumKind kind, int number) const {
  const auto& store = kind == DatumKind::machine_data ? md_ : sd_;
  const auto it = store.find(number);
  if (it == store.end()) return std::nullopt;
  return it->second;
}

std::expected<void, std::string> PcDataImage::store_datum(DatumKind kind, int number, const std::string& value) {
  if (check_)
    if (auto why = check_(kind, number, value)) return std::unexpected(*why);
  (kind == DatumKind::machine_data ? md_ : sd_)[number] = value;
  return {};
}

std::optional<PcValue> PcDataImage::r_parameter(int number) const {
  if (number < 0 || number > 99) return std::nullopt;
  return r_[static_cast<std::size_t>(number)];
}

std::expected<void, std::string> PcDataImage::store_r_parameter(int number, const PcValue& value) {
  if (number < 0 || number > 99) return std::unexpected(std::string("no such R parameter"));
  // The input parameters' ranges (5.1); other R parameters take any value of the channel.
  switch (number) {
    case 20:
      if (!whole(value, -999, 999)) return std::unexpected(std::string("Z0 (R20): a whole number -999..999"));
      break;
    case 21:
      if (!whole(value, 0, 999)) return std::unexpected(std::string("Z2 (R21): a whole number 0..999"));
      break;
    case 40:
      if (!whole(value, 0, 10000)) return std::unexpected(std::string("TOLER (R40): a whole number 0..10000"));
      break;
    case 60:
    case 61: {
      const auto x = e5(value);
      if (!x || std::llabs(*x) > 99999999) return std::unexpected(std::string("Udy/Udz: +-999.99999"));
      break;
    }
    default:
      break;
  }
  r_[static_cast<std::size_t>(number)] = value;
  if (number == 40) {
    // A TOLER below MD 169 is not accepted; the last valid limit stays (5.2). Also while coupled.
    (void)gearbox_.set_tolerance(*whole(value, 0, 10000));
  } else if (number == 20 || number == 21 || number == 60 || number == 61) {
    input_pending_ = true;
    if (!gearbox_.status().coupled) push_input();
  }
  return {};
}

void PcDataImage::push_input() {
  GearInput in;
  in.z0 = static_cast<std::int32_t>(whole(r_[20], -999, 999).value_or(0));
  in.z2 = static_cast<std::int32_t>(whole(r_[21], 0, 999).value_or(0));
  in.ud_y = Decimal5{e5(r_[60]).value_or(0)};
  in.ud_z = Decimal5{e5(r_[61]).value_or(0)};
  if (gearbox_.set_input(in)) input_pending_ = false;
}

std::optional<PcValue> PcDataImage::actual_value(int axis) const {
  if (axis < 1 || axis > 4) return std::nullopt;
  const auto& md = gearbox_.config().md;
  // Input units with three decimals: deg for B and C, mm for Z and Y (MS: 12.1).
  if (axis == declaration_.c)
    return milli(static_cast<double>(axes_.c + gearbox_.status().c_offset) * 90.0 / static_cast<double>(md.n02));
  if (axis == declaration_.b) return milli(static_cast<double>(axes_.b) * 90.0 / static_cast<double>(md.n00));
  if (axis == declaration_.z) return milli(static_cast<double>(axes_.z * md.ms_z_nm) * 1e-6);
  if (axis == declaration_.y) return milli(static_cast<double>(axes_.y * md.ms_y_nm) * 1e-6);
  return std::nullopt;
}

std::vector<int> PcDataImage::alarms() const {
  std::vector<int> out;
  for (Alarm a : gearbox_.alarms()) out.push_back(static_cast<int>(a));
  return out;
}

std::optional<PcValue> PcDataImage::service_datum(int number) const {
  if (number != 8000) return std::nullopt;
  // 8000: drive-axis following error in MS units (0.5 units).
  const std::int64_t fe = axes_.c_following_error;
  return PcValue{fe < 0, 0, static_cast<std::uint64_t>(fe < 0 ? -fe : fe)};
}

}  // namespace hil::controllers::elg
