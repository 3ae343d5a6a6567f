// SPDX-License-Identifier: MIT
// The amk-db line syntax into DataBlocks. See db_text.hpp.
#include "hil/controllers/amkasyn/db_text.hpp"

#include <fmt/format.h>

#include <cctype>
#include <optional>

#include "hil/profiles/db_integer_text.hpp"

#include "text_trim.hpp"

namespace hil::controllers::amkasyn {
namespace {

using detail::trim;

enum class Kind : std::uint8_t { dr, dl, dw, dd };

struct Item {
  bool init = false;
  Kind kind = Kind::dw;
  std::size_t word = 0;
  std::int64_t value = 0;
  std::string name;
};

/// One line: empty (nullopt without error), an item, or an error.
std::expected<std::optional<Item>, DbTextError> parse_line(std::string_view line, int number, bool allow_init,
                                                           std::size_t max_words) {
  if (const auto c = line.find_first_of(";#"); c != std::string_view::npos) line = line.substr(0, c);
  std::string_view t = trim(line);
  if (t.empty()) return std::optional<Item>{};
  Item it;
  if (t.size() > 4 && (t.starts_with("INIT") || t.starts_with("init")) &&
      (t[4] == ' ' || t[4] == '\t' || t[4] == '_')) {
    if (!allow_init)
      return std::unexpected(DbTextError{number, std::string(t.substr(0, 4)),
                                         "INIT lines belong to an SF file (FB 207 init DB), not to a table DB"});
    it.init = true;
    t = trim(t.substr(5));
  }
  std::size_t i = 0;
  while (i < t.size() && std::isalnum(static_cast<unsigned char>(t[i]))) ++i;
  std::string addr(t.substr(0, i));
  for (auto& c : addr) c = static_cast<char>(std::toupper(static_cast<unsigned char>(c)));
  it.name = it.init ? "INIT " + addr : addr;
  const bool shape =
      addr.size() >= 3 && addr.size() <= 7 &&
      (addr.starts_with("DR") || addr.starts_with("DL") || addr.starts_with("DW") || addr.starts_with("DD")) &&
      addr.find_first_not_of("0123456789", 2) == std::string::npos;
  if (!shape)
    return std::unexpected(DbTextError{number, std::string(trim(line)),
                                       "expected a data item DRn, DLn, DWn or DDn = value (INIT prefix for the "
                                       "FB 207 init DB)"});
  it.kind = addr[1] == 'R' ? Kind::dr : addr[1] == 'L' ? Kind::dl : addr[1] == 'W' ? Kind::dw : Kind::dd;
  it.word = static_cast<std::size_t>(std::stoul(addr.substr(2)));
  const std::size_t limit = it.init ? 10 : max_words;
  if (it.word + (it.kind == Kind::dd ? 2 : 1) > limit)
    return std::unexpected(
        DbTextError{number, it.name,
                    fmt::format("{} is outside the {}-word {}", it.name, limit,
                                it.init ? "init DB" : (max_words == 34 ? "commanding DB" : "table DB"))});
  t = trim(t.substr(i));
  if (t.starts_with("=") || t.starts_with(":")) t = trim(t.substr(1));
  const auto v = profiles::parse_db_integer(t);
  if (!v)
    return std::unexpected(
        DbTextError{number, it.name, fmt::format("'{}' is not an integer (decimal, 0x... or ...h)", t)});
  const auto [lo, hi] = it.kind == Kind::dr || it.kind == Kind::dl ? std::pair<std::int64_t, std::int64_t>{-128, 255}
                        : it.kind == Kind::dw ? std::pair<std::int64_t, std::int64_t>{-32768, 65535}
                                              : std::pair<std::int64_t, std::int64_t>{INT32_MIN, UINT32_MAX};
  if (*v < lo || *v > hi)
    return std::unexpected(
        DbTextError{number, it.name, fmt::format("{} = {} does not fit ({}..{})", it.name, *v, lo, hi)});
  it.value = *v;
  return std::optional<Item>{it};
}

void put(DataBlock& db, const Item& it) {
  switch (it.kind) {
    case Kind::dr:
      db.set_dr(it.word, static_cast<std::uint8_t>(it.value));
      break;
    case Kind::dl:
      db.set_dl(it.word, static_cast<std::uint8_t>(it.value));
      break;
    case Kind::dw:
      db.set_dw(it.word, static_cast<std::int32_t>(it.value));
      break;
    case Kind::dd:
      db.set_dd(it.word, it.value);
      break;
  }
}

template <class F>
std::optional<DbTextError> each_line(std::string_view text, F&& f) {
  int number = 0;
  while (!text.empty()) {
    ++number;
    const auto nl = text.find('\n');
    const std::string_view line = text.substr(0, nl);
    text = nl == std::string_view::npos ? std::string_view{} : text.substr(nl + 1);
    if (auto e = f(line, number)) return e;
  }
  return std::nullopt;
}

}  // namespace

std::expected<SfDbText, DbTextError> parse_sf_db_text(std::string_view text) {
  SfDbText out;
  auto e = each_line(text, [&](std::string_view line, int number) -> std::optional<DbTextError> {
    auto it = parse_line(line, number, true, 34);
    if (!it) return it.error();
    if (!*it) return std::nullopt;
    put((*it)->init ? out.init : out.command, **it);
    out.has_init = out.has_init || (*it)->init;
    return std::nullopt;
  });
  if (e) return std::unexpected(*e);
  return out;
}

std::expected<DataBlock, DbTextError> parse_table_db_text(std::string_view text) {
  DataBlock db(0);
  auto e = each_line(text, [&](std::string_view line, int number) -> std::optional<DbTextError> {
    auto it = parse_line(line, number, false, max_table_words);
    if (!it) return it.error();
    if (*it) put(db, **it);
    return std::nullopt;
  });
  if (e) return std::unexpected(*e);
  return db;
}

}  // namespace hil::controllers::amkasyn
