// SPDX-License-Identifier: MIT
#include "hil/controllers/s5/ip247_program.hpp"

#include <cctype>
#include <cstdio>
#include <string>

namespace hil::controllers::s5 {
namespace {

class SyntaxCategory final : public std::error_category {
 public:
  const char* name() const noexcept override { return "ip247-syntax"; }
  std::string message(int v) const override {
    switch (static_cast<Ip247SyntaxError>(v)) {
      case Ip247SyntaxError::none:
        return "no error";
      case Ip247SyntaxError::text_too_long:
        return "text too long or <LF> missing (Text zu lang oder <LF> fehlt)";
      case Ip247SyntaxError::block_type:
        return "wrong block type or N missing (Falsche Satzart oder N fehlt)";
      case Ip247SyntaxError::block_number_too_large:
        return "block number too large (Satznummer zu gross)";
      case Ip247SyntaxError::subprogram_number:
        return "subprogram number too large (Unterprogrammnummer zu gross)";
      case Ip247SyntaxError::function_after_g:
        return "function not allowed after G (Funktion nach G nicht erlaubt)";
      case Ip247SyntaxError::function_after_x:
        return "function not allowed after X (Funktion nach X nicht erlaubt)";
      case Ip247SyntaxError::final_block_lf:
        return "<LF> missing after the final block (<LF> nach Schlusssatz fehlt)";
      case Ip247SyntaxError::block_end:
        return "block end: <LF> missing or wrong function (Satzende: <LF> fehlt oder falsche Funktion)";
      case Ip247SyntaxError::path_too_large:
        return "path too large (Weg zu gross)";
      case Ip247SyntaxError::f_too_large:
        return "F value too large (F-Wert zu gross)";
      case Ip247SyntaxError::too_many_decimals:
        return "too many decimal places (Zu viele Nachkommastellen)";
      case Ip247SyntaxError::loop_end_missing:
        return "loop end missing (Schleifenende fehlt)";
      case Ip247SyntaxError::loop_start_missing:
        return "loop start missing (Schleifenanfang fehlt)";
      case Ip247SyntaxError::program_end_missing:
        return "program end missing (Programmende fehlt)";
      case Ip247SyntaxError::unknown_function:
        return "unknown function (Unbekannte Funktion)";
      case Ip247SyntaxError::m_too_large:
        return "M value too large (M-Wert zu gross)";
      case Ip247SyntaxError::block_after_final:
        return "new block after the final block (Neuer Satz nach Schlusssatz)";
      case Ip247SyntaxError::block_too_long:
        return "block too long (Satz zu lang)";
      case Ip247SyntaxError::g_not_implemented:
        return "G function not implemented (G-Funktion nicht implementiert)";
    }
    return "IP247 syntax error " + std::to_string(v);
  }
};

struct Fail {
  Ip247SyntaxError code;
  std::string what;
};

bool is_digit(char c) noexcept {
  return c >= '0' && c <= '9';
}
bool is_blank(char c) noexcept {
  return c == ' ' || c == '\r' || c == '\t';
}

/// Reads up to `max` digits (more digits: `too_many` = true, all are consumed).
int read_digits(std::string_view s, std::size_t& i, std::size_t max, bool& too_many, int& ndigits) {
  long v = 0;
  ndigits = 0;
  while (i < s.size() && is_digit(s[i])) {
    if (ndigits < 9) v = v * 10 + (s[i] - '0');
    ++ndigits;
    ++i;
  }
  too_many = static_cast<std::size_t>(ndigits) > max;
  return static_cast<int>(v);
}

// Function ranks in the fixed order N L G X F M.
enum Rank : int { rank_n = 0, rank_l = 1, rank_g = 2, rank_x = 3, rank_f = 4, rank_m = 5 };

Ip247SyntaxError order_error(int prev) noexcept {
  if (prev == rank_g) return Ip247SyntaxError::function_after_g;
  if (prev == rank_x) return Ip247SyntaxError::function_after_x;
  return Ip247SyntaxError::block_end;
}

std::expected<Ip247Block, Fail> parse_block(std::string_view s) {
  Ip247Block b;
  std::size_t i = 0;
  while (i < s.size() && is_blank(s[i])) ++i;
  if (i < s.size() && (s[i] == '/' || s[i] == ':')) b.kind = s[i++];
  if (i >= s.size() || s[i] != 'N')
    return std::unexpected(Fail{Ip247SyntaxError::block_type, "block must start with N"});
  ++i;
  bool many = false;
  int nd = 0;
  b.number = read_digits(s, i, 3, many, nd);
  if (nd == 0) return std::unexpected(Fail{Ip247SyntaxError::block_type, "N without a block number"});
  if (many) return std::unexpected(Fail{Ip247SyntaxError::block_number_too_large, "N has more than 3 digits"});
  int prev = rank_n;
  while (true) {
    const std::size_t before = i;
    while (i < s.size() && is_blank(s[i])) ++i;
    if (i >= s.size()) break;
    const char c = s[i];
    int rank = -1;
    switch (c) {
      case 'L':
        rank = rank_l;
        break;
      case 'G':
        rank = rank_g;
        break;
      case 'X':
        rank = rank_x;
        break;
      case 'F':
        rank = rank_f;
        break;
      case 'M':
        rank = rank_m;
        break;
      default:
        return std::unexpected(Fail{Ip247SyntaxError::unknown_function, std::string("unknown function '") + c + "'"});
    }
    if (i == before)
      return std::unexpected(Fail{Ip247SyntaxError::block_end, "functions must be separated by a blank"});
    if (rank <= prev) {
      return std::unexpected(Fail{order_error(prev), std::string(1, c) + " out of the order N L G X F M or repeated"});
    }
    ++i;
    switch (rank) {
      case rank_l: {
        const int v = read_digits(s, i, 3, many, nd);
        if (nd == 0 || many || v > ip247_max_program_number) {
          return std::unexpected(Fail{Ip247SyntaxError::subprogram_number, "L needs a program number 0..255"});
        }
        b.call = v;
        break;
      }
      case rank_g: {
        const int v = read_digits(s, i, 2, many, nd);
        if (nd == 0 || many || !ip247_g_known(v)) {
          return std::unexpected(Fail{Ip247SyntaxError::g_not_implemented, "G function not implemented"});
        }
        b.g = v;
        break;
      }
      case rank_x: {
        bool neg = false;
        if (i < s.size() && (s[i] == '+' || s[i] == '-')) neg = s[i++] == '-';
        const int ip = read_digits(s, i, 5, many, nd);
        if (many) return std::unexpected(Fail{Ip247SyntaxError::path_too_large, "X has more than 5 integer digits"});
        int frac = 0, fd = 0;
        if (i < s.size() && s[i] == '.') {
          ++i;
          bool fmany = false;
          frac = read_digits(s, i, 3, fmany, fd);
          if (fmany) return std::unexpected(Fail{Ip247SyntaxError::too_many_decimals, "X has more than 3 decimals"});
        }
        if (nd == 0 && fd == 0) return std::unexpected(Fail{Ip247SyntaxError::path_too_large, "X without digits"});
        for (int k = fd; k < 3; ++k) frac *= 10;
        const std::int64_t v = static_cast<std::int64_t>(ip) * 1000 + frac;
        b.x_milli = neg ? -v : v;
        break;
      }
      case rank_f: {
        const int v = read_digits(s, i, 5, many, nd);
        if (nd == 0 || many || v > 65000)
          return std::unexpected(Fail{Ip247SyntaxError::f_too_large, "F needs 0..65000"});
        b.f = v;
        break;
      }
      case rank_m: {
        const int v = read_digits(s, i, 2, many, nd);
        if (nd == 0 || many) return std::unexpected(Fail{Ip247SyntaxError::m_too_large, "M needs 2 digits 00..99"});
        b.m = v;
        break;
      }
      default:
        break;
    }
    if (i < s.size() && !is_blank(s[i])) {
      return std::unexpected(Fail{Ip247SyntaxError::block_end, "functions must be separated by a blank"});
    }
    prev = rank;
  }
  // Rules of §2.6.10.
  const auto fail = [](Ip247SyntaxError e, const char* what) { return std::unexpected(Fail{e, what}); };
  if (b.call && (b.g || b.x_milli || b.f || b.m)) return fail(Ip247SyntaxError::block_end, "nothing may follow L");
  if (b.g == 0) {
    if (!b.x_milli) return fail(Ip247SyntaxError::function_after_g, "G00 must be followed by X");
    if (b.f) return fail(Ip247SyntaxError::function_after_x, "G00 X takes no F (rapid = vmax)");
  } else if (b.g == 4) {
    if (b.x_milli) return fail(Ip247SyntaxError::function_after_g, "X not allowed after G04");
    if (!b.f) return fail(Ip247SyntaxError::function_after_g, "G04 needs F (dwell x 100 ms)");
    if (*b.f == 0) return fail(Ip247SyntaxError::f_too_large, "G04 dwell F must be 1..65000");
  } else if (b.g == 20) {
    if (b.x_milli || b.f || b.m) return fail(Ip247SyntaxError::function_after_g, "nothing may follow G20");
  } else if (b.g == 24) {
    if (b.x_milli || b.m) return fail(Ip247SyntaxError::function_after_g, "G24 takes only F (no X, no M)");
    if (!b.f) return fail(Ip247SyntaxError::function_after_g, "G24 needs F (loop count, F0 = endless)");
  } else if (b.g == 74) {
    if (b.x_milli) return fail(Ip247SyntaxError::function_after_g, "X not allowed with G74");
  } else if (b.x_milli) {
    if (!b.f) return fail(Ip247SyntaxError::function_after_x, "X must be followed by F (feed)");
    if (*b.f == 0) return fail(Ip247SyntaxError::f_too_large, "feed F must be 1..65000");
  } else if (b.f) {
    return fail(Ip247SyntaxError::block_end, "F only with X, G04, G24 or G74");
  }
  return b;
}

std::unexpected<Ip247SyntaxFault> fault(Ip247SyntaxError e, int block, int line, std::string what) {
  return std::unexpected(Ip247SyntaxFault{e, block, line, "line " + std::to_string(line) + ": " + std::move(what)});
}

}  // namespace

const std::error_category& ip247_syntax_category() noexcept {
  static const SyntaxCategory c;
  return c;
}

bool ip247_g_known(int g) noexcept {
  switch (g) {
    case 0:
    case 4:
    case 10:
    case 20:
    case 24:
    case 25:
    case 26:
    case 27:
    case 40:
    case 43:
    case 44:
    case 53:
    case 54:
    case 55:
    case 56:
    case 57:
    case 70:
    case 71:
    case 74:
    case 90:
    case 91:
      return true;
    default:
      return false;
  }
}

std::expected<Ip247Program, Ip247SyntaxFault> parse_ip247_program(std::string_view text) {
  if (text.size() > ip247_max_program_chars) {
    return fault(Ip247SyntaxError::text_too_long, 0, 1,
                 "program has " + std::to_string(text.size()) + " chars, at most 1023 including the header");
  }
  Ip247Program p;
  const std::size_t hl = text.find('\n');
  if (hl == std::string_view::npos)
    return fault(Ip247SyntaxError::text_too_long, 0, 1, "<LF> missing after the header");
  {
    const std::string_view h = text.substr(0, hl);
    std::size_t i = 0;
    while (i < h.size() && is_blank(h[i])) ++i;
    if (i >= h.size() || (h[i] != '%' && h[i] != 'L')) {
      return fault(Ip247SyntaxError::block_type, 0, 1, "header must start with % (main) or L (subprogram)");
    }
    p.subprogram = h[i] == 'L';
    ++i;
    const std::size_t field = i;
    while (i < h.size() && h[i] == ' ' && i - field < 2) ++i;  // right-aligned number field
    bool many = false;
    int nd = 0;
    p.number = read_digits(h, i, 3, many, nd);
    if (nd == 0 || many || p.number > ip247_max_program_number) {
      return fault(Ip247SyntaxError::subprogram_number, 0, 1, "header needs a program number 0..255");
    }
    if (i < h.size() && !is_blank(h[i]))
      return fault(Ip247SyntaxError::block_end, 0, 1, "blank needed after the number");
    if (i < h.size()) ++i;
    std::string_view t = h.substr(std::min(i, h.size()));
    while (!t.empty() && is_blank(t.back())) t.remove_suffix(1);
    if (t.size() > 58) return fault(Ip247SyntaxError::text_too_long, 0, 1, "header text longer than 58 chars");
    p.title.assign(t);
  }
  std::size_t pos = hl + 1;
  int line = 1;
  std::vector<int> loops;
  bool final_seen = false;
  while (pos < text.size()) {
    ++line;
    const std::size_t lf = text.find('\n', pos);
    const std::string_view rest = text.substr(pos, lf == std::string_view::npos ? std::string_view::npos : lf - pos);
    if (final_seen) {
      for (char c : text.substr(pos)) {
        if (!is_blank(c) && c != '\n' && c != '\0') {
          return fault(Ip247SyntaxError::block_after_final, p.blocks.back().number, line,
                       "text after the final block (M02)");
        }
      }
      break;
    }
    if (lf == std::string_view::npos) {
      bool blank = true;
      for (char c : rest) blank = blank && (is_blank(c) || c == '\0');
      if (blank) break;
    }
    const int number_guess = [&] {
      auto b = parse_block(rest);
      return b ? b->number : 0;
    }();
    if (rest.size() + 1 > ip247_max_block_chars) {
      return fault(Ip247SyntaxError::block_too_long, number_guess, line, "block longer than 50 chars including <LF>");
    }
    auto b = parse_block(rest);
    if (!b) {
      int n = 0;
      {  // best effort: the N number of the faulty block
        std::size_t i = 0;
        while (i < rest.size() && (is_blank(rest[i]) || rest[i] == '/' || rest[i] == ':')) ++i;
        if (i < rest.size() && rest[i] == 'N') {
          ++i;
          bool many = false;
          int nd = 0;
          n = read_digits(rest, i, 3, many, nd);
          if (many) n = 0;
        }
      }
      return fault(b.error().code, n, line, b.error().what);
    }
    b->line = line;
    const int idx = static_cast<int>(p.blocks.size());
    if (b->g == 24) loops.push_back(idx);
    if (b->g == 20) {
      if (loops.empty()) return fault(Ip247SyntaxError::loop_start_missing, b->number, line, "G20 without G24");
      b->partner = loops.back();
      p.blocks[static_cast<std::size_t>(loops.back())].partner = idx;
      loops.pop_back();
    }
    if (b->is_final()) {
      if (!loops.empty()) {
        return fault(Ip247SyntaxError::loop_end_missing, b->number, line, "program ends inside a G24 loop");
      }
      if (lf == std::string_view::npos) return fault(Ip247SyntaxError::final_block_lf, b->number, line, "<LF> missing");
      final_seen = true;
    } else if (lf == std::string_view::npos) {
      return fault(Ip247SyntaxError::block_end, b->number, line, "<LF> missing at the block end");
    }
    p.blocks.push_back(*b);
    pos = lf == std::string_view::npos ? text.size() : lf + 1;
  }
  if (!final_seen) {
    if (!loops.empty()) {
      return fault(Ip247SyntaxError::loop_end_missing, p.blocks[static_cast<std::size_t>(loops.back())].number, line,
                   "G24 without G20");
    }
    return fault(Ip247SyntaxError::program_end_missing, p.blocks.empty() ? 0 : p.blocks.back().number, line,
                 "no final block with M02");
  }
  return p;
}

std::string make_ip247_program_text(const Ip247Program& p) {
  std::string out;
  char buf[64];
  std::snprintf(buf, sizeof buf, "%c%3d", p.subprogram ? 'L' : '%', p.number);
  out += buf;
  if (!p.title.empty()) out += " " + p.title;
  out += '\n';
  for (const auto& b : p.blocks) {
    if (b.kind != 'N') out += b.kind;
    out += "N" + std::to_string(b.number);
    if (b.call) out += " L" + std::to_string(*b.call);
    if (b.g) {
      std::snprintf(buf, sizeof buf, " G%02d", *b.g);
      out += buf;
    }
    if (b.x_milli) {
      const std::int64_t v = *b.x_milli;
      const std::int64_t a = v < 0 ? -v : v;
      std::snprintf(buf, sizeof buf, " X%s%lld.%03lld", v < 0 ? "-" : "", static_cast<long long>(a / 1000),
                    static_cast<long long>(a % 1000));
      out += buf;
    }
    if (b.f) out += " F" + std::to_string(*b.f);
    if (b.m) {
      std::snprintf(buf, sizeof buf, " M%02d", *b.m);
      out += buf;
    }
    out += '\n';
  }
  return out;
}

}  // namespace hil::controllers::s5
