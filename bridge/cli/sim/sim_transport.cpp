// SPDX-License-Identifier: MIT
// CLI module `sim`: registers the `sim` transport (hil::mocks::make_sim_transport, SimDrive on the
// plant model), the default for scenarios with no hardware.
#include "hil/mocks/sim_transport.hpp"
#include "hil/cli/context.hpp"

namespace hil::cli {

void register_sim(Context& ctx) {
  ctx.transports.add("sim", [] { return mocks::make_sim_transport(); });
}

}  // namespace hil::cli
