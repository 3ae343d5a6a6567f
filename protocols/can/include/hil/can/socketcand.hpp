// SPDX-License-Identifier: MIT
#pragma once
// socketcand ASCII protocol codec (linux-can/socketcand doc/protocol.md; wire details from its
// src/state_raw.c, see docs/can.md). Pure: text in, typed elements or an error code out, no I/O.
//
// Every element is `< ... >`; there is no newline or length prefix, elements may be concatenated
// in one read or split across reads, and anything outside `< >` is ignored (as the daemon does).
//   server hello        < hi >
//   open a bus          < open can0 >            -> < ok > | < error could not open bus >
//   mode switch         < rawmode > < bcmmode > < controlmode > < isotpmode >   -> < ok >
//   rx (server->client) < frame 123 1700000000.123456 DEADBEEF >   (11-bit id: 3 hex digits,
//                       29-bit: 8; data %02X without spaces; SYNC gives two spaces before `>`)
//   tx (client->server) < send 123 4 de ad be ef >  (id hex, dlc DECIMAL, bytes hex, spaced)
//   error frame         < error 004 1700000000.123456 >  (error class, hex)
//   error text          < error unknown command >

#include <cstddef>
#include <cstdint>
#include <expected>
#include <string>
#include <string_view>
#include <system_error>
#include <variant>

#include "hil/can/frame.hpp"

namespace hil::can::socketcand {

inline constexpr std::uint16_t default_port = 29536;
inline constexpr std::size_t max_bus_name = 16;       ///< socketcand: bus names <= 16 chars
inline constexpr std::size_t max_element_size = 256;  ///< longer elements are garbage

enum class ParseErrc {
  not_an_element = 1,  ///< does not start with `<` and end with `>`
  empty_element,       ///< `< >`
  unknown_command,
  missing_argument,
  extra_argument,
  bad_id,            ///< not hex, too long, or out of the 11/29-bit range
  bad_dlc,           ///< not a decimal 0..8
  bad_data,          ///< not hex bytes, or more than 8 bytes, or count != dlc
  bad_timestamp,     ///< not SECONDS.FRACTION
  bad_bus_name,      ///< empty or longer than 16 characters
  element_too_long,  ///< no `>` within max_element_size characters
};
[[nodiscard]] const std::error_category& parse_category() noexcept;
[[nodiscard]] inline std::error_code make_error_code(ParseErrc e) noexcept {
  return {static_cast<int>(e), parse_category()};
}

/// Wall-clock timestamp as carried on the wire.
struct Timestamp {
  std::int64_t sec = 0;
  std::uint32_t usec = 0;  ///< 0..999999
  friend bool operator==(const Timestamp&, const Timestamp&) = default;
};

enum class Mode : std::uint8_t { bcm, raw, control, isotp };

struct Hi {
  friend bool operator==(const Hi&, const Hi&) = default;
};
struct Ok {
  friend bool operator==(const Ok&, const Ok&) = default;
};
struct Echo {
  friend bool operator==(const Echo&, const Echo&) = default;
};
struct Open {
  std::string bus;
  friend bool operator==(const Open&, const Open&) = default;
};
struct SwitchMode {
  Mode mode;
  friend bool operator==(const SwitchMode&, const SwitchMode&) = default;
};
/// `< frame ... >`: a frame the server received from the bus.
struct RxFrame {
  Frame frame;
  Timestamp time;
  friend bool operator==(const RxFrame&, const RxFrame&) = default;
};
/// `< send ... >`: a frame the client wants on the bus.
struct Send {
  Frame frame;
  friend bool operator==(const Send&, const Send&) = default;
};
/// `< error CLASS SEC.USEC >`: an error frame (frame.error set, frame.id = class).
struct ErrorFrame {
  Frame frame;
  Timestamp time;
  friend bool operator==(const ErrorFrame&, const ErrorFrame&) = default;
};
/// `< error text... >`: a refusal or diagnostic from the peer.
struct ErrorText {
  std::string text;
  friend bool operator==(const ErrorText&, const ErrorText&) = default;
};
/// A well-formed element whose command this codec does not model (BCM `add`, `subscribe`, ...).
struct Other {
  std::string command;
  std::string arguments;
  friend bool operator==(const Other&, const Other&) = default;
};

using Element = std::variant<Hi, Ok, Echo, Open, SwitchMode, RxFrame, Send, ErrorFrame, ErrorText, Other>;

/// Parse one element, `<` to `>` inclusive (surrounding whitespace allowed).
[[nodiscard]] std::expected<Element, std::error_code> parse_element(std::string_view text) noexcept;

/// Append the wire form of an element to `out`. Frames: as the daemon prints them (see above).
/// RTR frames have no socketcand form: format_rx_frame/format_send return false and append nothing.
bool format_rx_frame(std::string& out, const Frame& frame, Timestamp time);
bool format_send(std::string& out, const Frame& frame);
void format_error_frame(std::string& out, std::uint32_t error_class, Timestamp time);
void format_error_text(std::string& out, std::string_view text);
void format_open(std::string& out, std::string_view bus);
void format_mode(std::string& out, Mode mode);
void format_element(std::string& out, const Element& element);
inline constexpr std::string_view hi_element = "< hi >";
inline constexpr std::string_view ok_element = "< ok >";

/// Splits a TCP byte stream into elements. Bytes outside `< >` are skipped; a `<` inside an
/// unterminated element restarts the element (the earlier part is garbage); an element longer
/// than max_element_size is discarded and reported once. Thread: single owner.
class ElementSplitter {
 public:
  struct Item {
    std::string_view element;  ///< valid until the next feed()/next(); empty when `error` is set
    std::error_code error;     ///< element_too_long
  };
  /// Append received bytes (the unconsumed tail is kept; the buffer stays bounded).
  void feed(std::string_view bytes);
  /// The next complete element, or nothing until more bytes arrive.
  [[nodiscard]] bool next(Item& item);
  [[nodiscard]] std::size_t skipped_bytes() const noexcept { return skipped_; }
  [[nodiscard]] std::size_t buffered() const noexcept { return buf_.size() - pos_; }

 private:
  std::string buf_;
  std::size_t pos_ = 0;
  std::size_t skipped_ = 0;
};

}  // namespace hil::can::socketcand

template <>
struct std::is_error_code_enum<hil::can::socketcand::ParseErrc> : std::true_type {};
