// SPDX-License-Identifier: MIT
#include "hil/runtime/program.hpp"

#include <cmath>
#include <expected>

#include <fmt/format.h>

#include "axis_checks.hpp"
#include "hil/runtime/scenario_loader.hpp"
#include "overloaded.hpp"

namespace hil::runtime {

namespace {

/// The operand's value as the PLC reads it (double word: signed 32-bit; bit: 0/1).
std::expected<std::int64_t, std::string> read_plc(const controllers::Controller& c, const PlcOperand& o) {
  const auto w = c.read_data_word(o.db, o.dw);
  if (!w) return std::unexpected(w.error());
  switch (o.kind) {
    case PlcOperand::Kind::word:
      return *w;
    case PlcOperand::Kind::double_word: {
      const auto lo = c.read_data_word(o.db, o.dw + 1);
      if (!lo) return std::unexpected(lo.error());
      return static_cast<std::int32_t>((static_cast<std::uint32_t>(*w) << 16) | *lo);
    }
    case PlcOperand::Kind::bit:
      return (*w >> o.bit) & 1;
    case PlcOperand::Kind::left_byte:
      return *w >> 8;
    case PlcOperand::Kind::right_byte:
      return *w & 0xFF;
  }
  return 0;
}

/// Writes the operand (bits and bytes read-modify-write their data word).
std::expected<void, std::string> write_plc(controllers::Controller& c, const PlcOperand& o, std::int64_t value) {
  const auto w = c.read_data_word(o.db, o.dw);
  if (!w) return std::unexpected(w.error());
  std::uint16_t word = *w;
  switch (o.kind) {
    case PlcOperand::Kind::word:
      word = static_cast<std::uint16_t>(value);
      break;
    case PlcOperand::Kind::double_word: {
      const auto u = static_cast<std::uint32_t>(static_cast<std::int32_t>(value));
      if (auto r = c.write_data_word(o.db, o.dw + 1, static_cast<std::uint16_t>(u & 0xFFFF)); !r) return r;
      word = static_cast<std::uint16_t>(u >> 16);
      break;
    }
    case PlcOperand::Kind::bit:
      word = static_cast<std::uint16_t>(value != 0 ? (word | (1U << o.bit)) : (word & ~(1U << o.bit)));
      break;
    case PlcOperand::Kind::left_byte:
      word = static_cast<std::uint16_t>((word & 0x00FF) | ((value & 0xFF) << 8));
      break;
    case PlcOperand::Kind::right_byte:
      word = static_cast<std::uint16_t>((word & 0xFF00) | (value & 0xFF));
      break;
  }
  return c.write_data_word(o.db, o.dw, word);
}

std::string plc_text(const PlcOperand& o, std::int64_t v) {
  switch (o.kind) {
    case PlcOperand::Kind::word:
      return fmt::format("DB{} DW{} = {:04X}h", o.db, o.dw, v);
    case PlcOperand::Kind::double_word:
      return fmt::format("DB{} DD{} = {}", o.db, o.dw, v);
    case PlcOperand::Kind::bit:
      return fmt::format("DB{} D {}.{} = {}", o.db, o.dw, o.bit, v);
    case PlcOperand::Kind::left_byte:
      return fmt::format("DB{} DL{} = {:02X}h", o.db, o.dw, v);
    case PlcOperand::Kind::right_byte:
      return fmt::format("DB{} DR{} = {:02X}h", o.db, o.dw, v);
  }
  return {};
}

}  // namespace
namespace {

using detail::Overloaded;

motion::Direction to_motion(MoveDirection d) {
  switch (d) {
    case MoveDirection::positive:
      return motion::Direction::positive;
    case MoveDirection::negative:
      return motion::Direction::negative;
    case MoveDirection::shortest:
      break;
  }
  return motion::Direction::shortest;
}

std::optional<motion::Limits> limits_for(const motion::Axis& a, const MoveLimits& m) {
  if (!m.velocity && !m.acceleration && !m.jerk) return std::nullopt;
  motion::Limits l = a.config().limits;
  if (m.velocity) l.velocity = *m.velocity;
  if (m.acceleration) l.acceleration = *m.acceleration;
  if (m.jerk) l.jerk = *m.jerk > 0.0 ? *m.jerk : std::numeric_limits<double>::infinity();
  return l;
}

using detail::at_rest;
using detail::fault_matches;

}  // namespace

Program::Program(const Scenario& scenario, Machine& machine) : scenario_(scenario), machine_(machine) {}

motion::Axis& Program::axis(const std::string& name) {
  return *machine_.find(name)->axis;
}

std::optional<ConfigError> Program::check() const {
  std::optional<ConfigError> err;
  auto visit = [&](const auto& self, const Step& s) -> void {
    if (err) return;
    if (const auto* p = std::get_if<ParallelStep>(&s.action)) {
      for (const auto& c : p->steps) self(self, c);
      return;
    }
    if (const auto* p = std::get_if<PlcStep>(&s.action)) {
      // The operand must exist (and be writable for a write) before the run; a write is tried
      // with the value the word has now, which leaves the image as it is.
      auto* c = machine_.controller();
      if (c == nullptr) return;
      std::expected<void, std::string> ok;
      if (auto v = read_plc(*c, p->operand); !v) {
        ok = std::unexpected(v.error());
      } else if (p->action == PlcStep::Action::write) {
        ok = write_plc(*c, p->operand, *v);
      }
      if (!ok) err = ConfigError{scenario_.file, s.source.line, 0, s.source.path + ".plc", ok.error()};
      return;
    }
    const auto* i = std::get_if<InjectFaultStep>(&s.action);
    if (!i) return;
    MachineAxis* a = machine_.find(i->axis);
    if (!a->injectable) {
      err = ConfigError{scenario_.file, s.source.line, 0, s.source.path + ".inject_fault",
                        fmt::format("axis '{}' runs on transport '{}', whose drive does not support fault injection "
                                    "(only mock-backed drives do)",
                                    i->axis, a->transport)};
      return;
    }
    const auto names = a->injectable->injectable_faults();
    for (const auto& n : names)
      if (n == i->fault) return;
    std::string list;
    for (const auto& n : names) list += (list.empty() ? "" : ", ") + n;
    err = ConfigError{scenario_.file, s.source.line, 0, s.source.path + ".inject_fault.fault",
                      fmt::format("the drive of axis '{}' has no fault '{}'; it accepts: {}", i->axis, i->fault, list)};
  };
  for (const auto& s : scenario_.program) visit(visit, s);
  return err;
}

void Program::fail(const Step& s, Duration t, const std::string& what) {
  if (status_ == Status::failed) return;
  status_ = Status::failed;
  error_ = fmt::format("t={:.3f} s: {}:{} {} ({}): {}", to_seconds(t), scenario_.file, s.source.line, s.source.path,
                       s.name, what);
}

bool Program::launch(Running& r, Duration t) {
  const Step& s = *r.step;
  r.started = t;
  r.launched = true;
  auto check = [&](const std::string& name, std::error_code ec) {
    if (!ec) return true;
    const auto& st = axis(name).status();
    fail(s, t,
         fmt::format("axis {} rejected the command: {} (axis state {}{})", name, ec.message(),
                     motion::to_string(st.state), st.fault ? ", " + st.fault.describe() : ""));
    return false;
  };
  auto each = [&](const std::vector<std::string>& axes, auto&& fn) {
    for (const auto& n : axes)
      if (!check(n, fn(axis(n)))) return false;
    return true;
  };
  return std::visit(
      Overloaded{
          [&](const EnableStep& e) { return each(e.axes, [](motion::Axis& a) { return a.enable(); }); },
          [&](const DisableStep& e) { return each(e.axes, [](motion::Axis& a) { return a.disable(); }); },
          [&](const ResetStep& e) { return each(e.axes, [](motion::Axis& a) { return a.reset(); }); },
          [&](const HomeStep& e) { return each(e.axes, [](motion::Axis& a) { return a.home(); }); },
          [&](const StopStep& e) { return each(e.axes, [](motion::Axis& a) { return a.stop(); }); },
          [&](const QuickStopStep& e) { return each(e.axes, [](motion::Axis& a) { return a.quick_stop(); }); },
          [&](const MoveAbsoluteStep& m) {
            auto& a = axis(m.axis);
            return check(m.axis, a.move_absolute(m.position, to_motion(m.direction.value_or(MoveDirection::shortest)),
                                                 limits_for(a, m.limits)));
          },
          [&](const MoveRelativeStep& m) {
            auto& a = axis(m.axis);
            return check(m.axis, a.move_relative(m.distance, limits_for(a, m.limits)));
          },
          [&](const MoveVelocityStep& m) {
            auto& a = axis(m.axis);
            return check(m.axis, a.move_velocity(m.velocity, limits_for(a, m.limits)));
          },
          [&](const JogStep& j) { return check(j.axis, axis(j.axis).jog(j.positive ? 1 : -1)); },
          [&](const InjectFaultStep& i) {
            MachineAxis* a = machine_.find(i.axis);
            if (!a->injectable || !a->injectable->inject_fault(i.fault, i.active)) {
              fail(s, t, fmt::format("the drive of axis {} refused fault '{}'", i.axis, i.fault));
              return false;
            }
            return true;
          },
          [&](const ParallelStep& p) {
            r.children.clear();
            for (const auto& c : p.steps) r.children.push_back(Running{&c, t, false, false, {}});
            for (auto& child : r.children) {  // launch the children in this very cycle
              const Check cc = poll(child, t);
              if (cc == Check::failed) return false;
              if (cc == Check::done) child.step = nullptr;
            }
            return true;
          },
          [&](const CoupleStep& c) {
            const std::string e = machine_.couplings().command(c, machine_.axes());
            if (!e.empty()) fail(s, t, e);
            return e.empty();
          },
          [](const AcknowledgeStep&) { return true; },  // given at the controller's next cycle (poll)
          [&](const PlcStep& p) {
            auto* c = machine_.controller();
            if (p.action == PlcStep::Action::write) {
              if (auto w = write_plc(*c, p.operand, p.value); !w) {
                fail(s, t, w.error());
                return false;
              }
              r.issued = true;
            } else if (p.action == PlcStep::Action::expect) {
              const auto v = read_plc(*c, p.operand);
              if (!v || *v != p.value) {
                fail(s, t,
                     v ? fmt::format("expected {}, the device shows {}", plc_text(p.operand, p.value),
                                     plc_text(p.operand, *v))
                       : v.error());
                return false;
              }
            }
            return true;
          },
          [](const auto&) { return true; },  // waits start nothing
      },
      s.action);
}

Program::Check Program::poll(Running& r, Duration t) {
  const Step& s = *r.step;
  if (!r.launched) {
    if (s.at && t < *s.at) return Check::pending;
    if (!launch(r, t)) return Check::failed;
    if (!s.wait && !std::holds_alternative<ParallelStep>(s.action)) return Check::done;
    if (std::holds_alternative<InjectFaultStep>(s.action)) return Check::done;
    if (const auto* p = std::get_if<PlcStep>(&s.action); p && p->action == PlcStep::Action::expect)
      return Check::done;   // checked at once
    return Check::pending;  // a command takes effect at the next update: judge it from then on
  }
  const Duration timeout = s.timeout.value_or(scenario_.timeout);
  auto faulted = [&](const std::string& name) {
    const auto& st = axis(name).status();
    if (st.state != motion::AxisState::error) return false;
    fail(s, t, fmt::format("axis {} faulted: {}", name, st.fault.describe()));
    return true;
  };
  auto all = [&](const std::vector<std::string>& axes, auto&& done) {
    bool ok = true;
    for (const auto& n : axes) {
      if (faulted(n)) return Check::failed;
      ok = ok && done(axis(n).status());
    }
    return ok ? Check::done : Check::pending;
  };
  using hil::DriveState;
  using motion::AxisState;
  Check c = std::visit(
      Overloaded{
          [&](const EnableStep& e) {
            return all(e.axes, [](const motion::AxisStatus& st) {
              return st.state != AxisState::enabling && st.state != AxisState::disabled;
            });
          },
          [&](const DisableStep& e) {
            return all(e.axes, [](const motion::AxisStatus& st) { return st.state == AxisState::disabled; });
          },
          [&](const ResetStep& e) {
            // Done when the axis left error and its drive acknowledged the reset (a drive still in
            // fault would refuse the enable that usually follows).
            for (const auto& n : e.axes) {
              auto& a = axis(n);
              const auto ds = a.drive().feedback().state;
              if (a.status().state == AxisState::error || ds == DriveState::fault ||
                  ds == DriveState::fault_reaction_active)
                return Check::pending;
            }
            return Check::done;
          },
          [&](const HomeStep& e) {
            return all(e.axes, [](const motion::AxisStatus& st) { return at_rest(st) && st.referenced; });
          },
          [&](const StopStep& e) { return all(e.axes, at_rest); },
          [&](const QuickStopStep& e) { return all(e.axes, at_rest); },
          [&](const MoveAbsoluteStep& m) {
            return all({m.axis}, [](const motion::AxisStatus& st) { return at_rest(st) && st.in_position; });
          },
          [&](const MoveRelativeStep& m) {
            return all({m.axis}, [](const motion::AxisStatus& st) { return at_rest(st) && st.in_position; });
          },
          [&](const MoveVelocityStep& m) {
            const double v = m.velocity;
            return all({m.axis}, [v](const motion::AxisStatus& st) {
              return std::abs(st.command_velocity - v) <= 1e-9 * std::max(1.0, std::abs(v)) || !st.busy;
            });
          },
          [&](const JogStep& j) {
            if (!r.issued) {
              if (faulted(j.axis)) return Check::failed;
              if (t - r.started < j.duration) return Check::pending;
              r.issued = true;
              if (auto ec = axis(j.axis).stop()) {
                fail(s, t, fmt::format("axis {} rejected the stop ending the jog: {}", j.axis, ec.message()));
                return Check::failed;
              }
              return Check::pending;
            }
            return all({j.axis}, at_rest);
          },
          [&](const WaitStep& w) { return t - r.started >= w.duration ? Check::done : Check::pending; },
          [&](const WaitInPositionStep& w) {
            return all(w.axes, [](const motion::AxisStatus& st) { return at_rest(st) && st.in_position; });
          },
          [&](const WaitUntilStep& w) {
            const Condition& cond = w.condition;
            const auto& st = axis(cond.axis).status();
            bool met = false;
            switch (cond.kind) {
              case Condition::Kind::compare: {
                const double v = cond.quantity == Quantity::position   ? st.position
                                 : cond.quantity == Quantity::velocity ? st.velocity
                                                                       : st.following_error;
                met = cond.comparison == Comparison::above ? v > cond.value : v < cond.value;
                break;
              }
              case Condition::Kind::state:
                met = cond.state == motion::to_string(st.state);
                break;
              case Condition::Kind::fault:
                met = fault_matches(st.fault, cond.fault_code) ||
                      fault_matches(axis(cond.axis).drive().feedback().fault, cond.fault_code);
                break;
              case Condition::Kind::no_motion:
                met = at_rest(st);
                break;
              case Condition::Kind::in_position:
                met = at_rest(st) && st.in_position;
                break;
            }
            if (!met && cond.kind != Condition::Kind::fault && cond.kind != Condition::Kind::state &&
                faulted(cond.axis))
              return Check::failed;
            return met ? Check::done : Check::pending;
          },
          [&](const InjectFaultStep&) { return Check::done; },
          [&](const PlcStep& p) {
            if (p.action == PlcStep::Action::write)  // done when the device has had a cycle with it
              return machine_.controller_cycle_complete() ? Check::done : Check::pending;
            const auto v = read_plc(*machine_.controller(), p.operand);
            if (!v) {
              fail(s, t, v.error());
              return Check::failed;
            }
            return *v == p.value ? Check::done : Check::pending;
          },
          [&](const AcknowledgeStep& a) {
            // The device takes the operator's acknowledgement at its next cycle, after that
            // cycle's supervision (a fault of the last cycles has become its error by then).
            // The loader allows the step only with a controller.
            auto* ctl = machine_.controller();
            if (!r.issued) {
              if (!machine_.controller_cycle_complete()) return Check::pending;
              (void)ctl->acknowledge(static_cast<controllers::Acknowledgement>(static_cast<std::uint8_t>(a.how)));
              r.issued = true;
            }
            // Done when every controller axis whose device errors are gone has left error (the
            // controller reset it; its drive acknowledges within a few cycles).
            for (std::size_t i = 0; i < ctl->axis_count(); ++i) {
              const auto& spec = ctl->axis_specs()[i];
              if (ctl->errors().blocks_motion(static_cast<int>(i))) continue;
              if (axis(spec.name).status().state == motion::AxisState::error) return Check::pending;
            }
            return Check::done;
          },
          [&](const CoupleStep& cs) {
            if (cs.action != CoupleStep::Action::master_velocity && faulted(cs.slave)) return Check::failed;
            return machine_.couplings().done(cs, machine_.axes()) ? Check::done : Check::pending;
          },
          [&](const ParallelStep&) {
            bool done = true;
            for (auto& child : r.children) {
              if (child.step == nullptr) continue;  // finished
              const Check cc = poll(child, t);
              if (cc == Check::failed) return Check::failed;
              if (cc == Check::done)
                child.step = nullptr;
              else
                done = false;
            }
            return done ? Check::done : Check::pending;
          },
      },
      s.action);
  if (c == Check::pending && t - r.started > timeout) {
    std::string shows;  // a plc wait says what the device shows instead
    if (const auto* p = std::get_if<PlcStep>(&s.action); p && p->action == PlcStep::Action::wait)
      if (const auto v = read_plc(*machine_.controller(), p->operand))
        shows = fmt::format(" (waited for {}, the device shows {})", plc_text(p->operand, p->value),
                            plc_text(p->operand, *v));
    fail(s, t, fmt::format("did not complete within {:.3f} s{}", to_seconds(timeout), shows));
    return Check::failed;
  }
  return c;
}

Program::Status Program::step(Duration t) noexcept {
  if (status_ != Status::running) return status_;
  // Several steps may complete in one cycle (non-blocking ones, inject_fault); a blocking step
  // that was just launched waits for the next update, which bounds this loop.
  while (next_ < scenario_.program.size()) {
    if (!current_) current_ = Running{&scenario_.program[next_], t, false, false, {}};
    const Check c = poll(*current_, t);
    if (c == Check::failed) return status_ = Status::failed;
    if (c == Check::pending) return status_;
    current_.reset();
    ++next_;
  }
  return status_ = Status::done;
}

}  // namespace hil::runtime
