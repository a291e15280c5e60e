// Numbers as a control reads them, formatted with integer arithmetic (no printf on the hot
// path): the value is scaled, rounded once to an integer count of output increments, and that
// integer is what is written and what modal suppression compares.
#pragma once

#include <cstdint>
#include <string>

#include "machine/machine.h"

namespace clpc {

// The rounded value in output increments (value * scale * 10^decimals). False when it does not
// fit a control's range (|value| >= 1e15 increments) or is not finite.
inline bool quantize(double value, const AddressFormat& f, int64_t& q) {
  static constexpr double kScale[] = {1e0, 1e1, 1e2, 1e3, 1e4, 1e5, 1e6, 1e7, 1e8, 1e9, 1e10, 1e11, 1e12, 1e13, 1e14, 1e15};
  const double x = value * f.scale * kScale[f.decimals];
  if (!(x > -1e15 && x < 1e15)) return false;  // also NaN
  // llround (halves away from zero) without the library call: truncate, then look at what
  // was cut off, exactly (|x| < 1e15, so x - t is exact).
  int64_t t = int64_t(x);
  const double cut = x - double(t);
  if (cut >= 0.5) ++t;
  else if (cut <= -0.5) --t;
  q = t;
  return true;
}
// The value a control will take for the increments `q` (in unscaled units).
double dequantize(int64_t q, const AddressFormat& f);
// The value a control reads for `value` once written in format `f` (rounded to its
// increments); NaN when it cannot be written.
double as_written(double value, const AddressFormat& f);
// Appends the text for `q` increments.
void append_quantized(int64_t q, const AddressFormat& f, std::string& out);
// Appends `n` as a whole number, zero-padded to `width` digits.
void append_int(int64_t n, int width, std::string& out);

}  // namespace clpc
