// Numbers as a control reads them, formatted with integer arithmetic (no printf on the hot
// path): the value is scaled, rounded once to an integer count of output increments, and that
// integer is what is written and what modal suppression compares.
#pragma once

#include <cstdint>
#include <string>

#include "backends/machine.h"

namespace clpc {

// The rounded value in output increments (value * scale * 10^decimals). False when it does not
// fit a control's range (|value| >= 1e15 increments) or is not finite.
bool quantize(double value, const AddressFormat& f, int64_t& q);
// The value a control will take for the increments `q` (in unscaled units).
double dequantize(int64_t q, const AddressFormat& f);
// Appends the text for `q` increments.
void append_quantized(int64_t q, const AddressFormat& f, std::string& out);
// Appends `n` as a whole number, zero-padded to `width` digits.
void append_int(int64_t n, int width, std::string& out);

}  // namespace clpc
