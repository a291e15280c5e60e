// Decimal numbers as CL and G-code files write them ("-12.3456", "5.", ".25"), read exactly
// as std::from_chars reads them but faster: up to 15 significant digits and 22 decimals, the
// digits make an integer below 2^53 and the value is that integer divided by a power of ten
// no larger than 1e22. Both are exact doubles, so the one division rounds correctly: the same
// double from_chars gives. Anything else (an exponent, more digits, "inf") goes to from_chars.
#pragma once

#include <algorithm>
#include <charconv>
#include <cstdint>
#include <cstdlib>
#include <cstring>

namespace clpc {

// std::from_chars for a double, where the standard library has it (libstdc++); the browser
// build's libc++ (Emscripten's) has only the integer ones, and there strtod reads the same
// forms: an optional minus, digits with a point, an exponent, inf, nan (no plus, no spaces,
// no hexadecimal: a leading "0x" reads as 0, as from_chars reads it).
inline std::from_chars_result from_chars_double(const char* b, const char* e, double& v) {
#if defined(__cpp_lib_to_chars) && __cpp_lib_to_chars >= 201611L
  return std::from_chars(b, e, v);
#else
  char buf[128];
  const size_t n = std::min<size_t>(size_t(e - b), sizeof buf - 1);
  std::memcpy(buf, b, n);
  buf[n] = 0;
  const char* digits = buf + (n > 0 && buf[0] == '-');
  if (n == 0 || !(unsigned(*digits - '0') < 10 || *digits == '.' || *digits == 'i' || *digits == 'I' || *digits == 'n' ||
                  *digits == 'N'))
    return {b, std::errc::invalid_argument};
  if (digits[0] == '0' && (digits[1] == 'x' || digits[1] == 'X')) buf[digits + 1 - buf] = 0;
  char* end = nullptr;
  const double x = std::strtod(buf, &end);
  if (end == buf) return {b, std::errc::invalid_argument};
  // A number as long as the buffer may go on past it: refused, never read short.
  if (end == buf + n && n < size_t(e - b)) return {b, std::errc::result_out_of_range};
  v = x;
  return {b + (end - buf), std::errc()};
#endif
}

inline std::from_chars_result read_decimal(const char* b, const char* e, double& v) {
  static constexpr double kPow10[] = {1e0,  1e1,  1e2,  1e3,  1e4,  1e5,  1e6,  1e7,  1e8,  1e9,  1e10, 1e11,
                                      1e12, 1e13, 1e14, 1e15, 1e16, 1e17, 1e18, 1e19, 1e20, 1e21, 1e22};
  const char* p = b;
  const bool negative = p < e && *p == '-';
  if (negative) ++p;
  uint64_t m = 0;
  int digits = 0, decimals = 0;
  bool any = false;
  for (; p < e && unsigned(*p - '0') < 10; ++p) {
    any = true;
    if (m == 0 && *p == '0') continue;  // leading zeros are not significant
    m = m * 10 + unsigned(*p - '0');
    ++digits;
  }
  if (p < e && *p == '.') {
    ++p;
    for (; p < e && unsigned(*p - '0') < 10; ++p) {
      any = true;
      ++decimals;
      if (m == 0 && *p == '0') continue;
      m = m * 10 + unsigned(*p - '0');
      ++digits;
    }
  }
  if (!any || digits > 15 || decimals > 22 || (p < e && (*p == 'e' || *p == 'E'))) return from_chars_double(b, e, v);
  const double x = double(m) / kPow10[decimals];
  v = negative ? -x : x;
  return {p, std::errc()};
}

}  // namespace clpc
