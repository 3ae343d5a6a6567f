// SPDX-License-Identifier: MIT
// `hilbridge emulate wf725`'s RK512 request mapping (Wf725ModulePolicy): any sequence of SEND and
// FETCH jobs on DB 0..255 (the DB axes 10/11 of a two-axis module, the MD image DB 1, user DBs)
// and DX 0..255 (the axes' MD images), with both axes cycling on simulated drives in virtual time
// between them, never crashes and always answers with a valid RK512 reaction (rk512_requests.hpp).
// The axes share one program memory, preloaded with programs, and a user DB holds program text,
// so the input reaches modes, data codes (44/45 included), programs and motion.
#include <chrono>
#include <memory>

#include "hil/controllers/parameter_controller.hpp"
#include "hil/controllers/s5/wf725_module_endpoint.hpp"
#include "hil/mocks/sim_drive.hpp"
#include "rk512_requests.hpp"

using namespace hil::controllers::s5;
namespace hc = hil::controllers;

namespace {

/// One axis' MD list, loaded once (a profile parse per input would dominate the run).
struct AxisSetup {
  hc::LoadedParameters loaded;
  Wf725MachineData md;
  hc::ControllerAxis axis;
  hil::Duration cycle{};
};

AxisSetup load(const char* file, const char* name) {
  auto loaded = hc::load_parameter_file("wf725-726", file);
  if (!loaded) std::abort();
  hc::ControllerSpec spec;
  spec.device = "wf725-726";
  spec.parameters = file;
  spec.options.emplace("axis", name);
  auto mapped = hc::wf725_axes(*loaded, spec);
  if (!mapped) std::abort();
  AxisSetup s{*loaded, wf725_machine_data(*loaded, {}), mapped->axes.front(), mapped->cycle};
  s.axis.config.soft_limit_min.reset();
  s.axis.config.soft_limit_max.reset();
  return s;
}

std::vector<std::uint16_t> text_db(const std::string& text) {
  std::vector<std::uint16_t> w{static_cast<std::uint16_t>(text.size())};
  for (std::size_t i = 0; i < text.size(); i += 2)
    w.push_back(static_cast<std::uint16_t>(static_cast<std::uint8_t>(text[i]) << 8 |
                                           (i + 1 < text.size() ? static_cast<std::uint8_t>(text[i + 1]) : 0)));
  return w;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  static const AxisSetup a_setup = load(HIL_WF725_MD_A, "A");
  static const AxisSetup b_setup = load(HIL_WF725_MD_B, "B");
  hil::fuzz::Input in{{data, size}};
  std::vector<std::unique_ptr<Wf725Controller>> ctls;
  std::vector<std::unique_ptr<hil::motion::Axis>> axes;
  for (const auto* s : {&a_setup, &b_setup}) {
    Wf725Options opt;
    opt.axis = s->axis.name[0];
    opt.db = static_cast<std::uint16_t>(10 + ctls.size());
    ctls.push_back(std::make_unique<Wf725Controller>(s->loaded, s->md, s->axis, s->cycle, opt));
    hil::mocks::SimDriveConfig d;
    d.name = "sim:" + s->axis.name;
    d.plant.kv_per_s = 200.0;
    d.plant.velocity_lag_s = 0.0;
    d.plant.velocity_feedforward = 1.0;
    axes.push_back(std::make_unique<hil::motion::Axis>(s->axis.config, std::make_unique<hil::mocks::SimDrive>(d)));
    hil::motion::Axis* ptr = axes.back().get();
    if (!ctls.back()->bind_axes(std::span<hil::motion::Axis* const>(&ptr, 1))) std::abort();
  }
  auto progs = parse_wf725_programs("%7\nN1 G90 X 20 000 F 300 000\nN2 L8 P2\n%8 B\nN1 G91 X 1 000 F 100 000\n");
  for (auto& p : *progs) (void)ctls.front()->store_program(std::move(p));
  hil::TimePoint now{};
  std::int64_t tick = 0;
  auto owned = std::make_unique<Wf725ModulePolicy>(std::vector<Wf725Controller*>{ctls[0].get(), ctls[1].get()},
                                                   std::chrono::milliseconds(1), [&](const hil::CycleTime& c) {
                                                     ++tick;
                                                     for (std::size_t i = 0; i < ctls.size(); ++i) {
                                                       axes[i]->update(c);
                                                       const auto every =
                                                           ctls[i]->cycle_period() / std::chrono::milliseconds(1);
                                                       if (tick % every == 0)
                                                         ctls[i]->step(hil::CycleTime{c.now, ctls[i]->cycle_period()});
                                                     }
                                                   });
  auto& policy = *owned;
  hil::mocks::legacy::S5BlockEndpoint ep(std::move(owned));
  policy.share_store(ep.store());
  ep.store()[20] = text_db("%9\nN1 G90 X 5 000 F 100 000\nN2 G04 F 100\n");
  policy.on_time(now);
  hil::fuzz::run_requests(in, policy, ep.store(), [&](int ms) {
    now += std::chrono::milliseconds(ms);
    policy.on_time(now);
  });
  // The state file round trip of what the input left: the memory and the user DBs load back.
  (void)ep.load_state(ep.save_state());
  return 0;
}
