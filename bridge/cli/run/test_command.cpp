// SPDX-License-Identifier: MIT
#include "hil/cli/context.hpp"
namespace hil::cli {
void register_test_command(Context&) {}
}  // namespace hil::cli
