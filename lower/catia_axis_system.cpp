#include "lower/catia_axis_system.h"

#include <cmath>
#include <string>

#include "support/decimal.h"

namespace clpc {

namespace {

// Four numbers and nothing else ("    0.00000     1.00000     0.00000     0.00000").
bool read_row(std::string_view t, double* out) {
  const char* p = t.data();
  const char* e = p + t.size();
  auto blank = [&] {
    while (p < e && (*p == ' ' || *p == '\t' || *p == '\r')) ++p;
  };
  for (int i = 0; i < 4; ++i) {
    blank();
    if (p < e && *p == '+') ++p;
    auto [q, ec] = read_decimal(p, e, out[i]);
    if (ec != std::errc() || q == p) return false;
    p = q;
  }
  blank();
  return p == e;
}

}  // namespace

void CatiaAxisSystems::comment(std::string_view text, SourceLoc loc, Diagnostics& d) {
  if (text.substr(0, 7) == "*CATIA0") {
    rows_ = 0;
    other_lines_ = 0;
    at_ = loc;
    return;
  }
  if (rows_ == kNone) return;
  if (!read_row(text, &reading_[size_t(rows_) * 4])) {
    // Its name lines come before the rows; anything after a row, or a fifth name, ends it.
    if (rows_ > 0 || ++other_lines_ > 4) rows_ = kNone;
    return;
  }
  if (++rows_ < 3) return;
  rows_ = kNone;
  if (!have_first_ || !locked_) {
    first_ = reading_;
    have_first_ = true;
    return;
  }
  double worst = 0;
  for (size_t i = 0; i < 12; ++i) worst = std::max(worst, std::abs(reading_[i] - first_[i]));
  if (worst > 1e-4)
    d.error(at_, "CATIA changes the machining axis system here (its matrix is not that of the cuts before it): the points after "
                 "it are in the new axis system, which clpc does not put into the first; post each axis system's "
                 "operations from a file of its own, or give them one machining axis system in CATIA");
}

}  // namespace clpc
