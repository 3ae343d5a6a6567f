// SPDX-License-Identifier: MIT
#include "hil/serial/clm14/client.hpp"

#include <fmt/format.h>

#include <array>

#include "hil/serial/clm14/serial_error.hpp"

namespace hil::serial::clm14 {

namespace {
std::string shown(std::string_view s) {
  std::string out;
  for (char c : s) {
    if (c == '\r')
      out += "<CR>";
    else if (c == '\n')
      out += "<LF>";
    else
      out.push_back(c);
  }
  return out;
}
std::string_view trim_trailing_spaces(std::string_view s) {
  while (!s.empty() && s.back() == ' ') s.remove_suffix(1);
  return s;
}
}  // namespace

Client::Client(ByteStream& stream, const Clock& clock, ClientOptions options, std::shared_ptr<const DeviceData> data)
    : stream_(stream),
      clock_(clock),
      options_(options),
      data_(std::move(data)),
      station_(station_char(options.station).value_or(' ')) {}

void Client::drain() {
  std::array<std::uint8_t, 256> buf{};
  for (int i = 0; i < 64; ++i) {
    const ReadResult r = stream_.read_some(buf, Duration::zero());
    if (r.size == 0 && (!r.error || r.error == LineError::timeout)) return;
  }
}

std::expected<std::string, ClientError> Client::read_line(Duration first_byte_timeout) {
  std::string line;
  std::error_code line_error;
  TimePoint deadline = clock_.now() + first_byte_timeout;
  std::array<std::uint8_t, 1> b{};
  for (;;) {
    const TimePoint now = clock_.now();
    if (now >= deadline) {
      return std::unexpected(ClientError{
          LineError::timeout,
          line.empty() ? fmt::format("no reply from station {} within {} ms", options_.station,
                                     std::chrono::duration_cast<std::chrono::milliseconds>(first_byte_timeout).count())
                       : fmt::format("reply '{}' stopped before CR LF", shown(line))});
    }
    const ReadResult r = stream_.read_some(b, deadline - now);
    if (r.size == 1) {
      deadline = clock_.now() + options_.char_timeout;
      if (b[0] == '\n') {
        if (!line.empty() && line.back() == '\r') line.pop_back();
        if (line_error)
          return std::unexpected(ClientError{line_error, fmt::format("reply '{}' arrived with a character error: {}",
                                                                     shown(line), line_error.message())});
        if (line.empty()) continue;  // stray LF
        return line;
      }
      line.push_back(static_cast<char>(b[0]));
      if (line.size() > max_line_length)
        return std::unexpected(
            ClientError{SerialError::format_error,
                        fmt::format("reply longer than {} characters: noise on the line?", max_line_length)});
    }
    if (r.error && r.error != LineError::timeout) {
      if (r.error == LineError::closed || r.error == LineError::io)
        return std::unexpected(ClientError{r.error, r.error.message()});
      line_error = r.error;  // parity/framing/overrun: finish the line, then report
      deadline = clock_.now() + options_.char_timeout;
    }
  }
}

std::expected<Telegram, ClientError> Client::transact(char lead, std::string_view body, bool expect_reply) {
  const std::string request = make_telegram(lead, station_, body, true);
  const auto* p = reinterpret_cast<const std::uint8_t*>(request.data());
  ClientError last;
  for (int attempt = 0; attempt <= options_.retries; ++attempt) {
    if (attempt > 0) ++retries_used_;
    drain();
    if (auto ec = stream_.write(std::span(p, request.size()), options_.write_timeout)) {
      // A stalled line does not get better by repeating at once: report it.
      return std::unexpected(ClientError{ec, fmt::format("sending '{}': {}", shown(request), ec.message())});
    }
    if (!expect_reply) return Telegram{'Y', ' ', {}, std::nullopt};
    auto line = read_line(options_.response_timeout);
    if (!line) {
      last = line.error();
      last.message =
          fmt::format("'{}': {}", shown(trim_trailing_spaces(request.substr(0, request.size() - 2))), last.message);
      continue;
    }
    auto t = parse_telegram(*line, true);
    if (!t && *line != "Y") {
      last = ClientError{static_cast<SerialError>(t.error().code),
                         fmt::format("reply to '{}' unusable: {}", shown(request), t.error().message)};
      continue;
    }
    if (t->lead == 'X') {
      if (auto rep = parse_error_body(t->body)) {
        const std::string text = data_ ? data_->serial_error_text(rep->code) : rep->text;
        last = ClientError{
            static_cast<SerialError>(rep->code),
            fmt::format("station {} rejected '{}': CLM serial error {:02d} \"{}\"", options_.station,
                        shown(trim_trailing_spaces(request.substr(0, request.size() - 2))), rep->code, text),
            rep->code};
        // A checksum error means the request was damaged on the way: send it again.
        if (rep->code == static_cast<int>(SerialError::checksum_error) ||
            rep->code == static_cast<int>(SerialError::format_error))
          continue;
        return std::unexpected(last);
      }
    }
    if (t->station != station_ && !t->is_confirmation()) {
      last = ClientError{SerialError::format_error,
                         fmt::format("reply from station '{}' but station '{}' was asked", t->station, station_)};
      continue;
    }
    return *t;
  }
  return std::unexpected(last);
}

std::expected<std::string, ClientError> Client::read_program_line(int n) {
  auto t = transact('?', fmt::format("N{:04d}", n), true);
  if (!t) return std::unexpected(t.error());
  const std::string prefix = fmt::format("N{:04d} ", n);
  if (t->lead != '#' || !t->body.starts_with(prefix))
    return std::unexpected(
        ClientError{SerialError::format_error, fmt::format("asked for line {:04d}, got '{}{}'", n, t->lead, t->body)});
  return std::string(trim_trailing_spaces(std::string_view(t->body).substr(prefix.size())));
}

std::expected<void, ClientError> Client::write_program_line(int n, std::string_view text) {
  auto t = transact('#', fmt::format("N{:04d} {} ", n, trim_trailing_spaces(text)), options_.expect_confirmation);
  if (!t) return std::unexpected(t.error());
  if (options_.expect_confirmation && !t->is_confirmation())
    return std::unexpected(ClientError{SerialError::format_error,
                                       fmt::format("line {:04d}: expected Y, got '{}{}'", n, t->lead, t->body)});
  return {};
}

std::expected<std::string, ClientError> Client::read_parameter(std::string_view number) {
  auto t = transact('?', fmt::format("K {}", number), true);
  if (!t) return std::unexpected(t.error());
  const std::string prefix = fmt::format("K {}", number);
  if (t->lead != '#' || !t->body.starts_with(prefix))
    return std::unexpected(
        ClientError{SerialError::format_error, fmt::format("asked for {}, got '{}{}'", number, t->lead, t->body)});
  std::string_view rest = std::string_view(t->body).substr(prefix.size());
  if (!rest.empty() && rest.front() == ' ') rest.remove_prefix(1);
  return std::string(trim_trailing_spaces(rest));
}

std::expected<void, ClientError> Client::write_parameter(std::string_view number, std::string_view data) {
  // Parameters are sent without a space before '$' (manual Figs 9-14..16).
  auto t = transact('#', fmt::format("K {} {}", number, trim_trailing_spaces(data)), options_.expect_confirmation);
  if (!t) return std::unexpected(t.error());
  if (options_.expect_confirmation && !t->is_confirmation())
    return std::unexpected(
        ClientError{SerialError::format_error, fmt::format("{}: expected Y, got '{}{}'", number, t->lead, t->body)});
  return {};
}

std::expected<std::string, ClientError> Client::read_variable(int n) {
  auto t = transact('?', fmt::format("V{:03d}", n), true);
  if (!t) return std::unexpected(t.error());
  if (t->lead != 'V' || t->body.size() < 4)
    return std::unexpected(
        ClientError{SerialError::format_error, fmt::format("asked for V{:03d}, got '{}{}'", n, t->lead, t->body)});
  return std::string(trim_trailing_spaces(std::string_view(t->body).substr(4)));
}

std::expected<void, ClientError> Client::write_variable(int n, std::string_view value) {
  auto t = transact('#', fmt::format("V{:03d} {} ", n, value), options_.expect_confirmation);
  if (!t) return std::unexpected(t.error());
  return {};
}

std::expected<std::string, ClientError> Client::read_status(int n, std::string_view arg) {
  auto t = transact('?', arg.empty() ? fmt::format("X  {:02d} ", n) : fmt::format("X  {:02d} {} ", n, arg), true);
  if (!t) return std::unexpected(t.error());
  if (t->lead != 'X' || t->body.size() < 2)
    return std::unexpected(ClientError{SerialError::format_error,
                                       fmt::format("asked for status {:02d}, got '{}{}'", n, t->lead, t->body)});
  std::string_view rest = std::string_view(t->body).substr(2);
  if (!rest.empty() && rest.front() == ' ') rest.remove_prefix(1);
  return std::string(trim_trailing_spaces(rest));
}

std::expected<void, ClientError> Client::command(std::string_view name) {
  auto t = transact('!', fmt::format("{} ", name), options_.expect_confirmation);
  if (!t) return std::unexpected(t.error());
  return {};
}

}  // namespace hil::serial::clm14
