// SPDX-License-Identifier: MIT
#pragma once
// Finding the bundled examples (examples/demo.yaml) from the repo root, the build dir or an
// installed tree.

#include <filesystem>
#include <optional>
#include <string>
#include <vector>

namespace hil::cli {

/// Folders searched for the examples, in order: $HILBRIDGE_EXAMPLES, <exe>/../examples,
/// <exe>/examples, <exe>/../../examples, ./examples, <exe>/../share/hilbridge/examples, and
/// the source tree's examples/ this binary was built from.
[[nodiscard]] std::vector<std::filesystem::path> example_dirs();
/// The first existing `name` in example_dirs().
[[nodiscard]] std::optional<std::filesystem::path> find_example(const std::string& name);

}  // namespace hil::cli
