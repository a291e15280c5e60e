// Reading a record's parameters by position and by keyword, with located errors.
#pragma once

#include <cmath>
#include <optional>
#include <span>
#include <string>

#include "grammar/record.h"
#include "ir/ir.h"
#include "support/diagnostics.h"
#include "support/text.h"

namespace clpc {

class ParamReader {
 public:
  ParamReader(const Record& r, Diagnostics& d) : r_(r), p_(r.params), d_(d) {}

  size_t size() const { return p_.size(); }
  const Param& operator[](size_t i) const { return p_[i]; }
  bool all_numbers() const {
    for (const Param& p : p_)
      if (!p.is_number()) return false;
    return true;
  }
  size_t count_numbers() const {
    size_t n = 0;
    for (const Param& p : p_) n += p.is_number();
    return n;
  }
  // Index of the first parameter that is `word`, or -1.
  int find(std::string_view word) const {
    for (size_t i = 0; i < p_.size(); ++i)
      if (p_[i].is(word)) return int(i);
    return -1;
  }
  bool has(std::string_view word) const { return find(word) >= 0; }
  // The number right after `word` (e.g. OSETNO,4); reports if the word is there without one.
  std::optional<double> after(std::string_view word) const {
    int i = find(word);
    if (i < 0) return std::nullopt;
    if (size_t(i + 1) >= p_.size() || !p_[i + 1].is_number()) {
      d_.error(i + 1 < int(p_.size()) ? p_[i + 1].loc : r_.end,
               std::string(r_.major) + ": a number must follow " + std::string(word));
      return std::nullopt;
    }
    return p_[i + 1].number;
  }
  // The loc to blame for parameter i (or the record's end when it is missing).
  SourceLoc loc(size_t i) const { return i < p_.size() ? p_[i].loc : r_.end; }

  // Checks that parameter i is a whole number in [lo, hi].
  std::optional<int> integer(size_t i, const char* what, int lo, int hi) const {
    if (i >= p_.size() || !p_[i].is_number()) {
      d_.error(loc(i), std::string(r_.major) + ": expected " + what + " (a whole number)");
      return std::nullopt;
    }
    double v = p_[i].number;
    if (v != std::floor(v) || v < lo || v > hi) {
      d_.error(p_[i].loc, std::string(r_.major) + ": " + what + " must be a whole number from " +
                              std::to_string(lo) + " to " + std::to_string(hi) + ", found " + num_text(v));
      return std::nullopt;
    }
    return int(v);
  }

 private:
  const Record& r_;
  std::span<const Param> p_;
  Diagnostics& d_;
};

// The words of a cycle record (CYCLE/ROUGH, the groove cycles: `KEYWORD,number` in any
// order) ----------------------------------------------------------------------------------

// A value that must be above zero (or zero, where `zero_ok`); reported with the record's name.
inline bool positive_value(Diagnostics& d, const char* record, const char* what, double v, SourceLoc at, bool zero_ok) {
  if (v > 0 || (zero_ok && v == 0)) return true;
  d.error(at, std::string(record) + ": " + what + " must be " + (zero_ok ? "zero or more" : "greater than zero") + ", found " +
                  num_text(v));
  return false;
}

// FEED (per revolution, program units), MMPR, IPR, MMPM, IPM.
inline bool is_feed_word(const Param& p) { return p.is("FEED") || p.is("IPR") || p.is("MMPR") || p.is("IPM") || p.is("MMPM"); }

// The feed `v` given after feed word `p`, in program units, and its mode.
inline void read_feed_word(const Param& p, double v, ir::Units program, double& feed, ir::FeedMode& mode) {
  const bool inch = p.is("IPR") || p.is("IPM"), metric = p.is("MMPR") || p.is("MMPM");
  feed = v * (inch ? 25.4 / ir::mm_per_unit(program) : metric ? 1 / ir::mm_per_unit(program) : 1.0);
  mode = p.is("IPM") || p.is("MMPM") ? ir::FeedMode::PerMinute : ir::FeedMode::PerRev;
}

}  // namespace clpc
