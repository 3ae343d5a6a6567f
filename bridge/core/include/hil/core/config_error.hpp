// SPDX-License-Identifier: MIT
#pragma once
// Configuration errors name the file, the line and the key, and say what to do.

#include <string>

namespace hil {

struct ConfigError {
  std::string file;     ///< path as the user gave it ("" for in-memory input)
  int line = 0;         ///< 1-based; 0 when unknown
  int column = 0;       ///< 1-based; 0 when unknown
  std::string key;      ///< dotted path of the offending key ("axes[2].drive.node")
  std::string message;  ///< what is wrong and what is expected

  /// "demo.yaml:12:5: axes[2].drive.node: expected an integer 1..127, got 'five'"
  [[nodiscard]] std::string describe() const;
};

}  // namespace hil
