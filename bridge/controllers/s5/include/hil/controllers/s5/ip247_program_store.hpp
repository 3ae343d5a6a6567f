// SPDX-License-Identifier: MIT
#pragma once
// The IP247 program memory (manual §2.6.1, §4.3.12-4.3.16; digest ip247.md §3.1, §4.12): at most
// 255 programs and 6000 chars in total, stored in input order; no overwrite (delete, then write:
// error 49); a program some axis executes cannot be deleted (51); a program that fails the syntax
// check is not stored (48, the syntax error and block go back in the VP DB). Shared by the three
// axes of a module. Not thread-safe (the module cycle owns it).
//
// Memory is a sequence of segments in storage order (§4.3.14, digest §4.12): deleting a program
// frees its segment, and the memory behind the last program some axis executes is compacted at
// once; a segment before (or between) running programs stays a gap, counted as used, and the
// delete answers message 61 "VP only deleted from the directory". A later delete while no
// program lies behind it running compacts the gap away.

#include <cstdint>
#include <map>
#include <string>
#include <vector>

#include "hil/controllers/s5/ip247_program.hpp"
#include "hil/stepdir/ip247_error.hpp"

namespace hil::controllers::s5 {

inline constexpr std::size_t ip247_memory_chars = 6000;
inline constexpr std::size_t ip247_max_programs = 255;

class Ip247ProgramStore {
 public:
  /// BA22. On error 48 `fault` receives the syntax error; nothing is stored on any error.
  stepdir::Ip247Error write(int number, const std::string& text, Ip247SyntaxFault* fault = nullptr);
  /// BA23: none, or the message 61 when the memory stays a gap (the program is deleted either
  /// way); 13 not present, 51 running (nothing deleted).
  stepdir::Ip247Error erase(int number);
  [[nodiscard]] const Ip247Program* find(int number) const;
  [[nodiscard]] const std::string* text(int number) const;
  /// Directory in storage order: (number, length in words of its VP DB).
  [[nodiscard]] std::vector<std::pair<int, int>> directory() const;
  /// Chars in use, gaps included.
  [[nodiscard]] std::size_t used_chars() const noexcept { return used_; }
  /// Chars held by gaps (deleted programs before a running one).
  [[nodiscard]] std::size_t gap_chars() const noexcept;
  /// Running programs are counted so they cannot be deleted (error 51).
  void acquire(int number) { ++active_[number]; }
  void release(int number);
  [[nodiscard]] bool active(int number) const;
  void clear() { *this = Ip247ProgramStore{}; }
  /// The axis in teach-in (0 = none): only one axis at a time (error 22).
  int teach_axis = 0;

 private:
  struct Entry {
    std::string text;
    Ip247Program program;
  };
  struct Segment {
    int number = -1;  ///< -1: a gap
    std::size_t chars = 0;
  };
  /// Frees the gaps behind the last running program.
  void compact();

  std::map<int, Entry> programs_;
  std::vector<Segment> memory_;  ///< storage order
  std::map<int, int> active_;
  std::size_t used_ = 0;
};

}  // namespace hil::controllers::s5
