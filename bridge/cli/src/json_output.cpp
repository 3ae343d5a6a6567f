// SPDX-License-Identifier: MIT
#include "hil/cli/json_output.hpp"

#include <fmt/format.h>

namespace hil::cli {

void print_json(const nlohmann::json& j, std::FILE* out) {
  const std::string text = j.dump(-1, ' ', false, nlohmann::json::error_handler_t::replace);
  std::fwrite(text.data(), 1, text.size(), out);
  std::fputc('\n', out);
  std::fflush(out);
}

int report_error(bool json, std::string_view prefix, const std::string& message, int exit_code, nlohmann::json extra) {
  fmt::print(stderr, "{}{}\n", prefix, message);
  std::fflush(stderr);
  if (json) {
    if (!extra.is_object()) extra = nlohmann::json::object();
    extra["error"] = message;
    extra["exit_code"] = exit_code;
    print_json(extra);
  }
  return exit_code;
}

std::string hex_bytes(const unsigned char* data, std::size_t size) {
  static constexpr char digits[] = "0123456789abcdef";
  std::string out;
  out.reserve(size * 2);
  for (std::size_t i = 0; i < size; ++i) {
    out.push_back(digits[data[i] >> 4]);
    out.push_back(digits[data[i] & 0x0F]);
  }
  return out;
}

}  // namespace hil::cli
